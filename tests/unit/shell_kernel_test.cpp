// Belytschko-Lin-Tsay shell kernel (element/shell_block.cpp) driven directly. References are
// analytic (plane-stress elasticity, plate bending D kappa, the bilinear hardening law, the
// shell step formula of the LS-DYNA theory manual) or conservation laws (force and moment
// balance, objectivity), never the kernel's own output.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "element/shell_block.hpp"
#include "material/elastic.hpp"
#include "material/registry.hpp"
#include "shell_test_mesh.hpp"

namespace {

using rf::test::Axes;
using rf::test::element_axes;
using rf::test::make_patch;
using rf::test::node_force;
using rf::test::Patch;
using rf::test::plane_stress_of_in_plane_rate;
using rf::test::set_in_plane_linear_velocity;
using rf::test::ShellMesh;
using rf::test::to_element_axes;

using rf::element::ShellBlock;

constexpr double kE = 2.0e11, kNu = 0.3, kRho = 7800.0;

void set_section(ShellBlock& b, int material_index, int nip, rf::element::ThroughThicknessRule rule,
                 int ihq, double qm) {
  b.part_id = 3;
  b.material = rf::material::make_elastic(kRho, kE, kNu);
  b.material_index = material_index;
  b.nip = nip;
  b.rule = rule;
  b.hourglass.ihq = ihq;
  b.hourglass.qm = qm;
}

TEST(ShellThroughThickness, RulesIntegratePolynomialsExactly) {
  using rf::element::ThroughThicknessRule;
  for (auto rule : {ThroughThicknessRule::kGauss, ThroughThicknessRule::kLobatto})
    for (int n = rule == ThroughThicknessRule::kGauss ? 1 : 2; n <= 10; ++n) {
      std::vector<double> z, w;
      ASSERT_TRUE(rf::element::through_thickness_points(rule, n, z, w));
      const int exact_degree = rule == ThroughThicknessRule::kGauss ? 2 * n - 1 : 2 * n - 3;
      for (int k = 0; k <= exact_degree; ++k) {
        double s = 0.0;
        for (int i = 0; i < n; ++i) s += w[i] * std::pow(z[i], k);
        EXPECT_NEAR(s, k % 2 ? 0.0 : 2.0 / (k + 1), 1e-13) << "n " << n << " k " << k;
      }
      for (int i = 1; i < n; ++i) EXPECT_LT(z[i - 1], z[i]);
    }
  std::vector<double> z, w;
  rf::element::through_thickness_points(ThroughThicknessRule::kGauss, 2, z, w);
  EXPECT_NEAR(z[1], 1.0 / std::sqrt(3.0), 1e-15);
  rf::element::through_thickness_points(ThroughThicknessRule::kLobatto, 3, z, w);
  EXPECT_NEAR(z[0], -1.0, 1e-15);
  EXPECT_NEAR(w[1], 4.0 / 3.0, 1e-15);
  EXPECT_FALSE(rf::element::through_thickness_points(ThroughThicknessRule::kGauss, 11, z, w));
  EXPECT_FALSE(rf::element::through_thickness_points(ThroughThicknessRule::kLobatto, 1, z, w));
}

// Linear in-plane velocity field on an irregular patch in a tilted plane: every element gets
// the uniform plane-stress state C eps, and the interior node is in equilibrium.
TEST(ShellPatch, MembraneLinearFieldGivesUniformPlaneStress) {
  const double s = 1.0 / std::sqrt(3.0);
  const double u[3] = {s, s, s};
  const double w[3] = {1.0 / std::sqrt(2.0), -1.0 / std::sqrt(2.0), 0.0};
  const double t = 0.01;
  for (int ihq : {1, 4}) {
    Patch p = make_patch(u, w, t);
    ShellMesh& m = p.mesh;
    set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, ihq, 0.1);
    m.initialize();
    // In-plane rate L (plane coordinates a, b along u, w): symmetric with a spin part too.
    const double Lab[2][2] = {{2.0e-2, 0.7e-2}, {-0.3e-2, -1.1e-2}};
    const auto X = m.positions();
    set_in_plane_linear_velocity(m, X, u, w, Lab);
    const double dt = 1e-3;
    m.place_for_step(X, dt);
    const auto r = m.step(dt);
    ASSERT_FALSE(r.failed);
    // Analytic plane stress in plane axes, then in each element's axes (at X, the mid-step).
    double T[3][3];
    const double scale = plane_stress_of_in_plane_rate(Lab, dt, u, w, kE, kNu, T);
    for (std::size_t e = 0; e < 4; ++e) {
      std::array<double, 3> pe[4];
      for (int I = 0; I < 4; ++I) pe[I] = X[m.block.conn[4 * e + I]];
      const auto expect = to_element_axes(element_axes(pe), T);
      for (int q = 0; q < 2; ++q) {
        const double* st = &m.block.stress[10 * e + 5 * q];
        EXPECT_NEAR(st[0], expect[0], 1e-11 * scale);
        EXPECT_NEAR(st[1], expect[1], 1e-11 * scale);
        EXPECT_NEAR(st[2], expect[2], 1e-11 * scale);
        EXPECT_NEAR(st[3], 0.0, 1e-11 * scale);
        EXPECT_NEAR(st[4], 0.0, 1e-11 * scale);
      }
    }
    EXPECT_NEAR(r.hourglass_work, 0.0, 1e-12 * scale * t);
    const auto f = node_force(m.block, p.interior, 0);
    const auto mm = node_force(m.block, p.interior, 3);
    const double fscale = scale * t * 0.5;  // stress x thickness x a side
    // The stresses are uniform in the mid-step frames (checked above); the forces use the
    // end-of-step frames, and the BLT frame (side 1-2) of each element turns by its own O(L dt)
    // angle over the half step, so the interior residual is second order: measured 0.13 |L| dt
    // fscale at |L| dt = 2e-5 (a wrong force would be O(fscale)).
    const double tol = 0.5 * 2.0e-2 * dt * fscale;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(f[i], 0.0, tol);
      EXPECT_NEAR(mm[i], 0.0, tol);
    }
    // A corner node is not in equilibrium (the test can fail): it carries the boundary traction.
    const auto fc = node_force(m.block, 0, 0);
    EXPECT_GT(std::abs(fc[0]) + std::abs(fc[1]) + std::abs(fc[2]), 0.1 * fscale);
  }
}

// Uniform curvature rate: theta_y = kdot x (global, plate in the x-y plane) and the matching
// Kirchhoff deflection rate v_z = -kdot x^2 / 2. Moments M_xx = D kappa, M_yy = nu D kappa,
// M_xy = 0 with D = E t^3 / (12 (1 - nu^2)) in every element.
struct BendingCase {
  int nip;
  rf::element::ThroughThicknessRule rule;
  double expected_factor;  // M / (D kappa): 1 exact, 0 for the membrane-only NIP 1
};

class ShellBending : public ::testing::TestWithParam<BendingCase> {};

