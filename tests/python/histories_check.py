#!/usr/bin/env python3
"""Checks matsum.csv, spcforc.csv and elout.csv against references that do not come from them.

- column: a steel column (1 x 1 x 4 hexahedra) standing on fixed bottom nodes under a body load
  ramped up over 60 axial periods (quasi-static): the summed SPC reaction equals the weight M a
  (static equilibrium) within 2 %, its x and y sums vanish; the bottom element's sigma_zz equals
  minus the weight above its centre over the area (7/8 M a / A) within 3 %; elout rows equal the
  frames' stress of that element at the frame times (the same doubles); matsum adds up to glstat.
- deck DECK: *DATABASE_MATSUM (and the glstat interval) appended; at every glstat time the sums
  over parts of internal, kinetic and hourglass energy and of momentum equal glstat's
  (conservation bookkeeping: the parts partition the model) to round-off.

Usage: histories_check.py RIGIDFLEX column|DECK WORKDIR
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import read_csv, read_pvd, read_vtu  # noqa: E402

RHO, E, NU, H, N, ACC = 7800.0, 2.0e11, 0.3, 0.01, 4, 1000.0

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def column_deck(path):
    lines = ["*KEYWORD", "*TITLE", "column under a slowly ramped body load", "*NODE"]
    nid = 0
    for k in range(N + 1):
        for j in range(2):
            for i in range(2):
                nid += 1
                lines.append("%8d%16.8g%16.8g%16.8g" % (nid, i * H, j * H, k * H))
    lines.append("*ELEMENT_SOLID")
    for k in range(N):
        b = 4 * k
        c = [b + 1, b + 2, b + 4, b + 3, b + 5, b + 6, b + 8, b + 7]
        lines.append("%8d%8d" % (k + 1, 1) + "".join("%8d" % x for x in c))
    lines += ["*PART", "column", "1,1,1", "*SECTION_SOLID", "1,1", "*MAT_ELASTIC",
              "1,%g,%g,%g" % (RHO, E, NU), "*BOUNDARY_SPC_NODE"]
    lines += ["%d,0,1,1,1,1,1,1" % n for n in (1, 2, 3, 4)]
    lines += ["*DEFINE_CURVE", "99", "0.0,0.0", "2.0e-3,1.0", "1.0,1.0",
              "*LOAD_BODY_Z", "99,%g" % ACC, "*CONTROL_TERMINATION", "2.5e-3",
              "*CONTROL_TIMESTEP", "0.0,0.5",
              "*DATABASE_GLSTAT", "1.0e-4", "*DATABASE_BINARY_D3PLOT", "2.5e-4",
              "*DATABASE_MATSUM", "1.0e-4", "*DATABASE_SPCFORC", "1.0e-4",
              "*DATABASE_ELOUT", "5.0e-5", "*DATABASE_HISTORY_SOLID", "1", "*END"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def with_matsum(source, path):
    text = open(source).read()
    at = text.upper().rindex("*END")
    with open(path, "w") as f:
        f.write(text[:at] + "*DATABASE_MATSUM\n0.0\n" + text[at:])


def run(rigidflex, deck, out):
    subprocess.run([rigidflex, "run", deck, "-o", out, "--threads", "1", "--quiet"], check=True)


def check_matsum(out):
    glstat = {round(r["time"], 12): r for r in read_csv(os.path.join(out, "glstat.csv"))}
    sums = {}
    for r in read_csv(os.path.join(out, "matsum.csv")):
        s = sums.setdefault(round(r["time"], 12), [0.0] * 6)
        for k, name in enumerate(("internal_energy", "kinetic_energy", "hourglass_energy",
                                  "momentum_x", "momentum_y", "momentum_z")):
            s[k] += r[name]
    compared = 0
    for t, s in sums.items():
        g = glstat.get(t)
        if g is None:
            continue
        compared += 1
        energy = max(abs(g["kinetic_energy"]) + abs(g["internal_energy"]) + abs(g["hourglass_energy"]), 1e-300)
        momentum = max(abs(g["momentum_x"]) + abs(g["momentum_y"]) + abs(g["momentum_z"]), 1e-300)
        for k, name in enumerate(("internal_energy", "kinetic_energy", "hourglass_energy")):
            check(abs(s[k] - g[name]) <= 1e-10 * energy,
                  "t=%g: parts' %s sum to %r, glstat %r" % (t, name, s[k], g[name]))
        for k, name in enumerate(("momentum_x", "momentum_y", "momentum_z")):
            check(abs(s[3 + k] - g[name]) <= 1e-10 * momentum,
                  "t=%g: parts' %s sum to %r, glstat %r" % (t, name, s[3 + k], g[name]))
    check(compared >= 10, "only %d matsum times had a glstat row" % compared)
    return compared


def main():
    rigidflex, deck, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "out")
    if deck == "column":
        path = os.path.join(work, "column.k")
        column_deck(path)
        run(rigidflex, path, out)
        mass = RHO * H * H * N * H
        weight = mass * ACC
        last = max(r["time"] for r in read_csv(os.path.join(out, "spcforc.csv")))
        rows = [r for r in read_csv(os.path.join(out, "spcforc.csv")) if r["time"] == last]
        check(sorted(int(r["node"]) for r in rows) == [1, 2, 3, 4], "spcforc nodes %r" % [r["node"] for r in rows])
        fz = sum(r["force_z"] for r in rows)
        fx = sum(r["force_x"] for r in rows)
        fy = sum(r["force_y"] for r in rows)
        check(abs(fz - weight) <= 0.02 * weight, "summed z reaction %r, weight %r" % (fz, weight))
        check(abs(fx) <= 1e-6 * weight and abs(fy) <= 1e-6 * weight, "x, y reactions %r %r" % (fx, fy))
        elout = read_csv(os.path.join(out, "elout.csv"))
        end = [r for r in elout if r["time"] == max(e["time"] for e in elout)][0]
        expected = -(N - 0.5) / N * weight / (H * H)
        check(abs(end["szz"] - expected) <= 0.03 * abs(expected), "sigma_zz %r, expected %r" % (end["szz"], expected))
        check(end["effective_plastic_strain"] == 0.0, "plastic strain %r" % end["effective_plastic_strain"])
        by_time = {round(r["time"], 12): r for r in elout if int(r["element"]) == 1}
        matched = 0
        for t, name in read_pvd(os.path.join(out, "frames.pvd")):
            r = by_time.get(round(t, 12))
            if r is None:
                continue
            f = read_vtu(os.path.join(out, name))
            c = list(f["cell_data"]["element_id"]).index(1)
            stress = f["cell_data"]["stress"][c]
            values = [r[k] for k in ("sxx", "syy", "szz", "sxy", "syz", "szx")]
            check(list(stress) == values, "t=%g: elout %r, frame %r" % (t, values, stress))
            check(r["pressure"] == f["cell_data"]["pressure"][c], "t=%g: pressure differs" % t)
            matched += 1
        check(matched >= 5, "only %d frames had an elout row at their time" % matched)
        compared = check_matsum(out)
        summary = "column: reaction %.6g vs weight %.6g, sigma_zz %.6g vs %.6g, %d matsum times" % (
            fz, weight, end["szz"], expected, compared)
    else:
        path = os.path.join(work, "deck_with_matsum.k")
        with_matsum(deck, path)
        run(rigidflex, path, out)
        compared = check_matsum(out)
        summary = "%s: matsum sums equal glstat at %d times" % (os.path.basename(deck), compared)
    if failures:
        print("histories check failed:")
        for f in failures[:30]:
            print("  " + f)
        return 1
    print("histories match: " + summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
