// Hourglass control: resistance to hourglass modes, none for linear modes, and the exact
// bending energy of the Belytschko-Bindeman form (IHQ 6).
#include <gtest/gtest.h>

#include <cmath>

#include "element/hex_geometry.hpp"
#include "hex_test_support.hpp"

namespace {

using rf::test::HexMesh;

class Hourglass : public ::testing::TestWithParam<int> {};

TEST_P(Hourglass, ResistsEveryHourglassModeButNotLinearFields) {
  const int ihq = GetParam();
  const double dt = 1e-6;
  for (int mode = 0; mode < 4; ++mode)
    for (int dir = 0; dir < 3; ++dir) {
      HexMesh m = rf::test::single_hex(rf::test::kUnitCube);
      rf::test::set_material(m, 7800.0, 2.0e11, 0.3, 1, ihq, 0.1);
      m.initialize();
      std::vector<double>* v[3] = {&m.vx, &m.vy, &m.vz};
      std::vector<double>* x[3] = {&m.x, &m.y, &m.z};
      for (int n = 0; n < 8; ++n) {
        (*v[dir])[n] = rf::element::hex::kHourglassBase[mode][n];
        (*x[dir])[n] += dt * (*v[dir])[n];
      }
      const auto r = rf::element::compute_hex_forces(m.block, m.view(), dt);
      ASSERT_FALSE(r.failed);
      EXPECT_GT(r.hourglass_work, 0.0) << "mode " << mode << " dir " << dir;
      // Resisting: the internal force is parallel to the hourglass velocity.
      double fv = 0.0;
      for (int n = 0; n < 8; ++n) fv += m.block.force[3 * n + dir] * (*v[dir])[n];
      EXPECT_GT(fv, 0.0);
      // One-point stress sees nothing of the hourglass mode.
      for (int s = 0; s < 6; ++s) EXPECT_NEAR(m.block.stress[s], 0.0, 1.0);  // vs ~2e5 if seen
    }

  // A linear velocity field produces no hourglass force (IHQ 1 only on a parallelepiped).
  HexMesh m = rf::test::single_hex(ihq == 1 ? rf::test::kUnitCube : rf::test::kDistorted);
  rf::test::set_material(m, 7800.0, 2.0e11, 0.3, 1, ihq, 0.1);
  m.initialize();
  for (std::size_t n = 0; n < 8; ++n) {
    m.vx[n] = 0.3 * m.x[n] - 0.2 * m.y[n] + 0.5 * m.z[n];
    m.vy[n] = 0.1 * m.x[n] + 0.4 * m.y[n] - 0.3 * m.z[n];
    m.vz[n] = -0.2 * m.x[n] + 0.6 * m.y[n] + 0.2 * m.z[n];
  }
  const auto r = rf::element::compute_hex_forces(m.block, m.view(), 1e-7);
  EXPECT_NEAR(r.hourglass_work, 0.0, 1e-16);
  for (double q : m.block.hourglass_state) EXPECT_NEAR(q, 0.0, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Hex, Hourglass, ::testing::Values(1, 2, 3, 4, 5, 6));

TEST(Hourglass, ViscousFormIsNotOrthogonalOnDistortedElementsForIhq1) {
  // Documented LS-DYNA behaviour: IHQ 1 uses the raw base vectors, so a linear field on a
  // distorted element does work against the hourglass viscosity; IHQ 2 does not.
  for (int ihq : {1, 2}) {
    HexMesh m = rf::test::single_hex(rf::test::kDistorted);
    rf::test::set_material(m, 7800.0, 2.0e11, 0.3, 1, ihq, 0.1);
    m.initialize();
    for (std::size_t n = 0; n < 8; ++n) m.vx[n] = m.y[n];
    const auto r = rf::element::compute_hex_forces(m.block, m.view(), 1e-7);
    if (ihq == 1)
      EXPECT_GT(r.hourglass_work, 0.0);
    else
      EXPECT_NEAR(r.hourglass_work, 0.0, 1e-16);
  }
}

class PureBending : public ::testing::TestWithParam<double> {};

// Rectangular element 2a x 2b x 2c (x along the beam), pure bending about z with curvature
// kappa: u_x = -kappa x y, u_y = kappa x^2 / 2 (centred coordinates). The nodal values are a pure
// xi-eta hourglass mode in x plus a translation in y. Belytschko & Bindeman's element with QM = 1
// must store the exact beam energy E I kappa^2 L / 2, I = (2c)(2b)^3 / 12, L = 2a.
TEST_P(PureBending, Ihq6StoresExactBeamEnergy) {
  const double nu = GetParam();
  const double a = 2.0, b = 0.5, c = 0.25, kappa = 1e-6, E = 2.1e11;
  double corners[8][3];
  for (int k = 0; k < 8; ++k) {
    corners[k][0] = a * rf::element::hex::kXi[k];
    corners[k][1] = b * rf::element::hex::kEta[k];
    corners[k][2] = c * rf::element::hex::kZeta[k];
  }
  HexMesh m = rf::test::single_hex(corners);
  rf::test::set_material(m, 7800.0, E, nu, 1, 6, 1.0);
  m.initialize();
  const double dt = 1e-3;
  for (std::size_t n = 0; n < 8; ++n) {
    const double ux = -kappa * m.x[n] * m.y[n], uy = 0.5 * kappa * m.x[n] * m.x[n];
    m.vx[n] = ux / dt;
    m.vy[n] = uy / dt;
    m.x[n] += ux;
    m.y[n] += uy;
  }
  const auto r = rf::element::compute_hex_forces(m.block, m.view(), dt);
  const double inertia = (2 * c) * std::pow(2 * b, 3) / 12.0;
  const double exact = 0.5 * E * inertia * kappa * kappa * (2 * a);
  EXPECT_NEAR(r.hourglass_work, exact, 1e-6 * exact);
  for (int s = 0; s < 6; ++s) EXPECT_NEAR(m.block.stress[s], 0.0, 1e-6 * E * kappa * b);
}

INSTANTIATE_TEST_SUITE_P(Hex, PureBending, ::testing::Values(0.0, 0.3, 0.499));

}  // namespace
