#!/usr/bin/env python3
"""Benchmark deck: an N x N x N elastic steel cube (0.1 m) hitting a fixed plane at 10 m/s.

The plane is modelled by fixing the z translation of the cube's bottom face from t = 0 (the
cube arrives with all other nodes moving at -10 m/s), so a compressive wave runs up the cube.
Usage: make_cube_deck.py N [ELFORM] [IHQ] [CYCLES] [MATERIAL] > cube.k
The run ends after CYCLES cycles (default 200) so timings are comparable between sizes.
MATERIAL: elastic (default, *MAT_ELASTIC) or mat003 (*MAT_PLASTIC_KINEMATIC, SIGY 200 MPa,
ETAN 2 GPa, BETA 1: the impact stress rho c v = 460 MPa yields the elements near the plane),
mr (*MAT_MOONEY-RIVLIN_RUBBER, A 0.4 MPa, B 0.1 MPa, PR 0.495) or ogden (*MAT_OGDEN_RUBBER,
three terms mu 0.63, 0.0012, -0.01 MPa, alpha 1.3, 5, -2, PR 0.495); rubber density 1100;
jc (*MAT_JOHNSON_COOK with *EOS_LINEAR_POLYNOMIAL: G and K of the elastic steel, A 200 MPa,
B 400 MPa, N 0.3, C 0.02, M 1, TM 1800 K, TR 293 K, CP 450, PC -1e20, SPALL 1).
"""
import sys

n = int(sys.argv[1])
elform = int(sys.argv[2]) if len(sys.argv) > 2 else 1
ihq = int(sys.argv[3]) if len(sys.argv) > 3 else 1
cycles = int(sys.argv[4]) if len(sys.argv) > 4 else 200
material = sys.argv[5] if len(sys.argv) > 5 else "elastic"
size = 0.1
w = sys.stdout.write

def nid(i, j, k):
    return 1 + i + (n + 1) * (j + (n + 1) * k)

w("*KEYWORD\n*TITLE\nbenchmark cube %d^3 ELFORM %d IHQ %d\n" % (n, elform, ihq))
w("*CONTROL_TERMINATION\n%10.4g%10d\n" % (1.0, cycles))
w("*CONTROL_HOURGLASS\n%10d%10.4g\n" % (ihq, 0.1))
w("*DATABASE_GLSTAT\n%10.4g\n" % 1.0)
w("*DATABASE_BINARY_D3PLOT\n%10.4g\n" % 1.0)
w("*PART\ncube\n%10d%10d%10d%10d\n" % (1, 1, 1, 1 if material == "jc" else 0))
w("*SECTION_SOLID\n%10d%10d\n" % (1, elform))
if material == "elastic":
    w("*MAT_ELASTIC\n%10d%10.4g%10.4g%10.4g\n" % (1, 7850.0, 210e9, 0.3))
elif material == "mat003":
    w("*MAT_PLASTIC_KINEMATIC\n%10d%10.4g%10.4g%10.4g%10.4g%10.4g%10.4g\n"
      % (1, 7850.0, 210e9, 0.3, 200e6, 2e9, 1.0))
elif material == "mr":
    w("*MAT_MOONEY-RIVLIN_RUBBER\n%10d%10.4g%10.4g%10.4g%10.4g\n%10d\n"
      % (1, 1100.0, 0.495, 0.4e6, 0.1e6, 0))
elif material == "ogden":
    w("*MAT_OGDEN_RUBBER\n%10d%10.4g%10.4g%10d\n%10.4g%10.4g%10.4g\n%10.4g%10.4g%10.4g\n"
      % (1, 1100.0, 0.495, 0, 0.63e6, 0.0012e6, -0.01e6, 1.3, 5.0, -2.0))
elif material == "jc":
    g, k = 210e9 / 2.6, 210e9 / 1.2
    w("*MAT_JOHNSON_COOK\n%10d%10.4g%10.4g\n" % (1, 7850.0, g))
    w("%10.4g%10.4g%10.4g%10.4g%10.4g%10.4g%10.4g%10.4g\n"
      % (200e6, 400e6, 0.3, 0.02, 1.0, 1800.0, 293.0, 1.0))
    w("%10.4g%10.4g%10.4g\n" % (450.0, -1e20, 1.0))
    w("*EOS_LINEAR_POLYNOMIAL\n%10d%10.4g%10.4g\n" % (1, 0.0, k))
else:
    sys.exit("MATERIAL must be elastic, mat003, mr, ogden or jc")
w("*NODE\n")
for k in range(n + 1):
    for j in range(n + 1):
        for i in range(n + 1):
            w("%8d%16.8g%16.8g%16.8g\n" % (nid(i, j, k), size * i / n, size * j / n, size * k / n))
w("*ELEMENT_SOLID\n")
e = 0
for k in range(n):
    for j in range(n):
        for i in range(n):
            e += 1
            c = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                 nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]
            w("%8d%8d" % (e, 1) + "".join("%8d" % x for x in c) + "\n")
bottom = [nid(i, j, 0) for j in range(n + 1) for i in range(n + 1)]
w("*SET_NODE_LIST\n%10d\n" % 1)
for c in range(0, len(bottom), 8):
    w("".join("%10d" % x for x in bottom[c:c + 8]) + "\n")
w("*BOUNDARY_SPC_SET\n%10d%10d%10d%10d%10d\n" % (1, 0, 0, 0, 1))
# NSIDEX = 1 exempts the bottom face; its nodes get the card-3 velocity (zero).
w("*INITIAL_VELOCITY\n%10d%10d\n%10.4g%10.4g%10.4g\n%10.4g%10.4g%10.4g\n"
  % (0, 1, 0.0, 0.0, -10.0, 0.0, 0.0, 0.0))
w("*END\n")
