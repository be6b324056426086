#!/usr/bin/env python3
"""Writes the die-press deck of the flexible-body benchmark (docs/performance.md, "Flexible
bodies"): a die-like solid block (part 1) strikes a blank (part 2) through
*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID, the seed's forming example in small.

  make_die_press.py --die deformable|rigid|flexible [--modes N --form F --mode-file F] OUT.k
  make_die_press.py --die-only OUT.k          (the die alone, for `rigidflex eigen`)

Blank: 0.24 x 0.24 x 0.02 m steel, 30 x 30 x 2 hexahedra (ELFORM 1, IHQ 6), linear elastic
(RigidFlex has no plastic material yet), pinned along the edges of its bottom face. Die:
0.16 x 0.16 x 0.08 m steel, 16 x 16 x 8 hexahedra (ELFORM 2 when deformable), 0.1 mm above
the blank's centre, its nodes not coincident with the blank's (the blank's elements are 8 mm,
the die's 10 mm). The die is driven by an initial velocity of 5 m/s towards the blank (a
drop-hammer stroke): every variant then starts from the same state and is loaded only through
the contact, so the deformable, rigid and flexible dies are physically the same problem. A
prescribed motion would not be: on a rigid or flexible die it fixes the velocity of the centre
of mass, on a deformable die that of a face.
"""
import argparse

PLATE_N, PLATE_LAYERS, PLATE_SIZE, PLATE_T = 30, 2, 0.24, 0.02
DIE_N, DIE_LAYERS, DIE_SIZE, DIE_H = 16, 8, 0.16, 0.08
GAP, SPEED = 1e-4, 5.0
RHO, YOUNG, NU = 7850.0, 2.0e11, 0.3
DIE_FIRST_NODE, DIE_FIRST_ELEMENT = 100001, 100001


def plate_node(i, j, k):
    return 1 + i + (PLATE_N + 1) * (j + (PLATE_N + 1) * k)


def die_node(i, j, k):
    return DIE_FIRST_NODE + i + (DIE_N + 1) * (j + (DIE_N + 1) * k)


def hexa(eid, pid, n):
    def node(di, dj, dk):
        return n(di, dj, dk)

    return "{},{},{},{},{},{},{},{},{},{}\n".format(
        eid, pid, node(0, 0, 0), node(1, 0, 0), node(1, 1, 0), node(0, 1, 0),
        node(0, 0, 1), node(1, 0, 1), node(1, 1, 1), node(0, 1, 1))


def die_mesh():
    s = ["*NODE\n"]
    x0 = 0.5 * (PLATE_SIZE - DIE_SIZE)
    h, hz = DIE_SIZE / DIE_N, DIE_H / DIE_LAYERS
    for k in range(DIE_LAYERS + 1):
        for j in range(DIE_N + 1):
            for i in range(DIE_N + 1):
                s.append("{},{:.9g},{:.9g},{:.9g}\n".format(
                    die_node(i, j, k), x0 + i * h, x0 + j * h, PLATE_T + GAP + k * hz))
    s.append("*ELEMENT_SOLID\n")
    eid = DIE_FIRST_ELEMENT
    for k in range(DIE_LAYERS):
        for j in range(DIE_N):
            for i in range(DIE_N):
                s.append(hexa(eid, 1, lambda a, b, c: die_node(i + a, j + b, k + c)))
                eid += 1
    return "".join(s)


def plate_mesh():
    s = ["*NODE\n"]
    h, hz = PLATE_SIZE / PLATE_N, PLATE_T / PLATE_LAYERS
    for k in range(PLATE_LAYERS + 1):
        for j in range(PLATE_N + 1):
            for i in range(PLATE_N + 1):
                s.append("{},{:.9g},{:.9g},{:.9g}\n".format(plate_node(i, j, k), i * h, j * h,
                                                             k * hz))
    s.append("*ELEMENT_SOLID\n")
    eid = 1
    for k in range(PLATE_LAYERS):
        for j in range(PLATE_N):
            for i in range(PLATE_N):
                s.append(hexa(eid, 2, lambda a, b, c: plate_node(i + a, j + b, k + c)))
                eid += 1
    # Pinned edges: the perimeter of the bottom face.
    edge = [plate_node(i, j, 0) for j in range(PLATE_N + 1) for i in range(PLATE_N + 1)
            if i in (0, PLATE_N) or j in (0, PLATE_N)]
    s.append("*SET_NODE_LIST\n1\n")
    for c in range(0, len(edge), 8):
        s.append(",".join(str(n) for n in edge[c:c + 8]) + "\n")
    s.append("*BOUNDARY_SPC_SET\n1,0,1,1,1,0,0,0\n")
    s.append("*PART\nblank\n2,2,2,0,2\n*SECTION_SOLID\n2,1\n")
    s.append("*MAT_ELASTIC\n2,{},{},{}\n*HOURGLASS\n2,6,0.1\n".format(RHO, YOUNG, NU))
    return "".join(s)


def die_part(die, modes, form, mode_file):
    s = "*PART\ndie\n1,1,1\n*SECTION_SOLID\n1,2\n"
    if die == "deformable":
        return s + "*MAT_ELASTIC\n1,{},{},{}\n".format(RHO, YOUNG, NU)
    s += "*MAT_RIGID\n1,{},{},{}\n0,0,0\n".format(RHO, YOUNG, NU)
    if die == "flexible":
        s += "*PART_MODES\n1,{},{},0,3\n{}\n".format(modes, form, mode_file)
    return s


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out")
    p.add_argument("--die", choices=["deformable", "rigid", "flexible"], default="deformable")
    p.add_argument("--die-only", action="store_true", help="the die alone (eigen analysis)")
    p.add_argument("--modes", type=int, default=10)
    p.add_argument("--form", type=int, default=0)
    p.add_argument("--mode-file", default="die_eigen/modes.h5")
    p.add_argument("--end", type=float, default=1.0e-3, help="termination time (s)")
    a = p.parse_args()
    s = ["*KEYWORD\n*TITLE\ndie press ({})\n".format("die only" if a.die_only else a.die)]
    s.append(die_mesh())
    if a.die_only:
        s.append(die_part("deformable", 0, 0, ""))
        s.append("*CONTROL_TERMINATION\n{:.6g},\n*END\n".format(a.end))
    else:
        s.append(die_part(a.die, a.modes, a.form, a.mode_file))
        s.append(plate_mesh())
        s.append("*INITIAL_VELOCITY_GENERATION\n1,2,0,0,0,{}\n0,0,0,0,0,0\n".format(-SPEED))
        s.append("*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n1,die-blank\n1,2,3,3\n"
                 "0,0,0,0,0\n1,1\n")
        centre = plate_node(PLATE_N // 2, PLATE_N // 2, 0)
        s.append("*DATABASE_HISTORY_NODE\n{}\n".format(centre))
        # Comma after DT: free format (a long number would overrun the 10-column field).
        dt_out = "{:.4g},".format(a.end / 200)
        s.append("*DATABASE_NODOUT\n{0}\n*DATABASE_RCFORC\n{0}\n*DATABASE_GLSTAT\n{0}\n"
                 "*DATABASE_BINARY_D3PLOT\n{1:.6g},\n".format(dt_out, a.end))
        s.append("*CONTROL_TIMESTEP\n0,0.9\n*CONTROL_TERMINATION\n{:.6g},\n*END\n".format(a.end))
    with open(a.out, "w") as f:
        f.write("".join(s))


if __name__ == "__main__":
    main()
