// Fully integrated shells (*SECTION_SHELL ELFORM 16) through the whole deck path. References
// from outside the code: the Euler-Bernoulli cantilever (static tip deflection P L^3 / (3 E I),
// first frequency (1.8751^2 / 2 pi) sqrt(E I / (rho A L^4))) and conservation of energy.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "cantilever_strip.hpp"
#include "deck_builder.hpp"
#include "model/error.hpp"
#include "output/history_writers.hpp"
#include "shell_builder.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7800.0, kE = 2.0e11;

// Static tip load (ramped, then damped to rest as in shell_deck_test.cpp): within 2 % of beam
// theory with 10 elements over L / t = 100, i.e. no transverse shear locking.
double static_tip_ratio(int elform) {
  const CantileverStrip strip;
  const double load = 5.0;
  const double expected = load * std::pow(strip.length, 3) / (3.0 * strip.ei());
  solver::Simulation sim(read(strip.deck(elform) + strip.static_tip_load(load, 3)), {});
  sim.run();
  EXPECT_EQ(sim.energy().hourglass, 0.0);
  return strip.tip_displacement(sim, 2) / expected;
}

TEST(Shell16Deck, ThinCantileverStaticTipDeflectionMatchesBeamTheory) {
  const double ratio = static_tip_ratio(16);
  RecordProperty("tip_deflection_ratio", std::to_string(ratio));
  std::printf("ELFORM 16 cantilever L/t = 100, 10 elements: tip / beam theory = %.5f\n", ratio);
  EXPECT_NEAR(ratio, 1.0, 0.02);
}

TEST(Shell16Deck, ThinCantileverFirstFrequencyAndEnergy) {
  const CantileverStrip strip;
  const double f1 = strip.first_frequency();
  solver::Simulation sim(read(strip.deck(16) + strip.first_mode_velocity()), {});
  const double f = strip.run_and_measure_frequency(sim);
  RecordProperty("frequency_ratio", std::to_string(f / f1));
  std::printf("ELFORM 16 cantilever first frequency / beam theory = %.5f, energy ratio %.8f\n",
              f / f1, sim.energy().ratio());
  EXPECT_NEAR(f / f1, 1.0, 0.02);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-3);
  EXPECT_EQ(sim.energy().hourglass, 0.0);
}

// A free plate (nu 0.3, 6 x 6 skewed elements) set vibrating by a velocity field with bending
// and twist: the energy balance closes (glstat's ratio) and the vibration exchanges energy.
TEST(Shell16Deck, FreeVibratingPlateConservesEnergy) {
  ShellPlate p;
  p.nx = p.ny = 6;
  p.lx = p.ly = 0.3;
  p.place = [](double u, double v) { return Eigen::Vector3d(u + 0.2 * v, v, 0.0); };
  std::string deck = "*KEYWORD\n" + p.text() + shell_part(1, 0.003, kRho, kE, 0.3, 3, 1, 0.1, 16);
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int j = 0; j <= p.ny; ++j)
    for (int i = 0; i <= p.nx; ++i) {
      const double u = p.lx * i / p.nx - 0.15, v = p.ly * j / p.ny - 0.15;
      deck += fmt::format("{},0,0,{:.17g},0,0,0\n", p.node_id(i, j),
                          std::cos(10.0 * u) * std::cos(7.0 * v) + 20.0 * u * v);
    }
  deck += "*CONTROL_TERMINATION\n0.02\n*END\n";
  solver::Simulation sim(read(deck), {});
  const double kinetic0 = sim.energy().kinetic;
  double internal_max = 0.0;
  sim.run([&](const solver::Simulation& s) {
    internal_max = std::max(internal_max, s.energy().internal_work);
  });
  std::printf("ELFORM 16 free plate: energy ratio %.8f, max internal / initial kinetic %.3f\n",
              sim.energy().ratio(), internal_max / kinetic0);
  RecordProperty("energy_ratio", std::to_string(sim.energy().ratio()));
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-3);
  EXPECT_GT(internal_max, 0.2 * kinetic0);
  EXPECT_EQ(sim.energy().hourglass, 0.0);
}

// In-plane bending of the same strip, one element across its 0.1 m depth (element aspect 1):
// the fully integrated bilinear membrane carries parasitic shear in bending and is stiffer than
// Timoshenko's beam, P L^3 / (3 E I) + P L / (k G A) (shear locking in the plane; the one-point
// ELFORM 2 with its hourglass stiffness IHQ 4 is measured alongside).
double in_plane_tip_ratio(int elform, int ny) {
  CantileverStrip strip;
  strip.ny = ny;
  const double load = 5.0;
  const double iz = strip.thickness * std::pow(strip.width, 3) / 12.0;
  const double area = strip.thickness * strip.width;
  const double expected = load * std::pow(strip.length, 3) / (3.0 * kE * iz) +
                          load * strip.length / (5.0 / 6.0 * 0.5 * kE * area);
  solver::Simulation sim(read(strip.deck(elform) + strip.static_tip_load(load, 2)), {});
  sim.run();
  return strip.tip_displacement(sim, 1) / expected;
}

