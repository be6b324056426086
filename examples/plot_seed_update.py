#!/usr/bin/env python3
"""Runs the IMPETUS *RIGID_BODY_UPDATE seed deck for %type = 0, 1, 2 and draws the free end
face of the rigid cylinder after its 4*pi rotation (docs/images/seed_rigid_body_update.svg).

Usage: examples/plot_seed_update.py [path/to/rigidflex] [output.svg]
Only the Python standard library is used: the VTU files are read directly (raw appended data,
UInt64 headers, as docs/output.md describes).
"""
import json
import math
import pathlib
import re
import struct
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
DECK = HERE / "seed_rigid_body_update.k"


def read_vtu_arrays(path):
    data = path.read_bytes()
    header_end = data.index(b"<AppendedData")
    raw_start = data.index(b"_", header_end) + 1
    xml = data[:header_end].decode()
    arrays = {}
    for m in re.finditer(r'<DataArray([^>]*)>', xml):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        if "offset" not in attrs:
            continue
        start = raw_start + int(attrs["offset"])
        nbytes = struct.unpack_from("<Q", data, start)[0]
        fmt = {"Float64": "d", "Int64": "q", "UInt8": "B"}[attrs["type"]]
        count = nbytes // struct.calcsize(fmt)
        arrays[attrs["Name"]] = struct.unpack_from("<%d%s" % (count, fmt), data, start + 8)
    return arrays


def end_face(rigidflex, update_type, workdir):
    out = pathlib.Path(workdir) / ("type%d" % update_type)
    subprocess.run([rigidflex, "run", str(DECK), "-o", str(out), "--quiet", "--set",
                    "type=%d" % update_type], check=True)
    run = json.loads((out / "run.json").read_text())
    rows = (out / "glstat.csv").read_text().strip().splitlines()
    header, final = rows[0].split(","), rows[-1].split(",")
    run["energy_ratio"] = float(final[header.index("energy_ratio")])
    last = sorted(out.glob("frames_*.vtu"))[-1]
    a = read_vtu_arrays(last)
    pts, disp = a["Points"], a["displacement"]
    face = []
    for i in range(len(pts) // 3):
        x, y, z = pts[3 * i:3 * i + 3]
        z0 = z - disp[3 * i + 2]
        if abs(z0 - 1.15) < 1e-9:
            x0, y0 = x - disp[3 * i], y - disp[3 * i + 1]
            face.append((x, y, math.hypot(x, y) - math.hypot(x0, y0)))
    err = max(abs(f[2]) for f in face)
    return face, err, run


def svg(panels, path):
    size, gap = 300, 30
    width = len(panels) * size + (len(panels) + 1) * gap
    height = size + 90
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
           'font-family="sans-serif" font-size="13">' % (width, height),
           '<rect width="100%" height="100%" fill="white"/>']
    scale = size / 2 / 0.056
    for k, (title, face, err, run) in enumerate(panels):
        cx = gap + k * (size + gap) + size / 2
        cy = 40 + size / 2
        out.append('<circle cx="%.1f" cy="%.1f" r="%.1f" fill="none" stroke="#888" '
                   'stroke-dasharray="4 3"/>' % (cx, cy, 0.05 * scale))
        for x, y, _ in face:
            out.append('<circle cx="%.2f" cy="%.2f" r="1.6" fill="#c0392b"/>'
                       % (cx + x * scale, cy - y * scale))
        out.append('<text x="%.1f" y="24" text-anchor="middle" font-weight="bold">%s</text>'
                   % (cx, title))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">max radial error %.2e m</text>'
                   % (cx, height - 38, err))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">%d cycles, energy ratio %s</text>'
                   % (cx, height - 18, run["cycles"], "%.9f" % run["energy_ratio"]))
    out.append("</svg>")
    pathlib.Path(path).write_text("\n".join(out) + "\n")


def main():
    rigidflex = sys.argv[1] if len(sys.argv) > 1 else str(HERE.parent / "build" / "rigidflex")
    target = sys.argv[2] if len(sys.argv) > 2 else str(
        HERE.parent / "docs" / "images" / "seed_rigid_body_update.svg")
    panels = []
    with tempfile.TemporaryDirectory() as work:
        for t in (0, 1, 2):
            face, err, run = end_face(rigidflex, t, work)
            print("type %d: %d end-face nodes, max radial error %.3e m, %d cycles, %s"
                  % (t, len(face), err, run["cycles"], run["status"]))
            panels.append(("%%type = %d" % t, face, err, run))
    pathlib.Path(target).parent.mkdir(parents=True, exist_ok=True)
    svg(panels, target)
    print("wrote", target)


if __name__ == "__main__":
    main()
