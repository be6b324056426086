#!/usr/bin/env python3
"""Writes examples/switching_spinning_block.k: a free elastic block (1.2 x 0.8 x 0.4 m, 6 x 4 x 2
hexahedra) spinning at 10 rad/s about z, translating and stretching along x, switched rigid at
0.05 s by a paired *DEFORMABLE_TO_RIGID_AUTOMATIC set (DTMAX 5 ms) and back to deformable at
0.12 s. Run it and read switch.csv: the kinetic energy removed is the stretching motion's."""
import sys

nx, ny, nz = 6, 4, 2
lx, ly, lz = 1.2, 0.8, 0.4
w = 10.0


def nid(i, j, k):
    return 1 + i + (nx + 1) * (j + (ny + 1) * k)


out = ["*KEYWORD", "*TITLE", "spinning block switched rigid and back (paired CODE 0 sets)"]
out.append("*NODE")
coords = {}
for k in range(nz + 1):
    for j in range(ny + 1):
        for i in range(nx + 1):
            x, y, z = lx * i / nx - lx / 2, ly * j / ny - ly / 2, lz * k / nz - lz / 2
            coords[nid(i, j, k)] = (x, y, z)
            out.append(f"{nid(i, j, k):8d}{x:16.8f}{y:16.8f}{z:16.8f}")
out.append("*ELEMENT_SOLID")
e = 0
for k in range(nz):
    for j in range(ny):
        for i in range(nx):
            e += 1
            n = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                 nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]
            out.append(f"{e:8d}{1:8d}" + "".join(f"{v:8d}" for v in n))
out += ["*PART", "block", "         1         1         1         0         1",
        "*SECTION_SOLID", "         1         1",
        "*MAT_ELASTIC", "         1    1000.0     1.0E7       0.3",
        "*HOURGLASS", "         1         4       0.1",
        "*INITIAL_VELOCITY_NODE"]
for n, (x, y, z) in coords.items():
    vx = 1.0 - w * y + 0.8 * x
    vy = 0.5 + w * x
    vz = 0.2
    out.append(f"{n:10d}{vx:10.5f}{vy:10.5f}{vz:10.5f}")
out += ["$ switch set 10: rigid at 0.05 s (first of the pair), step capped at 5 ms",
        "*DEFORMABLE_TO_RIGID_AUTOMATIC",
        "$    swset      code     time1     time2     time3     entno     relsw    paired",
        "        10         0      0.05      0.06         0         0        20         1",
        "$     nrbf      ncsf       rwf     dtmax       d2r       r2d    offset",
        "         0         0         0     0.005         1         0",
        "         1",
        "$ switch set 20: deformable again at 0.12 s",
        "*DEFORMABLE_TO_RIGID_AUTOMATIC",
        "        20         0      0.12         0         0         0        10        -1",
        "         0         0         0         0         0         1",
        "         1",
        "*CONTROL_TERMINATION", "       0.2",
        "*DATABASE_GLSTAT", "     0.001",
        "*END"]
sys.stdout.write("\n".join(out) + "\n")
