#!/usr/bin/env bash
# Coverage-guided fuzzing with libFuzzer (docs/verification.md, "Fuzzing"): builds the "fuzz"
# preset (clang, ASan + UBSan, build-fuzz/), makes seed corpora and runs each target for a time.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default 30 s; all of fuzz_deck,
#                                                        fuzz_restart, fuzz_modes)
# Without clang++ or libFuzzer it says so and exits 0 (CI then skips fuzzing). Findings (crash-*,
# leak-*, timeout-*, oom-* files) are left in build-fuzz/findings/TARGET/ and make the script
# fail; each one fixed becomes a regression file in tests/decks/fuzz/{deck,restart,modes}/
# (replayed by tests/unit/fuzz_regression_test.cpp).
# Corpora grow in build-fuzz/corpus/TARGET/ between runs.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(fuzz_deck fuzz_restart fuzz_modes)

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: clang++ not found: fuzzing skipped (scripts/install-deps.sh installs clang," \
    "libclang-rt-dev and libomp-dev)"
  exit 0
fi
probe=$(mktemp -d)
echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' \
  >"$probe/probe.cpp"
if ! clang++ -fsanitize=fuzzer,address,undefined -fopenmp "$probe/probe.cpp" -o "$probe/probe" \
    2>/dev/null; then
  rm -rf "$probe"
  echo "fuzz: clang++ -fsanitize=fuzzer -fopenmp does not link (libclang-rt-dev or libomp-dev" \
    "missing): fuzzing skipped"
  exit 0
fi
rm -rf "$probe"

jobs=$(nproc)
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j"$jobs" --target rigidflex fuzz_deck fuzz_restart fuzz_modes

build=build-fuzz
corpus=$build/corpus
seeds=$build/seeds
mkdir -p "$corpus" "$seeds"

# Seeds. Decks: every deck of tests/decks and examples, as main.k, with the files it includes
# appended as "@@@ NAME" sections (fuzz_deck.cpp); plus the regression decks of past findings.
if [ ! -d "$seeds/fuzz_deck" ]; then
  mkdir -p "$seeds/fuzz_deck"
  python3 - "$seeds/fuzz_deck" <<'PY'
import os, re, sys
out = sys.argv[1]
roots = ["tests/decks", "examples"]
include = re.compile(r"^\*INCLUDE", re.I)
n = 0
for root in roots:
    for dirpath, _, names in os.walk(root):
        for name in sorted(names):
            if not name.endswith((".k", ".key", ".dyn", ".in")):
                continue
            path = os.path.join(dirpath, name)
            text = open(path, "rb").read()
            # Files it includes (one level, names on the line after *INCLUDE), relative to it.
            lines = text.decode("latin-1").splitlines()
            parts = [text]
            for i, line in enumerate(lines[:-1]):
                if include.match(line):
                    inc = lines[i + 1].strip()
                    p = os.path.join(dirpath, inc)
                    if os.path.isfile(p):
                        parts.append(b"\n@@@ " + inc.encode() + b"\n" + open(p, "rb").read())
            n += 1
            open(os.path.join(out, "%03d_%s" % (n, name)), "wb").write(b"".join(parts))
print("fuzz: %d deck seeds" % n)
PY
fi
# Dumps and mode databases: small runs of rigidflex (the Release build when there is one: the
# files are the same and it is faster than the instrumented build).
runner=$build/rigidflex
[ -x build/rigidflex ] && runner=build/rigidflex
if [ ! -d "$seeds/fuzz_restart" ]; then
  mkdir -p "$seeds/fuzz_restart" "$seeds/fuzz_modes"
  tmp=$(mktemp -d)
  # Solids, contact, a rigid wall, switching and a sensor: decks that `run` accepts as they are
  # (tests/decks/block_free.k and rigid_free.k, used before, are refused by `run`: no dump);
  # shells in contact (shell, rotation and contact-memory groups of the dump).
  for deck in tests/decks/contact_sliding_block.k tests/decks/rigidwall_switching_block.k \
      examples/switching_spinning_block.k examples/sensor_def2rig.k \
      tests/decks/contact_shell_plate.k; do
    name=$(basename "$deck" .k)
    OMP_NUM_THREADS=1 "$runner" run "$deck" -o "$tmp/$name" --quiet --dump-every 1e9 \
      >/dev/null 2>&1 || true
    for d in "$tmp/$name"/d3dump_*.h5; do
      [ -e "$d" ] && cp "$d" "$seeds/fuzz_restart/${name}_$(basename "$d")"
    done
  done
  # Mode databases of a solid beam (version 1) and of a shell strip (version 2, rotations).
  for deck in examples/flexible_beam_eigen.k tests/decks/eigen_free_strip_shells.k; do
    name=$(basename "$deck" .k)
    OMP_NUM_THREADS=1 "$runner" eigen "$deck" -o "$tmp/eigen_$name" --quiet >/dev/null 2>&1 || true
    for m in "$tmp/eigen_$name"/*.h5; do
      [ -e "$m" ] && cp "$m" "$seeds/fuzz_modes/${name}_$(basename "$m")"
    done
  done
  rm -rf "$tmp"
  echo "fuzz: $(ls "$seeds/fuzz_restart" | wc -l) dump seeds, $(ls "$seeds/fuzz_modes" | wc -l) mode database seeds"
fi

status=0
for target in "${targets[@]}"; do
  mkdir -p "$corpus/$target" "$build/findings/$target"
  # Past findings (fixed) are seeds too: tests/decks/fuzz/deck, restart, modes.
  regression=tests/decks/fuzz/${target#fuzz_}
  if [ -d "$regression" ]; then cp "$regression"/* "$seeds/$target/" 2>/dev/null || true; fi
  echo "fuzz: $target for $seconds s"
  # -rss_limit_mb: a deck may ask for a big model legitimately; 2 GB flags sizes taken on trust.
  # -max_len: decks up to 64 KiB (longer seeds are cut, still valid inputs); dumps and mode
  # databases (130-320 KiB) whole, or the HDF5 reader would only ever see truncated files.
  max_len=65536
  [ "$target" != fuzz_deck ] && max_len=524288
  # LSAN_OPTIONS: leaks inside libhdf5 on damaged files are the library's (tests/fuzz/lsan-hdf5.supp).
  if ! OMP_NUM_THREADS=1 LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan-hdf5.supp \
      "$build/$target" "$corpus/$target" "$seeds/$target" \
      -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -max_len="$max_len" \
      -artifact_prefix="$build/findings/$target/" -print_final_stats=1 \
      >"$build/findings/$target.log" 2>&1; then
    status=1
    echo "fuzz: $target found a problem: see $build/findings/$target.log"
    tail -40 "$build/findings/$target.log"
  fi
  grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss_mb)|cov:" \
    "$build/findings/$target.log" | tail -3 || true
done
exit $status
