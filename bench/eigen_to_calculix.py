#!/usr/bin/env python3
"""Converts a simple LS-DYNA solid deck (*NODE, *ELEMENT_SOLID with 8 distinct nodes, one
*MAT_ELASTIC) into a CalculiX input file with a *FREQUENCY step on the identical mesh.

usage: eigen_to_calculix.py DECK.k OUT.inp --modes N [--element C3D8]
Free-format (comma) and fixed-width (8/16-column) cards are read; only what the benchmark
decks contain is supported. CalculiX's C3D8 is the fully integrated 8-node brick (our ELFORM 2
is selective-reduced); CalculiX uses a consistent mass matrix, ours is lumped.
"""
import argparse
import sys

p = argparse.ArgumentParser()
p.add_argument("deck")
p.add_argument("out")
p.add_argument("--modes", type=int, required=True)
p.add_argument("--element", default="C3D8")
a = p.parse_args()


def fields(line, widths):
    if "," in line:
        return [s.strip() for s in line.split(",")]
    out, pos = [], 0
    for w in widths:
        out.append(line[pos:pos + w].strip())
        pos += w
    return out


nodes, elements, material = [], [], None
section = None
with open(a.deck) as f:
    for raw in f:
        line = raw.rstrip("\n")
        if line.startswith("$") or not line.strip():
            continue
        if line.startswith("*"):
            section = line.strip().upper()
            continue
        if section == "*NODE":
            v = fields(line, [8, 16, 16, 16])
            nodes.append((int(v[0]), float(v[1]), float(v[2]), float(v[3])))
        elif section == "*ELEMENT_SOLID":
            v = fields(line, [8] * 10)
            elements.append((int(v[0]), [int(x) for x in v[2:10]]))
        elif section in ("*MAT_ELASTIC", "*MAT_001") and material is None:
            v = fields(line, [10] * 4)
            material = (float(v[1]), float(v[2]), float(v[3]))
if material is None:
    sys.exit("no *MAT_ELASTIC in the deck")
rho, e, nu = material
with open(a.out, "w") as f:
    f.write("** converted from %s by bench/eigen_to_calculix.py\n*NODE, NSET=NALL\n" % a.deck)
    for n in nodes:
        f.write("%d,%.9g,%.9g,%.9g\n" % n)
    # LS-DYNA and CalculiX C3D8 share the node order (bottom face, then top face).
    f.write("*ELEMENT, TYPE=%s, ELSET=EALL\n" % a.element)
    for eid, c in elements:
        if len(set(c)) != 8:
            sys.exit("element %d is degenerate: not supported by the converter" % eid)
        f.write("%d,%s\n" % (eid, ",".join(map(str, c))))
    f.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n%.9g,%.9g\n*DENSITY\n%.9g\n" % (e, nu, rho))
    f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n")
    f.write("*STEP\n*FREQUENCY\n%d\n*NODE FILE\nU\n*END STEP\n" % a.modes)
