// Fully integrated shell (LS-DYNA ELFORM 16, element/shell_block.cpp section 11) driven
// directly. References are analytic (plane-stress elasticity, plate bending D kappa, the twist
// energy of a plate, the bilinear hardening law), conservation laws (force and moment balance,
// objectivity) or counts (rigid-body modes), never the kernel's own output.
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
#include "shell_test_mesh.hpp"

namespace {

using rf::test::element_axes;
using rf::test::make_patch;
using rf::test::node_force;
using rf::test::Patch;
using rf::test::plane_stress_of_in_plane_rate;
using rf::test::set_in_plane_linear_velocity;
using rf::test::ShellMesh;
using rf::test::to_element_axes;

using rf::element::ShellBlock;
using rf::element::ThroughThicknessRule;

constexpr double kE = 2.0e11, kNu = 0.3, kRho = 7800.0;

void set_section(ShellBlock& b, int material_index, int nip, int elform = 16) {
  b.part_id = 3;
  b.elform = elform;
  b.material = rf::material::make_elastic(kRho, kE, kNu);
  b.material_index = material_index;
  b.nip = nip;
  b.rule = ThroughThicknessRule::kGauss;
  b.hourglass.ihq = 4;
  b.hourglass.qm = elform == 16 ? 0.1 : 0.0;  // ELFORM 16 ignores it (checked below)
}

const double* point_stress(const ShellBlock& b, std::size_t e, int g, int q) {
  return &b.stress[5 * (static_cast<std::size_t>(b.points_per_element()) * e +
                        static_cast<std::size_t>(g * b.nip + q))];
}

TEST(Shell16Patch, ConstantMembraneStrainOnDistortedMeshIsExact) {
  const double s = 1.0 / std::sqrt(3.0);
  const double u[3] = {s, s, s};
  const double w[3] = {1.0 / std::sqrt(2.0), -1.0 / std::sqrt(2.0), 0.0};
  const double t = 0.01;
  Patch p = make_patch(u, w, t);
  ShellMesh& m = p.mesh;
  set_section(m.block, 0, 2);
  m.initialize();
  ASSERT_EQ(m.block.points_per_element(), 8);
  const double Lab[2][2] = {{2.0e-2, 0.7e-2}, {-0.3e-2, -1.1e-2}};
  const auto X = m.positions();
  set_in_plane_linear_velocity(m, X, u, w, Lab);
  const double dt = 1e-3;
  m.place_for_step(X, dt);
  const auto r = m.step(dt);
  ASSERT_FALSE(r.failed);
  EXPECT_EQ(r.hourglass_work, 0.0);
  double T[3][3];
  const double scale = plane_stress_of_in_plane_rate(Lab, dt, u, w, kE, kNu, T);
  double worst = 0.0;
  for (std::size_t e = 0; e < 4; ++e) {
    std::array<double, 3> pe[4];
    for (int I = 0; I < 4; ++I) pe[I] = X[m.block.conn[4 * e + I]];
    const auto expect = to_element_axes(element_axes(pe), T);
    for (int g = 0; g < 4; ++g)
      for (int q = 0; q < 2; ++q) {
        const double* st = point_stress(m.block, e, g, q);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(st[c], expect[c], 1e-11 * scale);
          worst = std::max(worst, std::abs(st[c] - expect[c]) / scale);
        }
        EXPECT_NEAR(st[3], 0.0, 1e-11 * scale);
        EXPECT_NEAR(st[4], 0.0, 1e-11 * scale);
        worst = std::max({worst, std::abs(st[3]) / scale, std::abs(st[4]) / scale});
      }
  }
  std::printf("ELFORM 16 membrane patch: largest stress error %.2e of the stress scale\n", worst);
  // Interior node in equilibrium up to the half-step frame turn (second order, as for ELFORM 2).
  const double fscale = scale * t * 0.5;
  const auto f = node_force(m.block, p.interior, 0);
  const auto mm = node_force(m.block, p.interior, 3);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(f[i], 0.0, 1e-5 * fscale);
    EXPECT_NEAR(mm[i], 0.0, 1e-5 * fscale);
  }
  const auto fc = node_force(m.block, 0, 0);
  EXPECT_GT(std::abs(fc[0]) + std::abs(fc[1]) + std::abs(fc[2]), 0.1 * fscale);
}

