#!/usr/bin/env python3
"""Writes examples/ball_drop_switching.k: an elastic ball (radius 0.1 m, rho 1000, E 1 MPa,
864 hexahedra) 0.01 m above a fixed *RIGIDWALL_PLANAR, moving down at 1 m/s under gravity, with a
paired *DEFORMABLE_TO_RIGID_AUTOMATIC pair on wall 1: set 10 (CODE 1, wall force zero) makes it
rigid (step DTMAX 1 ms), set 20 (CODE 3, force nonzero or a node within OFFSET 3 mm) makes it
deformable just before it touches. TIME3 keeps each set from undoing the other at once: 20 ms
after set 20 (the approach through the OFFSET zone has zero force), 5 ms after set 10 (the
rebounding ball is still within OFFSET). Expected switch.csv: rigid at 0, deformable at 7.2 ms,
rigid at 38.9 ms, after contact from 9.1 to 38.0 ms (tests/verification/switching_wall_test.cpp
builds the same deck).

  python3 examples/make_ball_drop.py > examples/ball_drop_switching.k

The mesh: an inner block of (2m)^3 hexahedra, the cube [-a, a]^3 with its concentric cube surfaces
blended halfway to spheres (so its corners are not right angles that would flatten the shell
elements there), and on each of its six faces (2m)^2 x LAYERS hexahedra along rays from the inner
block's surface to the sphere. Smallest scaled corner Jacobian 0.71."""
import math
import sys

M, LAYERS = 3, 3
RADIUS, INNER, ROUNDING = 0.1, 0.05, 0.5
GAP, V0, G = 0.01, 1.0, 9.81
CENTRE = (0.0, 0.0, RADIUS + GAP)


def inner_point(c):
    euclid = math.sqrt(sum(v * v for v in c))
    if euclid == 0.0:
        return (0.0, 0.0, 0.0)
    cube = max(abs(v) for v in c)
    return tuple(INNER * ((1.0 - ROUNDING) * v + ROUNDING * v * cube / euclid) for v in c)


def position(g, layer):
    c = tuple(v / M for v in g)
    t = layer / LAYERS
    p = inner_point(c)
    if layer > 0:
        euclid = math.sqrt(sum(v * v for v in c))
        p = tuple((1.0 - t) * p[k] + t * RADIUS * c[k] / euclid for k in range(3))
    return tuple(p[k] + CENTRE[k] for k in range(3))


def elements():
    """Each element as 8 (grid point, layer) corners in LS-DYNA order (positive volume)."""
    out = []
    for k in range(-M, M):
        for j in range(-M, M):
            for i in range(-M, M):
                g = lambda a, b, c: ((i + a, j + b, k + c), 0)
                out.append([g(0, 0, 0), g(1, 0, 0), g(1, 1, 0), g(0, 1, 0),
                            g(0, 0, 1), g(1, 0, 1), g(1, 1, 1), g(0, 1, 1)])
    for d in range(3):
        for s in (-1, 1):
            u_axis, v_axis = (d + 1) % 3, (d + 2) % 3
            if s < 0:
                u_axis, v_axis = v_axis, u_axis
            for u in range(-M, M):
                for v in range(-M, M):
                    for layer in range(LAYERS):
                        def g(a, b, lay):
                            p = [0, 0, 0]
                            p[d], p[u_axis], p[v_axis] = s * M, u + a, v + b
                            return (tuple(p), lay)
                        out.append([g(0, 0, layer), g(1, 0, layer), g(1, 1, layer),
                                    g(0, 1, layer), g(0, 0, layer + 1), g(1, 0, layer + 1),
                                    g(1, 1, layer + 1), g(0, 1, layer + 1)])
    return out


ids, nodes, connectivity = {}, [], []
for element in elements():
    row = []
    for corner in element:
        if corner not in ids:
            ids[corner] = len(nodes) + 1
            nodes.append(position(*corner))
        row.append(ids[corner])
    connectivity.append(row)

out = ["*KEYWORD", "*TITLE", "elastic ball dropped on a rigid wall, rigid in flight (paired CODE 1/3)",
       "*NODE"]
for n, (x, y, z) in enumerate(nodes, start=1):
    out.append(f"{n:8d}{x:16.12f}{y:16.12f}{z:16.12f}")
out.append("*ELEMENT_SOLID")
for e, row in enumerate(connectivity, start=1):
    out.append(f"{e:8d}{1:8d}" + "".join(f"{v:8d}" for v in row))
out += ["*PART", "ball", "         1         1         1         0         1",
        "*SECTION_SOLID", "         1         1",
        "*MAT_ELASTIC", "         1    1000.0     1.0E6       0.3",
        "*HOURGLASS", "         1         6       0.1",
        "*INITIAL_VELOCITY_GENERATION",
        "$       id      styp     omega        vx        vy        vz",
        f"         1         2       0.0       0.0       0.0{-V0:10.4f}",
        "       0.0       0.0       0.0       0.0       0.0       0.0",
        "$ gravity along -z: *LOAD_BODY_Z takes the base acceleration",
        "*LOAD_BODY_Z", "         9       1.0",
        "*DEFINE_CURVE", "         9", f"{0.0:20.1f}{G:20.4f}", f"{1e3:20.1f}{G:20.4f}",
        "*RIGIDWALL_PLANAR", "         0",
        "       0.0       0.0       0.0       0.0       0.0       1.0",
        "$ set 10: rigid while wall 1 pushes nothing (armed first); rigid step 1 ms",
        "*DEFORMABLE_TO_RIGID_AUTOMATIC",
        "$    swset      code     time1     time2     time3     entno     relsw    paired",
        "        10         1       0.0       0.0     0.005         1        20         1",
        "$     nrbf      ncsf       rwf     dtmax       d2r       r2d    offset",
        "         0         0         0     0.001         1         0",
        "         1",
        "$ set 20: deformable once the wall pushes or a node is within 3 mm of it",
        "*DEFORMABLE_TO_RIGID_AUTOMATIC",
        "        20         3       0.0       0.0      0.02         1        10        -1",
        "         0         0         0       0.0         0         1     0.003",
        "         1",
        "*CONTROL_TERMINATION", "      0.09",
        "*DATABASE_GLSTAT", "    0.0005",
        "*DATABASE_RWFORC", "    0.0005",
        "*DATABASE_RBDOUT", "    0.0005",
        "*DATABASE_BINARY_D3PLOT", "     0.002",
        "*END"]
sys.stdout.write("\n".join(out) + "\n")
