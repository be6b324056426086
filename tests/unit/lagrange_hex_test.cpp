// Lagrange hexahedra of order 2 and 3 (element/lagrange_hex.hpp): the GLL rule, patch tests on
// distorted elements, objectivity, mass and volume, and the critical-step eigenvalue estimate
// against a dense generalized eigen solve.
#include "element/lagrange_hex.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "element/hex_geometry.hpp"
#include "material/elastic.hpp"
#include "mesh/p_order.hpp"
#include "model/error.hpp"

namespace {

using rf::element::gll_rule;
using rf::element::HexBlock;
using Vec3 = std::array<double, 3>;

struct LagrangeMesh {
  std::vector<double> x, y, z, vx, vy, vz;
  HexBlock block;
  rf::element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
  std::size_t nodes() const { return x.size(); }
  void set_nodes(const std::vector<Vec3>& p) {
    x.clear();
    y.clear();
    z.clear();
    for (const auto& q : p) {
      x.push_back(q[0]);
      y.push_back(q[1]);
      z.push_back(q[2]);
    }
    vx.assign(p.size(), 0.0);
    vy.assign(p.size(), 0.0);
    vz.assign(p.size(), 0.0);
  }
  // Applies x <- f(x) to every node.
  void map(const std::function<Vec3(const Vec3&)>& f) {
    for (std::size_t n = 0; n < nodes(); ++n) {
      const Vec3 p = f({x[n], y[n], z[n]});
      x[n] = p[0];
      y[n] = p[1];
      z[n] = p[2];
    }
  }
};

constexpr double kRho = 7800.0, kYoung = 2.0e11, kNu = 0.3;

void set_block(LagrangeMesh& m, int order, std::size_t elements) {
  m.block.part_id = 3;
  m.block.order = order;
  m.block.material = rf::material::make_elastic(kRho, kYoung, kNu);
  for (std::size_t e = 0; e < elements; ++e)
    m.block.element_id.push_back(static_cast<rf::model::Id>(101 + e));
}

// Elements elevated from 8-node hexahedra (trilinear geometry) with mesh/p_order.
LagrangeMesh elevated(int order, std::vector<Vec3> corners,
                      const std::vector<std::array<std::int32_t, 8>>& hexes) {
  LagrangeMesh m;
  rf::mesh::HexElevator elevator(order, corners);
  m.block.conn = elevator.add_block(hexes);
  m.set_nodes(corners);
  set_block(m, order, hexes.size());
  rf::element::initialize_lagrange_hex_block(m.block, m.view());
  return m;
}

// One element whose nodes are X(xi, eta, zeta) at the GLL points (curved geometry allowed).
LagrangeMesh mapped(int order, const std::function<Vec3(double, double, double)>& X) {
  const auto& r = gll_rule(order);
  const int n = order + 1;
  std::vector<Vec3> p;
  LagrangeMesh m;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        p.push_back(X(r.points[i], r.points[j], r.points[k]));
        m.block.conn.push_back(static_cast<std::int32_t>(p.size() - 1));
      }
  m.set_nodes(p);
  set_block(m, order, 1);
  rf::element::initialize_lagrange_hex_block(m.block, m.view());
  return m;
}

// The distorted hexahedron of the 8-node tests: warped faces, not a parallelepiped.
const std::vector<Vec3> kDistorted = {{0.0, 0.0, 0.0},    {1.2, 0.1, -0.1},  {1.3, 1.1, 0.2},
                                      {-0.1, 0.9, 0.05},  {0.1, -0.05, 1.0}, {1.0, 0.2, 1.3},
                                      {1.15, 1.25, 0.95}, {0.05, 1.0, 1.1}};

LagrangeMesh distorted_element(int order) {
  return elevated(order, kDistorted, {{0, 1, 2, 3, 4, 5, 6, 7}});
}