// Uniform curvature (Kirchhoff: theta_y = kdot x, v_z = -kdot x^2 / 2) on the distorted patch:
// M_xx = D kappa, M_yy = nu D kappa, M_xy = 0 at every in-plane point, and the assumed natural
// transverse shear is exactly zero (the edge tying values of a quadratic w with linear
// rotations vanish; the Gauss-point shear of the plain bilinear element would not).
TEST(Shell16Patch, ConstantCurvatureOnDistortedMeshIsExact) {
  const double u[3] = {1, 0, 0}, w[3] = {0, 1, 0};
  const double t = 0.02;
  double worst = 0.0, worst_shear = 0.0;
  for (int nip : {2, 3, 5}) {
    Patch p = make_patch(u, w, t);
    ShellMesh& m = p.mesh;
    set_section(m.block, 0, nip);
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
    const double T[3][3] = {{D * kappa, 0, 0}, {0, kNu * D * kappa, 0}, {0, 0, 0}};
    for (std::size_t e = 0; e < 4; ++e) {
      std::array<double, 3> pe[4];
      for (int I = 0; I < 4; ++I) pe[I] = X[m.block.conn[4 * e + I]];
      const auto expect = to_element_axes(element_axes(pe), T);
      for (int g = 0; g < 4; ++g) {
        double M[3] = {0, 0, 0};
        for (int q = 0; q < nip; ++q) {
          const double zq = m.block.zeta[q] * t / 2;
          const double* st = point_stress(m.block, e, g, q);
          for (int k = 0; k < 3; ++k) M[k] += t / 2 * m.block.weight[q] * zq * st[k];
          EXPECT_NEAR(st[3], 0.0, 1e-9 * kE * kappa * t) << "shear yz, element " << e;
          EXPECT_NEAR(st[4], 0.0, 1e-9 * kE * kappa * t) << "shear zx, element " << e;
          worst_shear = std::max({worst_shear, std::abs(st[3]) / (kE * kappa * t),
                                  std::abs(st[4]) / (kE * kappa * t)});
        }
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(M[k], expect[k], 1e-10 * D * kappa) << "element " << e << " point " << g;
          worst = std::max(worst, std::abs(M[k] - expect[k]) / (D * kappa));
        }
      }
    }
  }
  std::printf(
      "ELFORM 16 curvature patch: largest moment error %.2e of D kappa, largest "
      "transverse shear %.2e of E kappa t\n",
      worst, worst_shear);
}

