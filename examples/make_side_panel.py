#!/usr/bin/python3
"""Writes the deck family of the seed paper's second application (Bitzenbauer, Franz &
Schweizerhof, seed 003, "Head impact against a side part"; docs/seed_paper.md, model 2): the
headform of examples/make_head_plate.py at 6.7 m/s against a stamped, curved car side panel of
shells, held at points along its edges by small deformable support parts (the paper's option
(i): the elements that carry the constraints stay out of the flexible body); the rest of the
panel is deformable (elasto-plastic or linear-elastic), rigid or a flexible body (*PART_MODES).

  side_panel_mesh.k          nodes and elements shared by every deck (*INCLUDE)
  side_panel_common.k        headform, support parts, contact, supports, output (*INCLUDE)
  side_panel_eigen.k         the panel's flexible part alone, free-free (rigidflex eigen
                             side_panel_eigen.k --parts 1; the two-step procedure is scripted in
                             examples/run_side_panel.py)
  side_panel_deformable.k    part 1 *MAT_PIECEWISE_LINEAR_PLASTICITY (the paper's deformable run)
  side_panel_elastic.k       part 1 *MAT_ELASTIC (separates plasticity from modal truncation)
  side_panel_rigid.k         part 1 *MAT_RIGID
  side_panel_modes_N_formF.k part 1 *MAT_RIGID + *PART_MODES, N modes, FORM F, reading
                             modes/modes.h5 next to the decks
  side_panel.json            the variants, the tracked nodes and the model data (for the scripts)

Model (units t, mm, s, N, MPa, mJ):
* panel: 168 x 77 Belytschko-Tsay shells (12936, 13182 nodes; the paper's side part has 12893
  shells and 13289 nodes) over 1500 x 700 mm (x along the car, y up the side), 1.0 mm steel,
  NIP 5; crowned in both directions (radii 3000 mm about y and 1200 mm about x; z is the
  panel's outward normal, the car's lateral axis) and stamped with two swage lines along x, a
  ridge 6 mm high at y ~ 130 mm and a groove 4 mm deep at y ~ -200 mm (Gaussian profiles of
  25 and 20 mm), both slightly inclined;
* supports: 28 points, spot-weld-like flange points every 150 mm along the long edges (11 per
  edge, corners included) and at y = +-117 mm on the short edges: the shells within two
  elements of each point (4 x 2 on an edge, 2 x 2 at a corner; 192 shells, 1.5 %) are part 2
  (always *MAT_ELASTIC), and the panel-edge nodes that belong to part 2 only (78) are held in
  x, y, z; part 1 is the other 12744 shells. (With ten points the free edges let the panel
  fold away: 67 mm under the head at 15 ms and the head still at 3 m/s.)
* material of part 1 in the deformable run: *MAT_PIECEWISE_LINEAR_PLASTICITY, a mild deep-
  drawing steel: E 210 GPa, nu 0.3, rho 7850 kg/m^3, SIGY 200 MPa and the Swift curve
  sigma = 550 (0.01 + eps_p)^0.22 MPa (LCSS, 12 points up to eps_p = 1), no rate effect;
  end time 20 ms (the head's rebound from the deformable panel begins at 17 ms);
* headform: examples/make_head_plate.py's (4.54 kg, rigid skull under an Ogden rubber skin),
  its skin four times as stiff (MU 1.6, 0.8 MPa: see SKIN_MU_PANEL), at 6.7 m/s in -z; its
  centre above (x, y) = (-450, -20) mm, near the left end, its lowest point 3.35 mm above the
  panel's surface (contact at 0.5 ms);
* contact: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE skin (part 12) against the panel (parts 1, 2);
* output: nodout.csv of the two tracked nodes: "near", the panel node under the head's centre,
  and "far", the node nearest (690, 0) mm at the right end, as the paper's Fig. 5; glstat.csv,
  spcforc.csv (support reactions), rcforc.csv, frames with the effective plastic strain.

--small writes the test's version (tests/python/side_panel_check.py): a 20 x 10 panel with
support points every 300 mm (1 x 1 shells at corners, 2 x 1 on edges), a 4 x 4 per face
headform, end time 6 ms,
every-cycle output of glstat and spcforc; --all-modes N adds a FORM 1 variant with N modes.

Standard library only. Usage:
  make_side_panel.py [--out DIR] [--small] [--speed V_MM_PER_S] [--thickness T] [--end T]
                     [--modes 10,20,...] [--forms 0,1] [--all-modes N]
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_head_plate import (HEAD_MASS, Mesh, STEEL_E, STEEL_NU, STEEL_RHO,  # noqa: E402
                             card, headform, headform_eigen_parts, headform_parts, impact_cards,
                             variant_writer)

LX, LY = 1500.0, 700.0
CROWN_RX, CROWN_RY = 3000.0, 1200.0  # radii of the crown about y (along x) and about x
RIDGE = (6.0, 130.0, 0.02, 25.0)  # height, y at x = 0, slope dy/dx, width (mm)
GROOVE = (-4.0, -200.0, -0.015, 20.0)
IMPACT_XY = (-450.0, -20.0)
CONTACT_TIME = 0.5e-3  # s
# Mild steel, Swift hardening: sigma = K (E0 + eps_p)^N, SIGY = K E0^N = 200 MPa.
SWIFT_K, SWIFT_E0, SWIFT_N = 550.0, 0.01, 0.22
CURVE_STRAINS = (0.0, 0.005, 0.01, 0.02, 0.04, 0.07, 0.1, 0.15, 0.2, 0.3, 0.5, 1.0)
# The headform's skin four times as stiff as model 1's (initial shear modulus 4 MPa): with model
# 1's 1 MPa the head bottoms out on the rigid (and the few-mode) panel, whose crown meets the
# head's curvature on a small area, and a skin element inverts at 3.05 ms (the rigid run stops);
# with 4 MPa the head rebounds from the rigid panel after 10.5 mm of skin compression.
SKIN_MU_PANEL = (1.6, 0.8)
SUPPORT_Y = (-350.0 / 3.0, 350.0 / 3.0)  # the short edges' inner support points
FAR_XY = (690.0, 0.0)


def surface(x, y):
    """The panel's mid-surface height z(x, y)."""
    z = -x * x / (2.0 * CROWN_RX) - y * y / (2.0 * CROWN_RY)
    for h, y0, slope, w in (RIDGE, GROOVE):
        z += h * math.exp(-((y - y0 - slope * x) / w) ** 2)
    return z


