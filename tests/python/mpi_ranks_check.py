"""Distributed runs against the one-process run (docs/parallel.md, ctest label "mpi").

Runs DECK once without mpirun (the reference), then under `mpirun -np N` for each N of --ranks,
and requires
- -np 1: every result file byte-identical to the reference (one rank makes no MPI call),
- -np N > 1: the histories of --files equal to the reference's to round-off: the same rows, the
  same text fields (switch events, part lists), every number a, b with
  |a - b| <= rtol * (largest magnitude of its column) + atol: relative to the column's scale
  (the components of a vector or matrix, e.g. ax ay az or r11..r33, share the largest), not the
  value's own, with an absolute floor for quantities that are round-off noise around zero (the
  angular momentum of a symmetric bar is 1e-17),
- run.json records the rank count, and no file appears outside the output directory,
- with --d3plot: every element value of every d3plot state (stresses, strains, history of
  solids, shells and beams; 32-bit floats) within --d3plot-rtol of its variable's largest
  magnitude: the element state each rank gathers before output is complete (an element whose
  state another rank computed would show its initial values),
- with --exclude-columns: the named columns (e.g. ax,ay,az) are not compared; for accelerations
  of nodes in stiff elastic elements, which are the small difference of large element forces and
  carry their round-off magnified (1 thread vs 2 threads of one process differ as much),
- with --repeat: a second run on the largest N gives byte-identical result files (determinism
  for a fixed ranks x threads count).
Standard library only. Exit status 0 on success; prints what differed otherwise.
"""
import argparse
import csv
import filecmp
import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigidflex_results import D3plot  # noqa: E402

NOT_COMPARED_BYTEWISE = {"run.json", "d3hsp.txt"}  # wall times, command line