// Finite rigid rotations (Cayley-consistent velocities) of a prestressed element, flat and
// warped: the co-rotational stresses at all 4 x NIP points stay unchanged.
TEST(Shell16Objectivity, FiniteRigidRotationLeavesStressUnchanged) {
  const double pi = std::acos(-1.0);
  double worst = 0.0;
  for (bool warped : {false, true})
    for (int axis_case : {0, 1, 2}) {
      ShellMesh m;
      const double h = warped ? 0.03 : 0.0;
      m.add_node(0.0, 0.0, h);
      m.add_node(1.1, 0.1, -h);
      m.add_node(1.2, 0.9, h);
      m.add_node(-0.1, 1.0, -h);
      m.add_element({0, 1, 2, 3}, 0.05);
      set_section(m.block, 0, 3);
      m.initialize();
      const double s0 = 1e8;
      for (std::size_t k = 0; k < m.block.stress.size(); ++k)
        m.block.stress[k] = s0 * std::sin(1.0 + 0.7 * static_cast<double>(k));
      const std::vector<double> stress0 = m.block.stress;
      double axis[3] = {1, 0, 0};
      if (axis_case == 1) axis[0] = 0, axis[2] = 1;
      if (axis_case == 2) axis[0] = 0.48, axis[1] = 0.6, axis[2] = 0.64;
      const int steps = 10;
      const double phi = 120.0 * pi / 180.0 / steps, dt = 1e-3;
      const double ctr[3] = {0.55, 0.5, 0.0};
      const double wmag = 2.0 * std::tan(phi / 2) / dt;
      for (int s = 0; s < steps; ++s) {
        for (int i = 0; i < 4; ++i) {
          const double r[3] = {m.x[i] - ctr[0], m.y[i] - ctr[1], m.z[i] - ctr[2]};
          const double k = axis[0] * r[0] + axis[1] * r[1] + axis[2] * r[2];
          const double cr[3] = {axis[1] * r[2] - axis[2] * r[1], axis[2] * r[0] - axis[0] * r[2],
                                axis[0] * r[1] - axis[1] * r[0]};
          double pnew[3];
          for (int d = 0; d < 3; ++d)
            pnew[d] = ctr[d] + r[d] * std::cos(phi) + cr[d] * std::sin(phi) +
                      axis[d] * k * (1 - std::cos(phi));
          m.vx[i] = (pnew[0] - m.x[i]) / dt;
          m.vy[i] = (pnew[1] - m.y[i]) / dt;
          m.vz[i] = (pnew[2] - m.z[i]) / dt;
          m.x[i] = pnew[0];
          m.y[i] = pnew[1];
          m.z[i] = pnew[2];
          m.wx[i] = wmag * axis[0];
          m.wy[i] = wmag * axis[1];
          m.wz[i] = wmag * axis[2];
        }
        ASSERT_FALSE(m.step(dt).failed);
      }
      for (std::size_t k = 0; k < stress0.size(); ++k) {
        EXPECT_NEAR(m.block.stress[k], stress0[k], 1e-10 * s0)
            << "warped " << warped << " axis " << axis_case << " component " << k;
        worst = std::max(worst, std::abs(m.block.stress[k] - stress0[k]) / s0);
      }
    }
  std::printf(
      "ELFORM 16 rigid rotation by 120 degrees: largest stress change %.2e of the "
      "prestress\n",
      worst);
}

// Forces and moments of arbitrary states balance (sum f = 0, sum x x f + m = 0).
TEST(Shell16Balance, ForcesAndMomentsBalanceForArbitraryStates) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (bool warped : {false, true}) {
    ShellMesh m;
    const double h = warped ? 0.05 : 0.0;
    m.add_node(0.1, 0.0, h);
    m.add_node(1.2, 0.2, -h);
    m.add_node(1.0, 1.1, h);
    m.add_node(-0.2, 0.9, -h);
    m.add_element({0, 1, 2, 3}, 0.04);
    set_section(m.block, 0, 3);
    m.initialize();
    for (double& s : m.block.stress) s = 1e7 * U(gen);
    const double dt = 1e-4;
    for (int s = 0; s < 5; ++s) {
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        for (int d = 0; d < 6; ++d) *m.dof(i, d) = (d < 3 ? 1.0 : 10.0) * U(gen);
        m.x[i] += dt * m.vx[i];
        m.y[i] += dt * m.vy[i];
        m.z[i] += dt * m.vz[i];
      }
      ASSERT_FALSE(m.step(dt).failed);
      double F[3] = {0, 0, 0}, Mm[3] = {0, 0, 0}, scale = 0.0;
      for (int I = 0; I < 4; ++I) {
        const double* f = &m.block.force[6 * I];
        const double r[3] = {m.x[I], m.y[I], m.z[I]};
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
        EXPECT_NEAR(F[i], 0.0, 1e-12 * scale) << warped;
        EXPECT_NEAR(Mm[i], 0.0, 1e-12 * scale) << warped;
      }
    }
  }
}

