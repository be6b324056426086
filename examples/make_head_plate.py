#!/usr/bin/python3
"""Writes the deck family of the seed paper's first application (Bitzenbauer, Franz &
Schweizerhof, seed 003, "Head impact"; docs/seed_paper.md): a headform dropped at 6.7 m/s onto
a shell plate whose four corner elements carry the supports and stay deformable (the paper's
option (i)); the rest of the plate is deformable, rigid or a flexible body (*PART_MODES).

  head_plate_mesh.k        nodes and elements shared by every deck (*INCLUDE)
  head_plate_common.k      headform, corner elements, contact, supports, output (*INCLUDE)
  head_plate_eigen.k       the plate's flexible part alone, free-free (rigidflex eigen
                           head_plate_eigen.k --parts 1; the paper's two-step procedure is
                           scripted in examples/run_head_plate.py)
  head_plate_deformable.k  part 1 *MAT_ELASTIC
  head_plate_rigid.k       part 1 *MAT_RIGID
  head_plate_modes_N_formF.k  part 1 *MAT_RIGID + *PART_MODES, N modes, FORM F, reading
                           modes/modes.h5 next to the decks
  head_plate.json          the variants, the tracked node and the model data (for the scripts)

Model (units t, mm, s, N, MPa, mJ):
* plate: 24 x 20 Belytschko-Tsay shells (480), 480 x 400 x 10 mm, linear-elastic steel, in the
  plane z = 0, centred at the origin; the four corner elements are part 2 (always *MAT_ELASTIC)
  and their outer corner nodes are pinned (x, y, z); part 1 is the other 476 shells;
* headform: an ellipsoid of 200 x 156 x 190 mm (the size of the Hybrid III 50th head): a rigid
  skull (part 11, *MAT_RIGID shells on the inner surface of the skin, *PART_INERTIA with the
  headform's mass 4.54 kg and inertia) under a 12 mm skin of *MAT_OGDEN_RUBBER hexahedra (part
  12, one element through the thickness, 6 x 8 x 8 per layer); its lowest point 20.1 mm above the
  plate's contact surface, so that it touches at 3 ms as in the paper;
* contact: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE skin (part 12) against the plate (parts 1, 2);
* output: the resultant displacement of the plate's centre node (below the head's centre),
  nodout.csv; glstat.csv; spcforc.csv (support reactions); rcforc.csv.

--small writes the test's version (tests/python/head_plate_check.py): a 12 x 10 plate, a 4 x 4
per face headform, every-cycle output of glstat and spcforc, and --all-modes N adds a FORM 1
variant with N modes (all the eigen analysis can give).

Standard library only. Usage:
  make_head_plate.py [--out DIR] [--small] [--speed V_MM_PER_S] [--end T] [--modes 10,20,...]
                     [--forms 0,1] [--all-modes N]
"""
import argparse
import json
import math
import os

# Data of the model; the paper takes geometry and material from the LS-DYNA FMH manual, which
# is not available here: docs/seed_paper.md lists what was chosen and why.
STEEL_RHO, STEEL_E, STEEL_NU = 7.85e-9, 2.1e5, 0.3
SKIN_RHO, SKIN_PR = 1.2e-9, 0.495
SKIN_MU = (0.4, 0.2)  # Ogden MU1, MU2 (MPa): initial shear modulus 0.5 sum mu alpha = 1.0 MPa
SKIN_ALPHA = (3.0, -2.0)
HEAD_MASS = 4.54e-3  # t (4.54 kg)
HEAD_INERTIA = (16.0, 22.0, 18.0)  # t mm^2 about x (fore-aft), y (lateral), z (vertical)
HEAD_SEMI_AXES = (100.0, 78.0, 95.0)  # mm
SKIN_THICKNESS = 12.0
CONTACT_TIME = 3e-3  # s: the paper's "contact occurs after three milliseconds"


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                 "..", "build", "head_plate"))
    p.add_argument("--small", action="store_true", help="the test's small model")
    p.add_argument("--speed", type=float, default=6700.0, help="impact speed, mm/s")
    p.add_argument("--thickness", type=float, default=10.0, help="plate thickness, mm")
    p.add_argument("--end", type=float, default=None, help="end time, s")
    p.add_argument("--modes", default=None, help="mode counts, comma separated")
    p.add_argument("--forms", default="0,1", help="FORM values, comma separated")
    p.add_argument("--all-modes", type=int, default=0,
                   help="add a FORM 1 variant with this many modes")
    return p.parse_args()


