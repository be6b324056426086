// Patch test: a distorted 2x2x2 block under a linear velocity field reaches the same exact
// constant stress in every element (every Gauss point for ELFORM 2) and the interior node is in
// equilibrium.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "hex_test_support.hpp"

namespace {

using rf::test::HexMesh;

HexMesh distorted_patch() {
  HexMesh m;
  auto id = [](int i, int j, int k) { return static_cast<std::int32_t>(i + 3 * j + 9 * k); };
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) m.add_node(i, j, k);
  // Interior node moved off-centre; face-centre nodes moved within their (planar) faces.
  m.x[id(1, 1, 1)] = 1.23;
  m.y[id(1, 1, 1)] = 0.81;
  m.z[id(1, 1, 1)] = 1.17;
  m.x[id(1, 1, 0)] = 0.85;
  m.y[id(1, 1, 0)] = 1.2;
  m.y[id(1, 0, 1)] = 0;
  m.x[id(1, 0, 1)] = 1.15;
  m.z[id(1, 0, 1)] = 0.9;
  m.y[id(2, 1, 1)] = 1.1;
  m.z[id(2, 1, 1)] = 1.2;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        m.add_element({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                       id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                       id(i, j + 1, k + 1)});
  return m;
}

struct Case {
  int elform;
  int ihq;
};

class Patch : public ::testing::TestWithParam<Case> {};

TEST_P(Patch, LinearFieldGivesExactConstantStressAndEquilibrium) {
  HexMesh m = distorted_patch();
  rf::test::set_material(m, 7800.0, 2.0e11, 0.3, GetParam().elform, GetParam().ihq, 0.1);
  m.initialize();
  Eigen::Matrix3d G;
  G << 1.0, 0.4, -0.3, 0.2, -0.7, 0.5, -0.6, 0.1, 0.9;
  const double eps = 1e-5, dt = 1e-6;
  for (std::size_t n = 0; n < m.nodes(); ++n) {
    const Eigen::Vector3d X(m.x[n], m.y[n], m.z[n]);
    const Eigen::Vector3d u = eps * G * X;
    m.x[n] += u.x();
    m.y[n] += u.y();
    m.z[n] += u.z();
    m.vx[n] = u.x() / dt;
    m.vy[n] = u.y() / dt;
    m.vz[n] = u.z() / dt;
  }
  const auto r = rf::element::compute_hex_forces(m.block, m.view(), dt);
  ASSERT_FALSE(r.failed);
  EXPECT_NEAR(r.hourglass_work, 0.0, 1e-20);

  // Exact rate on the mid-step configuration x_mid = (I + eps G / 2) X.
  const Eigen::Matrix3d Lmid = (eps * G) * (Eigen::Matrix3d::Identity() + 0.5 * eps * G).inverse();
  const Eigen::Matrix3d D = 0.5 * (Lmid + Lmid.transpose());
  const double d[6] = {D(0, 0), D(1, 1), D(2, 2), D(0, 1), D(1, 2), D(2, 0)};
  const auto expected = rf::test::elastic_stress(m.block.material, d);
  const double scale = std::abs(expected[0]) + std::abs(expected[1]) + std::abs(expected[2]);
  for (std::size_t s = 0; s < m.block.stress.size(); ++s)
    EXPECT_NEAR(m.block.stress[s], expected[s % 6], 1e-10 * scale) << "entry " << s;

  // Interior node 13 appears once in each of the 8 elements.
  double f[3] = {0, 0, 0}, fabs_max = 0.0;
  for (std::size_t e = 0; e < m.block.size(); ++e)
    for (int k = 0; k < 8; ++k) {
      for (int i = 0; i < 3; ++i)
        fabs_max = std::max(fabs_max, std::abs(m.block.force[24 * e + 3 * k + i]));
      if (m.block.conn[8 * e + k] != 13) continue;
      for (int i = 0; i < 3; ++i) f[i] += m.block.force[24 * e + 3 * k + i];
    }
  ASSERT_GT(fabs_max, 0.0);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(f[i], 0.0, 1e-12 * fabs_max);
}

INSTANTIATE_TEST_SUITE_P(Hex, Patch,
                         ::testing::Values(Case{1, 2}, Case{1, 3}, Case{1, 4}, Case{1, 5},
                                           Case{1, 6}, Case{2, 0}));

}  // namespace