TEST_P(ShellBending, UniformCurvatureGivesPlateMoment) {
  const BendingCase c = GetParam();
  const double u[3] = {1, 0, 0}, w[3] = {0, 1, 0};
  const double t = 0.02;
  Patch p = make_patch(u, w, t);
  ShellMesh& m = p.mesh;
  set_section(m.block, 0, c.nip, c.rule, 4, 0.1);
  m.initialize();
  const double kdot = 0.5, dt = 1e-4;
  const auto X = m.positions();
  for (std::size_t i = 0; i < X.size(); ++i) {
    m.wy[i] = kdot * X[i][0];
    m.vz[i] = -0.5 * kdot * X[i][0] * X[i][0];
  }
  m.place_for_step(X, dt);
  ASSERT_FALSE(m.step(dt).failed);
  const double kappa = kdot * dt;
  const double D = kE * t * t * t / (12 * (1 - kNu * kNu));
  double T[3][3] = {{D * kappa, 0, 0}, {0, kNu * D * kappa, 0}, {0, 0, 0}};
  const int nip = c.nip;
  for (std::size_t e = 0; e < 4; ++e) {
    std::array<double, 3> pe[4];
    for (int I = 0; I < 4; ++I) pe[I] = X[m.block.conn[4 * e + I]];
    auto expect = to_element_axes(element_axes(pe), T);
    double M[3] = {0, 0, 0};
    for (int q = 0; q < nip; ++q) {
      const double z = m.block.zeta[q] * t / 2;
      for (int k = 0; k < 3; ++k)
        M[k] += t / 2 * m.block.weight[q] * z * m.block.stress[5 * (nip * e + q) + k];
    }
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(M[k], c.expected_factor * expect[k], 1e-10 * D * kappa) << "element " << e;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Rules, ShellBending,
    ::testing::Values(BendingCase{2, rf::element::ThroughThicknessRule::kGauss, 1.0},
                      BendingCase{5, rf::element::ThroughThicknessRule::kGauss, 1.0},
                      // Lobatto 3 integrates up to z^3 exactly: the linear elastic moment
                      // (z^2) has no quadrature error.
                      BendingCase{3, rf::element::ThroughThicknessRule::kLobatto, 1.0},
                      BendingCase{1, rf::element::ThroughThicknessRule::kGauss, 0.0}));

// Single square element centred at the origin in pure bending: the nodal moments of the edge
// x = +a/2 add up to the edge moment M_x a, and there is no transverse shear force.
TEST(ShellBending, SquareElementNodalMomentsAreEdgeMoments) {
  ShellMesh m;
  const double a = 0.2, t = 0.01;
  m.add_node(-a / 2, -a / 2, 0);
  m.add_node(a / 2, -a / 2, 0);
  m.add_node(a / 2, a / 2, 0);
  m.add_node(-a / 2, a / 2, 0);
  m.add_element({0, 1, 2, 3}, t);
  set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
  m.initialize();
  const double kdot = 2.0, dt = 1e-5;
  const auto X = m.positions();
  for (int i = 0; i < 4; ++i) {
    m.wy[i] = kdot * X[i][0];
    m.vz[i] = -0.5 * kdot * X[i][0] * X[i][0];
  }
  m.place_for_step(X, dt);
  ASSERT_FALSE(m.step(dt).failed);
  const double D = kE * t * t * t / (12 * (1 - kNu * kNu));
  const double Mx = D * kdot * dt;
  const double* f = m.block.force.data();
  // Internal moments: the element resists the imposed curvature, so the moment at x = +a/2 is
  // +M_x a (about +y) and at x = -a/2 it is -M_x a.
  EXPECT_NEAR(f[6 * 1 + 4] + f[6 * 2 + 4], Mx * a, 1e-10 * Mx * a);
  EXPECT_NEAR(f[6 * 0 + 4] + f[6 * 3 + 4], -Mx * a, 1e-10 * Mx * a);
  // Edges y = +-a/2 carry the moment M_y = nu M_x about x, with the sign of the BLT convention
  // (d_y = -z B2 theta_x): -M_y a on y = +a/2.
  EXPECT_NEAR(f[6 * 2 + 3] + f[6 * 3 + 3], -kNu * Mx * a, 1e-10 * Mx * a);
  EXPECT_NEAR(f[6 * 0 + 3] + f[6 * 1 + 3], kNu * Mx * a, 1e-10 * Mx * a);
  for (int I = 0; I < 4; ++I) EXPECT_NEAR(f[6 * I + 2], 0.0, 1e-10 * Mx);
}

// Rigid rotation of an element about an axis through its centre in finite steps: the
// co-rotational stresses and hourglass forces stay exactly what they were (objectivity), for a
// pre-stressed and an unstressed element, flat and warped (with the warping correction).
struct RotationCase {
  bool warped;
  bool prestress;
  int axis;  // 0: in-plane axis (x), 1: out-of-plane (z), 2: oblique
  int steps;
  double total_degrees;
};

class ShellObjectivity : public ::testing::TestWithParam<RotationCase> {};

TEST_P(ShellObjectivity, RigidRotationLeavesStressAndEnergyUnchanged) {
  const RotationCase c = GetParam();
  const double pi = std::acos(-1.0);
  ShellMesh m;
  const double h = c.warped ? 0.03 : 0.0;
  m.add_node(0.0, 0.0, h);
  m.add_node(1.1, 0.1, -h);
  m.add_node(1.2, 0.9, h);
  m.add_node(-0.1, 1.0, -h);
  m.add_element({0, 1, 2, 3}, 0.05);
  for (int ihq : {1, 4}) {
    ShellMesh mm = m;
    set_section(mm.block, 0, 3, rf::element::ThroughThicknessRule::kGauss, ihq, 0.1);
    mm.block.warping_correction = c.warped;
    mm.initialize();
    const double s0 = 1e8;
    if (c.prestress) {
      for (int q = 0; q < 3; ++q) {
        double* s = &mm.block.stress[5 * q];
        s[0] = s0 * (1.0 + q);
        s[1] = -0.4 * s0;
        s[2] = 0.3 * s0 * (q - 1.0);
        s[3] = 0.05 * s0;
        s[4] = -0.07 * s0;
      }
      if (ihq == 4)
        for (int k = 0; k < 5; ++k) mm.block.hourglass_state[k] = 1e3 * (k + 1);
    }
    const std::vector<double> stress0 = mm.block.stress;
    const std::vector<double> hg0 = mm.block.hourglass_state;
    double axis[3] = {1, 0, 0};
    if (c.axis == 1) axis[0] = 0, axis[2] = 1;
    if (c.axis == 2) axis[0] = 0.48, axis[1] = 0.6, axis[2] = 0.64;
    const double phi = c.total_degrees * pi / 180.0 / c.steps;
    const double dt = 1e-3;
    const double ctr[3] = {0.55, 0.5, 0.0};
    // Rodrigues rotation by phi about axis through ctr.
    auto rotate = [&](double p[3]) {
      double r[3] = {p[0] - ctr[0], p[1] - ctr[1], p[2] - ctr[2]};
      const double k = axis[0] * r[0] + axis[1] * r[1] + axis[2] * r[2];
      const double cr[3] = {axis[1] * r[2] - axis[2] * r[1], axis[2] * r[0] - axis[0] * r[2],
                            axis[0] * r[1] - axis[1] * r[0]};
      for (int i = 0; i < 3; ++i)
        p[i] = ctr[i] + r[i] * std::cos(phi) + cr[i] * std::sin(phi) +
               axis[i] * k * (1 - std::cos(phi));
    };
    // Angular velocity of the mid-step rigid field (Cayley): |omega| = 2 tan(phi/2) / dt.
    const double wmag = 2.0 * std::tan(phi / 2) / dt;
    double fnorm0 = -1.0;
    for (int s = 0; s < c.steps; ++s) {
      for (int i = 0; i < 4; ++i) {
        double p[3] = {mm.x[i], mm.y[i], mm.z[i]};
        rotate(p);
        mm.vx[i] = (p[0] - mm.x[i]) / dt;
        mm.vy[i] = (p[1] - mm.y[i]) / dt;
        mm.vz[i] = (p[2] - mm.z[i]) / dt;
        mm.x[i] = p[0];
        mm.y[i] = p[1];
        mm.z[i] = p[2];
        mm.wx[i] = wmag * axis[0];
        mm.wy[i] = wmag * axis[1];
        mm.wz[i] = wmag * axis[2];
      }
      const auto r = mm.step(dt);
      ASSERT_FALSE(r.failed);
      double fn = 0.0;
      for (double f : mm.block.force) fn += f * f;
      if (fnorm0 < 0) fnorm0 = fn;
      EXPECT_NEAR(fn, fnorm0, 1e-9 * fnorm0 + 1e-6);
      EXPECT_NEAR(r.hourglass_work, 0.0, 1e-9 * (1.0 + hg0[4] * 1e-3));
    }
    for (std::size_t k = 0; k < stress0.size(); ++k)
      EXPECT_NEAR(mm.block.stress[k], stress0[k], 1e-10 * s0) << "ihq " << ihq;  // meas. 2e-12
    for (int k = 0; k < 5; ++k) EXPECT_NEAR(mm.block.hourglass_state[k], hg0[k], 1e-9 * 5e3);
  }
}

INSTANTIATE_TEST_SUITE_P(Rotations, ShellObjectivity,
                         ::testing::Values(RotationCase{false, true, 0, 12, 108.0},
                                           RotationCase{false, true, 1, 12, 108.0},
                                           RotationCase{false, false, 2, 3, 150.0},
                                           RotationCase{false, true, 2, 2, 170.0},
                                           RotationCase{true, true, 0, 10, 95.0},
                                           RotationCase{true, true, 1, 10, 95.0},
                                           RotationCase{true, false, 2, 4, 120.0}));

// Equibiaxial stretch of a square (equal rates in x and y: sigma_xx = sigma_yy = sigma by
// symmetry, von Mises stress sigma): with plane stress the bilinear law gives
//   eps_x = (1 - nu) sigma / E + eps_p / 2,  sigma = SIGY + Ep eps_p,
// eps_x the logarithmic strain. A sigma_zz != 0 would break the relation.
TEST(ShellPlasticity, EquibiaxialPlaneStressFollowsBilinearLaw) {
  for (int mat : {1, 2}) {  // *MAT_003, *MAT_024 in SolidMaterials
    ShellMesh m;
    const double a = 1.0;
    m.add_node(0, 0, 0);
    m.add_node(a, 0, 0);
    m.add_node(a, a, 0);
    m.add_node(0, a, 0);
    m.add_element({0, 1, 2, 3}, 0.01);
    set_section(m.block, mat, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
    const double sigy = 2.5e8, etan = 2.0e9;
    const double ep = kE * etan / (kE - etan);
    m.block.plastic.sigy = sigy;
    m.block.plastic.isotropic_modulus = ep;
    m.block.plastic.linear = true;
    m.block.plastic.strain = {0.0, 1.0};
    m.block.plastic.stress = {sigy, sigy + ep};
    m.initialize();
    const double rate = 1.0, dt = 2e-5;  // 1% strain in 500 steps
    double strain = 0.0;
    for (int s = 0; s < 500; ++s) {
      // Node i moves with v = rate * x (homogeneous stretch of the current square).
      double side = m.x[1] - m.x[0];
      const double next = side * std::exp(rate * dt);
      const double v = (next - side) / dt;
      m.vx[1] = m.vx[2] = v;
      m.vy[2] = m.vy[3] = v;
      m.x[1] = m.x[2] = next;
      m.y[2] = m.y[3] = next;
      ASSERT_FALSE(m.step(dt).failed);
      strain = std::log(next / a);
    }
    const double* st = m.block.stress.data();
    const double sigma = st[0];
    EXPECT_NEAR(st[1], sigma, 1e-9 * sigma);
    EXPECT_GT(sigma, sigy);
    const auto* eps = rf::element::find_history(m.block, "effective_plastic_strain");
    ASSERT_NE(eps, nullptr);
    const double eps_p = eps->values[0];
    EXPECT_NEAR(sigma, sigy + ep * eps_p, 1e-8 * sigma);
    // Mid-step rate over updated geometry: the accumulated strain is the log strain (measured
    // 3e-11 relative).
    EXPECT_NEAR((1 - kNu) * sigma / kE + 0.5 * eps_p, strain, 1e-8 * strain);
    EXPECT_NEAR(eps->values[1], eps_p, 1e-12);  // both points (pure membrane)
  }
}

// Uniaxial stress on one element: the lateral velocity is found by the test (secant on
// sigma_yy = 0 over trial copies of the block); the stress-strain curve then follows the
// bilinear law sigma = SIGY + Ep eps_p, eps_p = eps - sigma / E (logarithmic strain).
// *MAT_003 with BETA = 1 (isotropic) and BETA = 0 (kinematic: Prager back stress, the same
// monotonic uniaxial curve).
TEST(ShellPlasticity, UniaxialPlaneStressFollowsBilinearLaw) {
  for (bool kinematic : {false, true}) {
    ShellMesh m;
    m.add_node(0, 0, 0);
    m.add_node(1, 0, 0);
    m.add_node(1, 1, 0);
    m.add_node(0, 1, 0);
    m.add_element({0, 1, 2, 3}, 0.01);
    set_section(m.block, 1, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
    const double sigy = 2.5e8, etan = 1.0e9;
    const double ep = kE * etan / (kE - etan);
    m.block.plastic.sigy = sigy;
    m.block.plastic.isotropic_modulus = kinematic ? 0.0 : ep;
    m.block.plastic.kinematic_modulus = kinematic ? ep : 0.0;
    m.block.plastic.linear = true;
    m.block.plastic.strain = {0.0, 1.0};
    m.block.plastic.stress = {sigy, sigy + (kinematic ? 0.0 : ep)};
    m.initialize();
    const auto [lx, ly] = rf::test::pull_uniaxially(m, 400, 1e-5);
    const double sigma = m.block.stress[0];
    const double strain = std::log(lx);
    EXPECT_NEAR(m.block.stress[1], 0.0, 1e-2);  // vs sigma ~ 3e8
    const auto* eps = rf::element::find_history(m.block, "effective_plastic_strain");
    ASSERT_NE(eps, nullptr);
    const double eps_p = eps->values[0];
    EXPECT_GT(eps_p, 0.0);
    EXPECT_NEAR(sigma, sigy + ep * eps_p, 1e-8 * sigma);
    EXPECT_NEAR(eps_p, strain - sigma / kE, 1e-8 * strain);  // measured 1e-10
    // Plastic incompressibility + elastic plane stress: the lateral log strain is
    // -nu sigma / E - eps_p / 2.
    EXPECT_NEAR(std::log(ly), -kNu * sigma / kE - 0.5 * eps_p, 1e-8 * strain);
  }
}

// Hourglass modes of a square (tau = h): a viscous form opposes the mode's velocity, a
// stiffness form stores exactly the work done on it; rigid motions give no force at all.
TEST(ShellHourglass, ModesResistedRigidMotionFree) {
  const double a = 0.5, t = 0.01;
  const double pat[4] = {1, -1, 1, -1};
  for (int ihq : {1, 2, 3, 4, 5})
    for (int mode = 0; mode < 5; ++mode) {
      ShellMesh m;
      m.add_node(-a / 2, -a / 2, 0);
      m.add_node(a / 2, -a / 2, 0);
      m.add_node(a / 2, a / 2, 0);
      m.add_node(-a / 2, a / 2, 0);
      m.add_element({0, 1, 2, 3}, t);
      set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, ihq, 0.1);
      m.initialize();
      const double c = 0.1, dt = 1e-7;
      const auto X = m.positions();
      for (int i = 0; i < 4; ++i) {
        double* target = mode == 0   ? &m.vx[i]
                         : mode == 1 ? &m.vy[i]
                         : mode == 2 ? &m.vz[i]
                         : mode == 3 ? &m.wx[i]
                                     : &m.wy[i];
        *target = c * pat[i];
      }
      double work = 0.0, power = 0.0;
      const int steps = 5;
      auto Xs = X;
      for (int s = 0; s < steps; ++s) {
        m.place_for_step(Xs, dt);
        const auto r = m.step(dt);
        work += r.hourglass_work;
        power = 0.0;
        for (int i = 0; i < 4; ++i) {
          const double* f = &m.block.force[6 * i];
          power += f[0] * m.vx[i] + f[1] * m.vy[i] + f[2] * m.vz[i] + f[3] * m.wx[i] +
                   f[4] * m.wy[i] + f[5] * m.wz[i];
        }
        for (int i = 0; i < 4; ++i) {
          Xs[i][0] += dt * m.vx[i];
          Xs[i][1] += dt * m.vy[i];
          Xs[i][2] += dt * m.vz[i];
        }
      }
      // Internal forces resist the motion: positive power of f_int (stresses stay zero for a
      // pure hourglass mode, so all of it is hourglass).
      EXPECT_GT(power, 0.0) << "ihq " << ihq << " mode " << mode;
      EXPECT_GT(work, 0.0);
      for (double s : m.block.stress) EXPECT_NEAR(s, 0.0, 1e-6 * kE * c * dt);
      if (ihq >= 4) {
        // Stored energy: the generalised force grows linearly, work = Q q / 2 exactly.
        const double q = 4.0 * c * steps * dt;  // tau . (mode velocity) = 4 c
        EXPECT_NEAR(work, 0.5 * m.block.hourglass_state[mode] * q, 1e-6 * work);
      }
      if (ihq == 4 && mode == 0) {
        // QM = 1 stiffness reproduces the in-plane bending energy of u_x = k x y on the
        // square: t k^2 a^4 (E' + G) / 24 with u at the nodes k a^2/4 h (here scaled by QM).
        const double k = 4.0 * c * steps * dt / (a * a);
        const double exact =
            t * k * k * std::pow(a, 4) * (kE / (1 - kNu * kNu) + kE / (2 * (1 + kNu))) / 24.0;
        EXPECT_NEAR(work, 0.1 * exact, 1e-6 * exact);
      }
    }
}

// Rigid translation plus rotation of a distorted, warped element (warping correction on):
// no force, no moment, no hourglass work, for every hourglass form.
TEST(ShellHourglass, RigidBodyVelocityGivesNoForce) {
  for (bool warped : {false, true})
    for (int ihq : {1, 4}) {
      ShellMesh m;
      const double h = warped ? 0.04 : 0.0;
      m.add_node(0.0, 0.0, h);
      m.add_node(1.3, -0.1, -h);
      m.add_node(1.0, 0.8, h);
      m.add_node(0.2, 1.1, -h);
      m.add_element({0, 1, 2, 3}, 0.05);
      set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, ihq, 0.1);
      m.block.warping_correction = warped;
      m.initialize();
      const double V[3] = {1.0, -2.0, 0.5}, W[3] = {0.3, -0.7, 1.1};
      const auto X = m.positions();
      for (int i = 0; i < 4; ++i) {
        const double* r = X[i].data();
        m.vx[i] = V[0] + W[1] * r[2] - W[2] * r[1];
        m.vy[i] = V[1] + W[2] * r[0] - W[0] * r[2];
        m.vz[i] = V[2] + W[0] * r[1] - W[1] * r[0];
        m.wx[i] = W[0];
        m.wy[i] = W[1];
        m.wz[i] = W[2];
      }
      const double dt = 1e-4;
      m.place_for_step(X, dt);
      const auto r = m.step(dt);
      EXPECT_NEAR(r.hourglass_work, 0.0, 1e-12);
      for (double f : m.block.force) EXPECT_NEAR(f, 0.0, 1e-3) << "ihq " << ihq;  // vs ~1e5
      for (double s : m.block.stress) EXPECT_NEAR(s, 0.0, 1e-2);
    }
}

// Objectivity under a superimposed rigid spin (issue 16). Motion A deforms a distorted element:
// membrane stretch and shear, a Kirchhoff curvature rate (theta_y = kdot x, v_z = -kdot x^2 / 2)
// and a w-hourglass share (IHQ 4 stores forces), at constant nodal velocities. Motion B is the
// same motion seen from a frame spinning at a constant rate about an axis through the origin:
// x_B^n = Q^n x_A^n, Q^n the rotation by n phi, with the secant velocities of the step and the
// nodal angular velocities omega_B = omega_Q + Q^{n+1/2} omega_A. Objectivity requires the
// co-rotational stresses and hourglass forces of B to equal those of A, and B's nodal forces and
// moments to be A's turned by Q^{n+1}, whatever the spin axis (the normal, an in-plane axis,
// an oblique one). The two runs differ only in where the mid-step configuration lies (the chord
// midpoint of a rotated node lies inside the arc by r (1 - cos(phi / 2))), an O(phi^2) change of
// each increment: with phi = 2.5e-3 (phi^2 = 6e-6) and 400 steps (1 rad) everything agrees to
// 1e-5 of its size (measured 1.5e-6).
//
// The stresses are objective with and without the warping correction. The hourglass forces are
// objective only with it (BWC 1): without it (LS-DYNA's default BWC 2) a warped element turning
// about an axis with an in-plane component (omega_1, omega_2 in the element frame) has the
// in-plane nodal velocities omega_2 z_I, -omega_1 z_I with z_I = z (1, -1, 1, -1), exactly the
// membrane hourglass pattern, so a rigid spin loads the membrane hourglass (here 23 % of the
// hourglass forces of A for a spin about an in-plane axis, 0.2 % about the normal, where only the
// element's tilt gives the spin an in-plane part). That is the documented limitation of the
// uncorrected element (docs/elements.md), checked here so that a change shows.
TEST(ShellObjectivity, SuperimposedRigidSpinRotatesForcesAndKeepsStresses) {
  const double axes[3][3] = {{0, 0, 1}, {1, 0, 0}, {0.48, 0.6, 0.64}};
  for (bool warp : {false, true})
    for (const auto& ax : axes) {
      auto make = [&]() {
        ShellMesh m;
        m.add_node(-0.5, -0.45, 0.0);
        m.add_node(0.55, -0.5, 0.0);
        m.add_node(0.6, 0.5, 0.0);
        m.add_node(-0.45, 0.55, 0.0);
        m.add_element({0, 1, 2, 3}, 0.05);
        set_section(m.block, 0, 3, rf::element::ThroughThicknessRule::kGauss, 4, 0.1);
        m.block.warping_correction = warp;
        m.initialize();
        return m;
      };
      ShellMesh a = make(), b = make();
      // Motion A: constant nodal velocities (body frame).
      const double eps_x = 0.2, eps_y = -0.1, gamma = 0.15, kdot = 0.8, hg = 0.02;
      const double hpat[4] = {1, -1, 1, -1};
      std::vector<std::array<double, 3>> va(4), wa(4);
      for (int i = 0; i < 4; ++i) {
        const double x = a.x[i], y = a.y[i];
        va[i] = {eps_x * x + gamma * y, eps_y * y, -0.5 * kdot * x * x + hg * hpat[i]};
        wa[i] = {0.0, kdot * x, 0.0};
      }
      const int steps = 400;
      const double phi = 1.0 / steps, dt = 1e-3;
      const double wq = 2.0 * std::tan(0.5 * phi) / dt;  // the Cayley rate of a step's rotation
      const Eigen::Vector3d k = Eigen::Vector3d(ax[0], ax[1], ax[2]).normalized();
      auto Q = [&](double angle) { return Eigen::AngleAxisd(angle, k).toRotationMatrix(); };
      double max_stress = 0.0, max_force = 0.0, stress_diff = 0.0, force_diff = 0.0, hg_diff = 0.0,
             max_hg = 0.0;
      for (int n = 0; n < steps; ++n) {
        const Eigen::Matrix3d q0 = Q(n * phi), q1 = Q((n + 1) * phi), qh = Q((n + 0.5) * phi);
        for (int i = 0; i < 4; ++i) {
          const Eigen::Vector3d xa0(a.x[i], a.y[i], a.z[i]);
          const Eigen::Vector3d v(va[i][0], va[i][1], va[i][2]);
          const Eigen::Vector3d xa1 = xa0 + dt * v;
          a.vx[i] = v.x(), a.vy[i] = v.y(), a.vz[i] = v.z();
          a.x[i] = xa1.x(), a.y[i] = xa1.y(), a.z[i] = xa1.z();
          a.wx[i] = wa[i][0], a.wy[i] = wa[i][1], a.wz[i] = wa[i][2];
          const Eigen::Vector3d xb0 = q0 * xa0, xb1 = q1 * xa1;
          const Eigen::Vector3d vb = (xb1 - xb0) / dt;
          const Eigen::Vector3d wb = wq * k + qh * Eigen::Vector3d(wa[i][0], wa[i][1], wa[i][2]);
          b.vx[i] = vb.x(), b.vy[i] = vb.y(), b.vz[i] = vb.z();
          b.x[i] = xb1.x(), b.y[i] = xb1.y(), b.z[i] = xb1.z();
          b.wx[i] = wb.x(), b.wy[i] = wb.y(), b.wz[i] = wb.z();
        }
        ASSERT_FALSE(a.step(dt).failed);
        ASSERT_FALSE(b.step(dt).failed);
        for (std::size_t c = 0; c < a.block.stress.size(); ++c) {
          max_stress = std::max(max_stress, std::abs(a.block.stress[c]));
          stress_diff = std::max(stress_diff, std::abs(a.block.stress[c] - b.block.stress[c]));
        }
        for (int c = 0; c < 5; ++c) {
          max_hg = std::max(max_hg, std::abs(a.block.hourglass_state[c]));
          hg_diff =
              std::max(hg_diff, std::abs(a.block.hourglass_state[c] - b.block.hourglass_state[c]));
        }
        for (int I = 0; I < 4; ++I)
          for (int o : {0, 3}) {
            const double* fa = &a.block.force[6 * I + o];
            const double* fb = &b.block.force[6 * I + o];
            const Eigen::Vector3d turned = q1 * Eigen::Vector3d(fa[0], fa[1], fa[2]);
            max_force = std::max(max_force, turned.norm());
            force_diff =
                std::max(force_diff, (turned - Eigen::Vector3d(fb[0], fb[1], fb[2])).norm());
          }
      }
      RecordProperty("stress_diff", std::to_string(stress_diff / max_stress));
      EXPECT_GT(max_stress, 1e8);  // the motion does load the element
      EXPECT_GT(max_hg, 0.0);
      EXPECT_LT(stress_diff, 1e-5 * max_stress) << "axis " << k.transpose();
      if (warp) {
        EXPECT_LT(hg_diff, 1e-5 * max_hg) << "axis " << k.transpose();
        EXPECT_LT(force_diff, 1e-5 * max_force) << "axis " << k.transpose();
      } else if (k.z() < 0.9) {  // the spin has an in-plane part: see above
        EXPECT_GT(hg_diff, 0.05 * max_hg) << "axis " << k.transpose();
      }
      std::printf(
          "warp %d spin axis (%.2f %.2f %.2f): stresses %.3g (max %.3g), hourglass %.3g (max "
          "%.3g), "
          "forces %.3g (max %.3g)\n",
          int(warp), k.x(), k.y(), k.z(), stress_diff, max_stress, hg_diff, max_hg, force_diff,
          max_force);
    }
}

// LS-DYNA shell step: dt = (1 + beta) A / max side / sqrt(E / (rho (1 - nu^2))).
TEST(ShellTimeStep, MatchesShellLengthFormula) {
  ShellMesh m;
  const double a = 0.3, b = 0.2, t = 0.01;
  m.add_node(0, 0, 0);
  m.add_node(a, 0, 0);
  m.add_node(a, b, 0);
  m.add_node(0, b, 0);
  m.add_node(2 * a, 0, 0);
  m.add_node(2 * a, a, 0);
  m.add_element({0, 1, 2, 3}, t);  // rectangle: L = a b / a = b
  m.add_element({1, 4, 5, 5}, t);  // right isosceles triangle, legs a: L = 2 (a^2/2) / (a sqrt 2)
  set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
  m.initialize();
  const double c = std::sqrt(kE / (kRho * (1 - kNu * kNu)));
  const double tri = a / std::sqrt(2.0) / c;
  const auto r = rf::element::shell_critical_timestep(m.block, m.view());
  EXPECT_NEAR(r.min_dt, b / c, 1e-14 * b / c);
  EXPECT_EQ(r.min_dt_element, 0);
  const auto rk = m.step(1e-9);
  EXPECT_NEAR(rk.min_dt, b / c, 1e-12 * b / c);
  // Triangle alone.
  ShellMesh t1;
  t1.add_node(0, 0, 0);
  t1.add_node(a, 0, 0);
  t1.add_node(0, a, 0);
  t1.add_element({0, 1, 2, 2}, t);
  set_section(t1.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
  t1.initialize();
  EXPECT_NEAR(rf::element::shell_critical_timestep(t1.block, t1.view()).min_dt, tri, 1e-14 * tri);
  // Lumped mass: rho t A / 4 per node, rho t A / 3 per triangle node.
  std::vector<double> mass(6, 0.0), inertia(6, 0.0);
  rf::element::add_shell_lumped_mass(m.block, mass, inertia);
  EXPECT_NEAR(mass[0], kRho * t * a * b / 4, 1e-12);
  EXPECT_NEAR(mass[5], kRho * t * a * a / 2 / 3, 1e-12);
  EXPECT_NEAR(mass[1], kRho * t * (a * b / 4 + a * a / 6), 1e-12);
  double total = 0.0;
  for (double x : mass) total += x;
  EXPECT_NEAR(total, kRho * t * (a * b + a * a / 2), 1e-12);
}

// A degenerate element and a non-positive thickness are reported naming the element.
TEST(ShellInitialize, DegenerateElementIsAnError) {
  ShellMesh m;
  m.add_node(0, 0, 0);
  m.add_node(1, 0, 0);
  m.add_node(2, 0, 0);
  m.add_element({0, 1, 2, 2}, 0.01);
  set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
  try {
    m.initialize();
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("shell element 1 of part 3"), std::string::npos);
  }
  ShellMesh z;
  z.add_node(0, 0, 0);
  z.add_node(1, 0, 0);
  z.add_node(1, 1, 0);
  z.add_element({0, 1, 2, 2}, 0.0);
  set_section(z.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
  EXPECT_THROW(z.initialize(), std::exception);
  // Side 1-2 collapsed (not the N3 = N4 triangle pattern): no frame, an error.
  ShellMesh c;
  c.add_node(0, 0, 0);
  c.add_node(1, 0, 0);
  c.add_node(1, 1, 0);
  c.add_element({0, 0, 1, 2}, 0.01);
  set_section(c.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
  EXPECT_THROW(c.initialize(), std::exception);
  // A formulation without a kernel is said at initialisation, not silently run as ELFORM 2.
  ShellMesh f = z;
  f.block.thickness.assign(4, 0.01);
  f.block.elform = 5;
  EXPECT_THROW(f.initialize(), std::exception);
}

// During the run: a non-finite velocity or an element collapsed to zero area is reported with
// the element's index in the block (the solver names element, part and time), forces zeroed for
// the collapsed one.
TEST(ShellInitialize, RunTimeFailuresAreReported) {
  for (int kind : {0, 1})
    for (int mat : {0, 2}) {
      ShellMesh m;
      m.add_node(0, 0, 0);
      m.add_node(1, 0, 0);
      m.add_node(1, 1, 0);
      m.add_node(0, 1, 0);
      m.add_node(2, 0, 0);
      m.add_node(2, 1, 0);
      m.add_element({0, 1, 2, 3}, 0.01);
      m.add_element({1, 4, 5, 2}, 0.01);
      set_section(m.block, mat, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
      m.block.plastic.sigy = 2e8;
      m.block.plastic.strain = {0.0, 1.0};
      m.block.plastic.stress = {2e8, 2e8};
      m.initialize();
      if (kind == 0) {
        m.vx[5] = std::nan("");
      } else {
        m.x[4] = m.x[1];  // element 2 collapses onto a line
        m.y[4] = m.y[1];
        m.x[5] = m.x[2];
        m.y[5] = m.y[2];
      }
      const auto r = m.step(1e-6);
      EXPECT_TRUE(r.failed);
      EXPECT_EQ(r.failed_element, 1);
      if (kind == 1)
        for (int c = 0; c < 24; ++c) EXPECT_EQ(m.block.force[24 + c], 0.0);
      for (int c = 0; c < 24; ++c) EXPECT_TRUE(std::isfinite(m.block.force[c]));
    }
}

// A *MAT_RIGID block (no material in the registry) still gets areas and masses.
TEST(ShellInitialize, RigidBlockHasMass) {
  ShellMesh m;
  m.add_node(0, 0, 0);
  m.add_node(2, 0, 0);
  m.add_node(2, 1, 0);
  m.add_node(0, 1, 0);
  m.add_element({0, 1, 2, 3}, 0.01);
  set_section(m.block, -1, 2, rf::element::ThroughThicknessRule::kGauss, 1, 0.1);
  m.block.rigid = true;
  m.initialize();
  std::vector<double> mass(4, 0.0), inertia(4, 0.0);
  rf::element::add_shell_lumped_mass(m.block, mass, inertia);
  EXPECT_NEAR(mass[2], kRho * 0.01 * 2.0 / 4, 1e-12);
  EXPECT_NEAR(inertia[2], mass[2] * (2.0 / 4 + 1e-4 / 12), 1e-12);
}

// Arbitrary states: random velocities and angular velocities on distorted elements (flat, and
// warped with the warping correction), pre-stressed, over several steps: the internal forces
// sum to zero and their moments balance, sum (x_I x f_I + m_I) = 0.
TEST(ShellBalance, ForcesAndMomentsBalanceForArbitraryStates) {
  std::mt19937 gen(42);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (bool warped : {false, true})
    for (int ihq : {1, 4})
      for (bool tri : {false, true}) {
        ShellMesh m;
        const double h = warped ? 0.05 : 0.0;
        m.add_node(0.1, 0.0, h);
        m.add_node(1.2, 0.2, -h);
        m.add_node(1.0, 1.1, h);
        if (!tri) m.add_node(-0.2, 0.9, -h);
        m.add_element({0, 1, 2, tri ? 2 : 3}, 0.04);
        set_section(m.block, 0, 3, rf::element::ThroughThicknessRule::kLobatto, ihq, 0.1);
        m.block.warping_correction = warped;
        m.initialize();
        for (double& s : m.block.stress) s = 1e7 * U(gen);
        const double dt = 1e-4;
        for (int s = 0; s < 5; ++s) {
          for (std::size_t i = 0; i < m.x.size(); ++i) {
            m.vx[i] = U(gen);
            m.vy[i] = U(gen);
            m.vz[i] = U(gen);
            m.wx[i] = 10 * U(gen);
            m.wy[i] = 10 * U(gen);
            m.wz[i] = 10 * U(gen);
            m.x[i] += dt * m.vx[i];
            m.y[i] += dt * m.vy[i];
            // Without the correction the element must stay flat: the hourglass forces of a
            // warped element have a moment (the defect the correction removes).
            if (warped) m.z[i] += dt * m.vz[i];
          }
          ASSERT_FALSE(m.step(dt).failed);
          double F[3] = {0, 0, 0}, Mm[3] = {0, 0, 0}, scale = 0.0;
          for (int I = 0; I < 4; ++I) {
            const int n = m.block.conn[I];
            const double* f = &m.block.force[6 * I];
            const double r[3] = {m.x[n], m.y[n], m.z[n]};
            for (int i = 0; i < 3; ++i) {
              F[i] += f[i];
              Mm[i] += f[3 + i];
              scale += std::abs(f[i]) + std::abs(f[3 + i]);
            }
            Mm[0] += r[1] * f[2] - r[2] * f[1];
            Mm[1] += r[2] * f[0] - r[0] * f[2];
            Mm[2] += r[0] * f[1] - r[1] * f[0];
          }
          ASSERT_GT(scale, 1e3);
          for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(F[i], 0.0, 1e-12 * scale) << warped << ihq << tri;
            EXPECT_NEAR(Mm[i], 0.0, 1e-12 * scale) << warped << ihq << tri;
          }
        }
      }
}

// The scaled rotary inertia keeps the rotational frequencies below the membrane ones: the
// highest frequency of the element (lumped mass and inertia, stiffness by finite differences
// of the kernel's forces) is that of its translational degrees of freedom.
TEST(ShellMass, RotationsDoNotGovernTheStep) {
  struct Geometry {
    double p[4][3];
    double t;
  };
  const Geometry cases[] = {
      {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0.01},
      {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0.3},
      {{{0, 0, 0}, {1.3, 0.1, 0}, {1.0, 0.7, 0}, {0.1, 0.9, 0}}, 0.05},
      {{{0, 0, 0}, {3.0, 0, 0}, {3.0, 1, 0}, {0, 1, 0}}, 0.02},
  };
  for (const auto& g : cases) {
    ShellMesh m;
    for (const auto& p : g.p) m.add_node(p[0], p[1], p[2]);
    m.add_element({0, 1, 2, 3}, g.t);
    set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, 4, 0.1);
    m.initialize();
    std::vector<double> mass(4, 0.0), inertia(4, 0.0);
    rf::element::add_shell_lumped_mass(m.block, mass, inertia);
    const auto X = m.positions();
    Eigen::MatrixXd K(24, 24);
    const double eps = 1e-9;
    for (int j = 0; j < 24; ++j) {
      ShellMesh t = m;
      const int node = j / 6, dof = j % 6;
      std::vector<double>* target[6] = {&t.vx, &t.vy, &t.vz, &t.wx, &t.wy, &t.wz};
      (*target[dof])[node] = 1.0;
      t.place_for_step(X, eps);  // displacement eps in that dof, mid-step geometry X
      t.step(eps);
      for (int i = 0; i < 24; ++i) K(i, j) = t.block.force[i] / eps;
    }
    Eigen::MatrixXd Ks = 0.5 * (K + K.transpose());
    Eigen::VectorXd minv(24);
    for (int i = 0; i < 24; ++i)
      minv(i) = 1.0 / std::sqrt(i % 6 < 3 ? mass[i / 6] : inertia[i / 6]);
    const Eigen::MatrixXd A = minv.asDiagonal() * Ks * minv.asDiagonal();
    auto max_eig = [](const Eigen::MatrixXd& a) {
      return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues().maxCoeff();
    };
    std::vector<int> trans, rot;
    for (int i = 0; i < 24; ++i) (i % 6 < 3 ? trans : rot).push_back(i);
    const double w_full = std::sqrt(max_eig(A));
    const double w_trans = std::sqrt(max_eig(A(trans, trans)));
    const double w_rot = std::sqrt(max_eig(A(rot, rot)));
    EXPECT_LT(w_rot, w_trans) << "t " << g.t;
    EXPECT_LT(w_full, 1.001 * w_trans) << "t " << g.t;  // measured 1.0000
    // And the shell step formula is within the usual TSSFAC margin of the exact 2 / w_max.
    const double dt = rf::element::shell_critical_timestep(m.block, m.view()).min_dt;
    EXPECT_GT(2.0 / w_full, 0.85 * dt) << "t " << g.t;
  }
}

// The elastic kernel evaluates elements in SIMD batches: every element's forces, stresses and
// hourglass state must be exactly those it gets when evaluated alone (mixed quadrilaterals and
// triangles, warped, a block length that leaves a partial batch).
TEST(ShellBatch, ResultsDoNotDependOnBatching) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  ShellMesh all;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) all.add_node(i + 0.2 * U(gen), j + 0.2 * U(gen), 0.05 * U(gen));
  auto id = [](int i, int j) { return i + 4 * j; };
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      if ((i + j) % 3 == 1)
        all.add_element({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i + 1, j + 1)}, 0.03);
      else
        all.add_element({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}, 0.02 + 0.01 * i);
    }
  all.add_element({id(3, 0), id(3, 1), id(2, 1), id(2, 1)}, 0.02);  // 7 elements
  for (std::size_t n = 0; n < all.x.size(); ++n) {
    all.vx[n] = U(gen);
    all.vy[n] = U(gen);
    all.vz[n] = U(gen);
    all.wx[n] = U(gen);
    all.wy[n] = U(gen);
    all.wz[n] = U(gen);
  }
  for (int ihq : {1, 4}) {
    ShellMesh m = all;
    set_section(m.block, 0, 3, rf::element::ThroughThicknessRule::kGauss, ihq, 0.1);
    m.block.warping_correction = true;
    m.initialize();
    for (int s = 0; s < 3; ++s) m.step(1e-5);
    for (std::size_t e = 0; e < m.block.size(); ++e) {
      ShellMesh one = all;
      one.block.element_id = {m.block.element_id[e]};
      one.block.conn.assign(m.block.conn.begin() + 4 * e, m.block.conn.begin() + 4 * e + 4);
      one.block.rotation_conn = one.block.conn;
      one.block.thickness.assign(m.block.thickness.begin() + 4 * e,
                                 m.block.thickness.begin() + 4 * e + 4);
      set_section(one.block, 0, 3, rf::element::ThroughThicknessRule::kGauss, ihq, 0.1);
      one.block.warping_correction = true;
      one.initialize();
      for (int s = 0; s < 3; ++s) one.step(1e-5);
      for (int c = 0; c < 24; ++c) EXPECT_EQ(one.block.force[c], m.block.force[24 * e + c]);
      for (int c = 0; c < 15; ++c) EXPECT_EQ(one.block.stress[c], m.block.stress[15 * e + c]);
      for (int c = 0; c < 5; ++c)
        EXPECT_EQ(one.block.hourglass_state[c], m.block.hourglass_state[5 * e + c]);
    }
  }
}

