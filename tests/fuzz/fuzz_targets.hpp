// The bodies of the libFuzzer targets (tests/fuzz/fuzz_*.cpp), shared with the regression test
// of past findings (tests/unit/fuzz_regression_test.cpp, files in tests/decks/fuzz/), so a
// finding replays exactly as the fuzzer ran it. docs/verification.md, "Fuzzing".
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "io/keyword/reader.hpp"
#include "modal/mode_set.hpp"
#include "restart/restart.hpp"
#include "solver/simulation.hpp"

namespace rf::fuzz {

namespace detail {

constexpr std::string_view kMarker = "@@@ ";
// Bigger models only cost time per input; the reader's limits are tested elsewhere.
constexpr std::size_t kMaxNodes = 20000;
constexpr std::size_t kMaxElements = 10000;
// The set-up of higher-order hexahedra (*CHANGE_P-ORDER) estimates each element's largest
// eigenvalue from its dense stiffness of n = 3 (p + 1)^3 rows: ~n^3 operations per element.
// The IMPETUS seed deck (500 hexahedra at order 3, n = 192) takes 0.45 s in Release but over
// 20 s under ASan + coverage on a loaded machine, which libFuzzer reports as a hang although it
// is legitimate work. Models past this budget are read (the reader is fuzzed) but not set up.
constexpr double kMaxSetupCost = 2e8;

inline double setup_cost(const rf::model::Model& model) {
  int order = 1;
  for (const auto& change : model.p_order_changes) order = std::max(order, change.order);
  const double n = 3.0 * std::pow(order + 1.0, 3);
  return static_cast<double>(model.solids.size()) * n * n * n;
}

inline std::map<std::string, std::string> split_files(std::string_view input) {
  std::map<std::string, std::string> files;
  std::string name = "/fuzz/main.k";
  std::size_t start = 0;
  while (true) {
    std::size_t at = input.find(kMarker, start);
    while (at != std::string_view::npos && at != 0 && input[at - 1] != '\n') {
      at = input.find(kMarker, at + 1);
    }
    const std::string_view text =
        input.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start);
    files[name] = std::string(text);
    if (at == std::string_view::npos) break;
    const std::size_t eol = input.find('\n', at);
    const std::string_view file = input.substr(
        at + kMarker.size(),
        eol == std::string_view::npos ? std::string_view::npos : eol - at - kMarker.size());
    name = "/fuzz/" + std::string(file);
    if (eol == std::string_view::npos) break;
    start = eol + 1;
  }
  return files;
}

// A file with the input's bytes at a fixed name in a per-process temporary directory (the
// readers take paths).
inline std::filesystem::path write_temporary(const std::string& kind, const std::string& name,
                                             const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("rigidflex_fuzz_" + kind + "_" + std::to_string(::getpid()));
  fs::create_directories(dir / "out");
  const fs::path file = dir / name;
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (f == nullptr) return {};
  if (size > 0) std::fwrite(data, 1, size, f);
  std::fclose(f);
  return file;
}

}  // namespace detail

// The deck reader (both dialects, *INCLUDE, *PARAMETER and expressions) and the model set-up
// (solver::Simulation's constructor: state, rigid bodies, boundary, contact, switching, sensors,
// first forces), without output files. One input is one or more deck files: the text up to the
// first line "@@@ NAME" is main.k, each such line starts file NAME (includes are looked up among
// them, relative to main.k's directory), so the fuzzer can mutate a main deck and its includes
// together. The reader takes the files from memory (ReadOptions::file_texts), as a restart does.
inline void run_deck_input(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::map<std::string, std::string> files = detail::split_files(input);
  expect_clean_failure([&] {
    rf::io::ReadOptions options;
    options.file_texts = &files;
    rf::model::Model model = rf::io::read_deck("/fuzz/main.k", options);
    if (model.nodes.size() > detail::kMaxNodes || model.solids.size() > detail::kMaxElements ||
        detail::setup_cost(model) > detail::kMaxSetupCost) {
      return;
    }
    // Dynamic relaxation runs inside the set-up, and one that never converges runs until DRTERM,
    // unlimited by default (as in LS-DYNA; Ctrl-C stops it): one pseudo-step of it here, so that
    // its set-up is fuzzed without the fuzzer timing out on a run (finding of 2026-11-29,
    // tests/decks/fuzz/deck).
    model.dynamic_relaxation.drterm = 1e-300;
    // Set-up only (no output directory): the first force evaluation included.
    rf::solver::Simulation sim(model, {});
    (void)sim;
  });
}

// `rigidflex restart` on a damaged dump (truncated, bit-flipped, spliced HDF5):
// restart::restart_from_dump reads the dump, rebuilds the model from the deck texts it carries
// and restores the state, without running. The HDF5 library itself is Debian's, not
// instrumented: coverage guides through RigidFlex's checks.
inline void run_restart_input(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path dump =
      detail::write_temporary("restart", "d3dump_0001.h5", data, size);
  if (dump.empty()) return;
  expect_clean_failure([&] {
    rf::restart::RestartOptions options;
    options.dump = dump;
    options.output_directory = dump.parent_path() / "out";
    options.write_fields = false;
    options.threads = 1;
    rf::restart::Restarted restarted = rf::restart::restart_from_dump(options);
    (void)restarted;
  });
}

// The mode database reader (*PART_MODES FORMAT 3, modes.h5) on damaged files.
inline void run_modes_input(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = detail::write_temporary("modes", "modes.h5", data, size);
  if (file.empty()) return;
  expect_clean_failure([&] { (void)rf::modal::read_mode_database(file); });
}

}  // namespace rf::fuzz
