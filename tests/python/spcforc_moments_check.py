#!/usr/bin/env python3
"""Checks the moments and the vector constraints of spcforc.csv against static equilibrium, a
reference that does not come from RigidFlex.

A steel cantilever of 10 Belytschko-Schwer beams along x (1 m) carries at its tip x = L the
force F and the moment M, ramped up and then held while mass damping removes the motion. Its
root node 1 is held in two ways, one deck each:
  - *BOUNDARY_SPC_NODE on all six DOFs (translations and rotations);
  - *BOUNDARY_PRESCRIBED_MOTION_NODE, held (VAD 2, zero displacement): DOF 4 along (1, 1, 0),
    (1, -1, 0) and (0, 0, 1), and DOF 8 about (0, 1, 1), (0, 1, -1) and (1, 0, 0). (An SPC and
    a prescribed vector motion on one node are refused, so the two kinds cannot share it.)
In static equilibrium the root's reaction is the negative of the tip loads, force -F, and moment
-(M + r x F) about the root, r the tip's deflected position (nodout). With the vectors each component is the projection of the
reaction on several non-axis directions, so the span of the constrained vectors is checked.

Usage: spcforc_moments_check.py RIGIDFLEX WORKDIR
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import read_csv  # noqa: E402

L, N = 1.0, 10
F = (10.0, 30.0, 20.0)
M = (2.0, 5.0, 8.0)
END, RAMP = 0.3, 0.05


def deck(held_by_vectors):
    lines = ["*KEYWORD", "*TITLE", "cantilever held by SPC, DOF 4 vectors and a DOF 8 rotation", "*NODE"]
    for i in range(N + 1):
        lines.append("%d,%.10g,0.0,0.0" % (i + 1, i * L / N))
    lines.append("*ELEMENT_BEAM")
    for i in range(N):
        lines.append("%d,1,%d,%d" % (i + 1, i + 1, i + 2))
    # 20 mm square steel: A, Iss, Itt, J
    lines += ["*PART", "beam", "1,1,1", "*SECTION_BEAM", "1,2,0.8333",
              "4.0e-4,1.3333e-8,1.3333e-8,2.25e-8",
              "*MAT_ELASTIC", "1,7850.0,2.1e11,0.3",
              "*DEFINE_CURVE", "1", "0.0,0.0", "%g,1.0" % RAMP, "10.0,1.0",
              "*DEFINE_CURVE", "2", "0.0,0.0", "10.0,0.0",
              "*DEFINE_VECTOR", "11,0,0,0,1,1,0",
              "*DEFINE_VECTOR", "12,0,0,0,1,-1,0",
              "*DEFINE_VECTOR", "13,0,0,0,0,0,1",
              "*DEFINE_VECTOR", "14,0,0,0,0,1,1",
              "*DEFINE_VECTOR", "15,0,0,0,0,1,-1",
              "*DEFINE_VECTOR", "16,0,0,0,1,0,0"]
    if held_by_vectors:
        lines += ["*BOUNDARY_PRESCRIBED_MOTION_NODE",
                  "1,4,2,2,1.0,11", "1,4,2,2,1.0,12", "1,4,2,2,1.0,13",
                  "1,8,2,2,1.0,14", "1,8,2,2,1.0,15", "1,8,2,2,1.0,16"]
    else:
        lines += ["*BOUNDARY_SPC_NODE", "1,0,1,1,1,1,1,1"]
    lines += ["*LOAD_NODE_POINT"]
    tip = N + 1
    for k in range(3):
        lines.append("%d,%d,1,%.10g" % (tip, k + 1, F[k]))
        lines.append("%d,%d,1,%.10g" % (tip, k + 5, M[k]))
    # First bending mode ~ 105 rad/s: mass damping 2 x 105 decays every mode at least as fast.
    lines += ["*DAMPING_GLOBAL", "0,210.0",
              "*CONTROL_TERMINATION", "%g" % END,
              "*DATABASE_SPCFORC", "%g" % (END / 30),
              "*DATABASE_HISTORY_NODE", "%d" % tip, "*DATABASE_NODOUT", "%g" % (END / 30), "*END"]
    return "\n".join(lines) + "\n"


def check_case(rigidflex, work, held_by_vectors, failures):
    name = "vectors" if held_by_vectors else "spc"
    path = os.path.join(work, name + ".k")
    with open(path, "w") as f:
        f.write(deck(held_by_vectors))
    out = os.path.join(work, name)
    p = subprocess.run([rigidflex, "run", path, "-o", out, "--threads", "1", "--quiet"],
                       capture_output=True, text=True)
    if p.returncode != 0:
        failures.append("%s: run failed: %s" % (name, (p.stdout + p.stderr)[-500:]))
        return
    header = open(os.path.join(out, "spcforc.csv")).readline().strip()
    want_header = "time,node,force_x,force_y,force_z,moment_x,moment_y,moment_z"
    rows = read_csv(os.path.join(out, "spcforc.csv"))
    last = max(r["time"] for r in rows)
    root = [r for r in rows if r["time"] == last]
    if header != want_header:
        failures.append("%s: header %r" % (name, header))
    if [int(r["node"]) for r in root] != [1]:
        failures.append("%s: nodes at the last time %r, expected [1]" % (name, [r["node"] for r in root]))
        return
    force = [-f for f in F]
    # The lever of F is the tip's current position (the beam deflects 5 mm: 0.05 N m of the
    # moment about z, 0.13 %, comes from it), from nodout at the same time.
    tip = [x for x in read_csv(os.path.join(out, "nodout.csv")) if x["time"] == last][0]
    arm = (tip["x"] - 0.0, tip["y"], tip["z"])
    lever = (arm[1] * F[2] - arm[2] * F[1], arm[2] * F[0] - arm[0] * F[2],
             arm[0] * F[1] - arm[1] * F[0])  # arm x F
    moment = [-(M[k] + lever[k]) for k in range(3)]
    r = root[0]
    got_f = [r["force_x"], r["force_y"], r["force_z"]]
    got_m = [r["moment_x"], r["moment_y"], r["moment_z"]]
    scale_f = max(abs(f) for f in F)
    scale_m = max(abs(m) for m in moment)
    if any(abs(got_f[k] - force[k]) > 1e-3 * scale_f for k in range(3)):
        failures.append("%s: force %r, static %r" % (name, got_f, force))
    if any(abs(got_m[k] - moment[k]) > 1e-3 * scale_m for k in range(3)):
        failures.append("%s: moment %r, static %r" % (name, got_m, moment))
    # Early in the ramp the reaction is not yet the static one: the check could fail.
    early = [x for x in rows if 0.0 < x["time"] <= RAMP / 2]
    if not early or all(abs(x["moment_z"] - moment[2]) < 0.1 * scale_m for x in early):
        failures.append("%s: early rows already static" % name)
    print("%s: force (%.6g, %.6g, %.6g) N, moment (%.6g, %.6g, %.6g) N m at t = %g s; static "
          "(%.6g, %.6g, %.6g), (%.6g, %.6g, %.6g)" % (name, *got_f, *got_m, last, *force, *moment))


def main():
    rigidflex, work = sys.argv[1:3]
    os.makedirs(work, exist_ok=True)
    failures = []
    for held_by_vectors in (False, True):
        check_case(rigidflex, work, held_by_vectors, failures)
    if failures:
        print("spcforc differs from static equilibrium:\n  " + "\n  ".join(failures[:10]))
        return 1
    print("spcforc moments and vector constraints match static equilibrium")
    return 0


if __name__ == "__main__":
    sys.exit(main())