class Mesh:
    def __init__(self):
        self.nodes = []  # (id, x, y, z)
        self.shells = []  # (id, part, n1..n4)
        self.solids = []  # (id, part, n1..n8)


def plate(mesh, nx, ny, lx, ly):
    """Shells of the plate; returns the node-ID function, the corner node IDs, the centre."""
    def node(i, j):
        return 1 + i + (nx + 1) * j
    for j in range(ny + 1):
        for i in range(nx + 1):
            mesh.nodes.append((node(i, j), -lx / 2 + lx * i / nx, -ly / 2 + ly * j / ny, 0.0))
    eid = 0
    for j in range(ny):
        for i in range(nx):
            eid += 1
            corner = i in (0, nx - 1) and j in (0, ny - 1)
            mesh.shells.append((eid, 2 if corner else 1, node(i, j), node(i + 1, j),
                                node(i + 1, j + 1), node(i, j + 1)))
    corners = [node(0, 0), node(nx, 0), node(0, ny), node(nx, ny)]
    return corners, node(nx // 2, ny // 2)


def headform(mesh, n, centre, first_node, first_element):
    """Ellipsoidal skin of one layer of hexahedra (part 12) on a cube-sphere grid of n x n per
    face (equiangular), rigid skull shells (part 11) on its inner surface. Returns the skin's
    outer node IDs and the lumped mass of the skin at them (rho V / 8 per corner)."""
    a, b, c = HEAD_SEMI_AXES

    def point(key, shrink):
        d = [math.tan(math.pi / 4 * (2.0 * k / n - 1.0)) for k in key]
        r = math.sqrt(sum(v * v for v in d))
        d = [v / r for v in d]
        s = 1.0 / math.sqrt((d[0] / (a - shrink)) ** 2 + (d[1] / (b - shrink)) ** 2 +
                            (d[2] / (c - shrink)) ** 2)
        return [centre[k] + s * d[k] for k in range(3)]

    keys = [(i, j, k) for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)
            if 0 in (i, j, k) or n in (i, j, k)]
    outer, inner = {}, {}
    nid = first_node
    for key in keys:
        outer[key] = nid
        mesh.nodes.append((nid, *point(key, 0.0)))
        nid += 1
    for key in keys:
        inner[key] = nid
        mesh.nodes.append((nid, *point(key, SKIN_THICKNESS)))
        nid += 1
    coords = {node[0]: node[1:] for node in mesh.nodes}
    # Faces of the cube: the fixed axis and its value; quads in the other two axes.
    eid = first_element
    skin_mass = {}
    for axis in range(3):
        for value in (0, n):
            u_axis, v_axis = [x for x in range(3) if x != axis]
            for u in range(n):
                for v in range(n):
                    quad = []
                    for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        key = [0, 0, 0]
                        key[axis], key[u_axis], key[v_axis] = value, u + du, v + dv
                        quad.append(tuple(key))
                    lower = [inner[k] for k in quad]
                    upper = [outer[k] for k in quad]
                    # Order so that the inner quad's normal points outwards (to nodes 5-8).
                    p = [coords[i] for i in lower]
                    e1 = [p[2][k] - p[0][k] for k in range(3)]
                    e2 = [p[3][k] - p[1][k] for k in range(3)]
                    normal = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                              e1[0] * e2[1] - e1[1] * e2[0]]
                    out = [coords[upper[0]][k] - coords[lower[0]][k] for k in range(3)]
                    if sum(normal[k] * out[k] for k in range(3)) < 0:
                        lower = lower[::-1]
                        upper = upper[::-1]
                    mesh.solids.append((eid, 12, *lower, *upper))
                    mesh.shells.append((eid + 100000, 11, *lower))
                    volume = hexahedron_volume([coords[i] for i in lower + upper])
                    for i in upper:
                        skin_mass[i] = skin_mass.get(i, 0.0) + SKIN_RHO * volume / 8.0
                    eid += 1
    return sorted(outer.values()), sum(skin_mass.values()), [inner[k] for k in keys]


