// The 10-node tetrahedron kernel (element/tet10_block.cpp) on single elements:
//  - the 4-point stiffness has exactly the six rigid-body zero modes (no hourglass modes);
//  - the kernel's critical step is below 2 / omega_max of its own stiffness and lumped mass
//    (largest eigenvalue of M^-1 K, Eigen's dense solver) on regular, distorted and
//    curved-edge elements, at nu 0.3 and 0.49: stable with TSSFAC 1, hence with 0.9;
//  - the lumped mass: total rho V, and the HRZ fractions of the consistent mass diagonal
//    computed here from the exact integrals of products of volume coordinates,
//    int L1^a L2^b L3^c L4^d dV = 6 V a! b! c! d! / (a + b + c + d + 3)!.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "element/tet10_block.hpp"
#include "material/registry.hpp"

namespace rf::element {
namespace {

struct Element {
  std::vector<double> x, y, z, vx, vy, vz;
  HexBlock block;
  NodalView view() const { return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()}; }
};

Element make_element(const double coords[10][3], double nu) {
  Element el;
  for (int a = 0; a < 10; ++a) {
    el.x.push_back(coords[a][0]);
    el.y.push_back(coords[a][1]);
    el.z.push_back(coords[a][2]);
  }
  el.vx.assign(10, 0.0);
  el.vy.assign(10, 0.0);
  el.vz.assign(10, 0.0);
  el.block.elform = 16;
  el.block.part_id = 1;
  el.block.element_id = {1};
  for (int a = 0; a < 10; ++a) el.block.conn.push_back(a);
  el.block.material = material::make_elastic(1000.0, 1.0e7, nu);
  el.block.material_index = material::material_index(model::MaterialKind::Elastic);
  initialize_tet10_block(el.block, el.view());
  return el;
}

// Stiffness by central differences of the kernel's forces: displacement +-delta along one DOF
// as a velocity over dt = 1 from zero stress (the rate law gives sigma = C : eps).
Eigen::MatrixXd stiffness(Element& el) {
  Eigen::MatrixXd k(30, 30);
  const std::vector<double> x0 = el.x, y0 = el.y, z0 = el.z;
  const double delta = 1e-7;
  for (int j = 0; j < 30; ++j) {
    Eigen::VectorXd column = Eigen::VectorXd::Zero(30);
    for (const double sign : {1.0, -1.0}) {
      el.x = x0;
      el.y = y0;
      el.z = z0;
      std::fill(el.vx.begin(), el.vx.end(), 0.0);
      std::fill(el.vy.begin(), el.vy.end(), 0.0);
      std::fill(el.vz.begin(), el.vz.end(), 0.0);
      std::vector<double>* pos[3] = {&el.x, &el.y, &el.z};
      std::vector<double>* vel[3] = {&el.vx, &el.vy, &el.vz};
      (*pos[j % 3])[static_cast<std::size_t>(j / 3)] += sign * delta;
      (*vel[j % 3])[static_cast<std::size_t>(j / 3)] = sign * delta;
      std::fill(el.block.stress.begin(), el.block.stress.end(), 0.0);
      const KernelResult r = compute_tet10_forces(el.block, el.view(), 1.0);
      EXPECT_FALSE(r.failed);
      for (int i = 0; i < 30; ++i) column[i] += sign * el.block.force[static_cast<std::size_t>(i)];
    }
    k.col(j) = column / (2.0 * delta);
  }
  el.x = x0;
  el.y = y0;
  el.z = z0;
  return 0.5 * (k + k.transpose());
}

void regular(double out[10][3]) {
  const double corners[4][3] = {{0, 0, 0},
                                {1, 0, 0},
                                {0.5, std::sqrt(3.0) / 2.0, 0},
                                {0.5, std::sqrt(3.0) / 6.0, std::sqrt(2.0 / 3.0)}};
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) out[a][i] = corners[a][i];
  for (int m = 0; m < 6; ++m)
    for (int i = 0; i < 3; ++i)
      out[4 + m][i] = 0.5 * (out[kTet10Edge[m][0]][i] + out[kTet10Edge[m][1]][i]);
}

TEST(Tet10Kernel, StiffnessHasExactlyTheSixRigidBodyModes) {
  double x[10][3];
  regular(x);
  Element el = make_element(x, 0.3);
  const Eigen::MatrixXd k = stiffness(el);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(k);
  const double largest = eig.eigenvalues().maxCoeff();
  int zero = 0;
  for (int i = 0; i < 30; ++i) zero += std::abs(eig.eigenvalues()[i]) < 1e-6 * largest;
  const double smallest_nonzero = eig.eigenvalues()[6];
  std::printf("[measured] ELFORM 16 stiffness: %d zero modes, smallest nonzero %.3e of largest\n",
              zero, smallest_nonzero / largest);
  EXPECT_EQ(zero, 6);
  EXPECT_GT(smallest_nonzero, 1e-3 * largest);
}

