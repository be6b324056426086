#!/usr/bin/env python3
"""modes_NNNN.vtu convention (docs/output.md#modespvd-and-modes_nnnnvtu), checked against the deck:

- points - mode_scale * displacement = the deck's *NODE coordinates (the reference mesh);
- the largest |mode_scale * displacement| is 10 % of the reference bounding-box diagonal;
- `displacement` is the true mass-normalised shape: phi^T M phi = 1 with the lumped mass
  M = sum over elements rho V_e / 8 computed here from the deck (brick elements).

Usage: modes_check.py RIGIDFLEX DECK WORKDIR
"""
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import read_pvd, read_vtu  # noqa: E402


def read_deck(path):
    nodes, elements, rho, section = {}, [], None, None
    for line in open(path):
        if line.startswith("$"):
            continue
        if line.startswith("*"):
            section = line.strip().upper()
            continue
        if section == "*NODE":
            nodes[int(line[0:8])] = tuple(float(line[8 + 16 * k:24 + 16 * k]) for k in range(3))
        elif section == "*ELEMENT_SOLID":
            f = [int(line[8 * k:8 * k + 8]) for k in range(10)]
            elements.append(f[2:])
        elif section == "*MAT_ELASTIC" and rho is None:
            rho = float(line[10:20])
    return nodes, elements, rho


def main():
    rigidflex, deck, work = sys.argv[1:4]
    out = os.path.join(work, "out")
    subprocess.run([rigidflex, "run", deck, "-o", out, "--threads", "1", "--quiet"], check=True)
    nodes, elements, rho = read_deck(deck)
    mass = {n: 0.0 for n in nodes}
    for e in elements:
        xyz = [nodes[n] for n in e]
        size = [max(p[k] for p in xyz) - min(p[k] for p in xyz) for k in range(3)]
        for n in set(e):
            mass[n] += rho * size[0] * size[1] * size[2] / 8.0
    lo = [min(p[k] for p in nodes.values()) for k in range(3)]
    hi = [max(p[k] for p in nodes.values()) for k in range(3)]
    diagonal = math.dist(lo, hi)
    failures = []
    modes = read_pvd(os.path.join(out, "modes.pvd"))
    for number, name in modes:
        f = read_vtu(os.path.join(out, name))
        s = f["field_data"]["mode_scale"][0]
        phi = f["point_data"]["displacement"]
        ids = f["point_data"]["node_id"]
        largest = max(math.hypot(*p) for p in phi) * s
        if abs(largest - 0.1 * diagonal) > 1e-12 * diagonal:
            failures.append("mode %g: largest drawn displacement %r, 10 %% of the diagonal %r" % (number, largest, 0.1 * diagonal))
        for i, nid in enumerate(ids):
            x0 = [f["points"][i][k] - s * phi[i][k] for k in range(3)]
            if math.dist(x0, nodes[nid]) > 1e-12 * diagonal:
                failures.append("mode %g node %d: points - s phi = %r, *NODE %r" % (number, nid, x0, nodes[nid]))
                break
        generalized = sum(mass[nid] * (p[0] ** 2 + p[1] ** 2 + p[2] ** 2) for nid, p in zip(ids, phi))
        if abs(generalized - 1.0) > 1e-6:
            failures.append("mode %g: phi^T M phi = %r, not 1" % (number, generalized))
    if len(modes) < 2:
        failures.append("only %d modes written" % len(modes))
    if failures:
        print("modes check failed:")
        for f in failures[:20]:
            print("  " + f)
        return 1
    print("modes match: %d modes drawn at 10 %% of the diagonal %.6g, displacement mass-normalised" % (len(modes), diagonal))
    return 0


if __name__ == "__main__":
    sys.exit(main())
