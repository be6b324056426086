#!/usr/bin/env python3
"""Writes a free-free steel plate of hexahedra as an LS-DYNA deck for the eigen benchmark.

usage: eigen_make_plate.py OUT.k NX NY NZ [--elform 2] [--neig 20]
The plate is 2.5 mm elements, NX x NY x NZ of them (100 x 40 x 7 gives 99,384 DOFs), units
t, mm, s (frequencies in Hz). The deck asks for NEIG modes with LFLAG 1 (rigid modes removed).
"""
import argparse

p = argparse.ArgumentParser()
p.add_argument("out")
p.add_argument("nx", type=int)
p.add_argument("ny", type=int)
p.add_argument("nz", type=int)
p.add_argument("--elform", type=int, default=2)
p.add_argument("--neig", type=int, default=20)
p.add_argument("--size", type=float, default=2.5)
a = p.parse_args()
nx, ny, nz, h = a.nx, a.ny, a.nz, a.size


def nid(i, j, k):
    return 1 + i + (nx + 1) * (j + (ny + 1) * k)


with open(a.out, "w") as f:
    f.write("*KEYWORD\n*TITLE\nfree-free plate %d x %d x %d hexahedra\n" % (nx, ny, nz))
    f.write("*CONTROL_IMPLICIT_GENERAL\n1,0.001\n")
    f.write("*CONTROL_IMPLICIT_EIGENVALUE\n%d,0.0,1,1.0\n" % a.neig)
    f.write("*PART\nplate\n1,1,1,0,1\n*SECTION_SOLID\n1,%d\n" % a.elform)
    f.write("*MAT_ELASTIC\n1,7.8e-9,2.1e5,0.3\n*HOURGLASS\n1,6,1.0\n*NODE\n")
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                f.write("%d,%.6f,%.6f,%.6f\n" % (nid(i, j, k), h * i, h * j, h * k))
    f.write("*ELEMENT_SOLID\n")
    e = 0
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                e += 1
                n = (nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                     nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1),
                     nid(i, j + 1, k + 1))
                f.write("%d,1,%s\n" % (e, ",".join(map(str, n))))
    f.write("*END\n")