def hexahedron_volume(p):
    """Volume of a hexahedron (8 points, LS-DYNA order) from 6 tetrahedra per face pair."""
    def tet(a, b, c, d):
        u = [b[k] - a[k] for k in range(3)]
        v = [c[k] - a[k] for k in range(3)]
        w = [d[k] - a[k] for k in range(3)]
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0
    t = ((0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6))
    return abs(sum(tet(*(p[i] for i in q)) for q in t))


def card(*values):
    out = []
    for v in values:
        if isinstance(v, float):
            # The most digits that fit the 10-character field with a blank before them.
            for digits in range(8, 1, -1):
                text = f"{v:.{digits}g}"
                if len(text) <= 9:
                    break
            out.append(f"{text:>10}")
        else:
            out.append(f"{v:>10}")
    return "".join(out) + "\n"


def node_list(set_id, ids):
    text = f"*SET_NODE_LIST\n{set_id:10d}\n"
    for k in range(0, len(ids), 8):
        text += "".join(f"{i:10d}" for i in ids[k:k + 8]) + "\n"
    return text


def headform_parts(centre, skull_mass, speed, skin_mu=SKIN_MU):
    """The headform's parts (skull 11, skin 12) with sections, materials and the skull's
    *PART_INERTIA (moving at -speed in z), for a run deck; section 2, hourglass 3, materials 11,
    12; skin_mu the Ogden MU1, MU2. Shared with examples/make_side_panel.py."""
    return f"""*PART_INERTIA
headform skull (rigid, the headform's mass and inertia)
{card(11, 2, 11)}{card(*centre, skull_mass, 0, 0)}{card(HEAD_INERTIA[0], 0.0, 0.0, HEAD_INERTIA[1], 0.0, HEAD_INERTIA[2])}{card(0.0, 0.0, -speed, 0.0, 0.0, 0.0)}*SECTION_SHELL
{card(2, 2, 0.8333333, 2)}{card(1.0, 1.0, 1.0, 1.0)}*MAT_RIGID
{card(11, 7.85e-9, 2.1e5, 0.3)}{card(0.0, 0.0, 0.0)}*PART
headform skin (Ogden rubber)
{card(12, 3, 12, 0, 3)}*SECTION_SOLID
{card(3, 2)}*HOURGLASS
{card(3, 6, 0.1)}*MAT_OGDEN_RUBBER
{card(12, SKIN_RHO, SKIN_PR, 0, 0, 0.0, 0.0, 0.0)}{card(*skin_mu)}{card(*SKIN_ALPHA)}"""


def headform_eigen_parts(skin_mu=SKIN_MU):
    """The headform's parts for an eigen deck that includes its mesh (not part of the analysis:
    rigidflex eigen --parts names the flexible part only)."""
    return ("*PART\nskull\n" + card(11, 2, 1, 0, 1) + "*SECTION_SHELL\n" +
            card(2, 2, 0.8333333, 2) + card(1.0, 1.0, 1.0, 1.0) + "*PART\nskin\n" +
            card(12, 3, 12) + "*SECTION_SOLID\n" + card(3, 2) + "*MAT_OGDEN_RUBBER\n" +
            card(12, SKIN_RHO, SKIN_PR, 0, 0, 0.0, 0.0, 0.0) + card(*skin_mu) +
            card(*SKIN_ALPHA))