def swift(eps):
    return SWIFT_K * (SWIFT_E0 + eps) ** SWIFT_N


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                 "..", "build", "side_panel"))
    p.add_argument("--small", action="store_true", help="the test's small model")
    p.add_argument("--speed", type=float, default=6700.0, help="impact speed, mm/s")
    p.add_argument("--thickness", type=float, default=1.0, help="panel thickness, mm")
    p.add_argument("--end", type=float, default=None, help="end time, s")
    p.add_argument("--modes", default=None, help="mode counts, comma separated")
    p.add_argument("--forms", default="0,1", help="FORM values, comma separated")
    p.add_argument("--all-modes", type=int, default=0,
                   help="add a FORM 1 variant with this many modes")
    return p.parse_args()


def panel(mesh, nx, ny, small):
    """Shells of the panel; returns the node-ID function, the support nodes (held), the node
    IDs of part 1 and the number of part 2 shells."""
    def node(i, j):
        return 1 + i + (nx + 1) * j
    for j in range(ny + 1):
        for i in range(nx + 1):
            x, y = -LX / 2 + LX * i / nx, -LY / 2 + LY * j / ny
            mesh.nodes.append((node(i, j), x, y, surface(x, y)))
    # Support patches: the shells within h elements of each support point (a node on the edge).
    h, spacing = (1, 300.0) if small else (2, 150.0)
    points = []
    for k in range(round(LX / spacing) + 1):
        ic = round(k * spacing / LX * nx)
        points += [(ic, 0), (ic, ny)]
    for ys in SUPPORT_Y:
        jc = round((ys + LY / 2) / LY * ny)
        points += [(0, jc), (nx, jc)]
    patches = {(i, j) for ic, jc in points for i in range(max(0, ic - h), min(nx, ic + h))
               for j in range(max(0, jc - h), min(ny, jc + h))}
    eid = 0
    part_of_node = {}
    for j in range(ny):
        for i in range(nx):
            eid += 1
            part = 2 if (i, j) in patches else 1
            quad = (node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1))
            mesh.shells.append((eid, part, *quad))
            for n in quad:
                part_of_node.setdefault(n, set()).add(part)
    boundary = {node(i, j) for i in range(nx + 1) for j in range(ny + 1)
                if i in (0, nx) or j in (0, ny)}
    held = sorted(n for n in boundary if part_of_node[n] == {2})
    flexible = sorted(n for n, parts in part_of_node.items() if 1 in parts)
    return node, held, flexible, len(patches)


