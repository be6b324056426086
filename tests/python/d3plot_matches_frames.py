#!/usr/bin/env python3
"""Runs RigidFlex on a deck and reads its LS-DYNA d3plot back with an independent reader
(rigidflex_results.D3plot, written from the LS-DYNA manual's layout), comparing every field with
the VTU frames and CSV files of the same run:

- control words (NUMNP, NEL8, NV3D, flags), title, node and element user IDs, part IDs, part
  titles (those of the deck's *PART cards);
- reference coordinates = points of frame 0;
- per state: time = frame time; coordinates, displacement, velocity = the frame's points,
  `displacement`, `velocity`; 6 stresses = the frame's `stress` (p > 1 elements: every sub-hex
  carries its element's stress); plastic strain 0; every element active;
- globals: kinetic/internal/total energy = glstat.csv at the same time where glstat has a row;
- accelerations = nodout.csv at the same time where nodout has a row.

Usage: d3plot_matches_frames.py RIGIDFLEX DECK|generated WORKDIR
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
    out = os.path.join(work, "out")
    subprocess.run([rigidflex, "run", deck, "-o", out, "--threads", "1", "--quiet"], check=True)

    d = D3plot(os.path.join(out, "d3plot"))
    frames = read_pvd(os.path.join(out, "frames.pvd"))
    check(len(d.states) == len(frames), "%d d3plot states, %d frames" % (len(d.states), len(frames)))
    check(d.nv3d == 7 and d.iu == 1 and d.iv == 1 and d.ia == 1 and d.it == 0, "flags %r" % (d.control[15:28],))
    check(d.deletion, "MAXINT does not announce element deletion flags")
    first = read_vtu(os.path.join(out, frames[0][1]))
    check(d.numnp == len(first["points"]), "NUMNP %d, frame has %d points" % (d.numnp, len(first["points"])))
    check(d.node_ids == list(first["point_data"]["node_id"]), "node user IDs differ")
    close([c for p in d.x0 for c in p], [c for p in first["points"] for c in p], magnitude(first["points"]),
          "reference coordinates")

    # Solids: VTU cells in the same order, one per element (p > 1: one Lagrange cell for p^3
    # d3plot sub-hexes carrying the element's ID).
    cell_eids = list(first["cell_data"]["element_id"])
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

    titles = {1: "bar", 2: "wedge and tetra", 3: "rigid", 4: "order 2"}
    if deck.endswith("d3plot_check.k"):
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
    compared_globals = compared_acc = 0
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
        for e, values in enumerate(s["solid"]):
            if not close(values[:6], stress[cell_of_solid[e]], smax, where + ": stress of solid %d" % e):
                break
            check(values[6] == 0.0, where + ": plastic strain of solid %d is %r" % (e, values[6]))
        check(all(a == 1.0 for a in s["alive"]), where + ": an element is flagged deleted")
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
    check(magnitude(read_vtu(os.path.join(out, frames[-1][1]))["cell_data"]["stress"]) > 0.0,
          "no stress in the last frame: the stress comparison would be empty")

    if failures:
        print("d3plot differs from the frames:")
        for f in failures[:30]:
            print("  " + f)
        return 1
    print("d3plot matches: %d states, %d nodes, %d solids, %d parts (globals compared at %d, "
          "accelerations at %d states)" % (len(d.states), d.numnp, d.nel8, d.nmmat, compared_globals, compared_acc))
    return 0


if __name__ == "__main__":
    sys.exit(main())
