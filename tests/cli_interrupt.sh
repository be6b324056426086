#!/usr/bin/env bash
# Ctrl-C end to end (docs/cli.md, "Interrupting a run"): runs DECK uninterrupted once, then RUNS
# times with a SIGINT after a random delay (somewhere between start-up and the end of the run),
# and requires of every interrupted run:
#   - exit status 130, run.json status "interrupted";
#   - every CSV file whole: each row as many fields as the header, the file ending in a newline;
#   - a restart dump in the output directory, from which `rigidflex restart` finishes the run with
#     CSV files, frame collection and last frame byte-identical to the uninterrupted run's.
# One more run gets two SIGINTs in quick succession (abort at once): its CSV files must still hold
# whole rows only.
# Usage: cli_interrupt.sh RIGIDFLEX DECK WORK [RUNS] [EXTRA RUN ARGUMENTS...]
set -u
rigidflex=$1
deck=$2
work=$3
runs=${4:-4}
shift 4 2>/dev/null || shift $#
extra=("$@")

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# Every CSV in a directory has whole rows only.
check_csv_whole() {
  local dir=$1 f
  for f in "$dir"/*.csv; do
    [ -e "$f" ] || continue
    [ -s "$f" ] || continue
    [ -z "$(tail -c 1 "$f")" ] || fail "$f does not end in a newline (cut row)"
    awk -F, 'NR == 1 { n = NF } NF != n { print FILENAME ": line " NR " has " NF " fields, header " n; bad = 1 }
             END { exit bad }' "$f" >&2 || fail "$f has a cut row"
  done
}

rm -rf "$work"
mkdir -p "$work"
start=$(date +%s.%N)
"$rigidflex" run "$deck" -o "$work/reference" --threads 1 --quiet "${extra[@]}" \
  || fail "the uninterrupted run failed"
end=$(date +%s.%N)
# Random delays up to the length of a whole run, in milliseconds.
span_ms=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%d", (b - a) * 1000 }')
[ "$span_ms" -gt 20 ] || span_ms=20
echo "uninterrupted run: ${span_ms} ms"

interrupted=0
for k in $(seq 1 "$runs"); do
  dir="$work/run$k"
  delay_ms=$((RANDOM % span_ms))
  "$rigidflex" run "$deck" -o "$dir" --threads 1 --quiet "${extra[@]}" 2>"$work/run$k.err" &
  pid=$!
  sleep "$(awk -v ms="$delay_ms" 'BEGIN { printf "%.3f", ms / 1000 }')"
  kill -INT "$pid" 2>/dev/null
  wait "$pid"
  status=$?
  if [ "$status" -eq 0 ]; then
    echo "run $k: SIGINT after ${delay_ms} ms came after the end (normal termination)"
    continue
  fi
  [ "$status" -eq 130 ] || fail "run $k: exit status $status, expected 130: $(cat "$work/run$k.err")"
  interrupted=$((interrupted + 1))
  grep -q '"status": "interrupted"' "$dir/run.json" || fail "run $k: run.json does not say interrupted"
  check_csv_whole "$dir"
  dump=$(ls "$dir"/d3dump_*.h5 2>/dev/null | tail -n 1)
  [ -n "$dump" ] || fail "run $k: no restart dump written"
  echo "run $k: interrupted after ${delay_ms} ms: $(grep -o 'stopped by[^;"]*' "$dir/run.json")"
  "$rigidflex" restart "$dump" --quiet >"$work/restart$k.log" 2>&1 \
    || fail "run $k: restart from $dump failed: $(cat "$work/restart$k.log")"
  for f in "$work/reference"/*.csv "$work/reference"/*.pvd; do
    name=$(basename "$f")
    cmp -s "$f" "$dir/$name" || fail "run $k: $name after the restart differs from the uninterrupted run's"
  done
  last_frame=$(ls "$work/reference"/*.vtu | tail -n 1)
  cmp -s "$last_frame" "$dir/$(basename "$last_frame")" \
    || fail "run $k: last frame $(basename "$last_frame") differs"
done
echo "$interrupted of $runs runs interrupted and restarted to identical files"

# Two signals: the second ends the process at once, still without a cut row.
dir="$work/abort"
"$rigidflex" run "$deck" -o "$dir" --threads 1 --quiet "${extra[@]}" 2>/dev/null &
pid=$!
sleep "$(awk -v ms="$((span_ms / 3))" 'BEGIN { printf "%.3f", ms / 1000 }')"
kill -INT "$pid" 2>/dev/null
kill -INT "$pid" 2>/dev/null
wait "$pid"
status=$?
[ "$status" -eq 130 ] || [ "$status" -eq 0 ] || fail "abort: exit status $status, expected 130"
check_csv_whole "$dir"
echo "abort run: exit status $status, CSV rows whole"
exit 0
