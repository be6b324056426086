#!/usr/bin/env python3
"""Checks secforc.csv (*DATABASE_CROSS_SECTION_PLANE) against static equilibrium, a reference
that does not come from RigidFlex: a cantilever clamped at x = 0 carries tip loads Px (along
the axis) and Pz (transverse) at x = L. Once the motion has died out (mass damping, loads ramped
up), the free body beyond a cut at x = a holds the tip loads alone, so the positive side (x > a)
exerts on the negative side the force (Px, 0, Pz) and, about the section's centroid, the moment
(L - a) x_hat x (Px, 0, Pz) = (0, -(L - a) Pz, 0); the normal force is Px (tension).

Three families, each with its own deck: hexahedra (forces only), shells (the bending moment
crosses the cut mostly as nodal moments) and Belytschko-Schwer beams (one node in the cut).
Each deck has three sections at x = a: an unbounded plane, a rectangle (LENL, LENM) around the
cross-section and a disc (RADIUS); the hexahedra also one by sets (*DATABASE_CROSS_SECTION_SET:
the nodes at x = a and the elements just before them). A fourth section through a part set that does not hold the
structure must be refused, as must a plane that cuts nothing.

Usage: secforc_check.py RIGIDFLEX WORKDIR
       secforc_check.py --print-deck hex|shell|beam   (the deck on stdout: the MPI rank test)
"""
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import read_csv  # noqa: E402

RHO, E, NU = 7800.0, 2.0e11, 0.3
L, A_CUT = 1.0, 0.5
PX, PZ = 500.0, 900.0

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def common_cards(tip_nodes, omega1, end_time):
    """Tip loads ramped over a quarter of the run, mass damping critical for the first bending
    mode (every mode then decays at least as fast as exp(-omega1 t)), three sections at x = a."""
    lines = ["*DEFINE_CURVE", "9", "0.0,0.0", "%g,1.0" % (0.25 * end_time), "100.0,1.0"]
    lines.append("*LOAD_NODE_POINT")
    for n in tip_nodes:
        lines.append("%d,1,9,%.10g" % (n, PX / len(tip_nodes)))
        lines.append("%d,3,9,%.10g" % (n, PZ / len(tip_nodes)))
    lines += ["*DAMPING_GLOBAL", "0,%g" % (2.0 * omega1),
              "*CONTROL_TERMINATION", "%g" % end_time,
              "*DATABASE_SECFORC", "%g" % (end_time / 50),
              # unbounded plane x = a, normal +x
              "*DATABASE_CROSS_SECTION_PLANE_ID", "11,unbounded",
              "0,%g,0.0,0.0,%g,0.0,0.0" % (A_CUT, A_CUT + 1.0),
              # rectangle from (a, -0.5, -0.5) along y (1 m) and, by N x L = z, 1 m
              "*DATABASE_CROSS_SECTION_PLANE_ID", "12,rectangle",
              "1,%g,-0.5,-0.5,%g,-0.5,-0.5" % (A_CUT, A_CUT + 1.0),
              "%g,0.5,-0.5,1.0,1.0" % A_CUT,
              # disc of radius 0.5 about (a, 0, 0)
              "*DATABASE_CROSS_SECTION_PLANE_ID", "13,disc",
              "0,%g,0.0,0.0,%g,0.0,0.0,0.5" % (A_CUT, A_CUT + 1.0),
              "*SET_PART_LIST", "1", "1", "*END"]
    return lines