def main():
    args = parse_args()
    small = args.small
    nx, ny = (12, 10) if small else (24, 20)
    lx, ly, t = 480.0, 400.0, args.thickness
    head_n = 4 if small else 8
    end = args.end if args.end is not None else (12e-3 if small else 15e-3)
    modes = [int(m) for m in (args.modes or ("5,10,20,40" if small else "10,20,40,70,100"))
             .split(",")]
    forms = [int(f) for f in args.forms.split(",")]
    os.makedirs(args.out, exist_ok=True)

    mesh = Mesh()
    corners, centre_node = plate(mesh, nx, ny, lx, ly)
    gap = args.speed * CONTACT_TIME
    head_centre = (0.0, 0.0, t / 2 + gap + HEAD_SEMI_AXES[2])
    skin_outer, skin_mass, head_inner = headform(mesh, head_n, head_centre, 10001, 10001)
    head_nodes = sorted(skin_outer + head_inner)
    # The skull body's card mass: the headform's total minus the skin's mass lumped to the
    # outer skin nodes (the inner ones move with the skull, whose card replaces their mass).
    skull_mass = HEAD_MASS - skin_mass

    with open(os.path.join(args.out, "head_plate_mesh.k"), "w") as f:
        f.write("*KEYWORD\n$ Generated by examples/make_head_plate.py\n*NODE\n")
        for nid, x, y, z in mesh.nodes:
            f.write(f"{nid:8d}{x:16.8f}{y:16.8f}{z:16.8f}\n")
        f.write("*ELEMENT_SHELL\n")
        for e in mesh.shells:
            f.write("".join(f"{v:8d}" for v in e) + "\n")
        f.write("*ELEMENT_SOLID\n")
        for e in mesh.solids:
            f.write("".join(f"{v:8d}" for v in e) + "\n")
        f.write("*END\n")

    plate_section = (f"*SECTION_SHELL\n{card(1, 2, 0.8333333, 2)}{card(t, t, t, t)}"
                     "*HOURGLASS\n" + card(1, 4, 0.05))
    output_dt = 1e-9 if small else 1e-5  # small: every cycle (the test's impulse sums)
    common = f"""*KEYWORD
$ Generated by examples/make_head_plate.py: what every variant shares
*PART
plate corners (deformable, carry the supports: the paper's option (i))
{card(2, 1, 2, 0, 1)}*MAT_ELASTIC
{card(2, STEEL_RHO, STEEL_E, STEEL_NU)}""" + headform_parts(head_centre, skull_mass, args.speed)
    common += node_list(1, corners) + "*BOUNDARY_SPC_SET\n" + card(1, 0, 1, 1, 1, 0, 0, 0)
    common += node_list(2, head_nodes)
    common += ("*INITIAL_VELOCITY\n" + card(2, 0, 0, 1) + card(0.0, 0.0, -args.speed) +
               "*SET_PART_LIST\n" + card(1) + card(1, 2))
    common += ("*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n" + card(12, 1, 3, 2) + card(0.0) +
               card(1.0, 1.0))
    common += f"""*DATABASE_HISTORY_NODE
{centre_node:10d}
*DATABASE_NODOUT
{card(output_dt)}*DATABASE_GLSTAT
{card(output_dt)}*DATABASE_SPCFORC
{card(output_dt)}*DATABASE_RCFORC
{card(1e-5)}*DATABASE_RBDOUT
{card(1e-5)}*DATABASE_BINARY_D3PLOT
{card(end / 10)}*CONTROL_TERMINATION
{card(end)}*END
"""
    with open(os.path.join(args.out, "head_plate_common.k"), "w") as f:
        f.write(common)

    def deck(name, title, part1):
        with open(os.path.join(args.out, name), "w") as f:
            f.write(f"*KEYWORD\n*TITLE\nhead impact on a plate: {title}\n"
                    "$ Generated by examples/make_head_plate.py\n*INCLUDE\nhead_plate_mesh.k\n"
                    "*INCLUDE\nhead_plate_common.k\n*PART\nplate (flexible part)\n" +
                    card(1, 1, 1, 0, 1) + plate_section + part1 + "*END\n")

    variants = [{"name": "deformable", "deck": "head_plate_deformable.k", "kind": "deformable"},
                {"name": "rigid", "deck": "head_plate_rigid.k", "kind": "rigid"}]
    deck("head_plate_deformable.k", "fully deformable plate",
         "*MAT_ELASTIC\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU))
    deck("head_plate_rigid.k", "rigid plate body (deformable corners)",
         "*MAT_RIGID\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU) + card(0.0, 0.0, 0.0))
    for form in forms:
        for count in modes:
            name = f"head_plate_modes_{count}_form{form}.k"
            deck(name, f"flexible plate, {count} modes, FORM {form}",
                 "*MAT_RIGID\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU) + card(0.0, 0.0, 0.0) +
                 "*PART_MODES\n" + card(1, count, form, 0, 3, 0, 0, 0) + "modes/modes.h5\n")
            variants.append({"name": f"{count} modes FORM {form}", "deck": name,
                             "kind": "flexible", "modes": count, "form": form})
    if args.all_modes:
        # FORM 1 only: FORM 0's inertia terms cost O(n^2) per step (110 s against 6.5 s for the
        # small model's 827 modes), and the plate hardly turns, so the two forms agree.
        count = args.all_modes
        name = f"head_plate_modes_{count}_form1.k"
        deck(name, f"flexible plate, all {count} modes, FORM 1",
             "*MAT_RIGID\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU) + card(0.0, 0.0, 0.0) +
             "*PART_MODES\n" + card(1, count, 1, 0, 3, 0, 0, 0) + "modes/modes.h5\n")
        variants.append({"name": f"{count} modes FORM 1", "deck": name, "kind": "flexible",
                         "modes": count, "form": 1, "all": True})

    with open(os.path.join(args.out, "head_plate_eigen.k"), "w") as f:
        f.write("*KEYWORD\n*TITLE\nhead impact on a plate: free-free modes of the flexible part "
                "(rigidflex eigen --parts 1)\n$ Generated by examples/make_head_plate.py\n"
                "*INCLUDE\nhead_plate_mesh.k\n*CONTROL_IMPLICIT_GENERAL\n" + card(1, 1e-3) +
                "*CONTROL_IMPLICIT_EIGENVALUE\n" + card(max(modes), 0.0, 0, 0.0) +
                "*PART\nplate (flexible part)\n" + card(1, 1, 1, 0, 1) + plate_section +
                "*MAT_ELASTIC\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU) +
                "*PART\ncorners\n" + card(2, 1, 1, 0, 1) + headform_eigen_parts() +
                "*END\n")

    total_mass = skull_mass + skin_mass
    with open(os.path.join(args.out, "head_plate.json"), "w") as f:
        json.dump({"small": small, "tracked_node": centre_node, "corner_nodes": corners,
                   "plate": {"nx": nx, "ny": ny, "lx": lx, "ly": ly, "thickness": t,
                             "shells": nx * ny},
                   "head": {"mass": total_mass, "skull_card_mass": skull_mass,
                            "skin_outer_mass": skin_mass, "speed": args.speed,
                            "skin_elements": len(mesh.solids), "nodes": len(head_nodes)},
                   "end_time": end, "modes": modes, "forms": forms, "variants": variants},
                  f, indent=1)
    print(f"wrote {len(variants)} variants and the eigen deck to {os.path.abspath(args.out)}")


if __name__ == "__main__":
    main()
