#!/usr/bin/env python3
"""The seed paper's head impact against a side part, small version (issue 18,
docs/seed_paper.md model 2): the decks of examples/make_side_panel.py --small (a 20 x 10 shell
panel on ten support patches, a 4 x 4 per face headform). Two sets of runs:

* at SPEED (slow enough for the panel to stay linear) deformable (plastic, which stays elastic
  here), deformable linear-elastic, rigid and flexible with 5 / 10 / 20 / 40 modes (FORM 0 and
  1) and with every mode the eigen analysis gives (FORM 1);
* at the paper's 6.7 m/s the deformable plastic panel alone, which yields under the head.

Checks, with references that do not come from the modal code:

- energy: |energy_ratio - 1| <= 1e-6 at every cycle of every run (plastic work included);
- momentum: the change of the model's momentum (glstat.csv) equals the impulse of the support
  reactions, sum over cycles of dt_avg times the spcforc.csv sum (no other external force acts),
  to 1e-9 of the headform's initial momentum, in x, y and z, in every run, and the supports take
  a real share of it;
- plasticity: the 6.7 m/s run yields (largest effective plastic strain > 1e-3), the slow one
  does not;
- all modes: the flexible panel with every mode equals the deformable linear-elastic panel
  (both with the same deformable support patches): the deflection of the node under the head
  within 3 % (RMS) and 6 % (largest) of the elastic peak (measured 1.9 % and 3.9 %: the curved
  panel's flexible body is slightly stiffer, see docs/verification.md; the flat panel: 0.5 %);
- convergence: the RMS error of that deflection against the elastic panel falls monotonically
  with the mode count (rigid, 5, 10, 20, 40, all);
- the far node (right end) moves 2e-3 of the near node in the small model's 6 ms: its errors
  are printed, not checked.

Measured numbers: docs/verification.md. Usage: side_panel_check.py RIGIDFLEX WORKDIR
"""
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from rigidflex_results import read_csv, read_pvd, read_vtu, support_impulse  # noqa: E402

DRILLING_FACTOR = "1e-2"  # as examples/run_side_panel.py
SPEED = 100.0  # mm/s
failures = []


def check(condition, message):
    print(("ok      " if condition else "FAILED  ") + message)
    if not condition:
        failures.append(message)


def largest_plastic_strain(out):
    last = read_pvd(os.path.join(out, "frames.pvd"))[-1][1]
    return max(read_vtu(os.path.join(out, last))["cell_data"].get("effective_plastic_strain",
                                                                   [0.0]))


def run_and_check(rigidflex, env, model, v):
    """Runs one variant; checks energy and momentum; returns its output folder."""
    out = "out_" + v["deck"][len("side_panel_"):-2]
    subprocess.check_call([rigidflex, "run", v["deck"], "-o", out, "--threads", "1", "--quiet"],
                          env=env)
    name = f"{v['name']} at {model['head']['speed'] / 1000:g} m/s"
    p0_head = model["head"]["mass"] * model["head"]["speed"]
    glstat = read_csv(os.path.join(out, "glstat.csv"))
    worst = max(abs(r["energy_ratio"] - 1.0) for r in glstat)
    check(worst <= 1e-6, f"{name}: |energy ratio - 1| = {worst:.1e} <= 1e-6")
    impulse, every_cycle = support_impulse(out, glstat)
    check(every_cycle, f"{name}: spcforc and glstat at every cycle ({len(glstat)} rows)")
    worst = max(abs(glstat[-1][c] - glstat[0][c] - impulse[d]) for d, c in
                enumerate(("momentum_x", "momentum_y", "momentum_z")))
    check(worst <= 1e-9 * p0_head,
          f"{name}: momentum change = support impulse (largest difference {worst / p0_head:.1e} "
          "of the head's momentum <= 1e-9)")
    share = (glstat[-1]["momentum_z"] - glstat[0]["momentum_z"]) / p0_head
    check(share > 0.2, f"{name}: the supports take a real impulse ({share:.2f} of the head's "
          "momentum > 0.2)")
    return out


def deflections(out, nodes):
    rows = read_csv(os.path.join(out, "nodout.csv"))
    result = {}
    for name, nid in nodes.items():
        mine = [r for r in rows if int(r["node"]) == nid]
        result[name] = [mine[0]["z"] - r["z"] for r in mine]
    return result