// The kernel with its own lumped mass in a small central-difference loop: a clamped strip
// (nu = 0, so plate and beam stiffness agree) released with the velocity shape of the first
// cantilever mode oscillates at the Euler-Bernoulli frequency
// omega_1 = 1.8751^2 sqrt(E I / (rho A L^4)); the hourglass (IHQ 1) takes a negligible share.
TEST(ShellDynamics, CantileverStripFirstFrequencyMatchesBeamTheory) {
  const double L = 1.0, b = 0.1, t = 0.01, E = 2.0e11, rho = 7800.0;
  const int n = 20;
  ShellMesh m;
  for (int i = 0; i <= n; ++i) {
    m.add_node(L * i / n, 0.0, 0.0);
    m.add_node(L * i / n, b, 0.0);
  }
  for (int i = 0; i < n; ++i) m.add_element({2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1}, t);
  m.block.part_id = 1;
  m.block.material = rf::material::make_elastic(rho, E, 0.0);
  m.block.material_index = 0;
  m.block.nip = 2;
  m.block.hourglass.ihq = 1;
  m.block.hourglass.qm = 0.1;
  m.initialize();
  const std::size_t nn = m.x.size();
  std::vector<double> mass(nn, 0.0), inertia(nn, 0.0);
  rf::element::add_shell_lumped_mass(m.block, mass, inertia);
  // First cantilever mode phi(x) and its slope; v_z = V phi, omega_y = -V phi' (Kirchhoff).
  const double beta = 1.8751040687, sig = 0.7340955137, V = 1e-3;
  for (std::size_t k = 0; k < nn; ++k) {
    const double z = beta * m.x[k] / L;
    const double phi = std::cosh(z) - std::cos(z) - sig * (std::sinh(z) - std::sin(z));
    const double dphi =
        beta / L * (std::sinh(z) + std::sin(z) - sig * (std::cosh(z) - std::cos(z)));
    m.vz[k] = V * phi;
    m.wy[k] = -V * dphi;
  }
  double ke0 = 0.0;
  for (std::size_t k = 0; k < nn; ++k)
    ke0 += 0.5 * mass[k] * m.vz[k] * m.vz[k] + 0.5 * inertia[k] * m.wy[k] * m.wy[k];
  const double dt = 0.8 * rf::element::shell_critical_timestep(m.block, m.view()).min_dt;
  const double I = b * t * t * t / 12.0, A = b * t;
  const double omega = beta * beta * std::sqrt(E * I / (rho * A * std::pow(L, 4)));
  const double period = 2.0 * std::acos(-1.0) / omega;
  const std::size_t tip = nn - 1;
  double prev = 0.0, time = 0.0, hourglass = 0.0;
  std::vector<double> crossings;
  std::vector<double> f(nn * 6);
  while (time < 2.6 * period) {
    // x^{n+1} = x^n + dt v^{n+1/2}; forces at x^{n+1}; v^{n+3/2} = v^{n+1/2} - dt f / m.
    for (std::size_t k = 0; k < nn; ++k) {
      m.x[k] += dt * m.vx[k];
      m.y[k] += dt * m.vy[k];
      m.z[k] += dt * m.vz[k];
    }
    time += dt;
    const auto r = m.step(dt);
    ASSERT_FALSE(r.failed);
    hourglass += r.hourglass_work;
    std::fill(f.begin(), f.end(), 0.0);
    for (std::size_t e = 0; e < m.block.size(); ++e)
      for (int I4 = 0; I4 < 4; ++I4)
        for (int c = 0; c < 6; ++c)
          f[6 * static_cast<std::size_t>(m.block.conn[4 * e + I4]) + c] +=
              m.block.force[24 * e + 6 * I4 + c];
    for (std::size_t k = 2; k < nn; ++k) {  // nodes 0, 1 clamped
      m.vx[k] -= dt * f[6 * k + 0] / mass[k];
      m.vy[k] -= dt * f[6 * k + 1] / mass[k];
      m.vz[k] -= dt * f[6 * k + 2] / mass[k];
      m.wx[k] -= dt * f[6 * k + 3] / inertia[k];
      m.wy[k] -= dt * f[6 * k + 4] / inertia[k];
      m.wz[k] -= dt * f[6 * k + 5] / inertia[k];
    }
    // Tip velocity changes sign at the extremes of the displacement: half periods.
    const double vt = m.vz[tip];
    if (time > 0.1 * period && prev > 0.0 && vt <= 0.0) crossings.push_back(time);
    if (time > 0.1 * period && prev < 0.0 && vt >= 0.0) crossings.push_back(time);
    prev = vt;
  }
  ASSERT_GE(crossings.size(), 4u);
  const double measured =
      2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  // 20 elements: measured period 0.21% above the beam's (constant curvature per element, the
  // scaled rotary inertia and the transverse shear all lengthen it slightly).
  EXPECT_NEAR(measured / period, 1.0, 0.01) << "measured " << measured << " beam " << period;
  EXPECT_LT(std::abs(hourglass), 1e-3 * ke0);  // measured 4e-29
}