// Two distorted hexahedra sharing the face n2 n3 n7 n6 of the first.
LagrangeMesh two_element_patch(int order) {
  std::vector<Vec3> c = kDistorted;
  c.push_back({2.3, -0.1, 0.1});
  c.push_back({2.4, 1.2, -0.05});
  c.push_back({2.2, 1.1, 1.2});
  c.push_back({2.35, 0.05, 1.15});
  return elevated(order, c, {{0, 1, 2, 3, 4, 5, 6, 7}, {1, 8, 9, 2, 5, 11, 10, 6}});
}

// Analytic neo-Hookean Cauchy stress for a homogeneous deformation gradient F (Voigt).
std::array<double, 6> neo_hookean_cauchy(const rf::material::ElasticConstants& c,
                                         const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const Eigen::Matrix3d s = (c.shear * (F * F.transpose() - Eigen::Matrix3d::Identity()) +
                             c.lambda * std::log(J) * Eigen::Matrix3d::Identity()) /
                            J;
  return {s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(2, 0)};
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (const double a : v) m = std::max(m, std::abs(a));
  return m;
}

// Sum of element force slots per node (the assembly).
std::vector<double> assemble(const LagrangeMesh& m) {
  std::vector<double> f(3 * m.nodes(), 0.0);
  for (std::size_t s = 0; s < m.block.conn.size(); ++s)
    for (int i = 0; i < 3; ++i)
      f[3 * static_cast<std::size_t>(m.block.conn[s]) + i] += m.block.force[3 * s + i];
  return f;
}

// --- GLL rule ---------------------------------------------------------------------------------

TEST(GllRule, KnownPointsAndWeights) {
  const auto& r2 = gll_rule(2);
  ASSERT_EQ(r2.points.size(), 3u);
  EXPECT_DOUBLE_EQ(r2.points[0], -1.0);
  EXPECT_DOUBLE_EQ(r2.points[1], 0.0);
  EXPECT_DOUBLE_EQ(r2.points[2], 1.0);
  EXPECT_NEAR(r2.weights[0], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(r2.weights[1], 4.0 / 3.0, 1e-15);
  EXPECT_NEAR(r2.weights[2], 1.0 / 3.0, 1e-15);

  const auto& r3 = gll_rule(3);
  const double a = 1.0 / std::sqrt(5.0);
  const double expected3[4] = {-1.0, -a, a, 1.0};
  const double w3[4] = {1.0 / 6.0, 5.0 / 6.0, 5.0 / 6.0, 1.0 / 6.0};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(r3.points[i], expected3[i], 1e-15) << i;
    EXPECT_NEAR(r3.weights[i], w3[i], 1e-15) << i;
  }
  // p = 4: 0, +-sqrt(3/7); weights 1/10, 49/90, 32/45.
  const auto& r4 = gll_rule(4);
  EXPECT_NEAR(r4.points[1], -std::sqrt(3.0 / 7.0), 1e-15);
  EXPECT_NEAR(r4.weights[0], 0.1, 1e-15);
  EXPECT_NEAR(r4.weights[1], 49.0 / 90.0, 1e-15);
  EXPECT_NEAR(r4.weights[2], 32.0 / 45.0, 1e-15);
  EXPECT_THROW(gll_rule(0), std::invalid_argument);
  EXPECT_THROW(gll_rule(9), std::invalid_argument);
}

TEST(GllRule, SymmetricAscendingAndExactToDegree2pMinus1) {
  for (int p = 1; p <= 8; ++p) {
    const auto& r = gll_rule(p);
    for (int i = 0; i <= p; ++i) {
      EXPECT_EQ(r.points[i], -r.points[p - i]) << "p " << p;  // bitwise: elevation relies on it
      if (i > 0) EXPECT_LT(r.points[i - 1], r.points[i]);
    }
    for (int m = 0; m <= 2 * p - 1; ++m) {
      double s = 0.0;
      for (int i = 0; i <= p; ++i) s += r.weights[i] * std::pow(r.points[i], m);
      const double exact = m % 2 == 1 ? 0.0 : 2.0 / (m + 1);
      EXPECT_NEAR(s, exact, 1e-14) << "p " << p << " degree " << m;
    }
    // Degree 2p is not integrated exactly (the rule is not Gauss): a sanity check that the test
    // above can fail.
    double s = 0.0;
    for (int i = 0; i <= p; ++i) s += r.weights[i] * std::pow(r.points[i], 2 * p);
    EXPECT_GT(std::abs(s - 2.0 / (2 * p + 1)), 1e-6) << "p " << p;
  }
}

