#!/usr/bin/env bash
# Second set-up command: install dependencies, build (Release) and run the whole test suite;
# then the same suite under AddressSanitizer + UndefinedBehaviorSanitizer (preset "sanitize",
# build-sanitize/) and a short coverage-guided fuzzing run (scripts/fuzz.sh, skipped with a
# message when clang's libFuzzer is not installed). docs/verification.md, "Hardening".
#   RIGIDFLEX_SANITIZE=0      skip the sanitizer build and suite
#   RIGIDFLEX_FUZZ_SECONDS=N  seconds per fuzz target (default 20; 0 skips fuzzing)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"

if [ "${RIGIDFLEX_SANITIZE:-1}" != 0 ]; then
  cmake --preset sanitize
  cmake --build --preset sanitize -j"$(nproc)"
  ctest --preset sanitize -j"$(nproc)"
fi

fuzz_seconds=${RIGIDFLEX_FUZZ_SECONDS:-20}
if [ "$fuzz_seconds" != 0 ]; then
  scripts/fuzz.sh "$fuzz_seconds"
fi
