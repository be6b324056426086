"""Opens a RigidFlex d3plot with ParaView's own LS-DYNA reader (vtkLSDynaReader, through pvpython)
and compares what ParaView shows with the VTU frames of the same run: time values, current
coordinates and velocities of every node (by user node ID), and the 6 stresses and part of every
solid (by user element ID).

Usage: pvpython d3plot_paraview.py OUTPUT_DIR   (a directory with d3plot and frames.pvd)
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import read_pvd, read_vtu  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import LSDynaReader, MergeBlocks  # noqa: E402


def main():
    out = sys.argv[1]
    frames = read_pvd(os.path.join(out, "frames.pvd"))
    reader = LSDynaReader(FileName=os.path.join(out, "d3plot"))
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    failures = []
    if len(times) != len(frames):
        failures.append("ParaView sees %d time steps, frames.pvd lists %d" % (len(times), len(frames)))
    merged = MergeBlocks(Input=reader)
    for t, (frame_time, name) in zip(times, frames):
        if abs(t - frame_time) > 1e-6 * max(abs(frame_time), 1e-30):
            failures.append("time %r, frame time %r" % (t, frame_time))
        merged.UpdatePipeline(t)
        data = servermanager.Fetch(merged)
        f = read_vtu(os.path.join(out, name))
        index = {nid: i for i, nid in enumerate(f["point_data"]["node_id"])}
        pd, cd = data.GetPointData(), data.GetCellData()
        ids = pd.GetArray("UserID")
        vel = pd.GetArray("Velocity")
        if ids is None or vel is None:
            names = [pd.GetArrayName(k) for k in range(pd.GetNumberOfArrays())]
            failures.append("point arrays UserID/Velocity missing (have %r)" % names)
            break
        scale = max(abs(c) for p in f["points"] for c in p)
        vscale = max([abs(c) for p in f["point_data"]["velocity"] for c in p] + [1e-30])
        for k in range(data.GetNumberOfPoints()):
            i = index[int(ids.GetValue(k))]
            p = data.GetPoint(k)
            v = vel.GetTuple3(k)
            if any(abs(p[c] - f["points"][i][c]) > 2e-6 * scale for c in range(3)):
                failures.append("t=%g node %d: ParaView point %r, frame %r" % (t, ids.GetValue(k), p, f["points"][i]))
                break
            if any(abs(v[c] - f["point_data"]["velocity"][i][c]) > 2e-6 * vscale for c in range(3)):
                failures.append("t=%g node %d: ParaView velocity %r, frame %r" % (t, ids.GetValue(k), v, f["point_data"]["velocity"][i]))
                break
        cell_index = {eid: c for c, eid in enumerate(f["cell_data"]["element_id"])}
        eids = cd.GetArray("UserID")
        stress = cd.GetArray("Stress")
        if eids is None or stress is None:
            names = [cd.GetArrayName(k) for k in range(cd.GetNumberOfArrays())]
            failures.append("cell arrays UserID/Stress missing (have %r)" % names)
            break
        sscale = max([abs(c) for s in f["cell_data"]["stress"] for c in s] + [1e-30])
        seen = set()
        for k in range(data.GetNumberOfCells()):
            eid = int(eids.GetValue(k))
            seen.add(eid)
            s = stress.GetTuple(k)
            expected = f["cell_data"]["stress"][cell_index[eid]]
            if any(abs(s[c] - expected[c]) > 2e-6 * sscale for c in range(6)):
                failures.append("t=%g element %d: ParaView stress %r, frame %r" % (t, eid, s, expected))
                break
        if seen != set(cell_index):
            failures.append("t=%g: ParaView shows elements %r, the frame %r" % (t, sorted(seen), sorted(cell_index)))
    if failures:
        print("ParaView's LS-DYNA reader disagrees with the frames:")
        for f in failures[:20]:
            print("  " + f)
        return 1
    print("ParaView's LS-DYNA reader reads %d states that match the frames" % len(times))
    return 0


if __name__ == "__main__":
    sys.exit(main())
