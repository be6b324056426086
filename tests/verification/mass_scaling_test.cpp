// Mass scaling (*CONTROL_TIMESTEP DT2MS, MS1ST; solver/mass_scaling.hpp) against references
// computed here from the element sizes, not from the solver:
//  - an element of length L_e (= V / A_max, the smallest side of a box) in a nu = 0 material has
//    the step L_e / c, c = sqrt(E / rho); scaling its mass by s = (target / step)^2 brings its
//    step to the target, so the added mass is sum (s_e - 1) rho V_e over the scaled elements;
//  - a fixed-free bar whose density is raised uniformly by s vibrates at pi c / (2 L sqrt(s));
//  - mass added during a run keeps the step at TSSFAC |DT2MS| while the mesh is crushed, and the
//    energy balance closes with the added kinetic energy 1/2 dm v^2 booked as external work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7850.0, kE = 210e9;
constexpr double kLength = 1.0, kSide = 0.05;
constexpr int kElements = 40;
const double kWaveSpeed = std::sqrt(kE / kRho);  // nu = 0: bar and dilatational speed agree

// 40 elements along x: the first 20 of length kShort (part 1), the others kLong (part 2).
constexpr double kShort = 0.015, kLong = 0.035;

BoxMesh bar_mesh(bool graded) {
  BoxMesh mesh;
  mesh.nx = kElements;
  mesh.lx = kLength;
  mesh.ly = mesh.lz = kSide;
  if (graded) {
    mesh.distort = [](double& x, double&, double&) {
      const double i = std::round(x * kElements / kLength);
      x = i <= 20 ? i * kShort : 20 * kShort + (i - 20) * kLong;
    };
  }
  return mesh;
}

std::string two_parts() {
  return elastic(1, kRho, kE, 0.0, 4) + elastic(2, kRho, kE, 0.0, 4);
}

