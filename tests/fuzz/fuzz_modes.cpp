// libFuzzer target: the mode database reader (*PART_MODES FORMAT 3, modes.h5) on damaged files.
// docs/verification.md, "Fuzzing". Seeds: modes.h5 of `rigidflex eigen` runs (scripts/fuzz.sh).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "fuzz_input.hpp"
#include "modal/mode_set.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const fs::path file = [] {
    const fs::path d =
        fs::temp_directory_path() / ("rigidflex_fuzz_modes_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d / "modes.h5";
  }();
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (f == nullptr) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  rf::fuzz::expect_clean_failure([&] { (void)rf::modal::read_mode_database(file); });
  return 0;
}
