#!/usr/bin/python3
"""Writes the deck family of the seed paper's forming application (Bitzenbauer, Franz &
Schweizerhof, seed 003, "Sheet metal forming"; docs/seed_paper.md, model 3): a blank of
Barlat shells pushed by an elastic die into a rigid matrix with a counter form. The die's top
is driven through a layer of extra deformable solids whose top nodes carry the prescribed
motion (the paper's option (ii)); the die proper is deformable, rigid or a flexible body
(*PART_MODES).

  die_blank_mesh.k        nodes and elements shared by every deck (*INCLUDE)
  die_blank_common.k      blank, matrix, driver layer, contacts, motion, output (*INCLUDE)
  die_blank_eigen.k       the die alone, free-free (rigidflex eigen die_blank_eigen.k
                          --parts 1; the paper's two-step procedure is scripted in
                          examples/run_die_blank.py)
  die_blank_deformable.k  die *MAT_ELASTIC
  die_blank_rigid.k       die *MAT_RIGID
  die_blank_modes_N_formF.k  die *MAT_RIGID + *PART_MODES, N modes, FORM F, reading
                          modes/modes.h5 next to the decks
  die_blank.json          the variants, the tracked nodes and the model data (for the scripts)

Model (units t, mm, s, N, MPa, mJ); a U-channel die, i.e. the section in x-z is the same at
every y (the paper's Fig. 6 is not in the text; docs/seed_paper.md lists the choices):
* blank (part 3): 198 x 96 mm, 1 mm thick, 99 x 48 Belytschko-Tsay shells (4752; NIP 5),
  *MAT_3-PARAMETER_BARLAT (a DC04-like mild steel: M 6, R00/R45/R90 1.9/1.5/2.3, HR 2
  sigma = 530 (0.005 + eps_p)^0.22 MPa, yield 165 MPa), rolling direction along x, free
  (held by the contacts only), lying on the matrix;
* die (part 1): a block 80 (x) x 100 (y) x 45 (z) mm with 8 mm radii on its two bottom edges
  (the stamp face), 28 x 21 x 9 = 5292 ELFORM 2 hexahedra, elastic steel (E 210 GPa, nu 0.3,
  rho 7850 kg/m^3);
* driver layer (part 2): one layer of 28 x 21 ELFORM 2 elastic steel hexahedra, 5 mm, on top of
  the die (shared nodes); its top nodes are held in x and y and move in z by
  *BOUNDARY_PRESCRIBED_MOTION_SET (a velocity curve); everything starts at rest;
* matrix (part 4): rigid shells (*MAT_RIGID, fixed) of the profile flange - 8 mm shoulder
  radius - wall - 4 mm fillet - floor 12 mm below the flange, 1.1 mm clearance to the die
  per side, with a counter form in the middle of the floor: a rib 3 mm high and 32 mm wide
  (cos^2 profile) that the die presses the blank onto at the end of the stroke;
* motion: a cycloidal stroke of 9.15 mm, d(t) = S (t/T - sin(2 pi t/T) / 2 pi), from rest to
  the bottom dead centre at T = 1.5 ms (--time; mean speed 6.1 m/s, largest 12.2 m/s, a
  drop-hammer stroke), where the blank is squeezed to 0.9 t between the die and the rib (10 %
  overclosure, --squeeze), then the same motion back up for 0.25 T (end time 1.25 T); the
  cycloid has no jump in velocity or acceleration, so the die is not set ringing by the drive;
* contacts: *CONTACT_AUTOMATIC_ONE_WAY_SURFACE_TO_SURFACE, the blank's nodes (slave) against
  the die and against the matrix (the forming contacts' usual choice), SOFT 0, Coulomb friction
  0.1;
* output (nodout.csv): the die's bottom node at x = 0 nearest y = 0 (the paper's Fig. 7) and the
  node above it on the die's top face (so that the die's compression is their difference);
  glstat.csv, rcforc.csv.

Variants: deformable, rigid, flexible FORM 1 (the paper's first-order update) with --modes
(default 10,20,40,70,100) and FORM 0 with --form0-modes (default 10,40).

--small writes the test's version (tests/python/die_blank_check.py): a 33 x 8 blank, a die of
12 x 3 x 3 hexahedra, T = 0.75 ms, and --all-modes N adds a FORM 1 variant with N modes.

Standard library only. Usage:
  make_die_blank.py [--out DIR] [--small] [--time T] [--squeeze S] [--modes 10,...]
                    [--form0-modes 10,...] [--all-modes N]
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_head_plate import card, node_list  # noqa: E402  (the card writers of model 1)

STEEL_RHO, STEEL_E, STEEL_NU = 7.85e-9, 2.1e5, 0.3
# Barlat 1989 (*MAT_036): a DC04-like deep-drawing steel; HR 2 (Swift) sigma = K (E0 + eps)^N.
BARLAT_M, BARLAT_R = 6.0, (1.9, 1.5, 2.3)
SWIFT_K, SWIFT_N, SWIFT_E0 = 530.0, 0.22, 0.005
FRICTION = 0.1
T_BLANK = 1.0  # blank thickness
T_MATRIX = 0.1  # rigid matrix shells: contact surface at T_MATRIX / 2 from the mid-surface
DIE_A, DIE_LY, DIE_H, DIE_R = 40.0, 100.0, 45.0, 8.0  # half width, length in y, height, radius
DRIVER_H = 5.0
CLEARANCE = 1.1 * T_BLANK  # die side to matrix wall (contact surfaces)
SHOULDER_R, FILLET_R, DEPTH = 8.0, 4.0, 12.0
RIB_H, RIB_W = 3.0, 16.0  # counter form: height, half width
BLANK_LX, BLANK_LY = 198.0, 96.0
MATRIX_X, MATRIX_LY = 110.0, 120.0
GAP = 0.05  # die face above the blank at the start


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                 "..", "build", "die_blank"))
    p.add_argument("--small", action="store_true", help="the test's small model")
    p.add_argument("--time", type=float, default=None,
                   help="time of the stroke to the bottom dead centre, s (default 1.5e-3; "
                   "--small 0.75e-3)")
    p.add_argument("--squeeze", type=float, default=0.1,
                   help="overclosure at the bottom dead centre, fraction of the thickness")
    p.add_argument("--end-factor", type=float, default=1.25,
                   help="end time / time of the bottom dead centre")
    p.add_argument("--modes", default=None, help="mode counts of FORM 1, comma separated")
    p.add_argument("--form0-modes", default=None,
                   help="mode counts of FORM 0, comma separated ('' for none)")
    p.add_argument("--all-modes", type=int, default=0,
                   help="add a FORM 1 variant with this many modes")
    return p.parse_args()


def matrix_profile(step):
    """Points (x, z) of the matrix's contact surface for x >= 0 (z = 0 is the flange), at
    about `step` spacing along the arc, from the middle of the rib to the flange's end."""
    c = DIE_A + CLEARANCE  # wall
    pieces = []  # dense polyline, then resampled by arc length

    def add(points):
        for p in points:
            if not pieces or math.dist(p, pieces[-1]) > 1e-9:
                pieces.append(p)
    n = 400
    add([(RIB_W * i / n, -DEPTH + RIB_H * math.cos(0.5 * math.pi * i / n) ** 2)
         for i in range(n + 1)])
    add([(RIB_W + (c - FILLET_R - RIB_W) * i / n, -DEPTH) for i in range(n + 1)])
    add([(c - FILLET_R + FILLET_R * math.sin(0.5 * math.pi * i / n),
          -DEPTH + FILLET_R - FILLET_R * math.cos(0.5 * math.pi * i / n)) for i in range(n + 1)])
    add([(c, -DEPTH + FILLET_R + (DEPTH - FILLET_R - SHOULDER_R) * i / n) for i in range(n + 1)])
    add([(c + SHOULDER_R - SHOULDER_R * math.cos(0.5 * math.pi * i / n),
          -SHOULDER_R + SHOULDER_R * math.sin(0.5 * math.pi * i / n)) for i in range(n + 1)])
    add([(c + SHOULDER_R + (MATRIX_X - c - SHOULDER_R) * i / n, 0.0) for i in range(n + 1)])
    s = [0.0]
    for a, b in zip(pieces, pieces[1:]):
        s.append(s[-1] + math.dist(a, b))
    count = max(1, round(s[-1] / step))
    out, k = [], 0
    for i in range(count + 1):
        target = s[-1] * i / count
        while k < len(s) - 2 and s[k + 1] < target:
            k += 1
        f = (target - s[k]) / (s[k + 1] - s[k])
        out.append(tuple(pieces[k][d] + f * (pieces[k + 1][d] - pieces[k][d]) for d in range(2)))
    return out


