#!/usr/bin/env bash
# Coverage-guided fuzzing with libFuzzer (docs/verification.md, "Fuzzing"): builds the "fuzz"
# preset (clang, ASan + UBSan, build-fuzz/), makes seed corpora and runs each target for a time.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default 30 s; all of fuzz_deck,
#                                                        fuzz_restart, fuzz_modes)
# Without clang++ or libFuzzer it says so and exits 0 (CI then skips fuzzing). Findings (crash-*,
# leak-*, timeout-*, oom-* files) are left in build-fuzz/findings/TARGET/ and make the script
# fail; each one fixed becomes a regression deck in tests/decks/fuzz/ (run by the unit tests).
# Corpora grow in build-fuzz/corpus/TARGET/ between runs.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(fuzz_deck fuzz_restart fuzz_modes)

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: clang++ not found: fuzzing skipped (install clang and libclang-rt-dev)"
  exit 0
fi
probe=$(mktemp -d)
echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' \
  >"$probe/probe.cpp"
if ! clang++ -fsanitize=fuzzer,address "$probe/probe.cpp" -o "$probe/probe" 2>/dev/null; then
  rm -rf "$probe"
  echo "fuzz: clang++ -fsanitize=fuzzer does not link (libclang-rt-dev missing): fuzzing skipped"
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
  cp tests/decks/fuzz/* "$seeds/fuzz_deck/" 2>/dev/null || true
fi
# Dumps and mode databases: small runs of the fuzz build's own rigidflex.
if [ ! -d "$seeds/fuzz_restart" ]; then
  mkdir -p "$seeds/fuzz_restart" "$seeds/fuzz_modes"
  tmp=$(mktemp -d)
  for deck in tests/decks/block_free.k tests/decks/rigid_free.k examples/switching_spinning_block.k; do
    name=$(basename "$deck" .k)
    OMP_NUM_THREADS=1 "$build/rigidflex" run "$deck" -o "$tmp/$name" --quiet --dump-every 1e9 \
      >/dev/null 2>&1 || true
    for d in "$tmp/$name"/d3dump_*.h5; do
      [ -e "$d" ] && cp "$d" "$seeds/fuzz_restart/${name}_$(basename "$d")"
    done
  done
  OMP_NUM_THREADS=1 "$build/rigidflex" eigen examples/flexible_beam_eigen.k -o "$tmp/eigen" \
    --quiet >/dev/null 2>&1 || true
  find "$tmp" -name '*.h5' -path '*eigen*' -exec cp {} "$seeds/fuzz_modes/" \;
  rm -rf "$tmp"
  echo "fuzz: $(ls "$seeds/fuzz_restart" | wc -l) dump seeds, $(ls "$seeds/fuzz_modes" | wc -l) mode database seeds"
fi

status=0
for target in "${targets[@]}"; do
  mkdir -p "$corpus/$target" "$build/findings/$target"
  echo "fuzz: $target for $seconds s"
  # -rss_limit_mb: a deck may ask for a big model legitimately; 2 GB flags sizes taken on trust.
  if ! OMP_NUM_THREADS=1 "$build/$target" "$corpus/$target" "$seeds/$target" \
      -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -max_len=65536 \
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
