// libFuzzer target: `rigidflex restart` on a damaged dump (truncated, bit-flipped, spliced HDF5):
// restart::restart_from_dump reads the dump, rebuilds the model from the deck texts it carries
// and restores the state, without running. docs/verification.md, "Fuzzing". Seeds: dumps of
// small runs (scripts/fuzz.sh makes them). The HDF5 library itself is Debian's, not
// instrumented: coverage guides through RigidFlex's checks, and a crash inside libhdf5 on a
// malformed file is reported as such (docs/verification.md).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "fuzz_input.hpp"
#include "restart/restart.hpp"
#include "solver/simulation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("rigidflex_fuzz_restart_" +
                                                    std::to_string(::getpid()));
    fs::create_directories(d / "out");
    return d;
  }();
  const fs::path dump = dir / "d3dump_0001.h5";
  std::FILE* f = std::fopen(dump.c_str(), "wb");
  if (f == nullptr) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  rf::fuzz::expect_clean_failure([&] {
    rf::restart::RestartOptions options;
    options.dump = dump;
    options.output_directory = dir / "out";
    options.write_fields = false;
    options.threads = 1;
    rf::restart::Restarted restarted = rf::restart::restart_from_dump(options);
    (void)restarted;
  });
  return 0;
}