TEST(GllRule, DifferentiationExactForDegreeP) {
  for (int p = 1; p <= 8; ++p) {
    const auto& r = gll_rule(p);
    const int n = p + 1;
    EXPECT_NEAR(r.derivative[0], -p * (p + 1) / 4.0, 1e-12);
    for (int m = 0; m <= p; ++m)
      for (int i = 0; i < n; ++i) {
        double d = 0.0;
        for (int j = 0; j < n; ++j) d += r.derivative[i * n + j] * std::pow(r.points[j], m);
        const double exact = m == 0 ? 0.0 : m * std::pow(r.points[i], m - 1);
        EXPECT_NEAR(d, exact, 1e-12 * (1 + m * m)) << "p " << p << " degree " << m << " at " << i;
      }
  }
}

// --- Kernel -----------------------------------------------------------------------------------

class Lagrange : public ::testing::TestWithParam<int> {};

TEST_P(Lagrange, ReferenceVolumeAndMassOfDistortedElement) {
  const int p = GetParam();
  LagrangeMesh m = distorted_element(p);
  double xc[3][8];
  for (int c = 0; c < 8; ++c)
    for (int i = 0; i < 3; ++i) xc[i][c] = kDistorted[c][i];
  const double exact = rf::element::hex::hex_volume(xc);  // exact for the trilinear map
  EXPECT_NEAR(m.block.volume0[0], exact, 1e-13 * exact);
  std::vector<double> mass(m.nodes(), 0.0);
  rf::element::add_lagrange_hex_lumped_mass(m.block, mass);
  double total = 0.0;
  for (const double a : mass) {
    EXPECT_GT(a, 0.0);  // GLL weights are positive
    total += a;
  }
  EXPECT_NEAR(total, kRho * exact, 1e-12 * kRho * exact);
}