// 24 x 24 stiffness of a single free element from the kernel (unstressed, forces per unit
// velocity of one degree of freedom over a tiny step: K u with u = v dt), symmetrised.
Eigen::MatrixXd probed_stiffness(const ShellMesh& base) {
  const double dt = 1e-8;
  Eigen::MatrixXd K(24, 24);
  const auto X = base.positions();
  for (int j = 0; j < 24; ++j) {
    ShellMesh m = base;
    *m.dof(static_cast<std::size_t>(j / 6), j % 6) = 1.0;
    m.place_for_step(X, dt);
    EXPECT_FALSE(m.step(dt).failed);
    for (int i = 0; i < 24; ++i) K(i, j) = m.block.force[i] / dt;
  }
  return 0.5 * (K + K.transpose());
}

int zero_modes(const Eigen::MatrixXd& K, double* first_nonzero) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
  const Eigen::VectorXd& l = es.eigenvalues();
  const double tol = 1e-7 * l.cwiseAbs().maxCoeff();
  int zeros = 0;
  for (int i = 0; i < l.size(); ++i) zeros += std::abs(l[i]) < tol ? 1 : 0;
  *first_nonzero = l[zeros] / l.cwiseAbs().maxCoeff();
  return zeros;
}

// A free distorted element has 10 zero-energy modes: the 6 rigid-body motions and the 4 nodal
// drilling rotations (no drilling stiffness, as ELFORM 2 and LS-DYNA); no hourglass modes. The
// one-point ELFORM 2 without hourglass control has 6 more: 2 membrane (8 in-plane DOFs, 3
// strains, 3 rigid motions) and 4 out of plane (12 DOFs, 3 curvatures and 2 shears, 3 rigid).
TEST(Shell16Modes, SingleElementHasOnlyRigidAndDrillingZeroModes) {
  ShellMesh m;
  m.add_node(0.0, 0.0, 0.0);
  m.add_node(1.1, 0.1, 0.0);
  m.add_node(1.3, 0.9, 0.0);
  m.add_node(-0.1, 1.0, 0.0);
  m.add_element({0, 1, 2, 3}, 0.1);
  ShellMesh full = m;
  set_section(full.block, 0, 2);
  full.initialize();
  double gap = 0.0;
  EXPECT_EQ(zero_modes(probed_stiffness(full), &gap), 10);
  std::printf("ELFORM 16 free element: 10 zero modes, next eigenvalue %.2e of the largest\n", gap);
  EXPECT_GT(gap, 1e-5);  // the softest deformation mode is far from zero
  ShellMesh one = m;
  set_section(one.block, 0, 2, 2);
  one.initialize();
  double gap2 = 0.0;
  EXPECT_EQ(zero_modes(probed_stiffness(one), &gap2), 16);
}

// The step rule is ELFORM 2's: the highest frequency of a free element (lumped mass and scaled
// rotary inertia, stiffness probed from the kernel) stays that of the membrane dilatation mode,
// which the one-point element shares, so 2 / omega_max is the same fraction of L_s / c (0.877 on
// a square at nu 0.3, covered by TSSFAC 0.9) and the rotations never govern.
TEST(Shell16TimeStep, HighestElementFrequencyIsElform2s) {
  const double shapes[3][4][2] = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}},
                                  {{0, 0}, {1.1, 0.1}, {1.3, 0.9}, {-0.1, 1.0}},
                                  {{0, 0}, {3, 0}, {3, 1}, {0, 1}}};
  for (const auto& shape : shapes)
    for (double t : {0.01, 0.3}) {
      double ratio[2];
      for (int k = 0; k < 2; ++k) {
        ShellMesh m;
        for (const auto& p : shape) m.add_node(p[0], p[1], 0.0);
        m.add_element({0, 1, 2, 3}, t);
        set_section(m.block, 0, 2, k == 0 ? 16 : 2);
        m.block.hourglass.qm = 0.1;
        m.initialize();
        const Eigen::MatrixXd K = probed_stiffness(m);
        std::vector<double> mass(4, 0.0), inertia(4, 0.0);
        rf::element::add_shell_lumped_mass(m.block, mass, inertia);
        Eigen::VectorXd w(24);
        for (int i = 0; i < 24; ++i)
          w[i] = 1.0 / std::sqrt((i % 6) < 3 ? mass[i / 6] : inertia[i / 6]);
        const Eigen::MatrixXd A = w.asDiagonal() * K * w.asDiagonal();
        const double omega =
            std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues().maxCoeff());
        const double dt = rf::element::shell_critical_timestep(m.block, m.view()).min_dt;
        ratio[k] = 2.0 / omega / dt;
      }
      std::printf("shape %d t %.2f: 2/omega_max over L_s/c: ELFORM 16 %.4f, ELFORM 2 %.4f\n",
                  static_cast<int>(&shape - shapes), t, ratio[0], ratio[1]);
      EXPECT_GT(ratio[0], 0.87);
      EXPECT_NEAR(ratio[0], ratio[1], 0.02 * ratio[1]);
    }
}

