// Energy conservation of a free element integrated with a small stand-alone central-difference
// loop: kinetic energy + initial strain energy + accumulated internal work is constant.
#include <gtest/gtest.h>

#include <cmath>

#include "hex_test_support.hpp"

namespace {

using rf::test::HexMesh;

struct Case {
  int elform;
  int ihq;
};

class FreeElementEnergy : public ::testing::TestWithParam<Case> {};

TEST_P(FreeElementEnergy, IsConserved) {
  HexMesh m = rf::test::single_hex(rf::test::kDistorted);
  const double E = 1.0e3, nu = 0.3, rho = 1.0;
  rf::test::set_material(m, rho, E, nu, GetParam().elform, GetParam().ihq, 0.1);
  m.initialize();
  const auto& mat = m.block.material;

  // Initial strain eps0 -> stress C : eps0 at every point; strain energy 0.5 sigma:eps V.
  const double eps0[6] = {2e-3, -1e-3, 0.5e-3, 0.8e-3, -0.3e-3, 0.4e-3};
  const auto s0 = rf::test::elastic_stress(mat, eps0);
  for (int g = 0; g < m.block.points_per_element(); ++g)
    for (int k = 0; k < 6; ++k) m.block.stress[6 * g + k] = s0[k];
  double strain0 = 0.0;
  for (int k = 0; k < 6; ++k) strain0 += (k < 3 ? 1.0 : 2.0) * s0[k] * eps0[k];
  strain0 *= 0.5 * m.block.volume0[0];

  std::vector<double> mass(8, 0.0);
  rf::element::add_hex_lumped_mass(m.block, mass);
  // Initial velocities with hourglass content; internal forces at t = 0 from a dt = 0 call.
  std::vector<double> v0[3];
  for (int i = 0; i < 3; ++i) v0[i].assign(8, 0.0);
  for (int n = 0; n < 8; ++n) {
    v0[0][n] = 0.02 * std::sin(1.0 + 3.0 * n);
    v0[1][n] = 0.015 * std::cos(2.0 * n);
    v0[2][n] = 0.01 * std::sin(0.5 + 1.7 * n);
  }
  ASSERT_FALSE(rf::element::compute_hex_forces(m.block, m.view(), 0.0).failed);
  std::vector<double> f_old = m.block.force;

  const double dt = 0.1 * rf::element::hex_critical_timestep(m.block, m.view()).min_dt;
  std::vector<double>* x[3] = {&m.x, &m.y, &m.z};
  std::vector<double>* v[3] = {&m.vx, &m.vy, &m.vz};
  // Kinetic energy in the same product form as below: v^{-1/2} . v^{+1/2}.
  double kinetic0 = 0.0;
  for (int n = 0; n < 8; ++n)
    for (int i = 0; i < 3; ++i) {
      const double half_dv = 0.5 * dt * f_old[3 * n + i] / mass[n];
      (*v[i])[n] = v0[i][n] - half_dv;
      kinetic0 += 0.5 * mass[n] * (v0[i][n] + half_dv) * (v0[i][n] - half_dv);
    }

  const double total0 = kinetic0 + strain0;
  double work = 0.0, max_error = 0.0;
  for (int step = 0; step < 400; ++step) {
    double dx[24];
    for (int n = 0; n < 8; ++n)
      for (int i = 0; i < 3; ++i) {
        dx[3 * n + i] = dt * (*v[i])[n];
        (*x[i])[n] += dx[3 * n + i];
      }
    const auto r = rf::element::compute_hex_forces(m.block, m.view(), dt);
    ASSERT_FALSE(r.failed);
    const std::vector<double>& f = m.block.force;
    double kinetic = 0.0;
    for (int n = 0; n < 8; ++n)
      for (int i = 0; i < 3; ++i) {
        const int s = 3 * n + i;
        work += 0.5 * (f_old[s] + f[s]) * dx[s];
        const double v_new = (*v[i])[n] - dt * f[s] / mass[n];
        // v^{n+1/2} . v^{n+3/2}: the kinetic energy that the central-difference scheme
        // conserves exactly for a linear system (no O(omega^2 dt^2) oscillation).
        kinetic += 0.5 * mass[n] * (*v[i])[n] * v_new;
        (*v[i])[n] = v_new;
      }
    f_old = f;
    max_error = std::max(max_error, std::abs(kinetic + strain0 + work - total0) / total0);
  }
  EXPECT_LT(max_error, 1e-3);
  RecordProperty("max_relative_energy_error", std::to_string(max_error));
}

INSTANTIATE_TEST_SUITE_P(Hex, FreeElementEnergy,
                         ::testing::Values(Case{1, 2}, Case{1, 4}, Case{1, 6}, Case{2, 0}));

}  // namespace
