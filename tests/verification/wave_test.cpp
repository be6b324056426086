// 1D elastic wave in a bar (Poisson's ratio 0): a face driven at constant velocity v0 sends
// a step wave with stress -rho c v0 (c = sqrt(E/rho)); at the free end the wave reflects
// and the end moves at 2 v0 (d'Alembert's solution for a semi-infinite then finite bar).
#include <gtest/gtest.h>

#include <cmath>

#include "deck_builder.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7850.0, kE = 210e9, kV0 = 1.0, kLength = 1.0;

std::string bar_deck(int elform, int ihq, double end_time) {
  BoxMesh mesh;
  mesh.nx = 100;
  mesh.lx = kLength;
  mesh.ly = mesh.lz = 0.05;
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.0, elform, ihq);
  deck += node_set(1, mesh.face_x(0));
  deck += "*BOUNDARY_PRESCRIBED_MOTION_SET\n1,1,0,1,1.0\n";
  deck += "*DEFINE_CURVE\n1\n0.0,1.0\n1.0,1.0\n";
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", end_time);
  return deck;
}

class WaveInBar : public ::testing::TestWithParam<int> {};

TEST_P(WaveInBar, StressBehindFrontAndFreeEndVelocityMatchDAlembert) {
  const int elform = GetParam();
  const double c = std::sqrt(kE / kRho);
  const double transit = kLength / c;
  const model::Model model = read(bar_deck(elform, 6, 1.45 * transit));
  solver::Simulation sim(model, {});

  // Free-end node (x = L, y = z = 0): node id of (nx, 0, 0).
  const auto& ids = sim.state().nodes.id;
  std::size_t free_end = 0;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] == 101) free_end = i;

  bool checked_stress = false;
  double early_max = 0.0, late_sum = 0.0;
  int late_count = 0;
  while (!sim.finished()) {
    sim.cycle();
    const double t = sim.state().time;
    const double v = sim.state().nodes.v.x[free_end];
    if (t < 0.8 * transit) early_max = std::max(early_max, std::abs(v));
    if (t > 1.2 * transit && t < 1.45 * transit) {
      late_sum += v;
      ++late_count;
    }
    if (!checked_stress && t >= 0.75 * transit) {
      checked_stress = true;
      // Elements whose centre is well behind the front (x < 0.6 L) and past the driven end.
      const auto& block = sim.state().hex_blocks[0];
      const int points = block.points_per_element();
      double sum = 0.0;
      int n = 0;
      for (int e = 5; e < 60; ++e) {
        for (int p = 0; p < points; ++p) sum += block.stress[(e * points + p) * 6 + 0];
        n += points;
      }
      const double expected = -kRho * c * kV0;
      EXPECT_NEAR(sum / n, expected, 0.01 * std::abs(expected)) << "mean sigma_xx behind front";
    }
  }
  ASSERT_TRUE(checked_stress);
  EXPECT_LT(early_max, 0.02 * kV0) << "free end moved before the wave could arrive";
  ASSERT_GT(late_count, 10);
  EXPECT_NEAR(late_sum / late_count, 2.0 * kV0, 0.02 * kV0) << "free-end velocity after reflection";
}

INSTANTIATE_TEST_SUITE_P(Elform, WaveInBar, ::testing::Values(1, 2));

}  // namespace
}  // namespace rf::test