def main():
    args = parse_args()
    small = args.small
    nx, ny = (20, 10) if small else (168, 77)
    t = args.thickness
    head_n = 4 if small else 8
    end = args.end if args.end is not None else (6e-3 if small else 20e-3)
    modes = [int(m) for m in (args.modes or ("5,10,20,40" if small else "10,20,40,70,100"))
             .split(",")]
    forms = [int(f) for f in args.forms.split(",")]
    os.makedirs(args.out, exist_ok=True)

    mesh = Mesh()
    node, held, flexible, support_shells = panel(mesh, nx, ny, small)
    coords = {n[0]: n[1:] for n in mesh.nodes}

    def nearest(x, y):
        return min(coords, key=lambda n: (coords[n][0] - x) ** 2 + (coords[n][1] - y) ** 2)
    near = nearest(*IMPACT_XY)
    far = nearest(*FAR_XY)
    # The headform above the near node: built about z = 0, then lifted so that its lowest
    # point, measured along z from the panel's upper surface, is the gap.
    xi, yi = coords[near][0], coords[near][1]
    first = 20001
    count_before = len(mesh.nodes)
    skin_outer, skin_mass, head_inner = headform(mesh, head_n, (xi, yi, 0.0), first, first)
    gap = args.speed * CONTACT_TIME
    outer_set = set(skin_outer)
    lift = max(surface(x, y) + t / 2 + gap - z for _, x, y, z in mesh.nodes[count_before:]
               if _ in outer_set)
    mesh.nodes[count_before:] = [(n, x, y, z + lift) for n, x, y, z in mesh.nodes[count_before:]]
    head_centre = (xi, yi, lift)
    head_nodes = sorted(skin_outer + head_inner)
    skull_mass = HEAD_MASS - skin_mass

    mesh.write(os.path.join(args.out, "side_panel_mesh.k"), "examples/make_side_panel.py")

    section = (f"*SECTION_SHELL\n{card(1, 2, 0.8333333, 5)}{card(t, t, t, t)}"
               "*HOURGLASS\n" + card(1, 4, 0.05))
    output_dt = 1e-9 if small else 1e-5  # small: every cycle (the test's impulse sums)
    common = f"""*KEYWORD
$ Generated by examples/make_side_panel.py: what every variant shares
*PART
panel supports (deformable, carry the constraints: the paper's option (i))
{card(2, 1, 2, 0, 1)}*MAT_ELASTIC
{card(2, STEEL_RHO, STEEL_E, STEEL_NU)}""" + headform_parts(head_centre, skull_mass, args.speed,
                                                         SKIN_MU_PANEL)
    common += impact_cards(held, head_nodes, args.speed, [near, far], output_dt, end, end / 5)
    with open(os.path.join(args.out, "side_panel_common.k"), "w") as f:
        f.write(common)

    deck = variant_writer(args.out, "side_panel", "head impact on a side panel",
                          "examples/make_side_panel.py", "side panel (flexible part)", section)

    rigid = "*MAT_RIGID\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU) + card(0.0, 0.0, 0.0)
    curve = "*DEFINE_CURVE\n" + card(1) + "".join(
        f"{e:20.8g}{swift(e):20.8g}\n" for e in CURVE_STRAINS)
    variants = [{"name": "deformable", "deck": "side_panel_deformable.k", "kind": "deformable"},
                {"name": "deformable elastic", "deck": "side_panel_elastic.k",
                 "kind": "elastic"},
                {"name": "rigid", "deck": "side_panel_rigid.k", "kind": "rigid"}]
    deck("side_panel_deformable.k", "fully deformable panel, piecewise linear plasticity",
         "*MAT_PIECEWISE_LINEAR_PLASTICITY\n" +
         card(1, STEEL_RHO, STEEL_E, STEEL_NU, swift(0.0), 0.0, 0.0, 0.0) +
         card(0.0, 0.0, 1, 0, 0.0) + curve)
    deck("side_panel_elastic.k", "fully deformable panel, linear elastic",
         "*MAT_ELASTIC\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU))
    deck("side_panel_rigid.k", "rigid panel body (deformable supports)", rigid)

    def flexible_deck(count, form, label):
        name = f"side_panel_modes_{count}_form{form}.k"
        deck(name, f"flexible panel, {label}{count} modes, FORM {form}",
             rigid + "*PART_MODES\n" + card(1, count, form, 0, 3, 0, 0, 0) + "modes/modes.h5\n")
        return name
    for form in forms:
        for count in modes:
            variants.append({"name": f"{count} modes FORM {form}",
                             "deck": flexible_deck(count, form, ""), "kind": "flexible",
                             "modes": count, "form": form})
    if args.all_modes:
        count = args.all_modes  # FORM 1 only: FORM 0's inertia terms cost O(n^2)
        variants.append({"name": f"{count} modes FORM 1", "deck": flexible_deck(count, 1, "all "),
                         "kind": "flexible", "modes": count, "form": 1, "all": True})

    with open(os.path.join(args.out, "side_panel_eigen.k"), "w") as f:
        f.write("*KEYWORD\n*TITLE\nhead impact on a side panel: free-free modes of the flexible "
                "part (rigidflex eigen --parts 1)\n$ Generated by examples/make_side_panel.py\n"
                "*INCLUDE\nside_panel_mesh.k\n*CONTROL_IMPLICIT_GENERAL\n" + card(1, 1e-3) +
                "*CONTROL_IMPLICIT_EIGENVALUE\n" + card(max(modes), 0.0, 0, 0.0) +
                "*PART\nside panel (flexible part)\n" + card(1, 1, 1, 0, 1) + section +
                "*MAT_ELASTIC\n" + card(1, STEEL_RHO, STEEL_E, STEEL_NU) +
                "*PART\nsupports\n" + card(2, 1, 1, 0, 1) + headform_eigen_parts(SKIN_MU_PANEL) +
                "*END\n")

    with open(os.path.join(args.out, "side_panel.json"), "w") as f:
        json.dump({"small": small, "tracked_nodes": {"near": near, "far": far},
                   "held_nodes": held, "flexible_nodes": len(flexible),
                   "panel": {"nx": nx, "ny": ny, "lx": LX, "ly": LY, "thickness": t,
                             "shells": nx * ny, "nodes": (nx + 1) * (ny + 1),
                             "support_shells": support_shells},
                   "head": {"mass": skull_mass + skin_mass, "skull_card_mass": skull_mass,
                            "skin_outer_mass": skin_mass, "speed": args.speed,
                            "centre": head_centre, "skin_elements": len(mesh.solids),
                            "nodes": len(head_nodes)},
                   "material": {"sigy": swift(0.0), "swift": [SWIFT_K, SWIFT_E0, SWIFT_N]},
                   "end_time": end, "modes": modes, "forms": forms, "variants": variants},
                  f, indent=1)
    print(f"wrote {len(variants)} variants and the eigen deck to {os.path.abspath(args.out)}")


if __name__ == "__main__":
    main()