TEST(Tet10Kernel, CriticalStepIsBelowTheLargestEigenvalueLimit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double lowest = 1e300, highest = 0.0;
  int checked = 0;
  for (const double nu : {0.3, 0.49}) {
    for (int trial = 0; trial < 60; ++trial) {
      double x[10][3];
      regular(x);
      const double corner_jitter = 0.3 * (trial % 20) / 20.0;
      const double midside_jitter = trial >= 30 ? 0.08 : 0.0;  // curved edges
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) x[a][i] += corner_jitter * u(rng);
      for (int m = 0; m < 6; ++m)
        for (int i = 0; i < 3; ++i)
          x[4 + m][i] =
              0.5 * (x[kTet10Edge[m][0]][i] + x[kTet10Edge[m][1]][i]) + midside_jitter * u(rng);
      if (!tet10_geometry_problem(x).empty()) continue;
      Element el = make_element(x, nu);
      const Eigen::MatrixXd k = stiffness(el);
      std::vector<double> mass(10, 0.0);
      add_tet10_lumped_mass(el.block, mass);
      Eigen::VectorXd inv_sqrt(30);
      for (int i = 0; i < 30; ++i)
        inv_sqrt[i] = 1.0 / std::sqrt(mass[static_cast<std::size_t>(i / 3)]);
      const Eigen::MatrixXd a = inv_sqrt.asDiagonal() * k * inv_sqrt.asDiagonal();
      const double omega2 =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues().maxCoeff();
      const double limit = 2.0 / std::sqrt(omega2);
      const double step = tet10_critical_timestep(el.block, el.view()).min_dt;
      lowest = std::min(lowest, step / limit);
      highest = std::max(highest, step / limit);
      ++checked;
      EXPECT_LT(step, limit) << "nu " << nu << " trial " << trial;
    }
  }
  std::printf(
      "[measured] ELFORM 16 step / (2 / omega_max) over %d elements (regular, distorted, curved; "
      "nu 0.3, 0.49): %.3f .. %.3f\n",
      checked, lowest, highest);
  EXPECT_GT(checked, 80);
  EXPECT_GT(lowest, 0.3);  // not needlessly small either
}

double factorial(int n) {
  return n <= 1 ? 1.0 : n * factorial(n - 1);
}

// int L_i^p L_j^q dV / V for i != j (the other two exponents 0).
double moment(int p, int q) {
  return 6.0 * factorial(p) * factorial(q) / factorial(p + q + 3);
}

TEST(Tet10Kernel, LumpedMassIsTheScaledConsistentDiagonal) {
  double x[10][3];
  regular(x);
  x[3][2] *= 1.7;  // a less regular straight-sided element
  for (int m = 0; m < 6; ++m)
    for (int i = 0; i < 3; ++i)
      x[4 + m][i] = 0.5 * (x[kTet10Edge[m][0]][i] + x[kTet10Edge[m][1]][i]);
  Element el = make_element(x, 0.3);
  std::vector<double> mass(10, 0.0);
  add_tet10_lumped_mass(el.block, mass);
  const double total = 1000.0 * el.block.volume0[0];
  // Corner: int (L (2L - 1))^2 = int 4 L^4 - 4 L^3 + L^2; mid-side: int 16 L_i^2 L_j^2.
  const double corner = 4.0 * moment(4, 0) - 4.0 * moment(3, 0) + moment(2, 0);
  const double midside = 16.0 * moment(2, 2);
  const double diagonal_sum = 4.0 * corner + 6.0 * midside;
  double sum = 0.0;
  for (int a = 0; a < 10; ++a) {
    sum += mass[static_cast<std::size_t>(a)];
    const double expected = total * (a < 4 ? corner : midside) / diagonal_sum;
    EXPECT_NEAR(mass[static_cast<std::size_t>(a)], expected, 1e-13 * total) << "node " << a;
    EXPECT_GT(mass[static_cast<std::size_t>(a)], 0.0);
  }
  EXPECT_NEAR(sum, total, 1e-13 * total);
  // The volume by the 4-point rule against the corner tetrahedron's.
  const double e1[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
  const double e2[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
  const double e3[3] = {x[3][0] - x[0][0], x[3][1] - x[0][1], x[3][2] - x[0][2]};
  const double six_v = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) -
                       e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) +
                       e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
  EXPECT_NEAR(el.block.volume0[0], six_v / 6.0, 1e-14);
}

}  // namespace
}  // namespace rf::element
