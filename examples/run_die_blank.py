#!/usr/bin/python3
"""The seed paper's forming example (die on a blank) with one command (docs/seed_paper.md,
model 3):

  examples/run_die_blank.py [--rigidflex build/rigidflex] [--work build/die_blank]
                            [--images docs/images] [--repeat N] [--replot]
                            [generator options, e.g. --modes 10,40 --form0-modes '']

1. writes the decks (examples/make_die_blank.py) into WORK;
2. the paper's two-step eigen analysis of the die alone, free-free: a preliminary run of 20
   modes checks that exactly six rigid modes come first, then the final run removes them with
   LFTEND = half the seventh frequency (--remove-rigid) and keeps as many elastic modes as the
   largest mode count (WORK/modes/modes.h5);
3. runs every variant (deformable, rigid, flexible with each mode count and FORM) with
   OMP_NUM_THREADS=1, timing each (CPU seconds; --repeat N runs each N times and keeps the
   median, the results being deterministic);
4. reads the tracked nodes (nodout.csv): the z displacement of the die's bottom node (the
   paper's Fig. 7) and the die's compression there, i.e. the shortening of the die between that
   node and the node above it on the die's top face (zero for a rigid die); the peak
   compression and its error against the deformable run, the RMS error of the whole history,
   the peak die/blank contact force (rcforc.csv) and the energy ratio (glstat.csv);
5. writes WORK/die_blank_results.csv and .md (with the share of the compression's static
   compliance that the first N modes carry), WORK/die_blank_times.json, and the plot as
   IMAGES/die_blank_displacement.png (with --images; otherwise into WORK). --replot runs
   nothing and makes the tables and the plot again from those files.

Builds nothing: it uses the solver that is there. Needs python3 with matplotlib for the plot.
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
from rigidflex_results import read_csv, read_vtu  # noqa: E402
from run_head_plate import run  # noqa: E402  (CPU and wall time of one command)

# The paper's CPU times (seed 003, "Sheet metal forming", AMD Athlon 2200, first-order update,
# minutes) and its modal analysis (about 122 s for 70 modes).
PAPER_TIME = {"deformable": 599.0, 10: 233.0, 20: 271.0, 30: 298.0, 40: 331.0, 50: 382.0,
              60: 408.0, 70: 459.0}
PAPER_EIGEN_S = 122.0


def die_history(directory, bottom, top):
    """Times, z displacement of the bottom node, compression of the die (top to bottom)."""
    rows = read_csv(os.path.join(directory, "nodout.csv"))
    b = [r for r in rows if int(r["node"]) == bottom]
    t = [r for r in rows if int(r["node"]) == top]
    length0 = t[0]["z"] - b[0]["z"]
    times = [r["time"] for r in b]
    disp = [r["z"] - b[0]["z"] for r in b]
    compression = [length0 - (rt["z"] - rb["z"]) for rb, rt in zip(b, t)]
    return times, disp, compression


def compression_compliance(model, count):
    """Static compliance of the die's compression at the tracked nodes (a pair of opposite unit
    forces on the bottom and the top node, along z) carried by each of the first `count` modes:
    (phi_z(bottom) - phi_z(top))^2 / omega^2 with mass-normalised modes (modes/*.vtu)."""
    freqs = [r["frequency_hz"] for r in read_csv(os.path.join("modes", "eigout.csv"))]
    shares = []
    for k in range(count):
        vtu = read_vtu(os.path.join("modes", f"modes_{k:04d}.vtu"))
        index = {int(n): i for i, n in enumerate(vtu["point_data"]["node_id"])}
        phi = vtu["point_data"]["displacement"]
        c = phi[index[model["bottom_node"]]][2] - phi[index[model["top_node"]]][2]
        shares.append(c * c / (2.0 * math.pi * freqs[k]) ** 2)
    return shares


def interpolate(times, values, at):
    """values(times) linearly interpolated at the times `at` (held constant beyond the ends)."""
    out, k = [], 0
    for t in at:
        while k < len(times) - 2 and times[k + 1] < t:
            k += 1
        t0, t1 = times[k], times[k + 1]
        f = min(1.0, max(0.0, (t - t0) / (t1 - t0)))
        out.append(values[k] + f * (values[k + 1] - values[k]))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--rigidflex", default=os.path.join(ROOT, "build", "rigidflex"))
    p.add_argument("--work", default=os.path.join(ROOT, "build", "die_blank"))
    p.add_argument("--images", default=None, help="folder for the PNG (default: WORK)")
    p.add_argument("--repeat", type=int, default=1, help="runs per variant (median CPU time)")
    p.add_argument("--replot", action="store_true",
                   help="run nothing: the tables and the plot again from WORK's results and "
                   "WORK/die_blank_times.json")
    args, generator_args = p.parse_known_args()
    rigidflex = os.path.abspath(args.rigidflex)
    work = os.path.abspath(args.work)
    images = os.path.abspath(args.images) if args.images else work
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")

    if not args.replot:
        subprocess.check_call([sys.executable, os.path.join(HERE, "make_die_blank.py"), "--out",
                               work] + generator_args)
    with open(os.path.join(work, "die_blank.json")) as f:
        model = json.load(f)
    os.chdir(work)
    saved = {}
    if args.replot:
        with open("die_blank_times.json") as f:
            saved = json.load(f)

    def timed(key, command, log):
        """CPU seconds (median of --repeat runs for the variants) and wall seconds."""
        if args.replot:
            return saved[key]
        timings = [run(command, log, env) for _ in range(args.repeat if key in names else 1)]
        saved[key] = (statistics.median(t[0] for t in timings),
                      statistics.median(t[1] for t in timings), [t[0] for t in timings])
        return saved[key]
    names = [v["name"] for v in model["variants"]]

    # Step 1 of the paper's procedure: the preliminary analysis.
    t_pre = timed("eigen_check", [rigidflex, "eigen", "die_blank_eigen.k", "--parts", "1",
                                  "--modes", "20", "-o", "modes_check", "--quiet"],
                  "modes_check.log")[0]
    freqs = [r["frequency_hz"] for r in read_csv("modes_check/eigout.csv")]
    rigid = sum(1 for f in freqs if f < 1e-3 * max(freqs))
    if rigid != 6:
        sys.exit(f"the preliminary eigen analysis found {rigid} rigid modes, not 6: "
                 "see modes_check.log")
    lftend = 0.5 * freqs[6]
    print(f"eigen step 1: 6 rigid modes, first elastic mode {freqs[6]:.1f} Hz, "
          f"LFTEND = {lftend:.1f} Hz ({t_pre:.2f} s)")
    nmax = max(v["modes"] for v in model["variants"] if v["kind"] == "flexible")
    t_eigen = timed("eigen", [rigidflex, "eigen", "die_blank_eigen.k", "--parts", "1",
                              "--modes", str(nmax), "--remove-rigid", repr(lftend), "-o",
                              "modes", "--quiet"], "modes.log")[0]
    modes_freq = [r["frequency_hz"] for r in read_csv("modes/eigout.csv")]
    print(f"eigen step 2: {len(modes_freq)} elastic modes, {modes_freq[0]:.1f} to "
          f"{modes_freq[-1]:.1f} Hz ({t_eigen:.2f} s)")

    results = []
    for v in model["variants"]:
        out = "out_" + v["deck"][len("die_blank_"):-2]
        seconds, wall, all_seconds = timed(v["name"], [rigidflex, "run", v["deck"], "-o", out,
                                                       "--threads", "1", "--quiet"],
                                           out + ".log")
        times, disp, comp = die_history(out, model["bottom_node"], model["top_node"])
        glstat = read_csv(os.path.join(out, "glstat.csv"))
        ratio = max(abs(r["energy_ratio"] - 1.0) for r in glstat)
        force = max(math.hypot(r["master_fx"], r["master_fy"], r["master_fz"])
                    for r in read_csv(os.path.join(out, "rcforc.csv")) if r["contact"] == 1)
        with open(os.path.join(out, "run.json")) as f:
            info = json.load(f)
        results.append(dict(v, out=out, seconds=seconds, wall=wall, all_seconds=all_seconds,
                            times=times, disp=disp, comp=comp, peak=max(comp),
                            peak_time=times[comp.index(max(comp))], force=force, energy=ratio,
                            cycles=info.get("cycles", 0), dt=glstat[1]["dt"]))
        print(f"{v['name']:>18}: {seconds:7.2f} s CPU ({wall:.2f} s wall, "
              f"{info.get('cycles', 0)} cycles), peak compression {1e3 * max(comp):.3f} um, "
              f"contact force {1e-3 * force:.1f} kN, |energy ratio - 1| <= {ratio:.1e}")

    if not args.replot:
        with open("die_blank_times.json", "w") as f:
            json.dump(saved, f, indent=1)
    ref = results[0]
    rigid_run = next(r for r in results if r["kind"] == "rigid")
    for r in results:
        r["peak_error"] = 100.0 * (r["peak"] / ref["peak"] - 1.0)
        # The runs' output times differ by up to a step (their steps differ): compare at the
        # deformable run's times.
        comp = interpolate(r["times"], r["comp"], ref["times"])
        disp = interpolate(r["times"], r["disp"], ref["times"])
        n = len(ref["times"])
        r["rms_error"] = 100.0 * math.sqrt(
            sum((comp[i] - ref["comp"][i]) ** 2 for i in range(n)) / n) / ref["peak"]
        r["disp_error"] = max(abs(disp[i] - ref["disp"][i]) for i in range(n))
        r["vs_deformable"] = r["seconds"] / ref["seconds"]
        r["vs_rigid"] = r["seconds"] / rigid_run["seconds"]

    def paper_ratio(r):
        if r["kind"] == "deformable":
            return 1.0
        if r.get("form") == 1 and r.get("modes") in PAPER_TIME:
            return PAPER_TIME[r["modes"]] / PAPER_TIME["deformable"]
        return None

    with open("die_blank_results.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["variant", "modes", "form", "cpu_s", "cpu_s_all", "wall_s", "cycles", "dt_s",
                    "vs_deformable", "vs_rigid", "peak_compression_um", "peak_time_ms",
                    "peak_error_pct", "rms_error_pct", "max_disp_diff_um",
                    "peak_contact_force_kN", "energy_ratio_dev", "paper_vs_deformable"])
        for r in results:
            pr = paper_ratio(r)
            w.writerow([r["name"], r.get("modes", ""), r.get("form", ""), f"{r['seconds']:.3f}",
                        " ".join(f"{s:.2f}" for s in r["all_seconds"]), f"{r['wall']:.3f}",
                        r["cycles"], f"{r['dt']:.4e}", f"{r['vs_deformable']:.3f}",
                        f"{r['vs_rigid']:.3f}", f"{1e3 * r['peak']:.4f}",
                        f"{1e3 * r['peak_time']:.4f}", f"{r['peak_error']:.3f}",
                        f"{r['rms_error']:.3f}", f"{1e3 * r['disp_error']:.4f}",
                        f"{1e-3 * r['force']:.3f}", f"{r['energy']:.2e}",
                        f"{pr:.3f}" if pr else ""])
    lines = ["| variant | CPU time (s) | cycles | / deformable | / rigid | paper / deformable | "
             "peak compression (µm) | peak error | RMS error of the history | largest error of "
             "the displacement (µm) | peak contact force (kN) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        pr = paper_ratio(r)
        lines.append(
            f"| {r['name']} | {r['seconds']:.1f} | {r['cycles']} | {r['vs_deformable']:.2f} | "
            f"{r['vs_rigid']:.2f} | " + (f"{pr:.2f}" if pr else "") +
            f" | {1e3 * r['peak']:.2f} | {r['peak_error']:+.1f} % | {r['rms_error']:.1f} % | "
            f"{1e3 * r['disp_error']:.2f} | {1e-3 * r['force']:.0f} |")
    lines.append("")
    lines.append(f"Eigen analysis: preliminary 20 modes {t_pre:.2f} s, final {nmax} modes "
                 f"{t_eigen:.2f} s of CPU ({100 * t_eigen / ref['seconds']:.1f} % of the "
                 f"deformable run); first elastic mode {freqs[6]:.1f} Hz, mode {nmax} "
                 f"{modes_freq[-1]:.1f} Hz. Largest |energy ratio - 1| of all runs: "
                 f"{max(r['energy'] for r in results):.1e}.")
    shares = compression_compliance(model, nmax)
    counts = sorted({r["modes"] for r in results if r["kind"] == "flexible"})
    lines.append("")
    lines.append(f"Static compliance of the die's compression at the tracked nodes carried by the "
                 f"first N modes, in % of that of all {nmax}: " + ", ".join(
                     f"{n}: {100 * sum(shares[:n]) / sum(shares):.1f}" for n in counts) +
                 "; the largest single share: mode " +
                 f"{1 + shares.index(max(shares))} ({modes_freq[shares.index(max(shares))]:.0f} "
                 f"Hz, {100 * max(shares) / sum(shares):.0f} %).")
    with open("die_blank_results.md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not installed (Debian python3-matplotlib): no plot")
        return
    flexible = [r for r in results if r["kind"] == "flexible"]
    form1 = [r for r in flexible if r["form"] == 1]
    form0 = [r for r in flexible if r["form"] == 0]
    panels = 3 if form0 else 2
    fig, axes = plt.subplots(1, panels, figsize=(6.0 * panels, 4.6))
    colours = plt.cm.viridis([i / max(1, len(form1) - 1) for i in range(len(form1))])
    ax = axes[0]
    ax.plot([1e3 * t for t in ref["times"]], ref["disp"], "k-", lw=2.2, label="deformable")
    ax.plot([1e3 * t for t in rigid_run["times"]], rigid_run["disp"], "k:", lw=1.5,
            label="rigid die")
    for colour, r in zip(colours, form1):
        ax.plot([1e3 * t for t in r["times"]], r["disp"], "-", color=colour, lw=1.0,
                label=f"{r['modes']} modes")
    ax.set_title("z displacement of the die's bottom node (Fig. 7)")
    ax.set_ylabel("mm")
    for ax, group, title in ((axes[1], form1, "FORM 1"),
                             (axes[2] if form0 else None, form0, "FORM 0")):
        if ax is None:
            continue
        ax.plot([1e3 * t for t in ref["times"]], [1e3 * c for c in ref["comp"]], "k-", lw=2.2,
                label="deformable")
        ax.plot([1e3 * t for t in rigid_run["times"]], [1e3 * c for c in rigid_run["comp"]],
                "k:", lw=1.5, label="rigid die")
        cols = plt.cm.viridis([i / max(1, len(group) - 1) for i in range(len(group))])
        for colour, r in zip(cols, group):
            ax.plot([1e3 * t for t in r["times"]], [1e3 * c for c in r["comp"]], "-",
                    color=colour, lw=1.0, label=f"{r['modes']} modes ({r['peak_error']:+.1f} %)")
        ax.set_title(f"the die's compression there, {title}")
        ax.set_ylabel("µm")
    for ax in axes:
        ax.set_xlabel("time (ms)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Die on a blank (seed 003, Fig. 7): deformable vs rigid vs flexible die")
    fig.tight_layout()
    os.makedirs(images, exist_ok=True)
    png = os.path.join(images, "die_blank_displacement.png")
    fig.savefig(png, dpi=110)
    print(f"plot: {png}")


if __name__ == "__main__":
    main()
