// libFuzzer target: the deck reader (both dialects, includes, parameters) and the model
// set-up; inputs are a main deck and its includes separated by "@@@ NAME" lines.
// docs/verification.md, "Fuzzing"; the body is rf::fuzz::run_deck_input (fuzz_targets.hpp), which
// the regression test of past findings shares.
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rf::fuzz::run_deck_input(data, size);
  return 0;
}
