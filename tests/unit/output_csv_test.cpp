// glstat.csv / nodout.csv: exact headers and bit-exact round trip of every number.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "output/writers.hpp"

namespace rf::output {
namespace {

std::filesystem::path fresh_directory(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("rigidflex_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::vector<std::string> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream ss(line);
  for (std::string field; std::getline(ss, field, ',');) fields.push_back(field);
  return fields;
}

// Exact comparison of the bit patterns, so -0.0 and 0.0 differ and NaN payloads would too.
void expect_bits(const std::string& text, double expected) {
  char* end = nullptr;
  const double parsed = std::strtod(text.c_str(), &end);
  EXPECT_EQ(*end, '\0') << text;
  EXPECT_EQ(std::bit_cast<std::uint64_t>(parsed), std::bit_cast<std::uint64_t>(expected))
      << text << " vs " << expected;
}

TEST(OutputCsv, GlstatHeaderAndBitExactValues) {
  const auto dir = fresh_directory("glstat");
  GlstatRow row;
  row.time = 1.0 / 3.0;
  row.dt = 2.2250738585072014e-308 * 3.0;  // near the bottom of the normal range
  row.cycle = 123456789012LL;
  row.kinetic_energy = 0.1 + 0.2;
  row.internal_energy = 1e300 / 7.0;
  row.hourglass_energy = -0.0;
  row.external_work = std::nextafter(1.0, 2.0);
  row.total_energy = 5e-324;  // smallest subnormal
  row.energy_ratio = 0.99999999999999989;
  row.momentum[0] = -std::sqrt(2.0);
  row.momentum[1] = std::numbers::pi;
  row.momentum[2] = 6.02214076e23;
  row.angular_momentum[0] = -1e-17;
  row.angular_momentum[1] = 123456789.123456789;
  row.angular_momentum[2] = std::numeric_limits<double>::max();
  row.switch_energy = 1.0 / 3.0;
  row.frozen_energy = 2.5e-7;
  row.rigidwall_work = -1.0 / 7.0;
  row.contact_energy = 1.0 / 9.0;
  row.modal_energy = 2.0 / 9.0;
  row.damping_work = -4.0 / 11.0;
  row.added_mass = 5.0 / 13.0;
  row.mass_scaling_work = 6.0 / 17.0;
  row.bulk_viscosity_energy = 7.0 / 19.0;
  row.spring_energy = 3.0 / 23.0;
  row.damper_energy = 5.0 / 29.0;
  row.eroded_internal_energy = 7.0 / 31.0;
  row.eroded_kinetic_energy = 11.0 / 37.0;
  row.eroded_elements = 42.0;
  GlstatRow second = row;
  second.time = 2.0 / 3.0;
  second.cycle = 7;
  {
    GlstatWriter writer(dir / "glstat.csv");
    writer.write(row);
    writer.write(second);
  }
  const auto lines = read_lines(dir / "glstat.csv");
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0],
            "time,dt,cycle,kinetic_energy,internal_energy,hourglass_energy,external_work,"
            "total_energy,energy_ratio,momentum_x,momentum_y,momentum_z,angular_momentum_x,"
            "angular_momentum_y,angular_momentum_z,switch_energy,frozen_energy,rigidwall_work,"
            "contact_energy,modal_energy,damping_work,added_mass,mass_scaling_work,"
            "bulk_viscosity_energy,spring_energy,damper_energy,eroded_internal_energy,"
            "eroded_kinetic_energy,eroded_elements");
  const auto f = split_csv(lines[1]);
  ASSERT_EQ(f.size(), 29u);
  expect_bits(f[0], row.time);
  expect_bits(f[1], row.dt);
  EXPECT_EQ(f[2], "123456789012");
  const double rest[] = {row.kinetic_energy,
                         row.internal_energy,
                         row.hourglass_energy,
                         row.external_work,
                         row.total_energy,
                         row.energy_ratio,
                         row.momentum[0],
                         row.momentum[1],
                         row.momentum[2],
                         row.angular_momentum[0],
                         row.angular_momentum[1],
                         row.angular_momentum[2],
                         row.switch_energy,
                         row.frozen_energy,
                         row.rigidwall_work,
                         row.contact_energy,
                         row.modal_energy,
                         row.damping_work,
                         row.added_mass,
                         row.mass_scaling_work,
                         row.bulk_viscosity_energy,
                         row.spring_energy,
                         row.damper_energy,
                         row.eroded_internal_energy,
                         row.eroded_kinetic_energy,
                         row.eroded_elements};
  for (int i = 0; i < 26; ++i) expect_bits(f[3 + i], rest[i]);
  const auto g = split_csv(lines[2]);
  ASSERT_EQ(g.size(), 29u);
  expect_bits(g[0], second.time);
  EXPECT_EQ(g[2], "7");
}

TEST(OutputCsv, NodoutHeaderUserIdsAndBitExactValues) {
  const auto dir = fresh_directory("nodout");
  solver::State state;
  const std::size_t n = 3;
  state.nodes.id = {1001, 17, 5};
  for (auto* v : {&state.nodes.x0, &state.nodes.x, &state.nodes.v, &state.nodes.a}) {
    v->resize(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    state.nodes.x.x[i] = 0.1 * (i + 1) / 3.0;
    state.nodes.x.y[i] = -1.0 / (i + 7.0);
    state.nodes.x.z[i] = 1e-9 * std::sqrt(i + 2.0);
    state.nodes.v.x[i] = 10.0 / 3.0 * (i + 1);
    state.nodes.v.y[i] = -0.0;
    state.nodes.v.z[i] = std::exp(static_cast<double>(i));
    state.nodes.a.x[i] = 1e12 / 7.0;
    state.nodes.a.y[i] = -std::log(i + 2.0);
    state.nodes.a.z[i] = std::nextafter(0.0, 1.0);
  }
  {
    NodoutWriter writer(dir / "nodout.csv", {2, 0});
    state.time = 0.25 / 3.0;
    writer.write(state);
    state.time = 0.5 / 3.0;
    writer.write(state);
  }
  const auto lines = read_lines(dir / "nodout.csv");
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "time,node,x,y,z,vx,vy,vz,ax,ay,az");
  const std::size_t order[] = {2, 0, 2, 0};
  const double times[] = {0.25 / 3.0, 0.25 / 3.0, 0.5 / 3.0, 0.5 / 3.0};
  for (int r = 0; r < 4; ++r) {
    const auto f = split_csv(lines[r + 1]);
    ASSERT_EQ(f.size(), 11u);
    const std::size_t i = order[r];
    expect_bits(f[0], times[r]);
    EXPECT_EQ(f[1], std::to_string(state.nodes.id[i]));
    const auto& s = state.nodes;
    const double values[] = {s.x.x[i], s.x.y[i], s.x.z[i], s.v.x[i], s.v.y[i],
                             s.v.z[i], s.a.x[i], s.a.y[i], s.a.z[i]};
    for (int c = 0; c < 9; ++c) expect_bits(f[2 + c], values[c]);
  }
}

TEST(OutputCsv, OpenFailureNamesThePath) {
  const auto path =
      std::filesystem::temp_directory_path() / "rigidflex_no_such_dir" / "x" / "glstat.csv";
  try {
    GlstatWriter writer(path);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(OutputCsv, MovedFileKeepsWriting) {
  const auto dir = fresh_directory("csv_move");
  CsvFile a(dir / "a.csv", "h");
  CsvFile b = std::move(a);
  EXPECT_FALSE(a.is_open());
  b.write_line("1");
  b.write_text("2\n3\n");
  b.flush();
  EXPECT_EQ(read_lines(dir / "a.csv"), (std::vector<std::string>{"h", "1", "2", "3"}));
}

}  // namespace
}  // namespace rf::output
