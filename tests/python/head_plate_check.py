#!/usr/bin/env python3
"""The seed paper's head impact on a plate, small version (issue 18, docs/seed_paper.md): the
decks of examples/make_head_plate.py --small (12 x 10 shells, 4 x 4 per face headform) at
1 m/s, so that the plate stays linear (peak deflection 0.39 mm, 4 % of its thickness), run
deformable, rigid and flexible with 5 / 10 / 20 / 40 modes and with every mode the eigen
analysis gives (FORM 0 and 1). Checks, with references that do not come from the modal code:

- energy: |energy_ratio - 1| <= 1e-6 at every cycle of every variant (measured <= 3e-14);
- momentum: the change of the model's momentum (glstat.csv) equals the impulse of the support
  reactions, sum over cycles of dt_avg times the spcforc.csv sum (no other external force acts),
  to 1e-9 of the headform's initial momentum, in x, y and z, in every variant;
- all modes (FORM 1; FORM 0's O(n^2) inertia terms take 110 s here): the flexible plate
  with every mode equals the deformable linear-elastic plate
  (both with the same deformable corner elements): the tracked node's resultant displacement
  within 0.5 % of the deformable peak at every output time (RMS and largest difference;
  measured 2.4e-5 and 1.5e-4);
- convergence: the RMS error of that history falls monotonically with the mode count, and the
  rigid plate body's is the largest.

Usage: head_plate_check.py RIGIDFLEX WORKDIR
"""
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from rigidflex_results import read_csv, support_impulse  # noqa: E402

DRILLING_FACTOR = "1e-2"  # as examples/run_head_plate.py
failures = []


def check(condition, message):
    print(("ok      " if condition else "FAILED  ") + message)
    if not condition:
        failures.append(message)


def main():
    rigidflex, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    nx, ny = 12, 10
    elastic_all = 6 * ((nx + 1) * (ny + 1) - 4) - 7  # every elastic mode Lanczos can give
    subprocess.check_call([sys.executable, os.path.join(ROOT, "examples", "make_head_plate.py"),
                           "--out", work, "--small", "--speed", "1000", "--modes", "5,10,20,40",
                           "--all-modes", str(elastic_all)])
    with open(os.path.join(work, "head_plate.json")) as f:
        model = json.load(f)
    os.chdir(work)
    subprocess.check_call([rigidflex, "eigen", "head_plate_eigen.k", "--parts", "1", "--modes",
                           str(elastic_all), "--remove-rigid", "1.0", "--drilling-factor",
                           DRILLING_FACTOR, "-o", "modes", "--quiet"], env=env)
    node = model["tracked_node"]
    p0_head = model["head"]["mass"] * model["head"]["speed"]
    results = {}
    for v in model["variants"]:
        out = "out_" + v["deck"][len("head_plate_"):-2]
        subprocess.check_call([rigidflex, "run", v["deck"], "-o", out, "--threads", "1",
                               "--quiet"], env=env)
        glstat = read_csv(os.path.join(out, "glstat.csv"))
        worst = max(abs(r["energy_ratio"] - 1.0) for r in glstat)
        check(worst <= 1e-6, f"{v['name']}: |energy ratio - 1| = {worst:.1e} <= 1e-6")

        impulse, every_cycle = support_impulse(out, glstat)
        check(every_cycle, f"{v['name']}: spcforc and glstat at every cycle ({len(glstat)} rows)")
        for d, c in enumerate(("momentum_x", "momentum_y", "momentum_z")):
            change = glstat[-1][c] - glstat[0][c]
            check(abs(change - impulse[d]) <= 1e-9 * p0_head,
                  f"{v['name']}: {c} change {change:.6e} = support impulse {impulse[d]:.6e} "
                  f"(difference {abs(change - impulse[d]) / p0_head:.1e} of the head's)")
        if v["kind"] == "deformable":
            check(glstat[-1]["momentum_z"] - glstat[0]["momentum_z"] > 0.2 * p0_head,
                  f"{v['name']}: the supports take a real impulse "
                  f"({(glstat[-1]['momentum_z'] - glstat[0]['momentum_z']) / p0_head:.2f} of "
                  "the head's momentum)")

        rows = [r for r in read_csv(os.path.join(out, "nodout.csv")) if int(r["node"]) == node]
        x0 = (rows[0]["x"], rows[0]["y"], rows[0]["z"])
        results[v["name"]] = (v, [math.dist((r["x"], r["y"], r["z"]), x0) for r in rows])

    ref = results["deformable"][1]
    peak = max(ref)
    check(0.01 * model["plate"]["thickness"] < peak < 0.1 * model["plate"]["thickness"],
          f"deformable peak {peak:.4f} mm: small against the thickness (linear plate)")
    errors = {}
    for name, (v, disp) in results.items():
        n = min(len(disp), len(ref))
        check(len(disp) == len(ref), f"{name}: {len(disp)} output times as the deformable run")
        diff = [disp[i] - ref[i] for i in range(n)]
        errors[name] = (math.sqrt(sum(d * d for d in diff) / n) / peak,
                        max(abs(d) for d in diff) / peak, max(disp) / peak - 1.0)
        print(f"{name:>20}: RMS error {100 * errors[name][0]:.3f} %, largest "
              f"{100 * errors[name][1]:.3f} %, peak {100 * errors[name][2]:+.3f} % of the "
              "deformable peak")
    everything = f"{elastic_all} modes FORM 1"
    check(errors[everything][0] < 5e-3 and errors[everything][1] < 5e-3,
          f"{everything}: equals the deformable plate (RMS {errors[everything][0]:.2e}, largest "
          f"{errors[everything][1]:.2e} of the peak <= 5e-3)")
    for form in model["forms"]:
        counts = model["modes"] + ([elastic_all] if form == 1 else [])
        series = [errors["rigid"][0]] + [errors[f"{m} modes FORM {form}"][0] for m in counts]
        check(all(b < a for a, b in zip(series, series[1:])),
              f"FORM {form}: RMS error falls with the mode count (rigid, "
              + ", ".join(str(m) for m in counts) + "): "
              + ", ".join(f"{100 * e:.3f} %" for e in series))
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("OK")


if __name__ == "__main__":
    main()
