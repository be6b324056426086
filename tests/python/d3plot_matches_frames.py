#!/usr/bin/env python3
"""Runs RigidFlex on a deck and reads its LS-DYNA d3plot back with an independent reader
(rigidflex_results.D3plot, written from the LS-DYNA manual's layout), comparing every field with
the VTU frames and CSV files of the same run:

- control words (NUMNP, NEL8, NV3D, flags), title, node and element user IDs, part IDs, part
  titles (those of the deck's *PART cards);
- reference coordinates = points of frame 0;
- per state: time = frame time; coordinates, displacement, velocity = the frame's points,
  `displacement`, `velocity`; 6 stresses = the frame's `stress` (p > 1 elements: every sub-hex
  carries its element's stress); plastic strain = the frame's `effective_plastic_strain` (0 where
  the frame has none); every element active;
- globals: kinetic/internal/total energy = glstat.csv at the same time where glstat has a row;
- accelerations = nodout.csv at the same time where nodout has a row;
- shells and beams (the `structural` deck): element IDs, parts, connectivity (triangles with
  N3 = N4), NUMMAT2/NUMMAT4; per state the beam resultants N Qs Qt Ms Mt T = the frame's
  `beam_resultant` (N Qs Qt T Ms Mt), the shells' inner and outer points = `stress_bottom` and
  `stress_top`, thickness = `thickness`, and the mid, inner and outer points (stresses and plastic
  strain) = the middle, first and last point of elout_shell.csv at the same time.

Usage: d3plot_matches_frames.py RIGIDFLEX DECK|generated|structural WORKDIR
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import D3plot, read_csv, read_pvd, read_vtu  # noqa: E402


def generated_deck(path):
    """Four parts: an elastic hex bar spinning about z (1), a wedge and a tetrahedron glued to its
    end (2), a rigid block moving in x (3) and a spinning order-2 Lagrange hexahedron (4)."""
    nodes, solids = [], []
    h = 0.01
    nid = 0
    grid = {}
    for k in range(2):
        for j in range(2):
            for i in range(4):
                nid += 1
                grid[i, j, k] = nid
                nodes.append((nid, i * h, j * h, k * h))
    eid = 0
    for i in range(3):
        eid += 1
        c = [grid[i, 0, 0], grid[i + 1, 0, 0], grid[i + 1, 1, 0], grid[i, 1, 0],
             grid[i, 0, 1], grid[i + 1, 0, 1], grid[i + 1, 1, 1], grid[i, 1, 1]]
        solids.append((eid, 1, c))
    # wedge N1 N2 N3 N4 N5 N5 N6 N6 on the end face x = 3h, apex line at x = 4h
    a = nid + 1
    b = nid + 2
    nodes += [(a, 4 * h, 0.0, 0.5 * h), (b, 4 * h, h, 0.5 * h)]
    nid += 2
    solids.append((100, 2, [grid[3, 0, 0], grid[3, 1, 0], grid[3, 1, 1], grid[3, 0, 1], a, a, b, b]))
    # tetrahedron N1 N2 N3 N4 N4 N4 N4 N4 below the bar's end
    t = nid + 1
    nodes.append((t, 3.5 * h, 0.5 * h, -h))
    nid += 1
    solids.append((101, 2, [grid[2, 0, 0], grid[3, 1, 0], grid[3, 0, 0], t, t, t, t, t]))
    # rigid block, separate, and the order-2 hexahedron, separate
    for part, origin, first_eid in ((3, (0.0, 0.05, 0.0), 200), (4, (0.05, 0.05, 0.0), 300)):
        ids = {}
        for k in range(2):
            for j in range(2):
                for i in range(2):
                    nid += 1
                    ids[i, j, k] = nid
                    nodes.append((nid, origin[0] + i * h, origin[1] + j * h, origin[2] + k * h))
        c = [ids[0, 0, 0], ids[1, 0, 0], ids[1, 1, 0], ids[0, 1, 0],
             ids[0, 0, 1], ids[1, 0, 1], ids[1, 1, 1], ids[0, 1, 1]]
        solids.append((first_eid, part, c))
    with open(path, "w") as f:
        f.write("*KEYWORD\n*TITLE\nd3plot check: hex, wedge, tetra, rigid, p=2\n*NODE\n")
        for n in nodes:
            f.write("%8d%16.8g%16.8g%16.8g\n" % n)
        f.write("*ELEMENT_SOLID\n")
        for e, p, c in solids:
            f.write("%8d%8d" % (e, p) + "".join("%8d" % x for x in c) + "\n")
        f.write("*PART\nbar\n1,1,1\n*PART\nwedge and tetra\n2,1,1\n*PART\nrigid\n3,1,2\n"
                "*PART\norder 2\n4,1,1\n*SECTION_SOLID\n1,1\n"
                "*MAT_ELASTIC\n1,7800.0,2.0e11,0.3\n*MAT_RIGID\n2,7800.0,2.0e11,0.3\n"
                "*CHANGE_P-ORDER\nP,4,2\n"
                "*INITIAL_VELOCITY_GENERATION\n1,2,300.0,0.0,0.0,0.0\n0.0,0.0,0.0,0.0,0.0,1.0\n"
                "*INITIAL_VELOCITY_GENERATION\n2,2,300.0,0.0,0.0,0.0\n0.0,0.0,0.0,0.0,0.0,1.0\n"
                "*INITIAL_VELOCITY_GENERATION\n3,2,0.0,5.0,0.0,0.0\n0.0,0.0,0.0,0.0,0.0,0.0\n"
                "*INITIAL_VELOCITY_GENERATION\n4,2,300.0,0.0,0.0,0.0\n0.055,0.055,0.0,0.0,0.0,1.0\n"
                "*CONTROL_TERMINATION\n2.0e-5\n*DATABASE_BINARY_D3PLOT\n2.5e-6\n"
                "*DATABASE_GLSTAT\n1.0e-6\n*DATABASE_NODOUT\n1.0e-6\n"
                "*DATABASE_HISTORY_NODE\n1,2,3,4\n*END\n")


def structural_deck(path):
    """Solids, shells and beams: a spinning hexahedron of an elastic-plastic material with a low
    yield stress, so that it carries plastic strain (part 1); a plate of shells in z = 0
    clamped along x = 0.05, of NIP 3 elastic quadrilaterals (part 2) and a NIP 5 quadrilateral and two
    triangles of an elastic-plastic material that yields (part 3); three Belytschko-Schwer resultant beams (ELFORM 2) along the plate's edge
    y = 0, sharing its nodes (part 4). Plate and beams start moving out of and in their plane, so
    they bend and stretch: shell stresses differ through the thickness, beam resultants are
    nonzero."""
    h = 0.01
    nodes, solids, shells, beams = [], [], [], []
    ids = {}
    for k in range(2):
        for j in range(2):
            for i in range(2):
                ids["s", i, j, k] = len(nodes) + 1
                nodes.append((len(nodes) + 1, i * h, j * h, k * h))
    c = [ids["s", 0, 0, 0], ids["s", 1, 0, 0], ids["s", 1, 1, 0], ids["s", 0, 1, 0],
         ids["s", 0, 0, 1], ids["s", 1, 0, 1], ids["s", 1, 1, 1], ids["s", 0, 1, 1]]
    solids.append((1, 1, c))
    for j in range(3):
        for i in range(4):
            ids["p", i, j] = len(nodes) + 101
            nodes.append((len(nodes) + 101, 0.05 + i * h, j * h, 0.0))
    n = lambda i, j: ids["p", i, j]
    eid = 10
    for j in range(2):
        for i in range(2):
            eid += 1
            shells.append((eid, 2, [n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1)]))
    shells.append((21, 3, [n(2, 0), n(3, 0), n(3, 1), n(2, 1)]))
    shells.append((22, 3, [n(2, 1), n(3, 1), n(3, 2), n(3, 2)]))  # triangles: N3 = N4
    shells.append((23, 3, [n(2, 1), n(3, 2), n(2, 2), n(2, 2)]))
    for i in range(3):
        beams.append((31 + i, 4, n(i, 0), n(i + 1, 0)))
    t = 0.002
    side = 0.004
    area, inertia = side * side, side ** 4 / 12.0
    with open(path, "w") as f:
        f.write("*KEYWORD\n*TITLE\nd3plot check: solids, shells, beams\n*NODE\n")
        for nd in nodes:
            f.write("%8d%16.8g%16.8g%16.8g\n" % nd)
        f.write("*ELEMENT_SOLID\n")
        for e, p, c in solids:
            f.write("%8d%8d" % (e, p) + "".join("%8d" % x for x in c) + "\n")
        f.write("*ELEMENT_SHELL\n")
        for e, p, c in shells:
            f.write("%8d%8d" % (e, p) + "".join("%8d" % x for x in c) + "\n")
        f.write("*ELEMENT_BEAM_ORIENTATION\n")
        for e, p, a, b in beams:
            f.write("%d,%d,%d,%d\n0.0,1.0,0.0\n" % (e, p, a, b))
        f.write("*PART\nspinning hexahedron\n1,1,2\n*PART\nplate NIP 3\n2,2,1\n"
                "*PART\nplate NIP 5 with triangles\n3,3,3\n*PART\nedge beams\n4,4,1\n"
                "*SECTION_SOLID\n1,1\n"
                "*SECTION_SHELL\n2,2,0.833,3\n%g,%g,%g,%g\n"
                "*SECTION_SHELL\n3,2,0.833,5\n%g,%g,%g,%g\n"
                "*SECTION_BEAM\n4,2,0.833\n%g,%g,%g,%g,%g\n"
                "*MAT_ELASTIC\n1,7800.0,2.0e11,0.3\n"
                "*MAT_PIECEWISE_LINEAR_PLASTICITY\n2,7800.0,2.0e11,0.3,1.0e4,2.0e9\n0,0,0,0,0\n\n\n"
                "*MAT_PIECEWISE_LINEAR_PLASTICITY\n3,7800.0,2.0e11,0.3,3.0e7,2.0e9\n0,0,0,0,0\n\n\n" % ((t,) * 8 + (area, inertia, inertia, 2 * inertia,
                                                                     5.0 / 6.0 * area)))
        f.write("*BOUNDARY_SPC_NODE\n")
        for j in range(3):
            f.write("%d,0,1,1,1,1,1,1\n" % n(0, j))
        f.write("*INITIAL_VELOCITY_GENERATION\n1,2,300.0,0.0,0.0,0.0\n0.005,0.005,0.0,0.0,0.0,1.0\n")
        for part in (2, 3, 4):
            f.write("*INITIAL_VELOCITY_GENERATION\n%d,2,0.0,0.0,2.0,5.0\n0.0,0.0,0.0,0.0,0.0,0.0\n" % part)
        f.write("*DATABASE_HISTORY_SHELL\n" + ",".join("%d" % e for e, _, _ in shells) + "\n")
        f.write("*CONTROL_TERMINATION\n2.0e-5\n*DATABASE_BINARY_D3PLOT\n2.5e-6\n"
                "*DATABASE_GLSTAT\n1.0e-6\n*DATABASE_ELOUT\n1.25e-6\n*END\n")


failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def close(a, b, scale, what, rel=2e-6):
    """float32 words against doubles: relative to the field's magnitude."""
    tol = rel * max(scale, 1e-30)
    for i, (x, y) in enumerate(zip(a, b)):
        if abs(x - y) > tol:
            failures.append("%s: component %d is %r, expected %r (tolerance %g)" % (what, i, x, y, tol))
            return False
    return True


