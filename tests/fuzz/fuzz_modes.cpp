// libFuzzer target: the mode database reader (modes.h5 of `rigidflex eigen`) on damaged
// files. docs/verification.md, "Fuzzing"; the
// body is rf::fuzz::run_modes_input (fuzz_targets.hpp), which the regression test of past findings
// shares.
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rf::fuzz::run_modes_input(data, size);
  return 0;
}
