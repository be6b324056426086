"""Opens a RigidFlex d3plot with ParaView's own LS-DYNA reader (vtkLSDynaReader, through pvpython)
and compares what ParaView shows with the VTU frames of the same run: the time values, and per
time step the current coordinates and velocities of every node, the 6 stresses of every solid,
the inner and outer stresses and thickness of every shell (`stress_bottom`, `stress_top`,
`thickness`), the resultants of every beam (`beam_resultant`), and the number of cells of every
part and of each kind.

Nodes are matched by their reference position (the reader's undeformed points), not by the
reader's UserID array: ParaView 5.11 reads the 4-byte node IDs of the file as 8-byte values.
ParaView's stresses must be exactly the frames' stresses rounded to single precision, as a
multiset (an element of order p counts p^3 times: it is written as its p^3 sub-hexahedra).

Usage: pvpython d3plot_paraview.py OUTPUT_DIR   (a directory with d3plot and frames.pvd)
"""
import math
import os
import struct
import sys
from collections import Counter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import read_pvd, read_vtu  # noqa: E402

from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet  # noqa: E402
from vtkmodules.vtkIOLSDyna import vtkLSDynaReader  # noqa: E402


def main():
    out = sys.argv[1]
    frames = read_pvd(os.path.join(out, "frames.pvd"))
    reader = vtkLSDynaReader()
    reader.SetFileName(os.path.join(out, "d3plot"))
    reader.SetDeformedMesh(0)  # points = reference coordinates; current ones as an array
    reader.UpdateInformation()
    failures = []
    steps = reader.GetNumberOfTimeSteps()
    if steps != len(frames):
        failures.append("ParaView sees %d time steps, frames.pvd lists %d" % (steps, len(frames)))
    first = read_vtu(os.path.join(out, frames[0][1]))
    reference = first["points"]
    size = max(abs(c) for p in reference for c in p)
    by_float32 = {}
    for j, p in enumerate(reference):
        by_float32.setdefault(struct.pack("<3f", *p), j)
    parts_in_frames = sorted(set(first["cell_data"]["part_id"]))
    if reader.GetNumberOfPartArrays() != len(parts_in_frames):
        failures.append("ParaView lists %d parts, the frames %d" % (reader.GetNumberOfPartArrays(), len(parts_in_frames)))
    # Part titles: the blocks carry the titles of the deck's *PART cards (d3plot title section).
    pid_of_title = {}
    for name in ("d3plot_check.k", "d3plot_structural.k"):
        deck = os.path.join(os.path.dirname(os.path.abspath(out)), name)
        if not os.path.exists(deck):
            continue
        lines = open(deck).read().splitlines()
        pid_of_title = {lines[i + 1].strip(): int(lines[i + 2].split(",")[0])
                        for i, line in enumerate(lines) if line.strip() == "*PART"}
        titles = sorted(pid_of_title)
        shown = sorted(reader.GetPartArrayName(i) for i in range(reader.GetNumberOfPartArrays()))
        if shown != titles:
            failures.append("ParaView names the parts %r, the deck %r" % (shown, titles))
    # Cells per part in the frames (an element of order p counts p^3 times, as its sub-hexahedra).
    offsets0 = [0] + list(first["offsets"])
    cells_of_part = Counter()
    for c, pid in enumerate(first["cell_data"]["part_id"]):
        count = 1
        if first["types"][c] == 72:
            count = (round((offsets0[c + 1] - offsets0[c]) ** (1.0 / 3.0)) - 1) ** 3
        cells_of_part[pid] += count
    for step in range(min(steps, len(frames))):
        t, name = frames[step]
        if abs(reader.GetTimeValue(step) - t) > 1e-6 * max(abs(t), 1e-30):
            failures.append("step %d: time %r, frame time %r" % (step, reader.GetTimeValue(step), t))
        reader.SetTimeStep(step)
        reader.Update()
        data = reader.GetOutput()
        f = read_vtu(os.path.join(out, name))
        vscale = max([abs(c) for p in f["point_data"]["velocity"] for c in p] + [1e-30])
        seen_points = 0
        paraview_stresses = []
        paraview_shells = []  # (inner stresses, outer stresses, thickness)
        paraview_beams = []   # N, Qs, Qt, Ms, Mt, T
        for b in range(data.GetNumberOfBlocks()):
            grid = data.GetBlock(b)
            if grid is None:
                continue
            name = data.GetMetaData(b).Get(vtkCompositeDataSet.NAME())
            if step == 0 and name in pid_of_title and grid.GetNumberOfCells() != cells_of_part[pid_of_title[name]]:
                failures.append("part %r: ParaView shows %d cells, the frames %d" % (
                    name, grid.GetNumberOfCells(), cells_of_part[pid_of_title[name]]))
            kind = grid.GetCellType(0) if grid.GetNumberOfCells() else 0
            current = grid.GetPointData().GetArray("Deflected Coordinates")
            velocity = grid.GetPointData().GetArray("Velocity")
            cd = grid.GetCellData()
            names = {3: ("AxialForce", "ShearResultant", "BendingResultant", "TorsionResultant"),
                     9: ("StressInnerSurf", "StressOuterSurf", "Thickness")}.get(kind, ("Stress",))
            arrays = [cd.GetArray(n) for n in names]
            if current is None or velocity is None or None in arrays:
                failures.append("step %d: arrays Deflected Coordinates/Velocity/%s missing" % (step, "/".join(names)))
                break
            for k in range(grid.GetNumberOfPoints()):
                p = grid.GetPoint(k)
                # The file stores x0 as float32: look the point up by its float32 bytes, and
                # fall back to the nearest node (coincident nodes share a key).
                i = by_float32.get(struct.pack("<3f", *p))
                if i is None:
                    i = min(range(len(reference)), key=lambda j: math.dist(reference[j], p))
                if math.dist(reference[i], p) > 1e-6 * size:
                    failures.append("step %d: ParaView point %r is no node of the frames" % (step, p))
                    break
                x, v = current.GetTuple3(k), velocity.GetTuple3(k)
                if any(abs(x[c] - f["points"][i][c]) > 2e-6 * size for c in range(3)):
                    failures.append("step %d node %d: ParaView position %r, frame %r" % (step, i, x, f["points"][i]))
                    break
                if any(abs(v[c] - f["point_data"]["velocity"][i][c]) > 2e-6 * vscale for c in range(3)):
                    failures.append("step %d node %d: ParaView velocity %r, frame %r" % (step, i, v, f["point_data"]["velocity"][i]))
                    break
                seen_points += 1
            for k in range(grid.GetNumberOfCells()):
                values = sum((a.GetTuple(k) for a in arrays), ())
                if kind == 3:
                    paraview_beams.append(struct.pack("<6f", *values))
                elif kind == 9:
                    paraview_shells.append(struct.pack("<13f", *values))
                else:
                    paraview_stresses.append(values)
        expected = []
        offsets = [0] + list(f["offsets"])
        wanted_shells, wanted_beams = Counter(), Counter()
        for c, s in enumerate(f["cell_data"]["stress"]):
            if f["types"][c] in (5, 9):
                wanted_shells[struct.pack("<13f", *(f["cell_data"]["stress_bottom"][c] + f["cell_data"]["stress_top"][c]
                                                    + (f["cell_data"]["thickness"][c],)))] += 1
                continue
            if f["types"][c] == 3:
                r = f["cell_data"]["beam_resultant"][c]
                wanted_beams[struct.pack("<6f", r[0], r[1], r[2], r[4], r[5], r[3])] += 1
                continue
            count = 1
            if f["types"][c] == 72:  # Lagrange hexahedron: (p+1)^3 nodes, p^3 sub-hexahedra
                p = round((offsets[c + 1] - offsets[c]) ** (1.0 / 3.0)) - 1
                count = p ** 3
            expected += [s] * count
        if len(expected) != len(paraview_stresses):
            failures.append("step %d: ParaView shows %d solids, expected %d" % (step, len(paraview_stresses), len(expected)))
        else:
            # The file stores float32 words: ParaView's stresses must be, as a multiset, exactly
            # the frames' stresses rounded to float32 (mirror-symmetric elements differ only in
            # shear signs, so elements are not paired by order).
            shown = Counter(struct.pack("<6f", *a) for a in paraview_stresses)
            wanted = Counter(struct.pack("<6f", *e) for e in expected)
            if shown != wanted:
                extra = list((shown - wanted).elements())[:1]
                failures.append("step %d: %d of ParaView's stresses are no frame stress, e.g. %r" % (
                    step, sum((shown - wanted).values()), [struct.unpack("<6f", x) for x in extra]))
        # Shells and beams: as multisets, exactly the frames' values rounded to float32.
        for kind, shown, wanted in (("shell", Counter(paraview_shells), wanted_shells),
                                    ("beam", Counter(paraview_beams), wanted_beams)):
            if shown != wanted:
                failures.append("step %d: %d of ParaView's %d %ss match no %s of the frames" % (
                    step, sum((shown - wanted).values()), sum(shown.values()), kind, kind))
            if step == len(frames) - 1 and wanted and all(v == b"\0" * len(v) for v in wanted):
                failures.append("step %d: every %s value is zero: the comparison is empty" % (step, kind))
        if seen_points == 0:
            failures.append("step %d: ParaView shows no points" % step)
    if failures:
        print("ParaView's LS-DYNA reader disagrees with the frames:")
        for line in failures[:20]:
            print("  " + line)
        return 1
    print("ParaView's LS-DYNA reader reads %d states that match the frames" % steps)
    return 0


if __name__ == "__main__":
    sys.exit(main())
