#!/usr/bin/env python3
"""walls.pvd / walls_NNNN.vtu (docs/output.md#wallspvd-and-walls_nnnnvtu) on
tests/decks/rigidwall_block.k: one quadrilateral per *RIGIDWALL_PLANAR at every frame time; the
floor (ID 5, through (0, 0, -0.01) with normal +z) lies in z = -0.01; the finite moving ceiling
(ID 2: origin (0, 0, 3.01), LENL 2, LENM 3) is a 2 x 3 rectangle at z = 3.01 at t = 0.

Usage: walls_check.py RIGIDFLEX DECK WORKDIR
"""
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import read_pvd  # noqa: E402
import xml.etree.ElementTree as ET  # noqa: E402


def read_walls(path):
    root = ET.parse(path).getroot()
    piece = root.find("UnstructuredGrid").find("Piece")
    values = lambda a: a.text.split()
    pts = [float(v) for v in values(piece.find("Points").find("DataArray"))]
    points = [pts[3 * i:3 * i + 3] for i in range(len(pts) // 3)]
    cell = {a.get("Name"): values(a) for a in piece.find("CellData")}
    cells = {a.get("Name"): values(a) for a in piece.find("Cells")}
    return points, [int(v) for v in cell["wall_id"]], cells


def main():
    rigidflex, deck, work = sys.argv[1:4]
    out = os.path.join(work, "out")
    subprocess.run([rigidflex, "run", deck, "-o", out, "--threads", "1", "--quiet"], check=True)
    failures = []
    frames = read_pvd(os.path.join(out, "frames.pvd"))
    walls = read_pvd(os.path.join(out, "walls.pvd"))
    if [t for t, _ in frames] != [t for t, _ in walls]:
        failures.append("walls.pvd times differ from frames.pvd")
    for k, (t, name) in enumerate(walls):
        points, ids, cells = read_walls(os.path.join(out, name))
        if len(points) != 4 * len(ids) or cells["types"] != ["9"] * len(ids):
            failures.append("t=%g: %d points for %d quads" % (t, len(points), len(ids)))
            continue
        floor = ids.index(5)
        if any(p[2] != -0.01 for p in points[4 * floor:4 * floor + 4]):
            failures.append("t=%g: floor corners %r not at z = -0.01" % (t, points[4 * floor:4 * floor + 4]))
        if k == 0:
            c = points[4 * ids.index(2):4 * ids.index(2) + 4]
            sides = sorted(round(math.dist(c[i], c[(i + 1) % 4]), 12) for i in range(4))
            if sides != [2.0, 2.0, 3.0, 3.0] or any(abs(p[2] - 3.01) > 1e-12 for p in c):
                failures.append("ceiling at t = 0: corners %r" % c)
    if failures:
        print("walls check failed:")
        for f in failures[:20]:
            print("  " + f)
        return 1
    print("walls match: %d frames with walls %r" % (len(walls), ids))
    return 0


if __name__ == "__main__":
    sys.exit(main())
