// Faults of the output side a run must survive (issue 22): a file in place of the output
// directory, a directory that cannot be written, a full disk while writing CSVs, run.json or a
// restart dump. Errors name the path and the reason; nothing half-written is left under a final
// name. A full disk is a real one where the test may mount a small tmpfs (root, as in the CI
// container), and /dev/full (ENOSPC on every write) behind the file's name otherwise.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/keyword/reader.hpp"
#include "io/restart/hdf5_file.hpp"
#include "model/error.hpp"
#include "output/output_directory.hpp"
#include "output/writers.hpp"
#include "restart/dump.hpp"
#include "restart/dumper.hpp"
#include "solver/simulation.hpp"

namespace rf::output {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("rigidflex_fault_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A tmpfs of `bytes` mounted at a fresh directory for the test's lifetime; empty() when the
// test may not mount (not root, no CAP_SYS_ADMIN).
class SmallTmpfs {
 public:
  SmallTmpfs(const std::string& name, std::size_t bytes) : dir_(scratch(name)) {
    const std::string options = "size=" + std::to_string(bytes);
    mounted_ = ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, options.c_str()) == 0;
  }
  ~SmallTmpfs() {
    if (mounted_) ::umount(dir_.c_str());
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  bool mounted() const { return mounted_; }
  const fs::path& dir() const { return dir_; }
  // Fills the file system to the last byte.
  void fill() const {
    std::FILE* f = std::fopen((dir_ / "filler").c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::string block(4096, 'x');
    while (std::fwrite(block.data(), 1, block.size(), f) == block.size()) {
    }
    std::fclose(f);
    // Partial blocks: byte by byte until ENOSPC.
    f = std::fopen((dir_ / "filler2").c_str(), "wb");
    if (f != nullptr) {
      std::setvbuf(f, nullptr, _IONBF, 0);
      while (std::fputc('x', f) != EOF) {
      }
      std::fclose(f);
    }
  }

 private:
  fs::path dir_;
  bool mounted_ = false;
};

// A free steel cube of 1 m, one element (step about 5e-5 s at TSSFAC 0.5), output every cycle:
// many CSV rows.
std::string block_deck(double end_time) {
  std::string s = "*KEYWORD\n*CONTROL_TERMINATION\n" + std::to_string(end_time) + "\n";
  s += "*CONTROL_TIMESTEP\n0,0.5\n";
  s += "*DATABASE_GLSTAT\n1e-9\n*DATABASE_NODOUT\n1e-9\n*DATABASE_HISTORY_NODE\n1,2,3,4\n";
  s += "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n";
  s += "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n";
  s += "*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,7850,2.1e11,0.3\n";
  s += "*INITIAL_VELOCITY_NODE\n7,1.0,0,0\n*END\n";
  return s;
}

void expect_message(const std::exception& e, const fs::path& dir, const std::string& reason) {
  const std::string m = e.what();
  EXPECT_NE(m.find(dir.string()), std::string::npos) << m;
  EXPECT_NE(m.find(reason), std::string::npos) << m;
}

TEST(OutputFaults, FileInPlaceOfOutputDirectory) {
  const fs::path dir = scratch("file_in_place");
  const fs::path out = dir / "out";
  std::ofstream(out) << "not a directory\n";
  try {
    prepare_output_directory(out);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, out, "a file of that name is in its place");
  }
  // A file where a parent directory should be.
  try {
    prepare_output_directory(out / "sub");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, out / "sub", "cannot create output directory");
  }
  fs::remove_all(dir);
}

TEST(OutputFaults, DirectoryWithoutWritePermission) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes regardless of permissions";
  const fs::path dir = scratch("read_only");
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  try {
    prepare_output_directory(dir);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, dir, "Permission denied");
  }
  fs::permissions(dir, fs::perms::owner_all);
  fs::remove_all(dir);
}