// Linear displacement field x = A X + c: F = A exactly at every GLL point (collocation), so the
// stress is the analytic neo-Hookean value everywhere; nodes away from the patch boundary are in
// equilibrium because the GLL rule integrates a constant stress exactly on trilinear geometry
// (p >= 2, see lagrange_hex.cpp).
TEST_P(Lagrange, PatchTestLinearFieldOnDistortedTwoElementPatch) {
  const int p = GetParam();
  for (const double amplitude : {1e-4, 0.3}) {
    LagrangeMesh m = two_element_patch(p);
    Eigen::Matrix3d G;
    G << 1.0, 0.4, -0.3, 0.2, -0.7, 0.5, -0.6, 0.1, 0.9;
    const Eigen::Matrix3d A = Eigen::Matrix3d::Identity() + amplitude * G;
    const Eigen::Vector3d c(0.3, -1.2, 2.0);
    m.map([&](const Vec3& X) {
      const Eigen::Vector3d x = A * Eigen::Vector3d(X[0], X[1], X[2]) + c;
      return Vec3{x[0], x[1], x[2]};
    });
    const auto r = rf::element::compute_lagrange_hex_forces(m.block, m.view(), 1e-6);
    ASSERT_FALSE(r.failed);
    EXPECT_EQ(r.hourglass_work, 0.0);

    const auto expected = neo_hookean_cauchy(m.block.material, A);
    double scale = 0.0;
    for (const double s : expected) scale = std::max(scale, std::abs(s));
    double stress_err = 0.0;
    for (std::size_t s = 0; s < m.block.stress.size(); ++s)
      stress_err = std::max(stress_err, std::abs(m.block.stress[s] - expected[s % 6]));
    // Round-off: sigma is formed from b - I, so its error scales with E, not with |sigma|.
    EXPECT_LT(stress_err, 1e-14 * kYoung + 1e-12 * scale)
        << "p " << p << " amplitude " << amplitude;
    if (amplitude < 1e-3) {
      // Small strain: the neo-Hookean stress is *MAT_ELASTIC's to first order.
      const Eigen::Matrix3d eps = 0.5 * (A + A.transpose()) - Eigen::Matrix3d::Identity();
      const auto& mat = m.block.material;
      const double tr = eps.trace();
      EXPECT_NEAR(m.block.stress[0], mat.lambda * tr + 2 * mat.shear * eps(0, 0),
                  10 * amplitude * scale);
      EXPECT_NEAR(m.block.stress[3], 2 * mat.shear * eps(0, 1), 10 * amplitude * scale);
    }
    // Current volume = det A * V0.
    double v0 = 0.0, v = 0.0;
    for (std::size_t e = 0; e < 2; ++e) {
      v0 += m.block.volume0[e];
      v += m.block.volume[e];
    }
    EXPECT_NEAR(v, A.determinant() * v0, 1e-12 * v0);

    // Nodes on the patch boundary carry the traction resultants; every other node (the element
    // interiors and the interior of the shared face) must be in equilibrium.
    const auto f = assemble(m);
    const double fscale = max_abs(m.block.force);
    const int n = p + 1;
    std::vector<int> boundary(m.nodes(), 0);
    for (std::size_t e = 0; e < 2; ++e)
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            // The shared face is i == p of element 0 and i == 0 of element 1 (xi runs along x).
            const bool shared = (e == 0 && i == p) || (e == 1 && i == 0);
            const bool on_face = i == 0 || i == p || j == 0 || j == p || k == 0 || k == p;
            const bool on_shared_edge = shared && (j == 0 || j == p || k == 0 || k == p);
            if ((on_face && !shared) || on_shared_edge)
              boundary[m.block.conn[e * n * n * n + i + n * (j + n * k)]] = 1;
          }
    double interior_err = 0.0;
    int interior = 0;
    for (std::size_t a = 0; a < m.nodes(); ++a) {
      if (boundary[a]) continue;
      ++interior;
      for (int i = 0; i < 3; ++i) interior_err = std::max(interior_err, std::abs(f[3 * a + i]));
    }
    EXPECT_EQ(interior, 2 * (p - 1) * (p - 1) * (p - 1) + (p - 1) * (p - 1));
    EXPECT_LT(interior_err, 1e-14 * kYoung + 1e-12 * fscale)
        << "p " << p << " amplitude " << amplitude;
    std::printf(
        "[ patch ] p=%d amplitude=%g: max stress error / |sigma| = %.2e, max interior "
        "force / max force = %.2e (%d interior nodes)\n",
        p, amplitude, stress_err / scale, interior_err / fscale, interior);
  }
}

TEST_P(Lagrange, CurvedElementLinearFieldGivesExactStress) {
  // Nodes on a cylinder: curved geometry; F is still exactly A at every point.
  const int p = GetParam();
  LagrangeMesh m = mapped(p, [](double xi, double eta, double zeta) {
    const double r = 1.5 + 0.5 * xi, th = 0.4 * (eta + 1.0);
    return Vec3{r * std::cos(th), r * std::sin(th), 0.5 * (zeta + 1.0)};
  });
  Eigen::Matrix3d A;
  A << 1.1, 0.2, 0.0, -0.1, 0.95, 0.05, 0.0, 0.1, 1.2;
  m.map([&](const Vec3& X) {
    const Eigen::Vector3d x = A * Eigen::Vector3d(X[0], X[1], X[2]);
    return Vec3{x[0], x[1], x[2]};
  });
  ASSERT_FALSE(rf::element::compute_lagrange_hex_forces(m.block, m.view(), 0.0).failed);
  const auto expected = neo_hookean_cauchy(m.block.material, A);
  for (std::size_t s = 0; s < m.block.stress.size(); ++s)
    EXPECT_NEAR(m.block.stress[s], expected[s % 6], 1e-11 * std::abs(expected[0]));
}

