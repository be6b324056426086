// libFuzzer target: `rigidflex restart` on damaged dumps (seeds: dumps of small runs,
// made by scripts/fuzz.sh). docs/verification.md, "Fuzzing"; the
// body is rf::fuzz::run_restart_input (fuzz_targets.hpp), which the regression test of past
// findings shares.
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rf::fuzz::run_restart_input(data, size);
  return 0;
}