std::string timestep(double dt2ms, int ms1st = 0) {
  return fmt::format("*CONTROL_TIMESTEP\n0.0,0.9,0,0.0,{:.17g},0,0,{}\n", dt2ms, ms1st);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

int node_index(const solver::Simulation& sim, model::Id id) {
  const auto& ids = sim.state().nodes.id;
  return static_cast<int>(std::find(ids.begin(), ids.end(), id) - ids.begin());
}

double total_mass(const solver::Simulation& sim) {
  double m = 0.0;
  for (const double v : sim.state().nodes.mass) m += v;
  return m;
}

TEST(MassScaling, NegativeDt2msAddsMassOnlyToElementsBelowTheTarget) {
  const BoxMesh mesh = bar_mesh(true);
  const double target = 5e-6;  // between the short (2.9 us) and long (6.8 us) elements' steps
  const double short_step = kShort / kWaveSpeed, long_step = kLong / kWaveSpeed;
  ASSERT_LT(short_step, target);
  ASSERT_GT(long_step, target);
  const double s = (target / short_step) * (target / short_step);
  const double expected = 20 * (s - 1.0) * kRho * kShort * kSide * kSide;
  const double physical = kRho * kLength * kSide * kSide;

  std::string deck = "*KEYWORD\n" + mesh.keyword_text([](int i, int, int) {
    return i < 20 ? 1 : 2;
  }) + two_parts() + timestep(-target);
  deck += "*CONTROL_TERMINATION\n2e-4\n*DATABASE_MATSUM\n1e-4\n*END\n";
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_mass_scaling_negative";
  std::filesystem::remove_all(dir);
  solver::SimulationOptions options;
  options.output_directory = dir;
  solver::Simulation sim(read(deck), options);
  sim.run();
  const auto& scaling = sim.mass_scaling();
  std::printf("DT2MS -%g: s = %.6f on the short elements, added %.6g kg (expected %.6g)\n", target,
              s, scaling.added_mass, expected);
  EXPECT_NEAR(scaling.added_mass, expected, 1e-9 * expected);
  EXPECT_NEAR(total_mass(sim), physical + expected, 1e-9 * (physical + expected));
  EXPECT_NEAR(solver::added_mass_of_part(scaling, sim.state(), 1), expected, 1e-9 * expected);
  EXPECT_EQ(solver::added_mass_of_part(scaling, sim.state(), 2), 0.0);
  // The run's step is TSSFAC |DT2MS| (nothing moves, so nothing is added later).
  EXPECT_NEAR(sim.state().dt, 0.9 * target, 1e-9 * target);
  EXPECT_EQ(scaling.rescaled_cycles, 0);
  EXPECT_EQ(scaling.mass_scaling_work, 0.0);

  // glstat's added_mass and matsum's per-part column.
  std::ifstream glstat(dir / "glstat.csv");
  std::string header, line, last;
  std::getline(glstat, header);
  ASSERT_NE(header.find(",added_mass,mass_scaling_work"), std::string::npos) << header;
  while (std::getline(glstat, line)) last = line;
  const auto names = split_fields(header);
  const auto fields = split_fields(last);
  ASSERT_EQ(fields.size(), names.size());
  const auto column = std::find(names.begin(), names.end(), "added_mass") - names.begin();
  ASSERT_LT(column, static_cast<long>(names.size()));
  EXPECT_NEAR(std::stod(fields[column]), expected, 1e-9 * expected);
  std::ifstream matsum(dir / "matsum.csv");
  std::getline(matsum, header);
  const auto matsum_names = split_fields(header);
  const auto matsum_column =
      std::find(matsum_names.begin(), matsum_names.end(), "added_mass") - matsum_names.begin();
  ASSERT_LT(matsum_column, static_cast<long>(matsum_names.size())) << header;
  double part1 = -1.0, part2 = -1.0;
  while (std::getline(matsum, line)) {
    const auto f = split_fields(line);
    (f[1] == "1" ? part1 : part2) = std::stod(f[matsum_column]);
  }
  EXPECT_NEAR(part1, expected, 1e-9 * expected);
  EXPECT_EQ(part2, 0.0);
}

TEST(MassScaling, PositiveDt2msRemovesMassFromLargeElementsSoAllStartAtTheTarget) {
  const BoxMesh mesh = bar_mesh(true);
  const double target = 5e-6;
  const double s_short = std::pow(target * kWaveSpeed / kShort, 2);
  const double s_long = std::pow(target * kWaveSpeed / kLong, 2);  // < 1: mass removed
  ASSERT_LT(s_long, 1.0);
  const double element_volume_short = kShort * kSide * kSide,
               element_volume_long = kLong * kSide * kSide;
  const double expected_total =
      20 * kRho * (s_short * element_volume_short + s_long * element_volume_long);
  const double physical = kRho * kLength * kSide * kSide;
  std::string deck = "*KEYWORD\n" +
                     mesh.keyword_text([](int i, int, int) { return i < 20 ? 1 : 2; }) +
                     two_parts() + timestep(target) + "*CONTROL_TERMINATION\n1e-4\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  EXPECT_NEAR(total_mass(sim), expected_total, 1e-9 * expected_total);
  EXPECT_NEAR(sim.mass_scaling().added_mass, expected_total - physical, 1e-9 * physical);
  EXPECT_NEAR(solver::added_mass_of_part(sim.mass_scaling(), sim.state(), 2),
              20 * kRho * (s_long - 1.0) * element_volume_long, 1e-9 * physical);
  EXPECT_NEAR(sim.state().dt, 0.9 * target, 1e-9 * target);
}

// Fixed-free uniform bar, first mode excited: all elements are scaled by the same s, so the
// frequency falls by sqrt(s) (the physics of added density, not only the bookkeeping).
TEST(MassScaling, UniformlyScaledBarVibratesAtTheLoweredFrequency) {
  const BoxMesh mesh = bar_mesh(false);
  const double dx = kLength / kElements;
  const double target = 2e-5;
  const double s = std::pow(target * kWaveSpeed / dx, 2);
  const double period = 4.0 * kLength * std::sqrt(s) / kWaveSpeed;
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.0, 1, 4);
  deck += node_set(1, mesh.face_x(0)) + "*BOUNDARY_SPC_SET\n1,0,1,0,0,0,0,0\n";
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= mesh.nz; ++k)
    for (int j = 0; j <= mesh.ny; ++j)
      for (int i = 0; i <= mesh.nx; ++i) {
        deck += fmt::format("{},{:.17g},0,0\n", mesh.node_id(i, j, k),
                            std::sin(0.5 * std::numbers::pi * i / mesh.nx));
      }
  deck += timestep(-target) + "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n" +
          fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*END\n", 4.5 * period);
  solver::Simulation sim(read(deck), {});
  const int tip = node_index(sim, mesh.node_id(kElements, 0, 0));
  std::vector<double> crossings;
  const auto& v = sim.state().nodes.v.x;
  double t_prev = sim.state().time, v_prev = v[tip];
  double worst_ratio = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    const double t = sim.state().time, vi = v[tip];
    if (v_prev > 0.0 && vi <= 0.0)
      crossings.push_back(t_prev + (t - t_prev) * v_prev / (v_prev - vi));
    t_prev = t;
    v_prev = vi;
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  ASSERT_GE(crossings.size(), 4u) << "t = " << sim.state().time << ", dt " << sim.state().dt
                                  << ", cycle " << sim.state().cycle << ", end " << sim.end_time()
                                  << ", period " << period;
  const double measured = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  std::printf(
      "uniform s = %.4f: period %.6g s vs %.6g s (ratio %.6f), %lld cycles with mass "
      "added later, energy ratio within %.2e\n",
      s, measured, period, measured / period,
      static_cast<long long>(sim.mass_scaling().rescaled_cycles), worst_ratio);
  EXPECT_NEAR(measured / period, 1.0, 3e-3);
  // Without scaling the period would be sqrt(s) = 4.1x shorter.
  EXPECT_GT(measured, 0.5 * std::sqrt(s) * 4.0 * kLength / kWaveSpeed);
  EXPECT_LT(worst_ratio, 1e-10);
}