TEST_P(Lagrange, RigidRotationGivesZeroForceAndStress) {
  const int p = GetParam();
  LagrangeMesh m = distorted_element(p);
  // 90 degrees about a general axis, plus a translation.
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d(1.0, 2.0, -0.5).normalized())
          .toRotationMatrix();
  m.map([&](const Vec3& X) {
    const Eigen::Vector3d x = R * Eigen::Vector3d(X[0], X[1], X[2]) + Eigen::Vector3d(5, -3, 1);
    return Vec3{x[0], x[1], x[2]};
  });
  const auto r = rf::element::compute_lagrange_hex_forces(m.block, m.view(), 0.0);
  ASSERT_FALSE(r.failed);
  // Scale: the force of a unit strain would be ~ E * area.
  EXPECT_LT(max_abs(m.block.force), 1e-12 * kYoung);
  EXPECT_LT(max_abs(m.block.stress), 1e-12 * kYoung);
  EXPECT_NEAR(m.block.volume[0], m.block.volume0[0], 1e-13);
}

TEST_P(Lagrange, TranslationInvarianceAndFreeBodyEquilibrium) {
  const int p = GetParam();
  LagrangeMesh m = distorted_element(p);
  // A non-homogeneous deformation: quadratic bending-like field.
  m.map([](const Vec3& X) {
    return Vec3{X[0] + 0.05 * X[1] * X[1], X[1] - 0.03 * X[0] * X[2], X[2] + 0.02 * X[0] * X[0]};
  });
  ASSERT_FALSE(rf::element::compute_lagrange_hex_forces(m.block, m.view(), 0.0).failed);
  const std::vector<double> f0 = m.block.force;
  // Internal forces are self-equilibrated: zero resultant and zero moment about the origin.
  Eigen::Vector3d resultant = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  for (std::size_t a = 0; a < m.nodes(); ++a) {
    const Eigen::Vector3d fa(f0[3 * a], f0[3 * a + 1], f0[3 * a + 2]);
    const auto node = static_cast<std::size_t>(m.block.conn[a]);  // slot a is node conn[a]
    resultant += fa;
    moment += Eigen::Vector3d(m.x[node], m.y[node], m.z[node]).cross(fa);
  }
  const double scale = max_abs(f0);
  EXPECT_LT(resultant.norm(), 1e-12 * scale);
  EXPECT_LT(moment.norm(), 1e-11 * scale);

  m.map([](const Vec3& X) { return Vec3{X[0] + 1000.0, X[1] - 250.0, X[2] + 3.5}; });
  ASSERT_FALSE(rf::element::compute_lagrange_hex_forces(m.block, m.view(), 0.0).failed);
  for (std::size_t s = 0; s < f0.size(); ++s)
    EXPECT_NEAR(m.block.force[s], f0[s], 1e-9 * scale) << s;
}

// The force kernel linearised at the reference configuration is apply_linear_stiffness: checks
// the neo-Hookean small-strain limit and the stiffness operator the time step is computed from.
TEST_P(Lagrange, ForceTangentAtReferenceIsLinearStiffness) {
  const int p = GetParam();
  LagrangeMesh m = distorted_element(p);
  const std::size_t dofs = 3 * m.nodes();
  std::vector<double> u(dofs), ku(dofs);
  for (std::size_t s = 0; s < dofs; ++s) u[s] = std::sin(1.7 * s + 0.3);
  rf::element::apply_linear_stiffness(m.block, 0, u.data(), ku.data());
  const double h = 1e-7;
  const LagrangeMesh ref = m;
  // u is in element slot order; slot a is node conn[a].
  for (std::size_t a = 0; a < m.nodes(); ++a) {
    const auto node = static_cast<std::size_t>(m.block.conn[a]);
    m.x[node] = ref.x[node] + h * u[3 * a];
    m.y[node] = ref.y[node] + h * u[3 * a + 1];
    m.z[node] = ref.z[node] + h * u[3 * a + 2];
  }
  ASSERT_FALSE(rf::element::compute_lagrange_hex_forces(m.block, m.view(), 0.0).failed);
  const double scale = max_abs(ku);
  for (std::size_t s = 0; s < dofs; ++s)
    EXPECT_NEAR(m.block.force[s] / h, ku[s], 1e-5 * scale) << s;
}

