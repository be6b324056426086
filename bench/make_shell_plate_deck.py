#!/usr/bin/env python3
"""Benchmark deck: an N x N plate of 4-node shells (1 m square, 2 mm steel) clamped on one edge,
its other nodes moving out of plane at 1 m/s, so the plate bends from the first cycle.

Usage: make_shell_plate_deck.py N [NIP] [IHQ] [CYCLES] [MATERIAL] [PRESSURE] [ELFORM] [ISTUPD] > plate.k
MATERIAL: elastic (default), mat024 (*MAT_PIECEWISE_LINEAR_PLASTICITY, SIGY 200 MPa,
ETAN 1 GPa) or mat036 (*MAT_3-PARAMETER_BARLAT, the same linear hardening, M 6, R00 1.8,
R45 1.4, R90 2.1, AOPT 2 with the rolling direction at 30 degrees to x). PRESSURE (Pa, optional): a constant follower pressure on every shell through
*LOAD_SEGMENT_SET (one segment per shell; the pressure-load benchmark and MPI test). The run ends after CYCLES cycles (default 200): compare ns per element-cycle
(`rigidflex run` prints the wall time; d3hsp.txt has the phase times) with the hexahedron cube
of make_cube_deck.py.
"""
import sys

n = int(sys.argv[1])
nip = int(sys.argv[2]) if len(sys.argv) > 2 else 2
ihq = int(sys.argv[3]) if len(sys.argv) > 3 else 1
cycles = int(sys.argv[4]) if len(sys.argv) > 4 else 200
material = sys.argv[5] if len(sys.argv) > 5 else "elastic"
pressure = float(sys.argv[6]) if len(sys.argv) > 6 and sys.argv[6] != "none" else None
# ELFORM (optional, default 2): 16 for the fully integrated shell (PRESSURE "none" to skip it).
elform = int(sys.argv[7]) if len(sys.argv) > 7 else 2
# ISTUPD (optional, default 0): *CONTROL_SHELL thickness update (1 or 4).
istupd = int(sys.argv[8]) if len(sys.argv) > 8 else 0
size = 1.0
w = sys.stdout.write


def nid(i, j):
    return 1 + i + (n + 1) * j


w("*KEYWORD\n*TITLE\nbenchmark plate %d x %d shells NIP %d IHQ %d\n" % (n, n, nip, ihq))
w("*CONTROL_TERMINATION\n%10.4g%10d\n" % (1.0, cycles))
w("*DATABASE_GLSTAT\n%10.4g\n" % 1.0)
w("*DATABASE_BINARY_D3PLOT\n%10.4g\n" % 1.0)
if istupd:
    w("*CONTROL_SHELL\n%10.4g%10d%10d%10d\n" % (20.0, 0, -1, istupd))
w("*PART\nplate\n%10d%10d%10d%10d%10d\n" % (1, 1, 1, 0, 1))
w("*SECTION_SHELL\n%10d%10d%10.4g%10d\n%10.4g\n" % (1, elform, 0.8333, nip, 0.002))
w("*HOURGLASS\n%10d%10d%10.4g\n" % (1, ihq, 0.05))
if material == "elastic":
    w("*MAT_ELASTIC\n%10d%10.4g%10.4g%10.4g\n" % (1, 7850.0, 210e9, 0.3))
elif material == "mat024":
    w("*MAT_PIECEWISE_LINEAR_PLASTICITY\n%10d%10.4g%10.4g%10.4g%10.4g%10.4g\n"
      % (1, 7850.0, 210e9, 0.3, 200e6, 1e9))
elif material == "mat036":
    w("*MAT_3-PARAMETER_BARLAT\n%10d%10.4g%10.4g%10.4g%10d%10.4g%10.4g%10d\n"
      % (1, 7850.0, 210e9, 0.3, 1, 1e9, 200e6, 0))
    w("%10.4g%10.4g%10.4g%10.4g\n" % (6.0, 1.8, 1.4, 2.1))
    w("%10d\n" % 2)
    w("%10.4g%10.4g%10.4g%10.4g%10.4g%10.4g\n" % (0, 0, 0, 0.8660254, 0.5, 0))
    w("%10.4g\n" % 0)
else:
    sys.exit("MATERIAL must be elastic, mat024 or mat036")
w("*NODE\n")
for j in range(n + 1):
    for i in range(n + 1):
        w("%8d%16.8g%16.8g%16.8g\n" % (nid(i, j), size * i / n, size * j / n, 0.0))
w("*ELEMENT_SHELL\n")
e = 0
for j in range(n):
    for i in range(n):
        e += 1
        w("%8d%8d%8d%8d%8d%8d\n" % (e, 1, nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)))
w("*SET_NODE_LIST\n%10d\n" % 1)
edge = [nid(0, j) for j in range(n + 1)]
for k in range(0, len(edge), 8):
    w("".join("%10d" % x for x in edge[k:k + 8]) + "\n")
w("*BOUNDARY_SPC_SET\n%10d%10d%10d%10d%10d%10d%10d%10d\n" % (1, 0, 1, 1, 1, 1, 1, 1))
w("*INITIAL_VELOCITY_NODE\n")
for j in range(n + 1):
    for i in range(1, n + 1):
        w("%d,0,0,1.0\n" % nid(i, j))
if pressure is not None:
    w("*SET_SEGMENT\n%10d\n" % 1)
    for j in range(n):
        for i in range(n):
            w("%10d%10d%10d%10d\n" % (nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)))
    w("*LOAD_SEGMENT_SET\n%10d%10d%10.4g\n" % (1, 9, pressure))
    w("*DEFINE_CURVE\n%10d\n%20.8g%20.8g\n%20.8g%20.8g\n" % (9, 0.0, 1.0, 1.0, 1.0))
w("*END\n")