def run(cmd, cwd):
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        print("FAILED (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stdout))
        sys.exit(1)
    return p.stdout


def read_csv(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return rows[0], rows[1:]


def as_float(text):
    try:
        return float(text)
    except ValueError:
        return None


def compare_csv(name, ref_path, path, rtol, atol, excluded=frozenset()):
    """Largest relative difference (on the column's scale); exits on structural differences."""
    head_a, rows_a = read_csv(ref_path)
    head_b, rows_b = read_csv(path)
    if head_a != head_b or len(rows_a) != len(rows_b):
        print("%s: header or row count differs (%d vs %d rows)" % (name, len(rows_a), len(rows_b)))
        sys.exit(1)
    scale = [0.0] * len(head_a)
    for r in rows_a:
        for k, v in enumerate(r):
            x = as_float(v)
            if x is not None and k < len(scale):
                scale[k] = max(scale[k], abs(x))
    # Components of one vector or matrix share a scale: a body spinning about z has ax, ay at
    # round-off (1e-11 m/s^2, differences of velocities over a step) beside az = 3475 m/s^2.
    group = [re.sub(r"(_?[xyz]|[0-9][0-9])$", "", h) for h in head_a]
    for k in range(len(scale)):
        scale[k] = max(scale[j] for j in range(len(scale)) if group[j] == group[k])
    worst = (0.0, "")
    raw = 0.0  # the largest difference without the floor, for the log
    for i, (ra, rb) in enumerate(zip(rows_a, rows_b)):
        if len(ra) != len(rb):
            print("%s row %d: field count differs" % (name, i + 1))
            sys.exit(1)
        for k, (va, vb) in enumerate(zip(ra, rb)):
            if head_a[k] in excluded:
                continue
            xa, xb = as_float(va), as_float(vb)
            if xa is None or xb is None:
                if va != vb:
                    print("%s row %d column %s: %r vs %r" % (name, i + 1, head_a[k], va, vb))
                    sys.exit(1)
                continue
            s = scale[k] if k < len(scale) and scale[k] > 0.0 else 1.0
            d = max(0.0, abs(xa - xb) - atol) / s
            raw = max(raw, abs(xa - xb) / s)
            if d > worst[0]:
                worst = (d, "%s row %d column %s: %.17g vs %.17g" % (name, i + 1, head_a[k], xa, xb))
    if worst[0] > rtol:
        print("%s: difference %.3g above %.3g at %s" % (name, worst[0], rtol, worst[1]))
        sys.exit(1)
    return worst[0], raw


def compare_d3plot(ref_path, path, rtol):
    a, b = D3plot(ref_path), D3plot(path)
    if len(a.states) != len(b.states):
        print("d3plot: %d vs %d states" % (len(a.states), len(b.states)))
        sys.exit(1)
    worst = 0.0
    for family in ("solid", "shell", "beam"):
        rows_a = [r for st in a.states for r in st[family]]
        rows_b = [r for st in b.states for r in st[family]]
        if not rows_a:
            continue
        for k in range(len(rows_a[0])):
            scale = max(abs(r[k]) for r in rows_a) or 1.0
            d = max(abs(x[k] - y[k]) for x, y in zip(rows_a, rows_b)) / scale
            if d > rtol:
                print("d3plot %s variable %d: difference %.3g of its scale, above %.1g" % (family, k, d, rtol))
                sys.exit(1)
            worst = max(worst, d)
    return worst


def result_files(directory):
    return sorted(f for f in os.listdir(directory) if f not in NOT_COMPARED_BYTEWISE)


def compare_bytewise(a, b, what):
    fa, fb = result_files(a), result_files(b)
    if fa != fb:
        print("%s: different file sets %s vs %s" % (what, fa, fb))
        sys.exit(1)
    for f in fa:
        if not filecmp.cmp(os.path.join(a, f), os.path.join(b, f), shallow=False):
            print("%s: %s differs" % (what, f))
            sys.exit(1)
    print("%s: %d files byte-identical" % (what, len(fa)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rigidflex", required=True)
    ap.add_argument("--mpirun", required=True)
    ap.add_argument("--deck", help="the deck file")
    ap.add_argument("--deck-command", help="a command whose output is the deck (a generator)")
    ap.add_argument("--work", required=True)
    ap.add_argument("--ranks", default="1,2,3")
    ap.add_argument("--files", default="glstat.csv")
    ap.add_argument("--rtol", type=float, default=1e-10)
    ap.add_argument("--atol", type=float, default=1e-12)
    ap.add_argument("--exclude-columns", default="", help="columns not compared, comma-separated")
    ap.add_argument("--repeat", action="store_true")
    ap.add_argument("--d3plot", action="store_true")
    ap.add_argument("--d3plot-rtol", type=float, default=1e-6)
    ap.add_argument("--args", default="", help="extra run arguments, comma-separated")
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    if a.deck_command:
        a.deck = os.path.join(a.work, "deck.k")
        with open(a.deck, "w") as f:
            subprocess.run(a.deck_command.split(), stdout=f, check=True)
    extra = [x for x in a.args.split(",") if x]
    base = ["run", a.deck, "--threads", "1", "--quiet"] + extra
    mpirun = [a.mpirun, "--oversubscribe", "--allow-run-as-root", "--bind-to", "none", "-np"]
    ref = os.path.join(a.work, "plain")
    run([a.rigidflex] + base + ["-o", ref], a.work)
    files = [f for f in a.files.split(",") if f]
    for f in files:
        if not os.path.exists(os.path.join(ref, f)):
            print("the reference run wrote no %s" % f)
            sys.exit(1)
    ranks = [int(x) for x in a.ranks.split(",")]
    for n in ranks:
        out = os.path.join(a.work, "np%d" % n)
        run(mpirun + [str(n), a.rigidflex] + base + ["-o", out], a.work)
        with open(os.path.join(out, "run.json")) as f:
            summary = json.load(f)
        if summary.get("ranks") != n or summary.get("status") != "normal termination":
            print("np %d: run.json says ranks %r, status %r" % (n, summary.get("ranks"), summary.get("status")))
            sys.exit(1)
        if n == 1:
            compare_bytewise(ref, out, "np 1 vs one process")
            continue
        for f in files:
            d, raw = compare_csv(f, os.path.join(ref, f), os.path.join(out, f), a.rtol, a.atol,
                                 frozenset(x for x in a.exclude_columns.split(",") if x))
            print("np %d %s: largest difference %.3g of the column scale (%.3g beyond atol %.1g; "
                  "bound %.1g)" % (n, f, raw, d, a.atol, a.rtol))
        if a.d3plot:
            d = compare_d3plot(os.path.join(ref, "d3plot"), os.path.join(out, "d3plot"), a.d3plot_rtol)
            print("np %d d3plot element values: largest difference %.3g of the variable's scale "
                  "(bound %.1g)" % (n, d, a.d3plot_rtol))
    stray = sorted(set(os.listdir(a.work)) - {"plain"} - {"np%d" % n for n in ranks} - {"again", "deck.k"})
    if stray:
        print("files written outside the output directories: %s" % stray)
        sys.exit(1)
    if a.repeat:
        n = max(ranks)
        again = os.path.join(a.work, "again")
        run(mpirun + [str(n), a.rigidflex] + base + ["-o", again], a.work)
        compare_bytewise(os.path.join(a.work, "np%d" % n), again, "np %d twice" % n)
    print("OK")


if __name__ == "__main__":
    main()
