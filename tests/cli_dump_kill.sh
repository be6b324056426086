#!/usr/bin/env bash
# kill -9 in the middle of a restart dump (issue 22): the previous dump stays valid and a restart
# from it runs to normal termination. A cube run writes a dump every few cycles; the script
# watches for d3dump_0003.h5.partial (the third dump being written) and kills the run with
# SIGKILL at that moment, then restarts from d3dump_0002.h5.
# Usage: cli_dump_kill.sh RIGIDFLEX MAKE_CUBE_DECK WORK
set -euo pipefail
rigidflex=$1
make_cube=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
python3 "$make_cube" 14 1 1 600 >"$work/cube.k"
for attempt in 1 2 3 4 5; do
  out="$work/out$attempt"
  OMP_NUM_THREADS=1 "$rigidflex" run "$work/cube.k" -o "$out" --quiet --dump-every 1e-5 &
  pid=$!
  caught=0
  # Builtin tests only, so the poll is fast next to a dump (about a megabyte, fsynced).
  while kill -0 "$pid" 2>/dev/null; do
    if [ -e "$out/d3dump_0003.h5.partial" ]; then
      kill -9 "$pid"
      caught=1
      break
    fi
  done
  wait "$pid" 2>/dev/null || true
  if [ "$caught" = 1 ] && [ ! -e "$out/d3dump_0003.h5" ]; then
    echo "killed during the third dump (attempt $attempt)"
    if [ ! -e "$out/d3dump_0003.h5.partial" ]; then
      echo "note: the partial dump was gone before the kill landed"
    fi
    # The restart must not take the partial file for a dump; d3dump_0002.h5 is whole.
    if ! OMP_NUM_THREADS=1 "$rigidflex" restart "$out/d3dump_0002.h5" --quiet --dump-every 1; then
      echo "restart from the previous dump failed"
      exit 1
    fi
    grep -q '"status": "normal termination"' "$out/run.json" || {
      echo "run.json after the restart does not say normal termination"
      cat "$out/run.json"
      exit 1
    }
    echo "restart from d3dump_0002.h5: normal termination"
    exit 0
  fi
  echo "attempt $attempt: the kill did not land inside the third dump; again"
done
echo "could not kill the run inside a dump in 5 attempts"
exit 1