// A bar crushed at 50 m/s against a fixed end: its elements shorten, their steps fall, and mass
// is added during the run so that the step stays at TSSFAC |DT2MS|; with MS1ST 1 the masses
// stay as set at the start and the step falls.
std::string crush_deck(double target, int ms1st, bool bulk_viscosity = false) {
  const BoxMesh mesh = bar_mesh(false);
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.0, 1, 4);
  deck += node_set(1, mesh.face_x(0)) + node_set(2, mesh.face_x(mesh.nx));
  deck += "*BOUNDARY_SPC_SET\n1,0,1,0,0,0,0,0\n";
  deck += "*BOUNDARY_PRESCRIBED_MOTION_SET\n2,1,0,1,-1.0\n";
  deck += "*DEFINE_CURVE\n1\n0.0,0.0\n1.0e-4,50.0\n1.0,50.0\n";
  deck += timestep(-target, ms1st) + "*CONTROL_TERMINATION\n1.0e-3\n*END\n";
  // Off unless asked: the viscous reduction of a compressing element's step is not compensated
  // by added mass, so the step would dip below TSSFAC |DT2MS| (docs/theory.md).
  if (!bulk_viscosity) deck.insert(deck.rfind("*END"), "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n");
  return deck;
}

TEST(MassScaling, MassAddedDuringACrushKeepsTheStepAndClosesTheEnergyBalance) {
  const double target = 5e-6;  // the 25 mm elements' step is 4.8 us: all scaled at the start
  solver::Simulation sim(read(crush_deck(target, 0)), {});
  const double start_mass = sim.mass_scaling().added_mass;
  double smallest_dt = 1e300, worst_ratio = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    // The last step is cut to land on ENDTIM: left out.
    if (sim.state().time + 0.9 * target < 1.0e-3)
      smallest_dt = std::min(smallest_dt, sim.state().dt);
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  const auto& m = sim.mass_scaling();
  std::printf(
      "crush, MS1ST 0: added %.6g kg at the start, %.6g kg at the end, %lld cycles "
      "added mass, work %.6g J of external %.6g J, smallest dt %.6g, energy ratio within "
      "%.2e\n",
      start_mass, m.added_mass, static_cast<long long>(m.rescaled_cycles), m.mass_scaling_work,
      sim.energy().external_work, smallest_dt, worst_ratio);
  EXPECT_GT(m.rescaled_cycles, 10);
  EXPECT_GT(m.added_mass, 1.02 * start_mass);  // the crushed elements took more
  EXPECT_GE(smallest_dt, 0.9 * target * (1.0 - 1e-6));
  EXPECT_GT(m.mass_scaling_work, 0.0);
  EXPECT_LT(worst_ratio, 1e-10);  // without booking the work: 1.4e-3

  solver::Simulation fixed(read(crush_deck(target, 1)), {});
  const double fixed_start = fixed.mass_scaling().added_mass;
  EXPECT_NEAR(fixed_start, start_mass, 1e-12 * start_mass);
  double fixed_ratio = 0.0;
  while (!fixed.finished()) {
    fixed.cycle();
    fixed_ratio = std::max(fixed_ratio, std::abs(fixed.energy().ratio() - 1.0));
  }
  std::printf("crush, MS1ST 1: energy ratio within %.2e, final dt %.6g\n", fixed_ratio,
              fixed.state().dt);
  EXPECT_EQ(fixed.mass_scaling().added_mass, fixed_start);
  EXPECT_EQ(fixed.mass_scaling().rescaled_cycles, 0);
  EXPECT_LT(fixed.state().dt, 0.9 * target * 0.99);  // the step fell as the elements shortened
}