// Cylindrical bending of an elastic-perfectly plastic plate (*MAT_024, no hardening): the
// imposed curvature about y with eps_y = 0 gives at every yielded point sigma_y = sigma_x / 2,
// sigma_x = 2 SIGY / sqrt(3) (von Mises, plane stress); the moment tends to the limit moment
// M_p = (2 / sqrt 3) SIGY t^2 / 4, exactly so up to the rule's quadrature of |z|.
TEST(ShellPlasticity, CylindricalBendingReachesLimitMoment) {
  for (auto rule :
       {rf::element::ThroughThicknessRule::kGauss, rf::element::ThroughThicknessRule::kLobatto}) {
    ShellMesh m;
    const double a = 0.1, t = 0.01, sigy = 2.5e8;
    m.add_node(-a / 2, -a / 2, 0);
    m.add_node(a / 2, -a / 2, 0);
    m.add_node(a / 2, a / 2, 0);
    m.add_node(-a / 2, a / 2, 0);
    m.add_element({0, 1, 2, 3}, t);
    set_section(m.block, 2, 10, rule, 1, 0.1);
    m.block.plastic.sigy = sigy;
    m.block.plastic.isotropic_modulus = 0.0;
    m.block.plastic.linear = true;
    m.block.plastic.strain = {0.0, 1.0};
    m.block.plastic.stress = {sigy, sigy};
    m.initialize();
    // Surface strain 40 times the yield strain in 400 steps.
    const double kappa_end = 40.0 * sigy / kE / (t / 2), steps = 400, dt = 1e-4;
    const double kdot = kappa_end / (steps * dt);
    for (int i = 0; i < 4; ++i) {
      m.wy[i] = kdot * m.x[i];
      m.vz[i] = -0.5 * kdot * m.x[i] * m.x[i];
    }
    for (int s = 0; s < steps; ++s) ASSERT_FALSE(m.step(dt).failed);
    double M = 0.0;
    for (int q = 0; q < 10; ++q) {
      const double z = m.block.zeta[q] * t / 2;
      const double* st = &m.block.stress[5 * q];
      M += t / 2 * m.block.weight[q] * z * st[0];
      if (std::abs(m.block.zeta[q]) > 0.2) {  // well inside the plastic zone
        EXPECT_NEAR(st[0], std::copysign(2.0 * sigy / std::sqrt(3.0), z), 1e-3 * sigy);
        EXPECT_NEAR(st[1], 0.5 * st[0], 1e-3 * sigy);
      }
    }
    const double mp = 2.0 / std::sqrt(3.0) * sigy * t * t / 4.0;
    // Every point lies outside the elastic core |zeta| < 1/40, so the element's moment is M_p
    // times the rule's quadrature of |zeta| (integral 1): 1.0075 (Gauss 10), 1.0093 (Lobatto 10).
    double quad = 0.0;
    for (int q = 0; q < 10; ++q) quad += m.block.weight[q] * std::abs(m.block.zeta[q]);
    EXPECT_NEAR(M, mp * quad, 1e-4 * mp);
    EXPECT_NEAR(M / mp, 1.0, 0.01);
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Energy bookkeeping of a free plate kicked out of plane (issue 16: the kick deck). Central
// differences as the solver (x^{n+1} = x^n + dt v^{n+1/2}, forces at x^{n+1}, v^{n+3/2}); the
// work of the internal forces is summed as the solver does, f^{n+1} . dt (v^{n+1/2} +
// v^{n+3/2}) / 2, and the hourglass share of the forces is isolated by evaluating a copy of the
// block with QM = 0 on the same state (the stress update does not depend on the hourglass).
struct KickEnergies {
  double internal_work = 0.0;         // all internal forces and moments
  double hourglass_force_work = 0.0;  // the hourglass share, measured from the forces
  double hourglass_reported = 0.0;    // sum of KernelResult::hourglass_work
  double strain_energy = 0.0;         // 0.5 sigma : C^-1 : sigma from the stored stresses
  double kinetic0 = 0.0;
  double min_internal = 1e300;          // min over steps of internal_work - hourglass_reported
  double min_stress_work = 1e300;       // min over steps of internal_work - hourglass_force_work
  double max_hourglass_mismatch = 0.0;  // max over steps |reported - force work|
  double max_step_hourglass = 0.0;      // max over steps of sum over dofs |f_hg . dx|
};

KickEnergies run_kick(int ihq, double qm, double duration, int kicked = 9, double tssfac = 0.9) {
  const double t = 0.002, h = 0.1;
  ShellMesh m;
  const int nx = 4, ny = 2;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.add_node(h * i, h * j, 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i;
      m.add_element({a, a + 1, a + nx + 2, a + nx + 1}, t);
    }
  set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, ihq, qm);
  m.block.shear_factor = 5.0 / 6.0;
  m.initialize();
  const std::size_t nn = m.x.size();
  std::vector<double> mass(nn, 0.0), inertia(nn, 0.0);
  rf::element::add_shell_lumped_mass(m.block, mass, inertia);
  m.vz[kicked] = 0.5;
  KickEnergies out;
  out.kinetic0 = 0.5 * mass[kicked] * 0.25;
  const double dt = tssfac * rf::element::shell_critical_timestep(m.block, m.view()).min_dt;
  std::vector<double> f(nn * 6), fh(nn * 6);
  std::vector<std::vector<double>*> vel = {&m.vx, &m.vy, &m.vz, &m.wx, &m.wy, &m.wz};
  for (double time = 0.0; time < duration; time += dt) {
    for (std::size_t k = 0; k < nn; ++k) {
      m.x[k] += dt * m.vx[k];
      m.y[k] += dt * m.vy[k];
      m.z[k] += dt * m.vz[k];
    }
    ShellMesh stress_only = m;
    stress_only.block.hourglass.qm = 0.0;
    stress_only.step(dt);
    const auto r = m.step(dt);
    out.hourglass_reported += r.hourglass_work;
    std::fill(f.begin(), f.end(), 0.0);
    std::fill(fh.begin(), fh.end(), 0.0);
    for (std::size_t e = 0; e < m.block.size(); ++e)
      for (int I = 0; I < 4; ++I)
        for (int c = 0; c < 6; ++c) {
          const std::size_t s = 24 * e + 6 * static_cast<std::size_t>(I) + c;
          const std::size_t d = 6 * static_cast<std::size_t>(m.block.conn[4 * e + I]) + c;
          f[d] += m.block.force[s];
          fh[d] += m.block.force[s] - stress_only.block.force[s];
        }
    double step_hourglass = 0.0;
    for (std::size_t k = 0; k < nn; ++k)
      for (int c = 0; c < 6; ++c) {
        double& v = (*vel[c])[k];
        const double before = v;
        v -= dt * f[6 * k + c] / (c < 3 ? mass[k] : inertia[k]);
        const double dx = 0.5 * dt * (before + v);
        out.internal_work += f[6 * k + c] * dx;
        out.hourglass_force_work += fh[6 * k + c] * dx;
        step_hourglass += std::abs(fh[6 * k + c] * dx);
      }
    out.max_step_hourglass = std::max(out.max_step_hourglass, step_hourglass);
    out.min_internal = std::min(out.min_internal, out.internal_work - out.hourglass_reported);
    out.min_stress_work =
        std::min(out.min_stress_work, out.internal_work - out.hourglass_force_work);
    out.max_hourglass_mismatch = std::max(
        out.max_hourglass_mismatch, std::abs(out.hourglass_reported - out.hourglass_force_work));
  }
  // Strain energy of the stored stresses (plane stress, transverse shear SHRF G).
  const double E = kE, nu = kNu, G = kE / (2 * (1 + kNu)), Gs = 5.0 / 6.0 * G;
  for (std::size_t e = 0; e < m.block.size(); ++e)
    for (int q = 0; q < m.block.nip; ++q) {
      const double* s = &m.block.stress[(e * m.block.nip + q) * 5];
      const double w = 0.5 * t * m.block.weight[q] * m.block.area[e];
      const double u = (s[0] * s[0] + s[1] * s[1] - 2 * nu * s[0] * s[1]) / (2 * E) +
                       s[2] * s[2] / (2 * G) + (s[3] * s[3] + s[4] * s[4]) / (2 * Gs);
      out.strain_energy += w * u;
    }
  return out;
}

// Issue 16 (the kick deck: a free plate, one node kicked out of plane). What each energy is:
//
// (a) The reported hourglass work is the work of the hourglass forces and moments as the solver
//     books it, to one step's work: both forms use the trapezoid 0.5 (Q_old + Q_new) qd dt
//     (the viscous form used Q_new qd dt, which drifted by 20 % of the hourglass energy here).
//
// (b) At TSSFAC 0.9 the booked internal work minus the hourglass work still dips below zero
//     (-1.0e-3 of 9.75e-3 in this test) although it is then exactly the work of the stress forces:
//     that is central differences, not the kernel. The booked work of a mode of frequency w is
//     0.5 q^n K q^{n+1} (sum of f^n . (x^{n+1} - x^{n-1}) / 2), which swings below zero by about
//     (w dt)^2 / 4 of the mode's energy; a point kick puts much of its energy into the highest
//     out-of-plane modes (transverse shear with the rotary inertia, w dt ~ 1.2 at TSSFAC 0.9).
//     At TSSFAC 0.3 the minimum is positive, and as dt -> 0 the stress work approaches the strain
//     energy of the stored stresses (so forces and strain rates are consistent).
TEST(ShellEnergy, KickedPlateReportsTheWorkOfItsHourglassForces) {
  for (double tssfac : {0.9, 0.3})
    for (int ihq : {1, 4}) {
      const auto r = run_kick(ihq, 0.05, 0.02, 9, tssfac);
      const std::string what = "ihq " + std::to_string(ihq) + " tssfac " + std::to_string(tssfac);
      ASSERT_GT(r.hourglass_force_work, 1e-3 * r.kinetic0) << what;
      // At every step the two differ by at most about one step's hourglass work (measured 0.2
      // to 0.45 of the largest step's sum of |f_hg . dx|; the old viscous booking reached 0.95).
      EXPECT_LT(r.max_hourglass_mismatch, 0.6 * r.max_step_hourglass) << what;
      // The viscous work is dissipated: no stored energy, no end term (measured 3e-5 relative).
      if (ihq == 1)
        EXPECT_NEAR(r.hourglass_reported, r.hourglass_force_work, 1e-3 * r.hourglass_force_work)
            << what;
    }
}

TEST(ShellEnergy, KickedPlateInternalEnergyStaysPositive) {
  for (int ihq : {1, 4}) {
    const auto r = run_kick(ihq, 0.05, 0.02, 9, 0.3);
    // Internal energy as glstat reports it (internal work minus reported hourglass work):
    // measured minimum 1.6e-4 (IHQ 1) and 3.8e-4 (IHQ 4) of 9.75e-3; -4e-5 for IHQ 1 before.
    EXPECT_GT(r.min_internal, 0.0) << "ihq " << ihq;
    if (ihq == 4) {
      // Energy held by the hourglass springs: 2.1 % of the kick (11 % while the out-of-plane
      // mode resisted the elements' twist).
      EXPECT_LT(r.hourglass_reported, 0.04 * r.kinetic0);
    }
  }
  // Stress forces consistent with the strain rates: as dt -> 0 the booked stress work equals
  // the strain energy 0.5 sigma : C^-1 : sigma of the stored stresses (measured 0.4 %).
  const auto r = run_kick(4, 0.05, 0.02, 9, 0.1);
  const double stress_work = r.internal_work - r.hourglass_force_work;
  EXPECT_NEAR(stress_work, r.strain_energy, 0.02 * r.strain_energy);
  EXPECT_GT(r.strain_energy, 0.2 * r.kinetic0);
}

// Constant twist w = k xi eta (xi, eta along the unit vectors u, w of the plate's plane) with
// the Kirchhoff rotations theta_u = dw/deta, theta_w = -dw/dxi (the kernel's convention:
// gamma_zx = w_,x + theta_y = 0, gamma_yz = w_,y - theta_x = 0) is a constant-curvature state
// that the one-point element represents exactly: uniform twisting moment
// M_xi_eta = -D (1 - nu) k (sign as in ShellBending: M = -D ((1 - nu) w_,ij + nu lap(w) delta)),
// and no hourglass rate in any mode. On a rectangle the nodal w values form exactly the
// out-of-plane hourglass pattern h = (1, -1, 1, -1): a rate tau . v_z alone would resist the
// twist (issue 16: the kick deck put most of its energy in that "hourglass"). Irregular patch in
// an oblique plane, and a single rectangle where also the transverse shear and so every nodal
// out-of-plane force must vanish.
TEST(ShellHourglass, ConstantTwistIsHourglassFree) {
  const double t = 0.01, kdot = 0.7, dt = 1e-5;
  const double D = kE * t * t * t / (12 * (1 - kNu * kNu));
  const double u[3] = {0.8, 0.0, 0.6}, w[3] = {0.0, 1.0, 0.0};
  const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                       u[0] * w[1] - u[1] * w[0]};
  for (int ihq : {1, 4})
    for (bool rectangle : {false, true}) {
      ShellMesh m;
      if (rectangle) {
        const double a = 0.3, b = 0.1;
        const double q[4][2] = {{0.1, -0.2}, {0.1 + a, -0.2}, {0.1 + a, -0.2 + b}, {0.1, -0.2 + b}};
        for (const auto& c : q)
          m.add_node(c[0] * u[0] + c[1] * w[0], c[0] * u[1] + c[1] * w[1],
                     c[0] * u[2] + c[1] * w[2]);
        m.add_element({0, 1, 2, 3}, t);
      } else {
        m = make_patch(u, w, t).mesh;
      }
      set_section(m.block, 0, 2, rf::element::ThroughThicknessRule::kGauss, ihq, 0.1);
      m.initialize();
      const auto X = m.positions();
      for (std::size_t i = 0; i < X.size(); ++i) {
        const double xi = X[i][0] * u[0] + X[i][1] * u[1] + X[i][2] * u[2];
        const double eta = X[i][0] * w[0] + X[i][1] * w[1] + X[i][2] * w[2];
        const double vn = kdot * xi * eta, tu = kdot * xi, tw = -kdot * eta;
        m.vx[i] = vn * n[0];
        m.vy[i] = vn * n[1];
        m.vz[i] = vn * n[2];
        m.wx[i] = tu * u[0] + tw * w[0];
        m.wy[i] = tu * u[1] + tw * w[1];
        m.wz[i] = tu * u[2] + tw * w[2];
      }
      m.place_for_step(X, dt);
      const auto r = m.step(dt);
      ASSERT_FALSE(r.failed);
      const double k = kdot * dt;
      const double Mt = D * (1 - kNu) * k;
      // Uniform twisting moment, in element axes through the oblique plane's tensor.
      double T[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) T[i][j] = -Mt * (u[i] * w[j] + w[i] * u[j]);
      for (std::size_t e = 0; e < m.block.size(); ++e) {
        std::array<double, 3> pe[4];
        for (int I = 0; I < 4; ++I) pe[I] = X[m.block.conn[4 * e + I]];
        const auto expect = to_element_axes(element_axes(pe), T);
        double M[3] = {0, 0, 0};
        for (int q = 0; q < 2; ++q) {
          const double z = m.block.zeta[q] * t / 2;
          for (int c = 0; c < 3; ++c)
            M[c] += t / 2 * m.block.weight[q] * z * m.block.stress[5 * (2 * e + q) + c];
        }
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(M[c], expect[c], 1e-9 * Mt) << "element " << e << " ihq " << ihq;
        if (ihq == 4)
          for (int mode = 0; mode < 5; ++mode)  // vs K_w tau.v_z dt ~ 1e2 without the rotations
            EXPECT_NEAR(m.block.hourglass_state[5 * e + mode], 0.0, 1e-9)
                << "element " << e << " mode " << mode;
      }
      EXPECT_NEAR(r.hourglass_work, 0.0, 1e-15);
      if (rectangle) {
        // No transverse shear, no hourglass: no out-of-plane nodal force; the nodal moments are
        // those of the uniform twisting moment alone.
        const double scale = Mt;  // moments ~ Mt * side, forces would be ~ Mt
        for (int I = 0; I < 4; ++I) {
          const double* f = &m.block.force[6 * I];
          EXPECT_NEAR(f[0] * n[0] + f[1] * n[1] + f[2] * n[2], 0.0, 1e-9 * scale) << ihq;
        }
      }
    }
}