TEST(Shell16Deck, InPlaneBendingOfCoarseStripLocksAsBilinearElements) {
  const double one16 = in_plane_tip_ratio(16, 1), two16 = in_plane_tip_ratio(16, 2);
  const double one2 = in_plane_tip_ratio(2, 1);
  std::printf(
      "in-plane bending, 10 x 1 elements: ELFORM 16 %.4f, ELFORM 2 (IHQ 4, QM 0.05) "
      "%.4f; 10 x 2: ELFORM 16 %.4f of Timoshenko\n",
      one16, one2, two16);
  RecordProperty("elform16_in_plane_ratio", std::to_string(one16));
  // Element length a over the depth H: a bilinear element in bending stores parasitic shear
  // energy (G / E) (a / H)^2 times the bending energy, whatever the elements across the depth,
  // so the deflection is 1 / (1 + (a / H)^2 / (2 (1 + nu))) = 2/3 here (measured 0.666 for both).
  EXPECT_NEAR(one16, 2.0 / 3.0, 0.01);
  EXPECT_NEAR(two16, one16, 0.005);
}

// elout_shell.csv of an ELFORM 16 element: at each through-thickness point the mean of the 4
// in-plane points (a flat axis-aligned element: element axes = global axes).
TEST(Shell16Deck, EloutShellAveragesTheInPlanePoints) {
  ShellPlate p;
  const model::Model model =
      read("*KEYWORD\n" + p.text() + shell_part(1, 0.01, kRho, kE, 0.3, 3, 1, 0.1, 16) + "*END\n");
  const solver::NodeIndex index(model);
  solver::State state = solver::build_state(model, index);
  element::ShellBlock& block = state.shell_blocks.at(0);
  ASSERT_EQ(block.points_per_element(), 12);
  for (std::size_t k = 0; k < block.stress.size(); ++k)
    block.stress[k] = 1e6 * static_cast<double>(k % 7) + 1e5 * static_cast<double>(k);
  const std::string text = output::elout_shell_text(0.0, state, {{0, 0}});
  std::istringstream lines(text);
  std::string line;
  int rows = 0;
  while (std::getline(lines, line)) {
    std::vector<double> v;
    std::stringstream fields(line);
    std::string f;
    while (std::getline(fields, f, ',')) v.push_back(std::stod(f));
    ASSERT_GE(v.size(), 11u) << line;
    const int q = static_cast<int>(v[3]) - 1;  // point 1..NIP
    double mean[5] = {0, 0, 0, 0, 0};
    for (int g = 0; g < 4; ++g)
      for (int c = 0; c < 5; ++c) mean[c] += 0.25 * block.stress[5 * (g * 3 + q) + c];
    EXPECT_NEAR(v[5], mean[0], 1e-6) << line;   // sxx
    EXPECT_NEAR(v[6], mean[1], 1e-6) << line;   // syy
    EXPECT_NEAR(v[8], mean[2], 1e-6) << line;   // sxy
    EXPECT_NEAR(v[9], mean[3], 1e-6) << line;   // syz
    EXPECT_NEAR(v[10], mean[4], 1e-6) << line;  // szx
    ++rows;
  }
  EXPECT_EQ(rows, 3);
}

// *CONTROL_SHELL THEORY 16 makes ELFORM 0 sections fully integrated; an *HOURGLASS card of an
// unsupported type and triangles are refused naming the card or the element.
TEST(Shell16Deck, TheoryAndInputErrors) {
  ShellPlate p;
  p.nx = p.ny = 2;
  const std::string mat = "*MAT_ELASTIC\n1,7800,2e11,0.3\n*PART\np\n1,1,1\n";
  {
    const std::string deck = "*KEYWORD\n" + p.text() + mat +
                             "*SECTION_SHELL\n1,0,1,2\n0.01\n*CONTROL_SHELL\n20,0,-1,0,16\n"
                             "*CONTROL_TERMINATION\n1e-5\n*END\n";
    solver::Simulation sim(read(deck), {});
    ASSERT_EQ(sim.state().shell_blocks.size(), 1u);
    EXPECT_EQ(sim.state().shell_blocks[0].elform, 16);
    EXPECT_EQ(sim.state().shell_blocks[0].points_per_element(), 8);
  }
  try {
    const std::string deck = "*KEYWORD\n" + p.text() +
                             "*MAT_ELASTIC\n1,7800,2e11,0.3\n*PART\np\n1,1,1,0,1\n"
                             "*SECTION_SHELL\n1,16,1,2\n0.01\n*HOURGLASS\n1,8,0.1\n"
                             "*CONTROL_TERMINATION\n1e-5\n*END\n";
    solver::Simulation sim(read(deck), {});
    ADD_FAILURE() << "IHQ 8 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("HGID"), std::string::npos) << e.what();
  }
  try {
    const std::string deck = "*KEYWORD\n" + p.text() + mat +
                             "*SECTION_SHELL\n1,16,1,2\n0.01\n*ELEMENT_SHELL\n9,1,1,2,5,5\n"
                             "*CONTROL_TERMINATION\n1e-5\n*END\n";
    solver::Simulation sim(read(deck), {});
    ADD_FAILURE() << "triangle accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("shell element 9 of part 1 is a triangle"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rf::test