// With LS-DYNA's default bulk viscosity the crush still closes its energy balance (viscous
// energy included), adds mass, and keeps the step within the viscous reduction of the target.
TEST(MassScaling, CrushWithDefaultBulkViscosityClosesTheBalance) {
  const double target = 5e-6;
  solver::Simulation sim(read(crush_deck(target, 0, true)), {});
  double smallest_dt = 1e300, worst_ratio = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    if (sim.state().time + 0.9 * target < 1.0e-3)
      smallest_dt = std::min(smallest_dt, sim.state().dt);
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  std::printf("crush with bulk viscosity: %lld cycles added mass, smallest dt %.6g (%.4f of the "
              "target step), viscous energy %.6g J, energy ratio within %.2e\n",
              static_cast<long long>(sim.mass_scaling().rescaled_cycles), smallest_dt,
              smallest_dt / (0.9 * target), sim.energy().bulk_viscosity, worst_ratio);
  EXPECT_GT(sim.mass_scaling().rescaled_cycles, 10);
  EXPECT_GT(sim.energy().bulk_viscosity, 0.0);
  EXPECT_GE(smallest_dt, 0.9 * 0.9 * target);
  EXPECT_LT(worst_ratio, 1e-10);
}

TEST(MassScaling, UnsupportedOptionsAreInputErrors) {
  const BoxMesh mesh = bar_mesh(false);
  const std::string base = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.0, 1, 4) +
                           "*CONTROL_TERMINATION\n1e-4\n";
  struct Case {
    std::string cards;
    std::string field;
  };
  const Case cases[] = {
      {"*CONTROL_TIMESTEP\n0.0,0.9,0,0.0,-1e-6,0,0,2\n", "MS1ST"},
      {"*CONTROL_TIMESTEP\n0.0,0.9,0,0.0,-1e-6\n0.5\n", "DT2MSF"},
      {"*CONTROL_TIMESTEP\n0.0,0.9,0,0.0,-1e-6\n0,0,-3\n", "IMSCL"},
      {"*CONTROL_TIMESTEP\n0.0,0.9,0,0.0,-1e-6\n0,0,0,0,0,0,0.5\n", "EMSCL"},
      {"*CONTROL_TIMESTEP\n0.0,0.9,0,0.0,-1e-6\n*CHANGE_P-ORDER\nALL,0,2\n", "DT2MS"},
  };
  for (const auto& c : cases) {
    try {
      solver::Simulation sim(read(base + c.cards + "*END\n"), {});
      ADD_FAILURE() << "accepted: " << c.cards;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.field), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("*CONTROL_TIMESTEP"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace rf::test