// Twist of a rectangle, w = c x y with the Kirchhoff rotations theta_x = c x, theta_y = -c y:
// the strain energy is the plate's, G (2c)^2 t^3 / 24 A (constant twist, no transverse shear).
// The hourglass pattern w = h with no rotations (the one-point element's w mode) has a finite
// stiffness too.
TEST(Shell16Modes, TwistAndHourglassPatternsHaveTheirStiffness) {
  const double a = 0.8, b = 0.5, t = 0.02;
  ShellMesh m;
  m.add_node(-a / 2, -b / 2, 0);
  m.add_node(a / 2, -b / 2, 0);
  m.add_node(a / 2, b / 2, 0);
  m.add_node(-a / 2, b / 2, 0);
  m.add_element({0, 1, 2, 3}, t);
  set_section(m.block, 0, 2);
  m.initialize();
  const Eigen::MatrixXd K = probed_stiffness(m);
  const double c = 1e-3;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(24);
  for (int I = 0; I < 4; ++I) {
    u[6 * I + 2] = c * m.x[I] * m.y[I];
    u[6 * I + 3] = c * m.x[I];
    u[6 * I + 4] = -c * m.y[I];
  }
  const double G = kE / (2 * (1 + kNu));
  // Two-point Gauss through the thickness integrates z^2 exactly.
  const double exact = G * 4 * c * c * t * t * t / 24.0 * a * b;
  EXPECT_NEAR(0.5 * u.dot(K * u), exact, 1e-5 * exact);
  Eigen::VectorXd hg = Eigen::VectorXd::Zero(24);
  const double h[4] = {1, -1, 1, -1};
  for (int I = 0; I < 4; ++I) hg[6 * I + 2] = c * h[I];
  EXPECT_GT(0.5 * hg.dot(K * hg), 1e-3 * exact);
  for (int I = 0; I < 4; ++I) hg[6 * I + 2] = 0, hg[6 * I] = c * h[I];
  EXPECT_GT(0.5 * hg.dot(K * hg), 1e-3 * exact);
}

// Uniaxial tension of one element, *MAT_003 / *MAT_024 bilinear: at every one of the 4 x 2
// points sigma = SIGY + Ep eps_p, eps_p = ln(l) - sigma / E, sigma_yy = 0, and the lateral
// strain follows plastic incompressibility.
TEST(Shell16Plasticity, UniaxialTensionFollowsBilinearLaw) {
  for (bool kinematic : {false, true}) {
    ShellMesh m;
    m.add_node(0, 0, 0);
    m.add_node(1, 0, 0);
    m.add_node(1, 1, 0);
    m.add_node(0, 1, 0);
    m.add_element({0, 1, 2, 3}, 0.01);
    set_section(m.block, 1, 2);
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
    const double strain = std::log(lx);
    const auto* eps = rf::element::find_history(m.block, "effective_plastic_strain");
    ASSERT_NE(eps, nullptr);
    ASSERT_EQ(eps->values.size(), 8u);
    for (int g = 0; g < 4; ++g)
      for (int q = 0; q < 2; ++q) {
        const double* st = point_stress(m.block, 0, g, q);
        const double sigma = st[0];
        const double eps_p = eps->values[static_cast<std::size_t>(g * 2 + q)];
        EXPECT_NEAR(st[1], 0.0, 1e-2);
        EXPECT_GT(eps_p, 0.0);
        EXPECT_NEAR(sigma, sigy + ep * eps_p, 1e-8 * sigma);
        EXPECT_NEAR(eps_p, strain - sigma / kE, 1e-8 * strain);
        EXPECT_NEAR(std::log(ly), -kNu * sigma / kE - 0.5 * eps_p, 1e-8 * strain);
      }
  }
}