// Dense element K (operator applied to unit vectors) and GLL mass; exact top eigenvalue of
// M^-1/2 K M^-1/2.
double dense_max_eigenvalue(const LagrangeMesh& m, std::size_t e,
                            Eigen::MatrixXd* K_out = nullptr) {
  const int npe = m.block.nodes_per_element();
  const int n = 3 * npe;
  Eigen::MatrixXd K(n, n);
  std::vector<double> u(n, 0.0), f(n);
  for (int c = 0; c < n; ++c) {
    u[c] = 1.0;
    rf::element::apply_linear_stiffness(m.block, e, u.data(), f.data());
    u[c] = 0.0;
    for (int r = 0; r < n; ++r) K(r, c) = f[r];
  }
  Eigen::VectorXd s(n);
  for (int a = 0; a < npe; ++a)
    for (int i = 0; i < 3; ++i)
      s[3 * a + i] = 1.0 / std::sqrt(kRho * m.block.reference_weight[npe * e + a]);
  if (K_out) *K_out = K;
  const Eigen::MatrixXd Asym = s.asDiagonal() * (0.5 * (K + K.transpose())) * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Asym, Eigen::EigenvaluesOnly);
  return es.eigenvalues()[n - 1];
}

TEST_P(Lagrange, EigenvalueEstimateBoundsDenseSolveWithinOnePercent) {
  const int p = GetParam();
  const std::vector<Vec3> cube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  // A slender brick too, where the top mode is along the short side.
  std::vector<Vec3> brick = cube;
  for (auto& c : brick) c = {2.0 * c[0], 0.5 * c[1], c[2]};
  for (const auto& corners : {cube, kDistorted, brick}) {
    LagrangeMesh m = elevated(p, corners, {{0, 1, 2, 3, 4, 5, 6, 7}});
    Eigen::MatrixXd K;
    const double exact = dense_max_eigenvalue(m, 0, &K);
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
    const auto est = rf::element::estimate_max_eigenvalue_detail(m.block, 0);
    EXPECT_LE(est.ritz, exact * (1 + 1e-12));
    EXPECT_GE(est.estimate, exact) << "the estimate must not be below the exact value (unsafe)";
    EXPECT_LE(est.estimate, 1.01 * exact);
    EXPECT_NEAR(m.block.reference_dt[0], 2.0 / std::sqrt(est.estimate), 1e-15);
    std::printf(
        "[ eigen ] p=%d: Ritz/exact = %.8f, estimate/exact = %.8f after %d Lanczos steps "
        "(exact omega^2 = %.6e; dt = %.4e, L/c = %.4e)\n",
        p, est.ritz / exact, est.estimate / exact, est.steps, exact, m.block.reference_dt[0],
        m.block.reference_length[0] / m.block.material.wave_speed);
  }
}