def hex_deck(path):
    """20 x 2 x 2 hexahedra, 1 m x 0.1 m x 0.1 m."""
    nx, ny, h = 20, 2, 0.1
    lines = ["*KEYWORD", "*TITLE", "hex cantilever", "*NODE"]
    nid = {}
    for k in range(ny + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                nid[i, j, k] = len(nid) + 1
                lines.append("%8d%16.8g%16.8g%16.8g" % (nid[i, j, k], i * L / nx, j * h / ny - h / 2,
                                                        k * h / ny - h / 2))
    lines.append("*ELEMENT_SOLID")
    e = 0
    for k in range(ny):
        for j in range(ny):
            for i in range(nx):
                e += 1
                c = [nid[i, j, k], nid[i + 1, j, k], nid[i + 1, j + 1, k], nid[i, j + 1, k],
                     nid[i, j, k + 1], nid[i + 1, j, k + 1], nid[i + 1, j + 1, k + 1], nid[i, j + 1, k + 1]]
                lines.append("%8d%8d" % (e, 1) + "".join("%8d" % x for x in c))
    # stiffness hourglass control (IHQ 4): the static state has no free hourglass modes
    lines += ["*PART", "bar", "1,1,1,0,1", "*SECTION_SOLID", "1,1", "*MAT_ELASTIC", "1,%g,%g,%g" % (RHO, E, NU),
              "*HOURGLASS", "1,4,0.1", "*BOUNDARY_SPC_NODE"]
    lines += ["%d,0,1,1,1,0,0,0" % nid[0, j, k] for j in range(ny + 1) for k in range(ny + 1)]
    # Section 14 by sets: the nodes of the layer x = a and the elements just before it.
    lines += ["*SET_NODE_LIST", "8", ",".join(str(nid[nx // 2, j, k]) for j in range(ny + 1) for k in range(ny + 1)),
              "*SET_SOLID", "9", "10,30,50,70", "*DATABASE_CROSS_SECTION_SET_ID", "14,by sets", "8,9"]
    lines += ["*SET_SOLID", "4", "31,51,71,11", "*DATABASE_HISTORY_SOLID_SET", "4",
              "*DATABASE_HISTORY_SOLID_ID", "11,first", "*DATABASE_ELOUT", "0.003"]
    omega1 = 1.875 ** 2 * math.sqrt(E * h * h / 12.0 / RHO) / L ** 2
    tip = [nid[nx, j, k] for j in range(ny + 1) for k in range(ny + 1)]
    text = lines + common_cards(tip, omega1, 0.06)
    with open(path, "w") as f:
        f.write("\n".join(text) + "\n")


def shell_deck(path):
    """20 x 4 Belytschko-Lin-Tsay shells, 1 m x 0.2 m, 0.05 m thick, in the plane z = 0."""
    nx, ny, b, t = 20, 4, 0.2, 0.05
    lines = ["*KEYWORD", "*TITLE", "shell cantilever", "*NODE"]
    nid = {}
    for j in range(ny + 1):
        for i in range(nx + 1):
            nid[i, j] = len(nid) + 1
            lines.append("%8d%16.8g%16.8g%16.8g" % (nid[i, j], i * L / nx, j * b / ny - b / 2, 0.0))
    lines.append("*ELEMENT_SHELL")
    e = 0
    for j in range(ny):
        for i in range(nx):
            e += 1
            lines.append("%8d%8d%8d%8d%8d%8d" % (e, 1, nid[i, j], nid[i + 1, j], nid[i + 1, j + 1], nid[i, j + 1]))
    lines += ["*PART", "plate", "1,1,1", "*SECTION_SHELL", "1,2,0.833,3", "%g,%g,%g,%g" % (t, t, t, t),
              "*MAT_ELASTIC", "1,%g,%g,%g" % (RHO, E, NU), "*BOUNDARY_SPC_NODE"]
    lines += ["%d,0,1,1,1,1,1,1" % nid[0, j] for j in range(ny + 1)]
    # The four shells of the column x in [0.5, 0.55] in elout_shell.csv, named three ways
    # (element 11 twice: it must appear once).
    lines += ["*DATABASE_HISTORY_SHELL", "11", "*DATABASE_HISTORY_SHELL_ID", "31,second row",
              "*SET_SHELL_LIST", "5", "11,51,71", "*DATABASE_HISTORY_SHELL_SET", "5",
              "*DATABASE_ELOUT", "0.003"]
    omega1 = 1.875 ** 2 * math.sqrt(E * t * t / 12.0 / RHO) / L ** 2
    text = lines + common_cards([nid[nx, j] for j in range(ny + 1)], omega1, 0.15)
    with open(path, "w") as f:
        f.write("\n".join(text) + "\n")


def beam_deck(path):
    """10 Belytschko-Schwer beams with a 0.1 m x 0.1 m section."""
    n, h = 10, 0.1
    lines = ["*KEYWORD", "*TITLE", "beam cantilever", "*NODE"]
    lines += ["%8d%16.8g%16.8g%16.8g" % (i + 1, i * L / n, 0.0, 0.0) for i in range(n + 1)]
    lines.append("*ELEMENT_BEAM_ORIENTATION")
    lines += ["%d,1,%d,%d\n0.0,1.0,0.0" % (i + 1, i + 1, i + 2) for i in range(n)]
    area, inertia = h * h, h ** 4 / 12.0
    lines += ["*PART", "beam", "1,1,1", "*SECTION_BEAM", "1,2,0.833", "%g,%g,%g,%g,%g" % (area, inertia, inertia,
              2 * inertia, 5.0 / 6.0 * area), "*MAT_ELASTIC", "1,%g,%g,%g" % (RHO, E, NU),
              "*BOUNDARY_SPC_NODE", "1,0,1,1,1,1,1,1"]
    omega1 = 1.875 ** 2 * math.sqrt(E * inertia / (RHO * area)) / L ** 2
    text = lines + common_cards([n + 1], omega1, 0.06)
    with open(path, "w") as f:
        f.write("\n".join(text) + "\n")


def run(rigidflex, deck, out):
    return subprocess.run([rigidflex, "run", deck, "-o", out, "--threads", "1", "--quiet"],
                          capture_output=True, text=True)


def main():
    rigidflex, work = sys.argv[1:3]
    os.makedirs(work, exist_ok=True)
    expected_moment = (0.0, -(L - A_CUT) * PZ, 0.0)
    for name, make in (("hex", hex_deck), ("shell", shell_deck), ("beam", beam_deck)):
        deck = os.path.join(work, name + ".k")
        make(deck)
        result = run(rigidflex, deck, os.path.join(work, name))
        if result.returncode != 0:
            failures.append("%s: run failed: %s" % (name, (result.stdout + result.stderr)[-600:]))
            continue
        rows = read_csv(os.path.join(work, name, "secforc.csv"))
        last_time = max(r["time"] for r in rows)
        last = {int(r["section"]): r for r in rows if r["time"] == last_time}
        sections = [11, 12, 13, 14] if name == "hex" else [11, 12, 13]
        check(sorted(last) == sections, "%s: sections %r, expected %r" % (name, sorted(last), sections))
        for sid, r in sorted(last.items()):
            where = "%s section %d at t = %g" % (name, sid, last_time)
            force = (r["force_x"], r["force_y"], r["force_z"])
            moment = (r["moment_x"], r["moment_y"], r["moment_z"])
            for k, want in enumerate((PX, 0.0, PZ)):
                check(abs(force[k] - want) <= 2e-3 * PZ, "%s: force %r, expected (%g, 0, %g)" % (where, force, PX, PZ))
            for k, want in enumerate(expected_moment):
                check(abs(moment[k] - want) <= 2e-3 * PZ * L,
                      "%s: moment %r, expected %r" % (where, moment, expected_moment))
            want_normal = 0.0 if sid == 14 else PX  # a section by sets has no normal
            check(abs(r["normal_force"] - want_normal) <= 2e-3 * PZ,
                  "%s: normal force %g, expected %g" % (where, r["normal_force"], want_normal))
            check(abs(r["centroid_x"] - A_CUT) < 1e-2, "%s: centroid x %g" % (where, r["centroid_x"]))
            check(abs(r["force_resultant"] - math.hypot(*force)) <= 1e-9 * PZ, "%s: resultant" % where)
        # Early rows differ from the static value (the loads ramp up): the check above would
        # fail if the column merely held the load.
        first_loaded = [r for r in rows if 0.0 < r["time"] < 0.1 * last_time and int(r["section"]) == 11]
        check(any(abs(r["force_z"] - PZ) > 0.05 * PZ for r in first_loaded), "%s: early rows already static" % name)
        print("%s: F = (%.6g, %.6g, %.6g) N, M = (%.6g, %.6g, %.6g) N m at t = %g s" % (
            name, last[11]["force_x"], last[11]["force_y"], last[11]["force_z"],
            last[11]["moment_x"], last[11]["moment_y"], last[11]["moment_z"], last_time))

    # elout.csv from *DATABASE_HISTORY_SOLID_ID + _SET: elements 11, 31, 51, 71, each once per
    # output time, IDs first then the set in its order.
    rows = read_csv(os.path.join(work, "hex", "elout.csv"))
    first_time = rows[0]["time"]
    order = [int(r["element"]) for r in rows if r["time"] == first_time]
    check(order == [11, 31, 51, 71], "hex: elout.csv elements %r, expected [11, 31, 51, 71]" % order)
    # elout_shell.csv: shells 11, 31, 51, 71, three points each (NIP 3). Beam theory for the
    # column at x = 0.525 (far from the clamped edge): sigma_xx(z) = Px/(b t) - M z / I with
    # M = Pz (L - 0.525), I = b t^3 / 12, z = zeta t / 2 (the tip load bends the plate up, so
    # its top is in compression); the other components are small.
    rows = read_csv(os.path.join(work, "shell", "elout_shell.csv"))
    last_time = max(r["time"] for r in rows)
    last = [r for r in rows if r["time"] == last_time]
    elements = []
    for r in last:
        if int(r["element"]) not in elements:
            elements.append(int(r["element"]))
    check(elements == [11, 31, 51, 71],
          "shell: elout_shell.csv elements %r" % elements)
    check(len(last) == 12 and all(int(r["point"]) in (1, 2, 3) for r in last),
          "shell: %d rows at the last time, expected 4 shells x 3 points" % len(last))
    b, t = 0.2, 0.05
    moment = PZ * (L - 0.525)
    inertia = b * t ** 3 / 12.0
    peak = moment * (t / 2) / inertia
    worst = 0.0
    for r in last:
        z = r["zeta"] * t / 2
        want = PX / (b * t) - moment * z / inertia
        worst = max(worst, abs(r["sxx"] - want) / peak)
        check(abs(r["sxx"] - want) <= 0.02 * peak,
              "shell %d point %d: sxx %g, beam theory %g" % (r["element"], r["point"], r["sxx"], want))
        sx, sy, sz = r["sxx"], r["syy"], r["szz"]
        mises = math.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2)
                          + 3 * (r["sxy"] ** 2 + r["syz"] ** 2 + r["szx"] ** 2))
        check(abs(r["effective_stress"] - mises) <= 1e-6 * peak,
              "shell %d: effective stress is not the von Mises value" % r["element"])
    print("shell elout: sxx within %.2f %% of beam theory (peak %.4g Pa)" % (100 * worst, peak))

    # Bad input: a part set without the structure, a plane beyond the part, a missing set.
    deck = open(os.path.join(work, "hex.k")).read()
    for what, replacement, message in (
            ("plane beyond the bar", "0,5.0,0.0,0.0,6.0,0.0,0.0", "cuts no deformable element"),
            ("undefined part set", "7,%g,0.0,0.0,%g,0.0,0.0" % (A_CUT, A_CUT + 1.0), "part set 7 is not defined"),
            ("normal of zero length", "0,%g,0.0,0.0,%g,0.0,0.0" % (A_CUT, A_CUT), "equals its tail")):
        bad = deck.replace("0,%g,0.0,0.0,%g,0.0,0.0\n" % (A_CUT, A_CUT + 1.0), replacement + "\n", 1)
        path = os.path.join(work, "bad.k")
        with open(path, "w") as f:
            f.write(bad)
        result = run(rigidflex, path, os.path.join(work, "bad"))
        text = result.stdout + result.stderr
        check(result.returncode != 0 and message in text and "CROSS_SECTION_PLANE" in text,
              "%s: exit %d, output %r" % (what, result.returncode, text[-400:]))
        # `check` refuses what `run` refuses.
        result = subprocess.run([rigidflex, "check", path], capture_output=True, text=True)
        text = result.stdout + result.stderr
        check(result.returncode != 0 and message in text,
              "check, %s: exit %d, output %r" % (what, result.returncode, text[-400:]))

    if failures:
        print("secforc differs from static equilibrium:")
        for f in failures[:30]:
            print("  " + f)
        return 1
    print("secforc matches static equilibrium")
    return 0


def print_deck(name):
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, name + ".k")
        {"hex": hex_deck, "shell": shell_deck, "beam": beam_deck}[name](path)
        sys.stdout.write(open(path).read())
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--print-deck":
        sys.exit(print_deck(sys.argv[2]))
    sys.exit(main())
