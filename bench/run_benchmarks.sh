#!/usr/bin/env bash
# Times the benchmark cube at several sizes and thread counts and prints ns per element-cycle
# (wall time of the whole run, start-up and output included, divided by elements x cycles;
# median of REPEAT runs). Usage: bench/run_benchmarks.sh [SIZES] [REPEAT]
# Environment: RIGIDFLEX_EXE (default build/rigidflex) to time another build, FORMS (default
# "1,1 1,6 2,1": ELFORM,IHQ pairs) to restrict the cases.
set -euo pipefail
cd "$(dirname "$0")/.."
sizes=${1:-"20 40 60"}
repeat=${2:-3}
exe=${RIGIDFLEX_EXE:-build/rigidflex}
[ -x "$exe" ] || { echo "build first: scripts/test.sh or cmake --build build"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf "%-6s %-7s %-4s %-8s %12s\n" size elform ihq threads ns/el-cycle
forms=${FORMS:-"1,1 1,6 2,1"}
for n in $sizes; do
  for form in $forms; do
    set -- ${form/,/ }
    python3 bench/make_cube_deck.py "$n" "$1" "$2" 200 > "$work/cube.k"
    for t in $(seq 1 "$(nproc)"); do
      results=()
      for r in $(seq 1 "$repeat"); do
        "$exe" run "$work/cube.k" -o "$work/out" --threads "$t" --quiet
        results+=("$(python3 -c "import json;print(json.load(open('$work/out/run.json'))['ns_per_element_cycle'])")")
      done
      median=$(printf "%s\n" "${results[@]}" | sort -g | awk '{a[NR]=$1} END{print a[int((NR+1)/2)]}')
      printf "%-6s %-7s %-4s %-8s %12.1f\n" "$n^3" "$1" "$2" "$t" "$median"
    done
  done
done
