#!/usr/bin/env bash
# Second set-up command: install dependencies, build (Release) and run the whole test suite.
# Optional (docs/verification.md, "Hardening"), off by default until a CI run has timed them:
#   RIGIDFLEX_SANITIZE=1      then the same suite under AddressSanitizer + UndefinedBehavior-
#                             Sanitizer (preset "sanitize", build-sanitize/)
#   RIGIDFLEX_FUZZ_SECONDS=N  then N seconds of coverage-guided fuzzing per target
#                             (scripts/fuzz.sh; skipped with a message without clang's libFuzzer)
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

fuzz_seconds=${RIGIDFLEX_FUZZ_SECONDS:-0}
if [ "$fuzz_seconds" != 0 ]; then
  scripts/fuzz.sh "$fuzz_seconds"
fi
