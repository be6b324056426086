#!/usr/bin/env python3
"""The seed paper's forming example (die on a blank), small version (issue 18, docs/seed_paper.md,
model 3): the decks of examples/make_die_blank.py --small (a 33 x 8 Barlat blank, a die of
12 x 3 x 3 elastic hexahedra under a layer of 12 x 3 driver hexahedra, the rigid matrix with its
counter form, a 0.75 ms cycloidal stroke), run deformable, rigid and flexible with 10 / 40 / 160
modes and with every mode the eigen analysis gives (FORM 1), and 10 modes FORM 0. The tracked
quantity is the die's compression at its bottom node (its shortening between that node and the
node above it on the die's top face; zero for a rigid die). Checks:

- energy: |energy_ratio - 1| <= 1e-6 at every output time of every variant (measured <= 5e-14);
- the drive (the paper's option (ii)): the die's top node follows the prescribed cycloid (a
  closed form, not the solver's curve) to 5 um in every variant (the driver layer's compression
  under the die's inertia and the contact force; measured <= 2.0 um);
- all modes (FORM 1): the flexible die with every mode equals the deformable linear-elastic
  die: the compression history within 3 % of the deformable peak (RMS) up to half the stroke
  time, where the die is loaded by its own inertia and the forming of the blank (measured
  1.2 %), and within 15 % over the whole run (measured 7.1 %): after the blank is squeezed on the
  counter form, the contact chatter of the plastic blank between two stiff tools amplifies the
  difference of the two time integrations (the modes' exact flow against the leapfrog), which
  is the same at t = 0 to round-off;
- convergence: the RMS error of the compression history up to 0.75 of the stroke time (the
  loaded part of the run; measured 0.416 / 0.400 / 0.295 / 0.269 / 0.015 of the peak) falls
  monotonically rigid -> 10 -> 40 -> 160 -> all modes;
- FORM 0 and FORM 1 agree at 10 modes (the die does not turn): RMS difference <= 1e-3 of the
  peak (measured 3e-6).

Usage: die_blank_check.py RIGIDFLEX WORKDIR
"""
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "examples"))
from rigidflex_results import read_csv  # noqa: E402
from run_die_blank import die_history, interpolate  # noqa: E402

failures = []


def check(condition, message):
    print(("ok      " if condition else "FAILED  ") + message)
    if not condition:
        failures.append(message)


def rms(a, b, scale):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)) / max(1, len(a))) / scale


def main():
    rigidflex, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    die_nodes = 13 * 4 * 4  # the small die's nodes (12 x 3 x 3 hexahedra)
    elastic_all = 3 * die_nodes - 7  # every elastic mode Lanczos can give
    counts = [10, 40, 160]
    subprocess.check_call([sys.executable, os.path.join(ROOT, "examples", "make_die_blank.py"),
                           "--out", work, "--small", "--modes", ",".join(map(str, counts)),
                           "--form0-modes", "10", "--all-modes", str(elastic_all)])
    with open(os.path.join(work, "die_blank.json")) as f:
        model = json.load(f)
    check(model["die"]["nodes"] == die_nodes, f"the small die has {die_nodes} nodes")
    os.chdir(work)
    subprocess.check_call([rigidflex, "eigen", "die_blank_eigen.k", "--parts", "1", "--modes",
                           str(elastic_all), "--remove-rigid", "1000", "-o", "modes", "--quiet"],
                          env=env)
    stroke, t_bdc = model["stroke"], model["t_bdc"]

    def prescribed(t):  # the cycloid of make_die_blank.py, down to t_bdc and back
        if t <= t_bdc:
            return -stroke * (t / t_bdc - math.sin(2 * math.pi * t / t_bdc) / (2 * math.pi))
        s = t - t_bdc
        return -stroke + stroke * (s / t_bdc - math.sin(2 * math.pi * s / t_bdc) / (2 * math.pi))

    results = {}
    for v in model["variants"]:
        out = "out_" + v["deck"][len("die_blank_"):-2]
        subprocess.check_call([rigidflex, "run", v["deck"], "-o", out, "--threads", "1",
                               "--quiet"], env=env)
        glstat = read_csv(os.path.join(out, "glstat.csv"))
        worst = max(abs(r["energy_ratio"] - 1.0) for r in glstat)
        check(worst <= 1e-6, f"{v['name']}: |energy ratio - 1| = {worst:.1e} <= 1e-6")
        top = [r for r in read_csv(os.path.join(out, "nodout.csv"))
               if int(r["node"]) == model["top_node"]]
        drive = max(abs(r["z"] - top[0]["z"] - prescribed(r["time"])) for r in top)
        check(drive <= 5e-3, f"{v['name']}: the die's top follows the prescribed stroke to "
              f"{1e3 * drive:.2f} um <= 5 um")
        results[v["name"]] = die_history(out, model["bottom_node"], model["top_node"])

    times, _, ref = results["deformable"]
    peak = max(ref)
    check(peak > 1e-3, f"deformable die: peak compression {1e3 * peak:.2f} um > 1 um")

    def error(name, window):
        t, _, comp = results[name]
        at = [x for x in times if x <= window * t_bdc]
        return rms(interpolate(t, comp, at), ref[:len(at)], peak)

    everything = f"{elastic_all} modes FORM 1"
    first, whole = error(everything, 0.5), error(everything, 10.0)
    check(first <= 0.03, f"{everything}: equals the deformable die up to t_bdc / 2 (RMS "
          f"{first:.2e} of the peak <= 3e-2)")
    check(whole <= 0.15, f"{everything}: and over the whole run (RMS {whole:.2e} of the peak "
          "<= 0.15)")
    names = ["rigid"] + [f"{m} modes FORM 1" for m in counts] + [everything]
    series = [error(n, 0.75) for n in names]
    check(all(b < a for a, b in zip(series, series[1:])),
          "RMS error up to 0.75 t_bdc falls with the mode count (rigid, "
          + ", ".join(str(m) for m in counts) + f", {elastic_all}): "
          + ", ".join(f"{e:.4f}" for e in series))
    t0, _, c0 = results["10 modes FORM 0"]
    t1, _, c1 = results["10 modes FORM 1"]
    forms = rms(interpolate(t0, c0, t1), c1, peak)
    check(forms <= 1e-3, f"10 modes: FORM 0 equals FORM 1 (RMS difference {forms:.1e} of the "
          "peak <= 1e-3)")
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("OK")


if __name__ == "__main__":
    main()
