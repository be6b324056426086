#!/usr/bin/env bash
# Die-press benchmark (docs/performance.md, "Flexible bodies"): the die of bench/make_die_press.py
# strikes the blank through contact; the die is fully deformable, rigid, or a flexible rigid body
# with 10/20/40/70 modes (FORM 0 and 1) from `rigidflex eigen` of the die alone. Every variant
# runs REPS times with `rigidflex run`; the table gives medians of wall and CPU time, the time
# per cycle, ns per element-cycle (all elements of the model, rigid ones included, so the
# variants compare at equal size) and the accuracy against the deformable die: peak contact
# force (rcforc.csv) and peak deflection of the blank's centre (nodout.csv).
#
#   bench/die_press_bench.sh [REPS] [WORKDIR]        (defaults: 3, die_press_work)
#   RIGIDFLEX_EXE=build/rigidflex THREADS=1 END=6e-4 VARIANTS="deformable rigid 10,0 ..."
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
exe=$(realpath "${RIGIDFLEX_EXE:-build/rigidflex}")
reps=${1:-3}
work=${2:-die_press_work}
threads=${THREADS:-1}
end=${END:-6e-4}
variants=${VARIANTS:-"deformable rigid 10,0 20,0 40,0 70,0 10,1 20,1 40,1 70,1"}
mkdir -p "$work"
cd "$work"
python3 "$here/make_die_press.py" --die-only die_only.k
if [ ! -f die_eigen/modes.h5 ]; then
  # 76 modes: the 6 rigid ones and 70 elastic ones.
  "$exe" eigen die_only.k --modes 76 --threads "$threads" --quiet -o die_eigen
fi
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
python3 - "$exe" "$reps" "$threads" "$end" "$here/make_die_press.py" $variants <<'EOF'
import csv, json, os, resource, statistics, subprocess, sys, time

exe, reps, threads, end, generator = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
variants = sys.argv[6:]


def deck_for(v):
    if v in ("deformable", "rigid"):
        name, args = v, ["--die", v]
    else:
        modes, form = v.split(",")
        name = "flexible_{}_form{}".format(modes, form)
        args = ["--die", "flexible", "--modes", modes, "--form", form]
    subprocess.run(["python3", generator, name + ".k", "--end", end] + args, check=True)
    return name


def peaks(out):
    force = 0.0
    with open(os.path.join(out, "rcforc.csv")) as f:
        for row in csv.DictReader(f):
            force = max(force, abs(float(row["slave_fz"])))
    deflection, z0 = 0.0, None
    with open(os.path.join(out, "nodout.csv")) as f:
        for row in csv.DictReader(f):
            z = float(row["z"])
            z0 = z if z0 is None else z0
            deflection = max(deflection, z0 - z)
    return force, deflection


rows = []
for v in variants:
    name = deck_for(v)
    wall, cpu = [], []
    for r in range(reps):
        out = "{}_out".format(name)
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run([exe, "run", name + ".k", "-o", out, "--threads", threads, "--quiet"],
                       check=True)
        wall.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    summary = json.load(open(os.path.join(out, "run.json")))
    force, deflection = peaks(out)
    rows.append(dict(name=name, wall=statistics.median(wall), cpu=statistics.median(cpu),
                     cycles=summary["cycles"], elements=summary["elements"], force=force,
                     deflection=deflection))
    print("{:24s} wall {} cpu {}".format(name, " ".join("%.2f" % w for w in wall),
                                         " ".join("%.2f" % c for c in cpu)), flush=True)

print("load average after: {}".format(" ".join(open("/proc/loadavg").read().split()[:3])))
reference = next((r for r in rows if r["name"] == "deformable"), rows[0])
print()
print("| die | cycles | wall (median) | CPU (median) | CPU per cycle | ns per element-cycle (CPU) "
      "| CPU vs deformable | peak contact force | vs deformable | peak blank deflection | vs deformable |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for r in rows:
    per_cycle = r["cpu"] / r["cycles"]
    print("| {} | {} | {:.2f} s | {:.2f} s | {:.0f} us | {:.0f} | {:.2f} | {:.4g} N | {:+.1f} % | "
          "{:.4g} mm | {:+.1f} % |".format(
              r["name"], r["cycles"], r["wall"], r["cpu"], 1e6 * per_cycle,
              1e9 * per_cycle / r["elements"], r["cpu"] / reference["cpu"], r["force"],
              100 * (r["force"] / reference["force"] - 1), 1e3 * r["deflection"],
              100 * (r["deflection"] / reference["deflection"] - 1)))
EOF