def magnitude(rows):
    return max((abs(v) for r in rows for v in (r if isinstance(r, (list, tuple)) else [r])), default=0.0)


def main():
    rigidflex, deck, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    if deck == "generated":
        deck = os.path.join(work, "d3plot_check.k")
        generated_deck(deck)
    elif deck == "structural":
        deck = os.path.join(work, "d3plot_structural.k")
        structural_deck(deck)
    out = os.path.join(work, "out")
    subprocess.run([rigidflex, "run", deck, "-o", out, "--threads", "1", "--quiet"], check=True)

    d = D3plot(os.path.join(out, "d3plot"))
    frames = read_pvd(os.path.join(out, "frames.pvd"))
    check(len(d.states) == len(frames), "%d d3plot states, %d frames" % (len(d.states), len(frames)))
    check(d.nv3d == 7 and d.iu == 1 and d.iv == 1 and d.ia == 1 and d.it == 0, "flags %r" % (d.control[15:28],))
    check(d.deletion, "MAXINT does not announce element deletion flags")
    check(d.nv1d == 6 and d.shell_points == 3 and d.ioshl == [1, 1, 0, 1] and d.nv2d == 3 * 7 + 4
          and d.neips == 0 and d.neiph == 0,
          "NV1D %d, MAXINT %d, IOSHL %r, NV2D %d: expected 6, 3 points, stresses + plastic strain + "
          "thickness/energy, 25" % (d.nv1d, d.maxint, d.ioshl, d.nv2d))
    first = read_vtu(os.path.join(out, frames[0][1]))
    check(d.numnp == len(first["points"]), "NUMNP %d, frame has %d points" % (d.numnp, len(first["points"])))
    check(d.node_ids == list(first["point_data"]["node_id"]), "node user IDs differ")
    close([c for p in d.x0 for c in p], [c for p in first["points"] for c in p], magnitude(first["points"]),
          "reference coordinates")

    # Solids: VTU cells in the same order, one per element (p > 1: one Lagrange cell for p^3
    # d3plot sub-hexes carrying the element's ID).
    # VTU cell types: lines (3) are beams, triangles (5) and quads (9) shells.
    family = ["beam" if k == 3 else "shell" if k in (5, 9) else "solid" for k in first["types"]]
    cell_eids = [e for e, f in zip(first["cell_data"]["element_id"], family) if f == "solid"]
    cell_parts = list(first["cell_data"]["part_id"])
    cell_of_solid = []
    c = -1
    for e, eid in enumerate(d.solid_ids):
        if c < 0 or cell_eids[c] != eid:
            c += 1
        cell_of_solid.append(c)
        check(c < len(cell_eids) and cell_eids[c] == eid,
              "solid %d: user ID %d not in the frame's cell order" % (e, eid))
        if failures:
            break
    check(sorted(set(d.solid_ids)) == sorted(set(cell_eids)), "element user IDs differ")
    for e, m in enumerate(d.solid_material):
        pid = d.part_ids[m - 1]
        c = cell_of_solid[e]
        check(pid == cell_parts[c], "solid %d: part %d, frame says %d" % (e, pid, cell_parts[c]))
    # Degenerate solids keep their repeated nodes; connectivity must reference the frame's nodes.
    types = first["types"]
    offsets = [0] + list(first["offsets"])
    conn = first["connectivity"]
    for e, nodes in enumerate(d.solids):
        c = cell_of_solid[e]
        cell_nodes = set(conn[offsets[c]:offsets[c + 1]])
        check(set(n - 1 for n in nodes) <= cell_nodes, "solid %d: nodes %r not in cell %d" % (e, nodes, c))
        if types[c] == 12:
            check([n - 1 for n in nodes] == list(conn[offsets[c]:offsets[c + 1]]), "hexahedron %d node order" % e)

    # Shells and beams: the frame's cell of the same family and user ID.
    cell_of = {(f, eid): c for c, (f, eid) in enumerate(zip(family, first["cell_data"]["element_id"]))}
    check(family.count("shell") == d.nel4 and family.count("beam") == d.nel2,
          "NEL4 %d, NEL2 %d; the frame has %d shells, %d beams" % (d.nel4, d.nel2, family.count("shell"),
                                                                  family.count("beam")))
    cell_of_shell = [cell_of.get(("shell", eid), -1) for eid in d.shell_ids]
    cell_of_beam = [cell_of.get(("beam", eid), -1) for eid in d.beam_ids]
    check(-1 not in cell_of_shell and -1 not in cell_of_beam, "shell or beam user IDs not in the frame")
    for kind, materials, cells, nodes_of in (("shell", d.shell_material, cell_of_shell, d.shells),
                                             ("beam", d.beam_material, cell_of_beam, d.beams)):
        for e, (m, c) in enumerate(zip(materials, cells)):
            if c < 0:
                continue
            pid = d.part_ids[m - 1]
            check(pid == cell_parts[c], "%s %d: part %d, frame says %d" % (kind, e, pid, cell_parts[c]))
            vtu = list(conn[offsets[c]:offsets[c + 1]])
            written = [x - 1 for x in nodes_of[e]]
            if kind == "beam":
                check(written[:2] == vtu and written[2:] == [-1, -1, -1],
                      "beam %d: nodes %r, frame %r (orientation node and unused words 0)" % (e, nodes_of[e], vtu))
            elif len(vtu) == 3:
                check(written == vtu + [vtu[2]], "triangle %d: nodes %r, frame %r (N4 = N3)" % (e, nodes_of[e], vtu))
            else:
                check(written == vtu, "shell %d: nodes %r, frame %r" % (e, nodes_of[e], vtu))
    for name, count, materials in (("NUMMAT8", d.nummat8, d.solid_material), ("NUMMAT2", d.nummat2, d.beam_material),
                                   ("NUMMAT4", d.nummat4, d.shell_material)):
        check(count == len(set(materials)), "%s %d, elements use %d materials" % (name, count, len(set(materials))))
    check(d.nmmat == d.nummat8 + d.nummat2 + d.nummat4, "NMMAT %d is not the sum of the families" % d.nmmat)

    titles = {1: "bar", 2: "wedge and tetra", 3: "rigid", 4: "order 2"}
    if deck.endswith("d3plot_structural.k"):
        titles = {1: "spinning hexahedron", 2: "plate NIP 3", 3: "plate NIP 5 with triangles", 4: "edge beams"}
        check(d.part_titles == titles, "part titles %r, deck says %r" % (d.part_titles, titles))
    elif deck.endswith("d3plot_check.k"):
        check(d.part_titles == titles, "part titles %r, deck says %r" % (d.part_titles, titles))
    else:
        check(sorted(d.part_titles) == sorted(d.part_ids), "titles for parts %r, parts are %r"
              % (sorted(d.part_titles), d.part_ids))

    glstat = {round(r["time"], 12): r for r in read_csv(os.path.join(out, "glstat.csv"))}
    nodout_path = os.path.join(out, "nodout.csv")
    nodout = {}
    if os.path.exists(nodout_path):
        for r in read_csv(nodout_path):
            nodout.setdefault(round(r["time"], 12), {})[int(r["node"])] = r
    elout = {}
    elout_path = os.path.join(out, "elout_shell.csv")
    if os.path.exists(elout_path):
        for r in read_csv(elout_path):
            elout.setdefault(round(r["time"], 12), {}).setdefault(int(r["element"]), []).append(r)
    compared_globals = compared_acc = compared_points = 0
    bending = most_plastic = shell_plastic = 0.0
    index_of_id = {nid: i for i, nid in enumerate(d.node_ids)}
    moving = 0.0
    for s, (t, name) in zip(d.states, frames):
        f = read_vtu(os.path.join(out, name))
        where = "state at t = %g" % t
        close([s["time"]], [t], abs(t), where + ": time")
        pts = f["points"]
        close([c for p in s["coordinates"] for c in p], [c for p in pts for c in p], magnitude(pts), where + ": coordinates")
        disp = [[s["coordinates"][i][k] - d.x0[i][k] for k in range(3)] for i in range(d.numnp)]
        vdisp = f["point_data"]["displacement"]
        # difference of two float32 coordinates: absolute error of the coordinates' size
        close([c for p in disp for c in p], [c for p in vdisp for c in p], magnitude(pts), where + ": displacement")
        moving = max(moving, magnitude(vdisp))
        vel = f["point_data"]["velocity"]
        close([c for p in s["velocity"] for c in p], [c for p in vel for c in p], magnitude(vel), where + ": velocity")
        stress = f["cell_data"]["stress"]
        smax = magnitude(stress)
        plastic = f["cell_data"].get("effective_plastic_strain")
        pmax = magnitude(plastic or [])
        most_plastic = max(most_plastic, pmax)
        for e, values in enumerate(s["solid"]):
            if not close(values[:6], stress[cell_of_solid[e]], smax, where + ": stress of solid %d" % e):
                break
            if plastic is None:
                check(values[6] == 0.0, where + ": plastic strain of solid %d is %r" % (e, values[6]))
            elif not close(values[6:7], [plastic[cell_of_solid[e]]], pmax, where + ": plastic strain of solid %d" % e):
                break
        check(all(a == 1.0 for a in s["alive"] + s["shell_alive"] + s["beam_alive"]),
              where + ": an element is flagged deleted")
        # Beams: N Qs Qt Ms Mt T; the frame's beam_resultant is N Qs Qt T Ms Mt.
        resultant = f["cell_data"].get("beam_resultant", [])
        rmax = magnitude(resultant)
        for e, values in enumerate(s["beam"]):
            r = resultant[cell_of_beam[e]]
            if not close(values, [r[0], r[1], r[2], r[4], r[5], r[3]], rmax, where + ": resultants of beam %d" % e):
                break
        # Shells: points mid, inner (bottom), outer (top) of 6 stresses + plastic strain, then
        # thickness, two element variables and internal energy (0).
        bottom = f["cell_data"].get("stress_bottom", [])
        top = f["cell_data"].get("stress_top", [])
        thick = f["cell_data"].get("thickness", [])
        shell_max = max(magnitude(bottom), magnitude(top))
        rows = elout.get(round(t, 12), {})
        if rows:
            compared_points += 1
        for e, values in enumerate(s["shell"]):
            c = cell_of_shell[e]
            ok = close(values[7:13], bottom[c], shell_max, where + ": inner stresses of shell %d" % e)
            ok = ok and close(values[14:20], top[c], shell_max, where + ": outer stresses of shell %d" % e)
            ok = ok and close(values[21:22], [thick[c]], thick[c], where + ": thickness of shell %d" % e)
            check(list(values[22:25]) == [0.0, 0.0, 0.0], where + ": element variables of shell %d" % e)
            bending = max(bending, max(abs(a - b) for a, b in zip(bottom[c], top[c])))
            points = sorted(rows.get(d.shell_ids[e], []), key=lambda r: r["point"])
            if points:
                keys = ["sxx", "syy", "szz", "sxy", "syz", "szx", "effective_plastic_strain"]
                nip = len(points)
                mid = [points[nip // 2][k] for k in keys] if nip % 2 else \
                    [0.5 * (points[nip // 2 - 1][k] + points[nip // 2][k]) for k in keys]
                for name, got, want in (("mid", values[0:7], mid), ("inner", values[7:14], [points[0][k] for k in keys]),
                                        ("outer", values[14:21], [points[-1][k] for k in keys])):
                    ok = ok and close(got[:6], want[:6], shell_max, where + ": %s point of shell %d (elout_shell)" % (name, e))
                    ok = ok and close(got[6:7], want[6:7], max(abs(want[6]), 1e-12),
                                      where + ": %s plastic strain of shell %d (elout_shell)" % (name, e))
                    shell_plastic = max(shell_plastic, got[6])
            if not ok:
                break
        g = glstat.get(round(t, 12))
        if g is not None:
            compared_globals += 1
            scale = max(abs(g["kinetic_energy"]), abs(g["total_energy"]), abs(g["internal_energy"]))
            close(s["globals"][:3], [g["kinetic_energy"], g["internal_energy"], g["total_energy"]], scale,
                  where + ": kinetic, internal, total energy")
        rows = nodout.get(round(t, 12))
        if rows:
            compared_acc += 1
            amax = magnitude([s["acceleration"][index_of_id[n]] for n in rows])
            for n, r in rows.items():
                close(s["acceleration"][index_of_id[n]], [r["ax"], r["ay"], r["az"]], amax,
                      where + ": acceleration of node %d" % n)
    check(compared_globals >= 2, "only %d states had a glstat row at their time" % compared_globals)
    if nodout:
        check(compared_acc >= 2, "only %d states had nodout rows at their time" % compared_acc)
    check(moving > 0.0, "nothing moved: the comparison would not see swapped fields")
    if deck.endswith("d3plot_structural.k"):
        check(most_plastic > 0.0, "the hexahedron never yields: the plastic strain comparison is empty")
        check(shell_plastic > 0.0, "no shell point yields: the shell plastic strain comparison is empty")
    if d.nel4:
        check(compared_points >= 2, "only %d states had elout_shell rows at their time" % compared_points)
        check(bending > 0.0, "shell stresses equal at the bottom and top: inner/outer would not be told apart")
    if d.nel2:
        last = read_vtu(os.path.join(out, frames[-1][1]))["cell_data"]["beam_resultant"]
        check(all(magnitude([r[k] for r in last]) > 0.0 for k in range(6)),
              "a beam resultant is zero in every beam: a swap would not be seen")
    check(magnitude(read_vtu(os.path.join(out, frames[-1][1]))["cell_data"]["stress"]) > 0.0,
          "no stress in the last frame: the stress comparison would be empty")

    if failures:
        print("d3plot differs from the frames:")
        for f in failures[:30]:
            print("  " + f)
        return 1
    print("d3plot matches: %d states, %d nodes, %d solids, %d shells, %d beams, %d parts (globals compared at "
          "%d, accelerations at %d, shell points at %d states)" % (len(d.states), d.numnp, d.nel8, d.nel4, d.nel2,
                                                                   d.nmmat, compared_globals, compared_acc,
                                                                   compared_points))
    return 0


if __name__ == "__main__":
    sys.exit(main())
