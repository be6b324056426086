// Rigid-body motion and objectivity of the hexahedron kernels and the Jaumann update.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "hex_test_support.hpp"

namespace {

using rf::test::HexMesh;

Eigen::Matrix3d to_matrix(const double* s) {
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  return m;
}

// Moves every node to R(theta) * X + t and sets v = (x^{n+1} - x^n) / dt.
void move_rigidly(HexMesh& m, const std::vector<Eigen::Vector3d>& X, const Eigen::Matrix3d& R,
                  const Eigen::Vector3d& t, double dt) {
  for (std::size_t i = 0; i < X.size(); ++i) {
    const Eigen::Vector3d x = R * X[i] + t;
    m.vx[i] = (x.x() - m.x[i]) / dt;
    m.vy[i] = (x.y() - m.y[i]) / dt;
    m.vz[i] = (x.z() - m.z[i]) / dt;
    m.x[i] = x.x();
    m.y[i] = x.y();
    m.z[i] = x.z();
  }
}

std::vector<Eigen::Vector3d> reference(const HexMesh& m) {
  std::vector<Eigen::Vector3d> X;
  for (std::size_t i = 0; i < m.nodes(); ++i) X.emplace_back(m.x[i], m.y[i], m.z[i]);
  return X;
}

struct Case {
  int elform;
  int ihq;
  bool distorted;
};

class RigidMotion : public ::testing::TestWithParam<Case> {};

TEST_P(RigidMotion, TranslationAndRotationLeaveUnstressedElementForceFree) {
  const Case c = GetParam();
  HexMesh m = rf::test::single_hex(c.distorted ? rf::test::kDistorted : rf::test::kUnitCube);
  rf::test::set_material(m, 7800.0, 2.0e11, 0.3, c.elform, c.ihq, 0.1);
  m.initialize();
  const auto X = reference(m);
  const double dt = 1e-4;
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
  const int steps = 200;
  for (int s = 1; s <= steps; ++s) {
    const double theta = 0.5 * M_PI * s / steps;  // 90 degrees overall
    const Eigen::Matrix3d R = Eigen::AngleAxisd(theta, axis).toRotationMatrix();
    const Eigen::Vector3d t = Eigen::Vector3d(3.0, -1.0, 2.0) * (double(s) / steps);
    move_rigidly(m, X, R, t, dt);
    const auto r = rf::element::compute_hex_forces(m.block, m.view(), dt);
    ASSERT_FALSE(r.failed);
  }
  // Scale: a strain of 1e-12 would give a stress of 0.2 Pa; forces of a 1 m element likewise.
  for (double s : m.block.stress) EXPECT_LT(std::abs(s), 1.0) << "stress not rigid-body free";
  for (double f : m.block.force) EXPECT_LT(std::abs(f), 1.0) << "force not rigid-body free";
  EXPECT_NEAR(m.block.volume[0], m.block.volume0[0], 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Hex, RigidMotion,
                         ::testing::Values(Case{1, 1, false}, Case{1, 2, true}, Case{1, 3, true},
                                           Case{1, 4, true}, Case{1, 5, true}, Case{1, 6, true},
                                           Case{2, 0, true}));

class PrestressRotation : public ::testing::TestWithParam<int> {};

// A pre-stressed element rotated by 90 degrees in many steps: the Hughes-Winget update with rates
// on the mid-step configuration rotates the stress exactly (sigma = R sigma0 R^T), so the
// principal values are preserved to round-off.
TEST_P(PrestressRotation, StressRotatesObjectively) {
  HexMesh m = rf::test::single_hex(rf::test::kDistorted);
  rf::test::set_material(m, 7800.0, 2.0e11, 0.3, GetParam(), 6, 1.0);
  m.initialize();
  const double s0[6] = {3.0e8, -1.0e8, 0.5e8, 0.7e8, -0.4e8, 0.2e8};
  const int points = m.block.points_per_element();
  for (int g = 0; g < points; ++g)
    for (int k = 0; k < 6; ++k) m.block.stress[6 * g + k] = s0[k];
  const auto X = reference(m);
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -1, 2).normalized();
  const int steps = 1000;
  Eigen::Matrix3d R;
  for (int s = 1; s <= steps; ++s) {
    R = Eigen::AngleAxisd(0.5 * M_PI * s / steps, axis).toRotationMatrix();
    move_rigidly(m, X, R, Eigen::Vector3d::Zero(), 1e-5);
    ASSERT_FALSE(rf::element::compute_hex_forces(m.block, m.view(), 1e-5).failed);
  }
  const Eigen::Matrix3d sigma0 = to_matrix(s0);
  const Eigen::Vector3d p0 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(sigma0).eigenvalues();
  const Eigen::Matrix3d expected = R * sigma0 * R.transpose();
  for (int g = 0; g < points; ++g) {
    const Eigen::Matrix3d sigma = to_matrix(&m.block.stress[6 * g]);
    const Eigen::Vector3d p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(sigma).eigenvalues();
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], p0[k], 1e-10 * p0.cwiseAbs().maxCoeff());
    EXPECT_LT((sigma - expected).norm(), 1e-9 * sigma0.norm());
  }
}

INSTANTIATE_TEST_SUITE_P(Hex, PrestressRotation, ::testing::Values(1, 2));

TEST(ElasticUpdate, CayleyRotationIsOrthogonalForLargeSpin) {
  // Rotating an isotropic stress must leave it unchanged; a deviatoric one keeps its norm.
  double iso[6] = {5, 5, 5, 0, 0, 0};
  const double w[3] = {3.0, -7.0, 11.0};
  rf::material::hughes_winget_rotate(w, 0.3, iso);
  EXPECT_NEAR(iso[0], 5.0, 1e-13);
  EXPECT_NEAR(iso[3], 0.0, 1e-13);
  double s[6] = {1, -2, 1, 0.5, 0.25, -0.75};
  const double n0 = to_matrix(s).norm();
  rf::material::hughes_winget_rotate(w, 0.3, s);
  EXPECT_NEAR(to_matrix(s).norm(), n0, 1e-13);
  EXPECT_GT(std::abs(s[0] - 1.0), 1e-3);  // it did rotate
}

}  // namespace
