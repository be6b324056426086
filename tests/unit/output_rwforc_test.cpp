// rwforc.csv: exact header, one row per wall, numbers read back bit-identical.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "output/writers.hpp"

namespace rf::output {
namespace {

TEST(OutputRwforc, HeaderRowsAndBitExactValues) {
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_rwforc";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  RwforcRow a;
  a.time = 1.0 / 3.0;
  a.wall = 12;
  a.normal_force = 0.1 + 0.2;
  a.force = {-1.0 / 7.0, 5e-324, 1e300 / 3.0};
  a.displacement = -0.0;
  a.velocity = 2.0 / 3.0;
  a.normal_impulse = 1e-17;
  a.work = -123.456;
  a.segment_force = {1.0 / 9.0, -2.5, 0.0};
  RwforcRow b = a;
  b.wall = 2;
  b.work = 7.0;
  {
    RwforcWriter writer(dir / "rwforc.csv");
    writer.write({a, b});
  }
  std::ifstream in(dir / "rwforc.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0],
            "time,wall,normal_force,force_x,force_y,force_z,wall_displacement,wall_velocity,"
            "normal_impulse,work,segment_force_x,segment_force_y,segment_force_z");
  std::vector<std::string> fields;
  std::stringstream ss(lines[1]);
  for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
  ASSERT_EQ(fields.size(), 13u);
  EXPECT_EQ(fields[1], "12");
  const double expected[] = {a.time,
                             0.0,
                             a.normal_force,
                             a.force[0],
                             a.force[1],
                             a.force[2],
                             a.displacement,
                             a.velocity,
                             a.normal_impulse,
                             a.work,
                             a.segment_force[0],
                             a.segment_force[1],
                             a.segment_force[2]};
  for (int k = 0; k < 13; ++k) {
    if (k == 1) continue;
    const double parsed = std::strtod(fields[k].c_str(), nullptr);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(parsed), std::bit_cast<std::uint64_t>(expected[k]))
        << fields[k];
  }
  EXPECT_EQ(lines[2].substr(0, lines[2].find(',', lines[2].find(',') + 1)),
            lines[1].substr(0, lines[1].find(',')) + ",2");
}

}  // namespace
}  // namespace rf::output
