// The output directory rule (docs/output.md, "A reused output directory"): only RigidFlex's own
// result names are cleared, and the closing line's list names what is there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/result_files.hpp"

namespace {

namespace fs = std::filesystem;
using rf::app::ResultKind;

TEST(ResultFiles, OwnNamesOnly) {
  for (const char* name :
       {"glstat.csv", "nodout.csv", "rbdout.csv", "switch.csv", "run.json", "d3hsp.txt",
        "d3plot.pvd", "d3plot_0000.vtu", "d3plot_12345.vtu", "frames.pvd", "frames_0003.vtu",
        "d3dump_0001.h5", "d3plot", "d3plot01", "plot_energies.png", "matsum.csv"}) {
    EXPECT_TRUE(rf::app::is_result_file(name, ResultKind::kTransient)) << name;
  }
  for (const char* name :
       {"deck.k", "notes.txt", "glstat.csv.bak", "my_glstat.csv", "d3plot_12.vtu", "modes.h5",
        "eigout.csv", "modes_0001.vtu", "picture.png", "d3dump_0001.h5.tmp", "run.json~"}) {
    EXPECT_FALSE(rf::app::is_result_file(name, ResultKind::kTransient)) << name;
  }
  EXPECT_TRUE(rf::app::is_result_file("modes.h5", ResultKind::kEigen));
  EXPECT_TRUE(rf::app::is_result_file("modes_0007.vtu", ResultKind::kEigen));
  EXPECT_FALSE(rf::app::is_result_file("glstat.csv", ResultKind::kEigen));
}

TEST(ResultFiles, ClearAndList) {
  const fs::path dir = fs::temp_directory_path() / "rigidflex_result_files_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "sub");
  for (const char* name : {"glstat.csv", "d3plot.pvd", "d3plot_0000.vtu", "d3plot_0001.vtu",
                           "run.json", "deck.k", "modes.h5", "sub/glstat.csv"}) {
    std::ofstream(dir / name) << "x\n";
  }
  EXPECT_EQ(rf::app::list_results(dir, ResultKind::kTransient),
            "d3plot.pvd, d3plot_NNNN.vtu (2 files, d3plot_0000.vtu to d3plot_0001.vtu), "
            "glstat.csv, run.json");
  const auto removed = rf::app::clear_earlier_results(dir, ResultKind::kTransient);
  EXPECT_EQ(removed.size(), 5u);
  EXPECT_TRUE(fs::exists(dir / "deck.k"));
  EXPECT_TRUE(fs::exists(dir / "modes.h5"));            // a transient run keeps mode databases
  EXPECT_TRUE(fs::exists(dir / "sub" / "glstat.csv"));  // subdirectories are not ours
  EXPECT_FALSE(fs::exists(dir / "d3plot_0001.vtu"));
  EXPECT_EQ(rf::app::list_results(dir, ResultKind::kTransient), "");
  EXPECT_EQ(rf::app::short_list({"a", "b", "c"}, 2), "a, b and 1 more");
  fs::remove_all(dir);
}

}  // namespace