TEST_P(Lagrange, ElementBoundHoldsForAssembledPatch) {
  // Irons-Treharne: the assembled top eigenvalue is at most the largest element one.
  const int p = GetParam();
  LagrangeMesh m = two_element_patch(p);
  const int npe = m.block.nodes_per_element();
  const int n = static_cast<int>(3 * m.nodes());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(n);
  std::vector<double> u(3 * npe, 0.0), f(3 * npe);
  for (std::size_t e = 0; e < 2; ++e) {
    for (int c = 0; c < 3 * npe; ++c) {
      u[c] = 1.0;
      rf::element::apply_linear_stiffness(m.block, e, u.data(), f.data());
      u[c] = 0.0;
      const int gc = 3 * m.block.conn[e * npe + c / 3] + c % 3;
      for (int r = 0; r < 3 * npe; ++r) K(3 * m.block.conn[e * npe + r / 3] + r % 3, gc) += f[r];
    }
    for (int a = 0; a < npe; ++a)
      for (int i = 0; i < 3; ++i)
        mass[3 * m.block.conn[e * npe + a] + i] += kRho * m.block.reference_weight[e * npe + a];
  }
  const Eigen::VectorXd s = mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd A = s.asDiagonal() * (0.5 * (K + K.transpose())) * s.asDiagonal();
  const double assembled = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly)
                               .eigenvalues()[n - 1];
  const double element = std::max(rf::element::estimate_max_eigenvalue(m.block, 0),
                                  rf::element::estimate_max_eigenvalue(m.block, 1));
  EXPECT_LE(assembled, element);
  std::printf("[ eigen ] p=%d two-element patch: assembled / max element omega^2 = %.4f\n", p,
              assembled / element);
}

TEST_P(Lagrange, TimeStepScalesWithCurrentNodeSpacing) {
  const int p = GetParam();
  LagrangeMesh m = distorted_element(p);
  const auto r0 = rf::element::lagrange_hex_critical_timestep(m.block, m.view());
  ASSERT_FALSE(r0.failed);
  EXPECT_NEAR(r0.min_dt, m.block.reference_dt[0], 1e-15);
  EXPECT_EQ(r0.min_dt_element, 0);
  m.map([](const Vec3& X) { return Vec3{0.5 * X[0], 0.5 * X[1], 0.5 * X[2]}; });
  const auto r1 = rf::element::compute_lagrange_hex_forces(m.block, m.view(), 0.0);
  ASSERT_FALSE(r1.failed);
  EXPECT_NEAR(r1.min_dt, 0.5 * m.block.reference_dt[0], 1e-15);
  const auto r2 = rf::element::lagrange_hex_critical_timestep(m.block, m.view());
  EXPECT_EQ(r2.min_dt, r1.min_dt);
  EXPECT_EQ(r2.min_dt_element, r1.min_dt_element);
}

TEST_P(Lagrange, CurvedElementVolumeConvergesToCylinderSector) {
  // A quarter of a thick-walled tube, r in [1, 2], theta in [0, pi/2], z in [0, 1], as one
  // element with nodes on the exact surfaces: V = 3 pi / 4. The mapped geometry is a polynomial
  // interpolant of the circle, so the error is the interpolation error of order p (plus GLL
  // quadrature error), and it shrinks fast with p and with the sector angle.
  const int p = GetParam();
  auto sector = [p](double angle) {
    return mapped(p, [angle](double xi, double eta, double zeta) {
      const double r = 1.5 + 0.5 * xi, th = 0.5 * angle * (eta + 1.0);
      return Vec3{r * std::cos(th), r * std::sin(th), 0.5 * (zeta + 1.0)};
    });
  };
  const double quarter = std::numbers::pi / 2;
  const LagrangeMesh q = sector(quarter);
  const double exact = 1.5 * quarter;
  const double err_quarter = std::abs(q.block.volume0[0] - exact) / exact;
  const LagrangeMesh s = sector(quarter / 6);
  const double err_sector = std::abs(s.block.volume0[0] - exact / 6) / (exact / 6);
  std::printf("[ volume ] p=%d: relative volume error quarter tube %.2e, 15-degree sector %.2e\n",
              p, err_quarter, err_sector);
  EXPECT_LT(err_quarter, p == 2 ? 2e-2 : 2e-3);
  EXPECT_LT(err_sector, p == 2 ? 2e-5 : 2e-7);
  std::vector<double> mass(s.nodes(), 0.0);
  rf::element::add_lagrange_hex_lumped_mass(s.block, mass);
  double total = 0.0;
  for (const double a : mass) total += a;
  EXPECT_NEAR(total, kRho * s.block.volume0[0], 1e-12 * total);
}

