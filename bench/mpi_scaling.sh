#!/usr/bin/env bash
# Strong scaling of a distributed run (docs/parallel.md): the benchmark cube
# (make_cube_deck.py N 1 1 CYCLES) on 1 process and on 2 MPI ranks, --threads THREADS each,
# REPEATS interleaved repetitions; prints each run's wall time of the time loop (run.json), rank
# 0's time in the per-cycle reductions (d3hsp.txt) and the medians. The machine's load average
# is printed before and after: on a shared machine compare medians and ratios only.
# Usage: bench/mpi_scaling.sh [BUILD_DIR] [N] [CYCLES] [REPEATS] [THREADS]
set -euo pipefail
build=${1:-build}
n=${2:-40}
cycles=${3:-200}
repeats=${4:-3}
threads=${5:-1}
here=$(cd "$(dirname "$0")" && pwd)
exe=$(cd "$build" && pwd)/rigidflex
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 "$here/make_cube_deck.py" "$n" 1 1 "$cycles" > "$work/cube.k"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=$threads
echo "cube $n^3, $cycles cycles, $threads thread(s) per rank; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
wall() { python3 -c "import json,sys; print('%.3f' % json.load(open(sys.argv[1]))['wall_seconds'])" "$1/run.json"; }
one=(); two=(); red=()
for r in $(seq "$repeats"); do
  "$exe" run "$work/cube.k" -o "$work/p1_$r" --threads "$threads" --quiet
  mpirun --bind-to none -np 2 "$exe" run "$work/cube.k" -o "$work/p2_$r" --threads "$threads" --quiet
  one+=("$(wall "$work/p1_$r")")
  two+=("$(wall "$work/p2_$r")")
  red+=("$(sed -n 's/.*rank 0 spent \([0-9.]*\) s in the per-cycle reductions.*/\1/p' "$work/p2_$r/d3hsp.txt")")
  echo "repeat $r: 1 process ${one[-1]} s, 2 ranks ${two[-1]} s (rank 0 in reductions ${red[-1]} s)"
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
m1=$(median "${one[@]}"); m2=$(median "${two[@]}"); mr=$(median "${red[@]}")
echo "median: 1 process $m1 s, 2 ranks $m2 s (reductions $mr s), speed-up $(python3 -c "print('%.2f' % ($m1/$m2))")"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