def main():
    rigidflex, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    generator = os.path.join(ROOT, "examples", "make_side_panel.py")

    # The paper's speed: the plastic panel alone.
    fast = os.path.join(work, "fast")
    subprocess.check_call([sys.executable, generator, "--out", fast, "--small", "--modes", "5",
                           "--forms", "1"])
    with open(os.path.join(fast, "side_panel.json")) as f:
        model = json.load(f)
    os.chdir(fast)
    out = run_and_check(rigidflex, env, model, model["variants"][0])
    eps = largest_plastic_strain(out)
    check(eps > 1e-3, f"deformable at 6.7 m/s: the panel yields (largest effective plastic "
          f"strain {eps:.4f} > 1e-3)")

    # Slow: every variant.
    os.chdir(work)
    subprocess.check_call([sys.executable, generator, "--out", work, "--small", "--speed",
                           str(SPEED), "--modes", "5,10,20,40"])
    with open(os.path.join(work, "side_panel.json")) as f:
        model = json.load(f)
    # Every elastic mode Lanczos gives for the flexible part (asked for 6 per node; it returns
    # a few less), then the decks again with a variant holding all of them.
    subprocess.check_call([rigidflex, "eigen", "side_panel_eigen.k", "--parts", "1", "--modes",
                           str(6 * model["flexible_nodes"]), "--remove-rigid", "1.0",
                           "--drilling-factor", DRILLING_FACTOR, "-o", "modes", "--quiet"],
                          env=env)
    elastic_all = len(read_csv(os.path.join(work, "modes", "eigout.csv")))
    check(elastic_all > 6 * model["flexible_nodes"] - 12,
          f"all modes: {elastic_all} elastic modes of {6 * model['flexible_nodes']} DOFs")
    subprocess.check_call([sys.executable, generator, "--out", work, "--small", "--speed",
                           str(SPEED), "--modes", "5,10,20,40", "--all-modes", str(elastic_all)])
    with open(os.path.join(work, "side_panel.json")) as f:
        model = json.load(f)
    nodes = model["tracked_nodes"]
    results = {}
    for v in model["variants"]:
        out = run_and_check(rigidflex, env, model, v)
        results[v["name"]] = deflections(out, nodes)
        if v["kind"] == "deformable":
            eps = largest_plastic_strain(out)
            check(eps == 0.0, f"deformable at {SPEED / 1000:g} m/s: no plastic strain ({eps:.1e})")

    ref = results["deformable elastic"]
    plastic = results["deformable"]
    errors = {}
    everything = f"{elastic_all} modes FORM 1"
    for node in nodes:
        peak = max(abs(x) for x in ref[node])
        same = max(abs(a - b) for a, b in zip(plastic[node], ref[node])) / peak
        check(same < 1e-9, f"{node} node: the plastic panel that does not yield equals the "
              f"elastic one ({same:.1e} of the peak)")
        for name, hist in results.items():
            check(len(hist[node]) == len(ref[node]),
                  f"{name}: {len(hist[node])} output times as the elastic run ({node} node)")
            diff = [a - b for a, b in zip(hist[node], ref[node])]
            errors[(name, node)] = (math.sqrt(sum(d * d for d in diff) / len(diff)) / peak,
                                    max(abs(d) for d in diff) / peak)
            print(f"{name:>20} {node:>4}: RMS error {100 * errors[(name, node)][0]:.3f} %, "
                  f"largest {100 * errors[(name, node)][1]:.3f} % of the elastic peak "
                  f"{peak:.2e} mm")
    # The far node moves 2e-3 of the near node in the small model's 6 ms (the wave has hardly
    # reached it): printed above, not checked. The near node:
    near = "near"
    peak = max(abs(x) for x in ref[near])
    check(peak < 0.2 * model["panel"]["thickness"],
          f"near node: elastic peak {peak:.4f} mm < 0.2 of the thickness (linear panel)")
    # Every mode against the deformable elastic panel: 1.9 % RMS, 3.9 % largest on this curved
    # panel, where the flexible body is a little stiffer (the same panel made flat: 0.5 %
    # largest; docs/verification.md, "All modes on a curved panel"), so the tolerance is 3 % / 6 %.
    rms, largest = errors[(everything, near)]
    check(rms < 3e-2 and largest < 6e-2,
          f"{everything}: equals the elastic panel at the near node (RMS {rms:.2e} < 3e-2, "
          f"largest {largest:.2e} < 6e-2 of the peak)")
    for form in model["forms"]:
        counts = model["modes"] + ([elastic_all] if form == 1 else [])
        series = ([errors[("rigid", near)][0]] +
                  [errors[(f"{m} modes FORM {form}", near)][0] for m in counts])
        check(all(b < a for a, b in zip(series, series[1:])),
              f"FORM {form}, near node: RMS error falls with the mode count (rigid, "
              + ", ".join(str(m) for m in counts) + "): "
              + ", ".join(f"{100 * e:.3f} %" for e in series))
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("OK")


if __name__ == "__main__":
    main()