// Membrane bulk viscosity (*CONTROL_BULK_VISCOSITY TYPE -1/-2): the element's q from its mean
// area rate on every point. A uniform in-plane compression of a distorted element is a uniform
// membrane state, which the one-point and the 2x2 element integrate alike (the mean gradient
// is the one-point B): forces, viscous work and the viscous step equal ELFORM 2's (hourglass
// off).
TEST(Shell16BulkViscosity, UniformCompressionMatchesElform2) {
  ShellMesh m;
  m.add_node(0.0, 0.0, 0.0);
  m.add_node(0.3, 0.02, 0.0);
  m.add_node(0.35, 0.2, 0.0);
  m.add_node(-0.03, 0.25, 0.0);
  m.add_element({0, 1, 2, 3}, 0.01);
  for (int i = 0; i < 4; ++i) {
    m.vx[i] = -300.0 * m.x[i];
    m.vy[i] = -200.0 * m.y[i];
  }
  ShellMesh b = m;
  set_section(m.block, 0, 2);
  set_section(b.block, 0, 2, 2);
  m.block.bulk_viscosity = {1.5, 0.06};
  b.block.bulk_viscosity = {1.5, 0.06};
  m.initialize();
  b.initialize();
  const double dt = 1e-7;
  const auto r16 = m.step(dt), r2 = b.step(dt);
  EXPECT_GT(r16.bulk_viscosity_work, 0.0);
  EXPECT_NEAR(r16.bulk_viscosity_work, r2.bulk_viscosity_work, 1e-10 * r2.bulk_viscosity_work);
  EXPECT_NEAR(r16.min_dt, r2.min_dt, 1e-12 * r2.min_dt);
  double scale = 0.0;
  for (double f : b.block.force) scale = std::max(scale, std::abs(f));
  for (int c = 0; c < 24; ++c) EXPECT_NEAR(m.block.force[c], b.block.force[c], 1e-10 * scale) << c;
}

// Triangles (N3 = N4) are refused naming the element; the step and the lumped mass are
// ELFORM 2's.
TEST(Shell16Initialize, TriangleIsAnErrorNamingTheElement) {
  ShellMesh m;
  m.add_node(0, 0, 0);
  m.add_node(1, 0, 0);
  m.add_node(1, 1, 0);
  m.add_element({0, 1, 2, 2}, 0.01);
  set_section(m.block, 0, 2);
  try {
    m.initialize();
    FAIL() << "no error";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("shell element 1 of part 3 is a triangle"), std::string::npos) << what;
    EXPECT_NE(what.find("ELFORM 16"), std::string::npos) << what;
  }
}

TEST(Shell16TimeStep, SameRuleAsElform2) {
  ShellMesh m;
  m.add_node(0, 0, 0);
  m.add_node(0.3, 0, 0);
  m.add_node(0.35, 0.2, 0);
  m.add_node(0, 0.25, 0);
  m.add_element({0, 1, 2, 3}, 0.01);
  ShellMesh b = m;
  set_section(m.block, 0, 2);
  set_section(b.block, 0, 2, 2);
  m.initialize();
  b.initialize();
  EXPECT_EQ(rf::element::shell_critical_timestep(m.block, m.view()).min_dt,
            rf::element::shell_critical_timestep(b.block, b.view()).min_dt);
  const double dt = 1e-7;
  const auto r16 = m.step(dt), r2 = b.step(dt);
  EXPECT_NEAR(r16.min_dt, r2.min_dt, 1e-14 * r2.min_dt);
}

}  // namespace
