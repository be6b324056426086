#!/usr/bin/env bash
# Second set-up command: install dependencies, build (Release) and run the whole test suite, then
# the hardening stage (docs/verification.md, "Hardening"; README says what CI runs):
#   RIGIDFLEX_FUZZ_SECONDS=N  (default 60) N seconds of coverage-guided fuzzing per target:
#                             scripts/fuzz.sh builds the library with clang, ASan + UBSan and
#                             libFuzzer (preset "fuzz", build-fuzz/, ~7 min on 2 cores) and runs
#                             the deck, restart-dump and mode-database targets; any finding fails.
#                             Skipped with a message where clang's libFuzzer is missing. 0: off.
#   RIGIDFLEX_SANITIZE=1      (default off: ~20 min build + ~10 min suite on 2 cores) then the
#                             suite under AddressSanitizer + UndefinedBehaviorSanitizer (preset
#                             "sanitize", build-sanitize/; the tests labelled "slow" left out).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"

if [ "${RIGIDFLEX_SANITIZE:-0}" != 0 ]; then
  cmake --preset sanitize
  cmake --build --preset sanitize -j"$(nproc)"
  ctest --preset sanitize -j"$(nproc)"
fi

fuzz_seconds=${RIGIDFLEX_FUZZ_SECONDS:-60}
if [ "$fuzz_seconds" != 0 ]; then
  scripts/fuzz.sh "$fuzz_seconds" fuzz_deck fuzz_restart fuzz_modes
fi