TEST(OutputFaults, ReadOnlyFileSystem) {
  SmallTmpfs fs_("read_only_fs", 1 << 20);
  if (!fs_.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here";
  ASSERT_EQ(::mount("tmpfs", fs_.dir().c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, nullptr), 0);
  try {
    prepare_output_directory(fs_.dir());
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, fs_.dir(), "Read-only file system");
  }
}

TEST(OutputFaults, FullDiskFoundBeforeTheRun) {
  SmallTmpfs fs_("full_before", 64 << 10);
  if (!fs_.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here";
  fs_.fill();
  try {
    prepare_output_directory(fs_.dir());
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, fs_.dir(), "No space left on device");
  }
}

// run.json (write_file_atomically): on a full disk the old file stays whole and no temporary
// is left.
TEST(OutputFaults, AtomicFileOnFullDiskKeepsTheOldFile) {
  SmallTmpfs fs_("atomic_full", 64 << 10);
  if (!fs_.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here";
  const fs::path path = fs_.dir() / "run.json";
  write_file_atomically(path, "{\"status\": \"old\"}\n");
  fs_.fill();
  RunSummary summary;
  summary.status = "normal termination";
  summary.message = std::string(20000, 'm');  // more than one page
  try {
    write_run_json(path, summary);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, path, "No space left on device");
  }
  EXPECT_EQ(read_file(path), "{\"status\": \"old\"}\n");
  EXPECT_FALSE(fs::exists(fs_.dir() / "run.json.tmp"));
}

// The CSV files on a full disk: the run stops with an error naming the file. /dev/full behind
// glstat.csv needs no privileges.
TEST(OutputFaults, CsvOnFullDiskStopsTheRunNamingTheFile) {
  const fs::path dir = scratch("csv_dev_full");
  fs::create_symlink("/dev/full", dir / "glstat.csv");
  try {
    solver::Simulation sim(io::read_deck_text(block_deck(1e-3), "block.k"), {dir, false});
    sim.run();
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, dir / "glstat.csv", "No space left on device");
  }
  fs::remove_all(dir);
}

TEST(OutputFaults, RunOnSmallTmpfsStopsWithTheReason) {
  SmallTmpfs fs_("run_full", 64 << 10);
  if (!fs_.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here";
  try {
    solver::Simulation sim(io::read_deck_text(block_deck(2e-2), "block.k"), {fs_.dir(), false});
    sim.run();
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, fs_.dir(), "No space left on device");
  }
}

// A dump on a full disk: the error names the file that could not be written (the dump, or a CSV
// file the dump flushes first), no partial dump is left, and the dump before it still opens and
// reads.
TEST(OutputFaults, DumpOnFullDiskLeavesThePreviousDumpValid) {
  SmallTmpfs fs_("dump_full", 4 << 20);
  if (!fs_.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here";
  const fs::path out = fs_.dir() / "out";
  fs::create_directories(out);
  const std::string deck = block_deck(5e-3);
  restart::ModelInput input;
  input.main_deck = "block.k";
  input.files["block.k"] = deck;
  solver::Simulation sim(io::read_deck_text(deck, "block.k"), {out, false});
  sim.enable_restart_dumps(
      std::make_unique<restart::Dumper>(std::move(input), restart::Dumper::every(1e-3)));
  bool filled = false;
  try {
    sim.run([&](const solver::Simulation& s) {
      if (!filled && s.restart_dumper()->written().size() == 1) {
        fs_.fill();
        filled = true;
      }
    });
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    expect_message(e, out, "cannot write");
  }
  ASSERT_TRUE(filled);
  EXPECT_FALSE(fs::exists(out / "d3dump_0002.h5.partial"));
  EXPECT_FALSE(fs::exists(out / "d3dump_0002.h5"));
  const io::h5::File file = io::h5::File::open(out / "d3dump_0001.h5");
  const restart::DumpHeader header = restart::read_dump_header(file, out / "d3dump_0001.h5");
  EXPECT_GT(header.cycle, 0);
}

}  // namespace
}  // namespace rf::output