def die_bottom(x):
    """Height of the die's stamp face above its flat part at x (8 mm radii at the edges)."""
    s = abs(x) - (DIE_A - DIE_R)
    return 0.0 if s <= 0 else DIE_R - math.sqrt(max(0.0, DIE_R ** 2 - s * s))


def main():
    args = parse_args()
    small = args.small
    bnx, bny = (33, 8) if small else (99, 48)
    dnx, dny, dnz = (12, 3, 3) if small else (28, 21, 9)
    mstep, mny = (6.0, 4) if small else (2.5, 24)
    modes = [int(m) for m in (args.modes or ("5,10,20,40" if small else "10,20,40,70,100"))
             .split(",")]
    form0 = args.form0_modes if args.form0_modes is not None else ("10" if small else "10,40")
    modes0 = [int(m) for m in form0.split(",") if m]
    os.makedirs(args.out, exist_ok=True)

    nodes, shells, solids = [], [], []
    # Blank: mid-surface T_MATRIX/2 + T_BLANK/2 above the flange (resting on it).
    z_blank = 0.5 * T_MATRIX + 0.5 * T_BLANK

    def bnode(i, j):
        return 1 + i + (bnx + 1) * j
    for j in range(bny + 1):
        for i in range(bnx + 1):
            nodes.append((bnode(i, j), -BLANK_LX / 2 + BLANK_LX * i / bnx,
                          -BLANK_LY / 2 + BLANK_LY * j / bny, z_blank))
    eid = 0
    for j in range(bny):
        for i in range(bnx):
            eid += 1
            shells.append((eid, 3, bnode(i, j), bnode(i + 1, j), bnode(i + 1, j + 1),
                           bnode(i, j + 1)))

    # Matrix: the profile mirrored about x = 0, mid-surface T_MATRIX/2 below the contact surface
    # (offset along z: the walls' offset is then along the wall, which is what matters less).
    half = matrix_profile(mstep)
    profile = [(-x, z) for x, z in reversed(half[1:])] + half
    # Shift the mid-surface by T_MATRIX/2 along the profile's normal (pointing up/inwards).
    mid = []
    for k, (x, z) in enumerate(profile):
        a = profile[max(0, k - 1)]
        b = profile[min(len(profile) - 1, k + 1)]
        tx, tz = b[0] - a[0], b[1] - a[1]
        norm = math.hypot(tx, tz)
        nx_, nz_ = -tz / norm, tx / norm  # left normal of the direction of increasing x: up
        mid.append((x - 0.5 * T_MATRIX * nx_, z - 0.5 * T_MATRIX * nz_))

    def mnode(i, j):
        return 100001 + i + len(mid) * j
    for j in range(mny + 1):
        for i, (x, z) in enumerate(mid):
            nodes.append((mnode(i, j), x, -MATRIX_LY / 2 + MATRIX_LY * j / mny, z))
    eid = 100000
    for j in range(mny):
        for i in range(len(mid) - 1):
            eid += 1
            shells.append((eid, 4, mnode(i, j), mnode(i + 1, j), mnode(i + 1, j + 1),
                           mnode(i, j + 1)))

    # Die and driver layer: columns from the stamp face up to the top, z = 0 at the flat face.
    z_die = z_blank + 0.5 * T_BLANK + GAP  # the flat face's height at the start

    def dnode(i, j, k):
        return 200001 + i + (dnx + 1) * (j + (dny + 1) * k)
    for k in range(dnz + 2):
        for j in range(dny + 1):
            for i in range(dnx + 1):
                x = -DIE_A + 2 * DIE_A * i / dnx
                zb = die_bottom(x)
                z = zb + (DIE_H - zb) * k / dnz if k <= dnz else DIE_H + DRIVER_H
                nodes.append((dnode(i, j, k), x, -DIE_LY / 2 + DIE_LY * j / dny, z_die + z))
    eid = 200000
    for k in range(dnz + 1):
        for j in range(dny):
            for i in range(dnx):
                eid += 1
                part = 1 if k < dnz else 2
                if k == dnz and eid < 300001:
                    eid = 300001
                solids.append((eid, part, dnode(i, j, k), dnode(i + 1, j, k),
                               dnode(i + 1, j + 1, k), dnode(i, j + 1, k), dnode(i, j, k + 1),
                               dnode(i + 1, j, k + 1), dnode(i + 1, j + 1, k + 1),
                               dnode(i, j + 1, k + 1)))
    jc = dny // 2  # the node row nearest y = 0 (y = 0 itself when dny is even)
    bottom_node, top_node = dnode(dnx // 2, jc, 0), dnode(dnx // 2, jc, dnz)
    driven = [dnode(i, j, dnz + 1) for j in range(dny + 1) for i in range(dnx + 1)]

    # Stroke: the flat face goes down to the rib's top + T_MATRIX/2 + (1 - squeeze) t.
    z_bdc = -DEPTH + RIB_H + 0.5 * T_MATRIX + (1.0 - args.squeeze) * T_BLANK
    stroke = z_die - z_bdc
    t_bdc = args.time if args.time else (0.75e-3 if small else 1.5e-3)
    end = args.end_factor * t_bdc

    def velocity(t):
        """Cycloidal stroke down to the bottom dead centre at t_bdc, then the same back up:
        zero velocity and acceleration at the start and at the bottom dead centre."""
        sign = -1.0 if t <= t_bdc else 1.0
        return sign * stroke / t_bdc * (1.0 - math.cos(2.0 * math.pi * t / t_bdc))
    v0 = 2.0 * stroke / t_bdc  # the largest speed
    curve = "".join(f"{end * 1.02 * i / 400:20.12g}{velocity(end * 1.02 * i / 400):20.12g}\n"
                    for i in range(401))

    with open(os.path.join(args.out, "die_blank_mesh.k"), "w") as f:
        f.write("*KEYWORD\n$ Generated by examples/make_die_blank.py\n*NODE\n")
        for nid, x, y, z in nodes:
            f.write(f"{nid:8d}{x:16.8f}{y:16.8f}{z:16.8f}\n")
        f.write("*ELEMENT_SHELL\n")
        for e in shells:
            f.write("".join(f"{v:8d}" for v in e) + "\n")
        f.write("*ELEMENT_SOLID\n")
        for e in solids:
            f.write("".join(f"{v:8d}" for v in e) + "\n")
        f.write("*END\n")

    out_dt = end / 400
    blank_part = ("*PART\nblank\n" + card(3, 3, 3, 0, 3) + "*SECTION_SHELL\n" +
                  card(3, 2, 0.8333333, 5) + card(T_BLANK, T_BLANK, T_BLANK, T_BLANK) +
                  "*HOURGLASS\n" + card(3, 4, 0.05))
    barlat = ("*MAT_3-PARAMETER_BARLAT\n" +
              card(3, STEEL_RHO, STEEL_E, STEEL_NU, 2, SWIFT_K, SWIFT_N, 0) +
              card(BARLAT_M, *BARLAT_R, 0, SWIFT_E0, 0.0, 0.0) + card(0))
    common = ("*KEYWORD\n$ Generated by examples/make_die_blank.py: what every variant shares\n"
              + blank_part + barlat +
              "*PART\ndriver layer (deformable, carries the prescribed motion: option (ii))\n" +
              card(2, 1, 2) + "*MAT_ELASTIC\n" + card(2, STEEL_RHO, STEEL_E, STEEL_NU) +
              "*PART\nmatrix with counter form (rigid, fixed)\n" + card(4, 4, 4) +
              "*SECTION_SHELL\n" + card(4, 2, 0.8333333, 2) +
              card(T_MATRIX, T_MATRIX, T_MATRIX, T_MATRIX) + "*MAT_RIGID\n" +
              card(4, STEEL_RHO, STEEL_E, STEEL_NU) + card(1, 7, 7))
    common += node_list(1, driven) + "*BOUNDARY_SPC_SET\n" + card(1, 0, 1, 1, 0, 0, 0, 0)
    common += ("*BOUNDARY_PRESCRIBED_MOTION_SET\n" + card(1, 3, 0, 1, 1.0) +
               "*DEFINE_CURVE\n" + card(1) + curve)
    for cid, (slave, master) in enumerate(((3, 1), (3, 4)), start=1):
        common += ("*CONTACT_AUTOMATIC_ONE_WAY_SURFACE_TO_SURFACE_ID\n" +
                   card(cid) + card(slave, master, 3, 3) + card(FRICTION, FRICTION) +
                   card(1.0, 1.0))
    common += ("*DATABASE_HISTORY_NODE\n" + card(bottom_node, top_node) + "*DATABASE_NODOUT\n"
               + card(out_dt) + "*DATABASE_GLSTAT\n" + card(out_dt) + "*DATABASE_RCFORC\n" +
               card(out_dt) + "*DATABASE_BINARY_D3PLOT\n" + card(end / 5) +
               "*CONTROL_TERMINATION\n" + card(end) + "*END\n")
    with open(os.path.join(args.out, "die_blank_common.k"), "w") as f:
        f.write(common)

    die_section = "*SECTION_SOLID\n" + card(1, 2)
    elastic = "*MAT_ELASTIC\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU)
    rigid = "*MAT_RIGID\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU) + card(0.0, 0.0, 0.0)

    def deck(name, title, material):
        with open(os.path.join(args.out, name), "w") as f:
            f.write(f"*KEYWORD\n*TITLE\ndie on a blank: {title}\n"
                    "$ Generated by examples/make_die_blank.py\n*INCLUDE\ndie_blank_mesh.k\n"
                    "*INCLUDE\ndie_blank_common.k\n*PART\ndie (flexible part)\n" +
                    card(1, 1, 1) + die_section + material + "*END\n")

    variants = [{"name": "deformable", "deck": "die_blank_deformable.k", "kind": "deformable"},
                {"name": "rigid", "deck": "die_blank_rigid.k", "kind": "rigid"}]
    deck("die_blank_deformable.k", "fully deformable die", elastic)
    deck("die_blank_rigid.k", "rigid die (deformable driver layer)", rigid)
    counts = [(c, 1, False) for c in modes] + [(c, 0, False) for c in modes0]
    if args.all_modes:
        # FORM 1 only: FORM 0's inertia terms cost O(n^2) per step; the die hardly turns.
        counts.append((args.all_modes, 1, True))
    for count, form, everything in counts:
        name = f"die_blank_modes_{count}_form{form}.k"
        deck(name, f"flexible die, {count} modes, FORM {form}",
             rigid + "*PART_MODES\n" + card(1, count, form, 0, 3, 0, 0, 0) + "modes/modes.h5\n")
        v = {"name": f"{count} modes FORM {form}", "deck": name, "kind": "flexible",
             "modes": count, "form": form}
        if everything:
            v["all"] = True
        variants.append(v)

    with open(os.path.join(args.out, "die_blank_eigen.k"), "w") as f:
        f.write("*KEYWORD\n*TITLE\ndie on a blank: free-free modes of the die (rigidflex eigen "
                "--parts 1)\n$ Generated by examples/make_die_blank.py\n*INCLUDE\n"
                "die_blank_mesh.k\n*CONTROL_IMPLICIT_GENERAL\n" + card(1, 1e-3) +
                "*CONTROL_IMPLICIT_EIGENVALUE\n" + card(max(modes + modes0), 0.0, 0, 0.0) +
                "*PART\ndie (flexible part)\n" + card(1, 1, 1) + die_section + elastic +
                "*PART\ndriver layer\n" + card(2, 1, 1) + blank_part + barlat +
                "*PART\nmatrix\n" + card(4, 4, 1) + "*SECTION_SHELL\n" +
                card(4, 2, 0.8333333, 2) + card(T_MATRIX, T_MATRIX, T_MATRIX, T_MATRIX) +
                "*END\n")

    die_mass = STEEL_RHO * DIE_LY * (2 * DIE_A * DIE_H - 0.5 * (4 - math.pi) * DIE_R ** 2)
    with open(os.path.join(args.out, "die_blank.json"), "w") as f:
        json.dump({"small": small, "bottom_node": bottom_node, "top_node": top_node,
                   "blank": {"nx": bnx, "ny": bny, "shells": bnx * bny, "thickness": T_BLANK},
                   "die": {"nx": dnx, "ny": dny, "nz": dnz, "solids": dnx * dny * dnz,
                           "driver_solids": dnx * dny, "nodes": (dnx + 1) * (dny + 1) *
                           (dnz + 1), "mass": die_mass},
                   "matrix_shells": mny * (len(mid) - 1),
                   "speed": v0, "stroke": stroke, "t_bdc": t_bdc, "end_time": end,
                   "modes": modes, "form0_modes": modes0, "variants": variants}, f, indent=1)
    print(f"wrote {len(variants)} variants and the eigen deck to {os.path.abspath(args.out)}: "
          f"stroke {stroke:.3f} mm, bottom dead centre at {1e3 * t_bdc:.4f} ms, end "
          f"{1e3 * end:.4f} ms")


if __name__ == "__main__":
    main()
