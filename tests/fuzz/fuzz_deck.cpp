// libFuzzer target: the deck reader (both dialects, *INCLUDE, *PARAMETER and expressions) and the
// model set-up (solver::Simulation's constructor: state, rigid bodies, boundary, contact,
// switching, sensors, first forces), without output files. docs/verification.md, "Fuzzing".
//
// One input is one or more deck files: the text up to the first line "@@@ NAME" is main.k, each
// such line starts file NAME (includes are looked up among them, relative to main.k's directory),
// so the fuzzer can mutate a main deck and its includes together. The reader takes the files from
// memory (ReadOptions::file_texts), as a restart does.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "io/keyword/reader.hpp"
#include "solver/simulation.hpp"

namespace {

constexpr std::string_view kMarker = "@@@ ";
// Bigger models only cost time per input; the reader's limits are tested elsewhere.
constexpr std::size_t kMaxNodes = 20000;
constexpr std::size_t kMaxElements = 10000;

std::map<std::string, std::string> split_files(std::string_view input) {
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
    const std::string_view file =
        input.substr(at + kMarker.size(),
                     eol == std::string_view::npos ? std::string_view::npos
                                                   : eol - at - kMarker.size());
    name = "/fuzz/" + std::string(file);
    if (eol == std::string_view::npos) break;
    start = eol + 1;
  }
  return files;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::map<std::string, std::string> files = split_files(input);
  rf::fuzz::expect_clean_failure([&] {
    rf::io::ReadOptions options;
    options.file_texts = &files;
    const rf::model::Model model = rf::io::read_deck("/fuzz/main.k", options);
    if (model.nodes.size() > kMaxNodes || model.solids.size() > kMaxElements) return;
    // Set-up only (no output directory): the first force evaluation included.
    rf::solver::Simulation sim(model, {});
    (void)sim;
  });
  return 0;
}
