#!/usr/bin/python3
"""rigidflex-plot: PNG plots of a RigidFlex run's histories, without writing code.

    rigidflex-plot DIR [-o OUTDIR]

Reads the CSV files of an output directory (docs/output.md) and writes, into OUTDIR (default
DIR), the plots whose data exist:

  plot_energies.png  glstat.csv: energies vs time, and the energy ratio below
  plot_nodout.png    nodout.csv: displacement and velocity of each history node
  plot_rbdout.png    rbdout.csv: centre displacement, velocity and angular velocity per body
  plot_forces.png    rcforc.csv / rwforc.csv: contact and rigid-wall force magnitudes
  plot_secforc.png   secforc.csv: normal force and resultant moment of each cross section

Part switches (switch.csv) are marked on every time axis as vertical lines. Columns are taken
by name, so files with more columns (appended later) still plot. Needs matplotlib (Debian:
python3-matplotlib, installed by scripts/install-deps.sh); exits with status 77 when it is
missing, so that tests can skip.
"""

import argparse
import csv
import math
import os
import sys

SKIP_STATUS = 77  # ctest SKIP_RETURN_CODE


def read_csv(path):
    """Columns of a CSV file as {name: [float, ...]}, or None when the file is absent or empty."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        return None
    header = rows[0]
    columns = {name: [] for name in header}
    for row in rows[1:]:
        if len(row) != len(header):
            continue  # not ours to judge here; a cut row is skipped
        for name, value in zip(header, row):
            try:
                columns[name].append(float(value))
            except ValueError:
                columns[name].append(math.nan)
    return columns


def read_switches(directory):
    """Times and labels of the part switches in switch.csv."""
    path = os.path.join(directory, "switch.csv")
    if not os.path.isfile(path):
        return []
    events = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            try:
                events.append((float(row["time"]), f"{row.get('direction', '')} {row.get('parts', '')}".strip()))
            except (KeyError, ValueError):
                continue
    return events


def group_by(columns, key):
    """Splits a multi-entity history (nodout: node, rbdout: body, ...) into one per entity."""
    groups = {}
    for i, entity in enumerate(columns[key]):
        g = groups.setdefault(int(entity), {name: [] for name in columns})
        for name, values in columns.items():
            g[name].append(values[i])
    return groups


def mark_switches(axes, switches):
    for ax in axes:
        for k, (t, label) in enumerate(switches):
            ax.axvline(t, color="0.4", linestyle=":", linewidth=1.0,
                       label="part switch" if k == 0 else None)


def finish(fig, axes, path, written):
    for ax in axes:
        ax.grid(True, alpha=0.3)
        handles, labels = ax.get_legend_handles_labels()
        if handles:
            ax.legend(fontsize="small", loc="best")
    axes[-1].set_xlabel("time")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    written.append(path)


def plot_energies(plt, directory, out, switches, written):
    g = read_csv(os.path.join(directory, "glstat.csv"))
    if g is None:
        return
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
    t = g["time"]
    for name in ("kinetic_energy", "internal_energy", "hourglass_energy", "external_work",
                 "total_energy", "contact_energy", "switch_energy", "rigidwall_work",
                 "modal_energy"):
        values = g.get(name)
        if values and any(abs(v) > 0.0 for v in values if not math.isnan(v)):
            top.plot(t, values, label=name)
    top.set_ylabel("energy")
    top.set_title(f"energies: {os.path.abspath(directory)}")
    ratio = g["energy_ratio"]
    bottom.plot(t, ratio, color="k", label="energy_ratio")
    bottom.set_ylabel("energy ratio")
    # A conserving run stays at 1 to round-off: show it against a +-10 % band, not magnified.
    finite = [r for r in ratio if not math.isnan(r)] or [1.0]
    bottom.set_ylim(min(0.9, min(finite) - 0.01), max(1.1, max(finite) + 0.01))
    bottom.ticklabel_format(axis="y", useOffset=False)
    mark_switches((top, bottom), switches)
    finish(fig, (top, bottom), os.path.join(out, "plot_energies.png"), written)
    plt.close(fig)


def plot_nodout(plt, directory, out, switches, written):
    n = read_csv(os.path.join(directory, "nodout.csv"))
    if n is None:
        return
    nodes = group_by(n, "node")
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    for node, h in sorted(nodes.items())[:12]:  # a readable number of curves
        x0, y0, z0 = h["x"][0], h["y"][0], h["z"][0]
        u = [math.sqrt((x - x0) ** 2 + (y - y0) ** 2 + (z - z0) ** 2)
             for x, y, z in zip(h["x"], h["y"], h["z"])]
        v = [math.sqrt(a * a + b * b + c * c) for a, b, c in zip(h["vx"], h["vy"], h["vz"])]
        top.plot(h["time"], u, label=f"node {node}")
        bottom.plot(h["time"], v, label=f"node {node}")
    top.set_ylabel("|displacement|")
    top.set_title("node histories (nodout.csv)")
    bottom.set_ylabel("|velocity|")
    mark_switches((top, bottom), switches)
    finish(fig, (top, bottom), os.path.join(out, "plot_nodout.png"), written)
    plt.close(fig)


def plot_rbdout(plt, directory, out, switches, written):
    r = read_csv(os.path.join(directory, "rbdout.csv"))
    if r is None:
        return
    bodies = group_by(r, "body")
    fig, axes = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    for body, h in sorted(bodies.items())[:8]:
        for k, c in enumerate("xyz"):
            u = [value - h[c][0] for value in h[c]]
            axes[0].plot(h["time"], u, label=f"body {body} {c}")
            axes[1].plot(h["time"], h["v" + c], label=f"body {body} v{c}")
            axes[2].plot(h["time"], h["w" + c], label=f"body {body} w{c}")
    axes[0].set_ylabel("centre displacement")
    axes[0].set_title("rigid bodies (rbdout.csv)")
    axes[1].set_ylabel("velocity")
    axes[2].set_ylabel("angular velocity")
    mark_switches(axes, switches)
    finish(fig, axes, os.path.join(out, "plot_rbdout.png"), written)
    plt.close(fig)


def plot_forces(plt, directory, out, switches, written):
    contacts = read_csv(os.path.join(directory, "rcforc.csv"))
    walls = read_csv(os.path.join(directory, "rwforc.csv"))
    if contacts is None and walls is None:
        return
    fig, ax = plt.subplots(1, 1, figsize=(9, 5))
    if contacts is not None:
        for cid, h in sorted(group_by(contacts, "contact").items()):
            f = [math.sqrt(a * a + b * b + c * c)
                 for a, b, c in zip(h["slave_fx"], h["slave_fy"], h["slave_fz"])]
            ax.plot(h["time"], f, label=f"contact {cid}")
    if walls is not None:
        for wid, h in sorted(group_by(walls, "wall").items()):
            ax.plot(h["time"], h["normal_force"], label=f"rigid wall {wid} (normal)")
    ax.set_ylabel("force")
    ax.set_title("contact and rigid-wall forces (rcforc.csv, rwforc.csv)")
    mark_switches((ax,), switches)
    finish(fig, (ax,), os.path.join(out, "plot_forces.png"), written)
    plt.close(fig)


def plot_secforc(plt, directory, out, switches, written):
    sections = read_csv(os.path.join(directory, "secforc.csv"))
    if sections is None:
        return
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    for sid, h in sorted(group_by(sections, "section").items()):
        top.plot(h["time"], h["normal_force"], label=f"section {sid} normal")
        top.plot(h["time"], h["force_resultant"], "--", label=f"section {sid} resultant")
        bottom.plot(h["time"], h["moment_resultant"], label=f"section {sid}")
    top.set_ylabel("force")
    bottom.set_ylabel("moment")
    top.set_title("section forces (secforc.csv; normal force positive in tension)")
    mark_switches((top, bottom), switches)
    finish(fig, (top, bottom), os.path.join(out, "plot_secforc.png"), written)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description="PNG plots of a RigidFlex output directory")
    parser.add_argument("directory", help="output directory of `rigidflex run`")
    parser.add_argument("-o", "--output", help="where the PNGs go (default: the directory)")
    args = parser.parse_args()
    if not os.path.isfile(os.path.join(args.directory, "glstat.csv")):
        print(f"rigidflex-plot: {args.directory} holds no glstat.csv: not a RigidFlex output "
              "directory", file=sys.stderr)
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")  # headless: files only
        import matplotlib.pyplot as plt
    except ImportError:
        print("rigidflex-plot: matplotlib is not installed (Debian: apt-get install "
              "python3-matplotlib, or scripts/install-deps.sh)", file=sys.stderr)
        return SKIP_STATUS
    out = args.output or args.directory
    os.makedirs(out, exist_ok=True)
    switches = read_switches(args.directory)
    written = []
    for plot in (plot_energies, plot_nodout, plot_rbdout, plot_forces, plot_secforc):
        plot(plt, args.directory, out, switches, written)
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
