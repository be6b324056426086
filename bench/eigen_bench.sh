#!/usr/bin/env bash
# Eigen benchmark (docs/performance.md, "Eigen analysis"): a free-free plate of hexahedra,
# RigidFlex `eigen` against CalculiX `ccx` (*FREQUENCY) on the identical mesh, N elastic modes
# (RigidFlex removes the six rigid modes with LFLAG; CalculiX is asked for N + 6 modes).
# Wall time and peak memory from /usr/bin/time -v, median of REPEATS runs.
#
# usage: bench/eigen_bench.sh [BUILD_DIR] [WORK_DIR] [NX NY NZ] [REPEATS] [THREADS]
#        default build, /tmp/rigidflex_eigen_bench, 100 40 7 (99,384 DOFs), 3 repeats, 2 threads
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$(cd "${1:-$here/../build}" && pwd)"
work="${2:-/tmp/rigidflex_eigen_bench}"
nx="${3:-100}" ny="${4:-40}" nz="${5:-7}"
repeats="${6:-3}"
threads="${7:-2}"
mkdir -p "$work"
cd "$work"
export OMP_NUM_THREADS="$threads" OMP_WAIT_POLICY=passive CCX_NPROC_EQUATION_SOLVER="$threads"

median() { sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
measure() {  # label, command...: prints "label wall_s peak_MiB" (medians)
  local label="$1"; shift
  local walls=() mems=()
  for r in $(seq "$repeats"); do
    /usr/bin/time -v "$@" > "$label.$r.log" 2> "$label.$r.time"
    walls+=("$(awk -F': ' '/Elapsed/ {n=split($2,t,":"); s=0; for(i=1;i<=n;i++) s=s*60+t[i]; print s}' "$label.$r.time")")
    mems+=("$(awk -F': ' '/Maximum resident/ {printf "%.0f", $2/1024}' "$label.$r.time")")
  done
  echo "$label $(printf '%s\n' "${walls[@]}" | median) $(printf '%s\n' "${mems[@]}" | median)"
}

for modes in 20 100; do
  python3 "$here/eigen_make_plate.py" "plate_$modes.k" "$nx" "$ny" "$nz" --neig "$modes"
  python3 "$here/eigen_to_calculix.py" "plate_$modes.k" "plate_$modes.inp" --modes $((modes + 6))
  measure "rigidflex_$modes" "$build/rigidflex" eigen "plate_$modes.k" -o "out_$modes" \
    --threads "$threads" --quiet
  measure "ccx_$modes" ccx -i "plate_$modes"
done
echo "frequencies (Hz), first 10 elastic modes:"
paste -d, <(tail -n +2 out_20/eigout.csv | cut -d, -f3 | head -10) \
  <(awk '/E I G E N V A L U E   O U T P U T/ {f=1; next} f && $1 ~ /^[0-9]+$/ {print $4} /P A R T I C I P/ {f=0}' plate_20.dat | sed -n 7,16p)
