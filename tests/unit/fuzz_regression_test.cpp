// Regression files of fuzzing findings (docs/verification.md, "Fuzzing"): every file under
// tests/decks/fuzz/restart and modes is an input on which a libFuzzer target once reported a
// problem (a crash, hang, sanitizer report or escaped exception). Each is replayed through the very
// body the fuzz target runs (tests/fuzz/fuzz_targets.hpp): it must end in a model or a clean
// InputError, SolverError or runtime_error. Under the sanitizer preset the same replay also catches
// the memory errors some of them were.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "../fuzz/fuzz_targets.hpp"
#include "keyword_test_util.hpp"

namespace {

std::vector<std::filesystem::path> findings(const std::string& target) {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path dir = rf::test::deck_path("fuzz") / target;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

template <class Run>
void replay(const std::string& target, Run run) {
  for (const auto& file : findings(target)) {
    SCOPED_TRACE(file.string());
    const std::string bytes = rf::test::read_text_file(file);
    // expect_clean_failure aborts on anything but a model or a clean error (a crash of the test).
    run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
}

}  // namespace

// tests/decks/fuzz/restart: dumps on which libhdf5 leaked inside H5Dopen2 or asked for 4 GB
// inside H5Dread (a damaged chunk record; Group::check_storage now refuses it first)
// (tests/fuzz/lsan-hdf5.supp); tests/decks/fuzz/modes: mode databases on which it leaked inside
// H5Gopen2. Beyond ending cleanly, both must be refused with an InputError.
TEST(FuzzRegression, RestartFindingsAreRefusedWithAnInputError) {
  ASSERT_FALSE(findings("restart").empty());
  replay("restart", rf::fuzz::run_restart_input);
  for (const auto& file : findings("restart")) {
    const std::string bytes = rf::test::read_text_file(file);
    const auto dump = rf::fuzz::detail::write_temporary(
        "regression", "d3dump_0001.h5", reinterpret_cast<const std::uint8_t*>(bytes.data()),
        bytes.size());
    rf::restart::RestartOptions options;
    options.dump = dump;
    options.output_directory = dump.parent_path() / "out";
    options.write_fields = false;
    options.threads = 1;
    EXPECT_THROW((void)rf::restart::restart_from_dump(options), rf::InputError) << file;
  }
}

TEST(FuzzRegression, ModeDatabaseFindingsAreRefusedWithAnInputError) {
  ASSERT_FALSE(findings("modes").empty());
  replay("modes", rf::fuzz::run_modes_input);
  for (const auto& file : findings("modes")) {
    EXPECT_THROW((void)rf::modal::read_mode_database(file), rf::InputError) << file;
  }
}

// tests/decks/fuzz/deck: decks on which the deck target timed out (a dynamic relaxation that
// never converges, unlimited without DRTERM: the target now runs one pseudo-step of it).
TEST(FuzzRegression, DeckFindingsEndCleanly) {
  ASSERT_FALSE(findings("deck").empty());
  replay("deck", rf::fuzz::run_deck_input);
}