TEST_P(Lagrange, InvertedElementIsRejectedAndCollapseIsReported) {
  const int p = GetParam();
  // Mirror image: nodes 1-4 clockwise seen from 5-8.
  std::vector<Vec3> mirrored = kDistorted;
  for (auto& c : mirrored) c[2] = -c[2];
  LagrangeMesh m;
  rf::mesh::HexElevator elevator(p, mirrored);
  m.block.conn = elevator.add_block({{0, 1, 2, 3, 4, 5, 6, 7}});
  m.set_nodes(mirrored);
  set_block(m, p, 1);
  try {
    rf::element::initialize_lagrange_hex_block(m.block, m.view());
    ADD_FAILURE() << "expected rf::SolverError";
  } catch (const rf::SolverError& error) {
    EXPECT_NE(std::string(error.what()).find("element 101 of part 3"), std::string::npos)
        << error.what();
  }

  LagrangeMesh good = two_element_patch(p);
  // Push corner n2 of the second element (not shared with the first) back through its n1 n4 n8
  // n5 face.
  const std::int32_t node = good.block.conn[good.block.nodes_per_element() + p];
  good.x[node] -= 3.0;
  const auto r = rf::element::compute_lagrange_hex_forces(good.block, good.view(), 0.0);
  EXPECT_TRUE(r.failed);
  EXPECT_EQ(r.failed_element, 1);
  EXPECT_TRUE(rf::element::lagrange_hex_critical_timestep(good.block, good.view()).failed);
}

TEST_P(Lagrange, ThreadCountDoesNotChangeResults) {
  const int p = GetParam();
  // A 3 x 2 x 2 distorted grid.
  std::vector<Vec3> corners;
  auto id = [](int i, int j, int k) { return static_cast<std::int32_t>(i + 4 * (j + 3 * k)); };
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i)
        corners.push_back({i + 0.1 * std::sin(1.0 * j + k), j + 0.1 * std::cos(0.7 * i * k),
                           k + 0.05 * std::sin(2.0 * i + j)});
  std::vector<std::array<std::int32_t, 8>> hexes;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
        hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                         id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                         id(i, j + 1, k + 1)});
  LagrangeMesh m = elevated(p, corners, hexes);
  m.map([](const Vec3& X) {
    return Vec3{X[0] * (1 + 0.01 * X[1]), X[1] + 0.02 * X[2] * X[2], X[2] * 0.99};
  });
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto r1 = rf::element::compute_lagrange_hex_forces(m.block, m.view(), 0.0);
  const std::vector<double> f1 = m.block.force, s1 = m.block.stress;
  omp_set_num_threads(2);
  const auto r2 = rf::element::compute_lagrange_hex_forces(m.block, m.view(), 0.0);
  omp_set_num_threads(saved);
  EXPECT_EQ(f1, m.block.force);
  EXPECT_EQ(s1, m.block.stress);
  EXPECT_EQ(r1.min_dt, r2.min_dt);
  EXPECT_EQ(r1.min_dt_element, r2.min_dt_element);
}

INSTANTIATE_TEST_SUITE_P(Orders, Lagrange, ::testing::Values(2, 3),
                         [](const auto& info) { return "p" + std::to_string(info.param); });

TEST(LagrangeHex, UnsupportedOrderAndBadConnectivityThrow) {
  LagrangeMesh m = distorted_element(2);
  HexBlock b = m.block;
  b.order = 4;
  EXPECT_THROW(rf::element::initialize_lagrange_hex_block(b, m.view()), rf::SolverError);
  b = m.block;
  b.conn.pop_back();
  EXPECT_THROW(rf::element::initialize_lagrange_hex_block(b, m.view()), rf::SolverError);
}

}  // namespace
