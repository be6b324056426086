// A run that breaks down stops with a message naming where and when, and leaves the state at
// detection on disk.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

TEST(Breakdown, UnstableStepStopsWithMessageAndWritesLastState) {
  BoxMesh mesh;
  mesh.nx = mesh.ny = mesh.nz = 2;
  mesh.lx = mesh.ly = mesh.lz = 0.1;
  // TSSFAC 1 on a 2x2x2 free block is above its stability limit (see docs/verification.md):
  // the run must stop, not produce garbage silently.
  std::vector<int> bottom;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) bottom.push_back(mesh.node_id(i, j, 0));
  const std::string deck = "*KEYWORD\n" + mesh.keyword_text() +
                           elastic_part(7850, 210e9, 0.3, 1, 4) + node_set(1, bottom) +
                           "*BOUNDARY_SPC_SET\n1,0,0,0,1\n" +
                           "*INITIAL_VELOCITY\n0\n0.0,0.0,-5.0\n" +
                           "*CONTROL_TIMESTEP\n0.0,1.0\n*CONTROL_TERMINATION\n1.0e-3,\n*END\n";
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_breakdown_test";
  std::filesystem::remove_all(dir);
  solver::Simulation sim(read(deck), {dir, true});
  std::string message;
  try {
    sim.run();
  } catch (const SolverError& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty()) << "an unstable run finished normally";
  EXPECT_NE(message.find("at time"), std::string::npos) << message;
  EXPECT_LT(sim.state().time, 1.0e-3);
  // glstat has the row of the breakdown time, the field output a last frame.
  std::ifstream glstat(dir / "glstat.csv");
  std::string line, last;
  int rows = 0;
  while (std::getline(glstat, line)) {
    last = line;
    ++rows;
  }
  EXPECT_GE(rows, 3);
  EXPECT_EQ(std::stod(last.substr(0, last.find(','))), sim.state().time);
  EXPECT_TRUE(std::filesystem::exists(dir / "frames.pvd"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rf::test
