// The spin-up beam of Kane, Ryan & Banerjee (J. Guidance 10(2) 139-151, 1987): a uniform
// cantilever clamped to a hub that is driven from rest to the spin Omega_s by
//
//   Omega(t) = Omega_s / T_s (t - T_s / (2 pi) sin(2 pi t / T_s))   (t < T_s), then Omega_s,
//
// with the chordwise (in-plane) tip deflection relative to the hub's rotating frame as the
// output. Their beam: L = 10 m, A = 4e-4 m^2, I = 2e-7 m^4, E = 7e10 Pa, rho = 3000 kg/m^3, so
// the first chordwise cantilever frequency is omega_c = 3.516 sqrt(EI / (rho A L^4)) = 3.80
// rad/s, and T_s = 15 s, Omega_s = 6 rad/s: T_s omega_c = 57, Omega_s / omega_c = 1.58. The
// spin passes the chordwise frequency; the "conventional linear" floating-frame model (modes
// without geometric stiffening) then diverges, their "correct" model stays bounded.
//
// Reference (not from our code): their correct model as a 1-D Euler-Bernoulli cantilever in
// the rotating hub frame, clamped at hub radius r,
//
//   rho A w_tt + EI w'''' - (T w')' - rho A Omega^2 w = -rho A alpha (r + x),
//   T(x) = rho A Omega^2 int_x^L (r + s) ds            (alpha = dOmega/dt),
//
// solved here by Hermite-cubic elements reduced to the lowest clamped modes, RK4 in time. It
// is checked first against two limits stated analytically: the static tip deflection under the
// Euler load at Omega = 0, r = 0 (w_tip = 11 rho A alpha L^4 / (120 EI)), and the rotating
// chordwise frequencies omega^2 = omega_flap^2 - Omega^2 with the published flapwise table
// (r = 0; Wright et al. 1982, Hodges & Rutkowski 1981, see flexible_spin_test.cpp). Dropping
// the stiffening term gives the conventional linear model, which must diverge.
//
// The model: the hub a separate *MAT_RIGID part driven by *BOUNDARY_PRESCRIBED_MOTION_RIGID
// (angular velocity curve, translations fixed by CMO), the beam a cantilever on its outer
// face whose first element column stays deformable (the beam's own material) and whose other
// columns are the flexible body (*MAT_RIGID + *PART_MODES); the column shares its nodes with
// hub and flexible part. The driving torque reaches the flexible part as nodal forces at its
// root, so the Euler load reaches the modes (a prescribed motion of the flexible body itself
// would drive its mean-axis frame and load no mode: docs/flexible_bodies.md). The same mesh
// runs fully deformable (the physics check), as a flexible body with FORM 0 and with FORM 1.
// The beam is scaled to 1 m and to a slenderness L / r_g = 100 (Kane's: 447) to keep the
// explicit runs cheap (the step count grows as (L / r_g) (L / h_element)); the dimensionless
// parameters of the spin-up, T_s omega_c and Omega_s / omega_c, are Kane's, the hub radius is
// r = L / 20. Numbers quoted in docs/flexible_bodies.md and docs/verification.md.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "deck_builder.hpp"
#include "flexible_body_modes.hpp"
#include "modal/eigen_analysis.hpp"
#include "modal/mode_set.hpp"
#include "modal/stiffness_assembly.hpp"
#include "solver/simulation.hpp"

namespace rf::test {
namespace {

constexpr double kPi = std::numbers::pi;

// Kane's dimensionless spin-up: T_s omega_c and Omega_s / omega_c (15 s x 3.798 rad/s, 6 rad/s
// / 3.798 rad/s).
constexpr double kKaneRampTimesOmegaC = 15.0 * 3.7978;
constexpr double kKaneSpinOverOmegaC = 6.0 / 3.7978;

double spin_profile(double spin, double ramp, double t) {
  if (t >= ramp) return spin;
  return spin / ramp * (t - ramp / (2 * kPi) * std::sin(2 * kPi * t / ramp));
}

double spin_acceleration(double spin, double ramp, double t) {
  if (t >= ramp) return 0.0;
  return spin / ramp * (1.0 - std::cos(2 * kPi * t / ramp));
}

// ---------------------------------------------------------------------------------------
// 1-D reference: the cantilever in the hub frame (chordwise), Hermite-cubic elements with
// consistent mass, reduced to its lowest clamped modes.
struct ReferenceBeam {
  double ei = 1.0, rho_a = 1.0, length = 1.0, radius = 0.0;
  int elements = 24;
  bool stiffening = true;  // false: Kane's "conventional linear" model

  // Full matrices (clamped root removed): bending K, geometric K per Omega^2 (the tension
  // T / Omega^2), consistent mass M, Euler load vector f = int N^T rho A (r + x) dx.
  Eigen::MatrixXd bending, geometric, mass;
  Eigen::VectorXd euler_load;

  void assemble() {
    const int dofs = 2 * (elements + 1);
    bending = geometric = mass = Eigen::MatrixXd::Zero(dofs, dofs);
    euler_load = Eigen::VectorXd::Zero(dofs);
    const double h = length / elements;
    // 3-point Gauss: exact for the quadratic T and the cubic N (r + x) integrands.
    const double gauss_point[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    const double gauss_weight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    for (int e = 0; e < elements; ++e) {
      Eigen::Matrix4d kb, m, kg = Eigen::Matrix4d::Zero();
      kb << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h,
          6 * h, 2 * h * h, -6 * h, 4 * h * h;
      kb *= ei / (h * h * h);
      m << 156, 22 * h, 54, -13 * h, 22 * h, 4 * h * h, 13 * h, -3 * h * h, 54, 13 * h, 156,
          -22 * h, -13 * h, -3 * h * h, -22 * h, 4 * h * h;
      m *= rho_a * h / 420.0;
      Eigen::Vector4d fe = Eigen::Vector4d::Zero();
      for (int g = 0; g < 3; ++g) {
        const double xi = 0.5 * (gauss_point[g] + 1.0);
        const double x = (e + xi) * h;
        const double tension = rho_a * (radius * (length - x) + 0.5 * (length * length - x * x));
        Eigen::Vector4d shape, slope;
        shape << 1 - 3 * xi * xi + 2 * xi * xi * xi, h * (xi - 2 * xi * xi + xi * xi * xi),
            3 * xi * xi - 2 * xi * xi * xi, h * (xi * xi * xi - xi * xi);
        slope << 6.0 * (xi * xi - xi) / h, 1.0 - 4.0 * xi + 3.0 * xi * xi, 6.0 * (xi - xi * xi) / h,
            3.0 * xi * xi - 2.0 * xi;
        kg += gauss_weight[g] * 0.5 * h * tension * slope * slope.transpose();
        fe += gauss_weight[g] * 0.5 * h * rho_a * (radius + x) * shape;
      }
      bending.block<4, 4>(2 * e, 2 * e) += kb;
      geometric.block<4, 4>(2 * e, 2 * e) += kg;
      mass.block<4, 4>(2 * e, 2 * e) += m;
      euler_load.segment<4>(2 * e) += fe;
    }
    const int n = dofs - 2;  // clamped root
    bending = bending.bottomRightCorner(n, n).eval();
    geometric = geometric.bottomRightCorner(n, n).eval();
    mass = mass.bottomRightCorner(n, n).eval();
    euler_load = euler_load.tail(n).eval();
  }

  // Stiffness at spin Omega: K + Omega^2 (K_g - M) (stiffening and softening), or
  // K - Omega^2 M without stiffening.
  Eigen::MatrixXd stiffness(double spin) const {
    return bending + spin * spin * ((stiffening ? geometric : 0.0 * geometric) - mass);
  }

  // Chordwise frequencies at constant spin (ascending; negative squares signal divergence).
  Eigen::VectorXd frequencies_squared(double spin) const {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(stiffness(spin), mass);
    return eig.eigenvalues();
  }

  // Tip deflection history under the spin-up, in the lowest `modes` clamped modes (RK4,
  // 60 steps per period of the highest kept mode at Omega_s), sampled every `sample` s.
  // Negative: lagging behind the hub.
  std::vector<double> spin_up(double spin, double ramp, double end, double sample,
                              int modes = 8) const {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(bending, mass);
    const Eigen::MatrixXd phi = eig.eigenvectors().leftCols(modes);  // M-orthonormal
    const Eigen::MatrixXd k0 = phi.transpose() * bending * phi;
    const Eigen::MatrixXd k2 =
        phi.transpose() * ((stiffening ? geometric : 0.0 * geometric) - mass) * phi;
    const Eigen::VectorXd load = phi.transpose() * euler_load;
    const Eigen::RowVectorXd tip = phi.row(phi.rows() - 2);  // w at the free end
    const double highest =
        std::sqrt(eig.eigenvalues()[modes - 1] + spin * spin * std::abs(k2.diagonal().maxCoeff()));
    const int per_sample = static_cast<int>(std::ceil(sample / (2 * kPi / highest / 60)));
    const double h = sample / per_sample;
    Eigen::VectorXd q = Eigen::VectorXd::Zero(modes), v = Eigen::VectorXd::Zero(modes);
    const auto accel = [&](double t, const Eigen::VectorXd& qq) -> Eigen::VectorXd {
      const double w = spin_profile(spin, ramp, t);
      return -(k0 + w * w * k2) * qq - spin_acceleration(spin, ramp, t) * load;
    };
    std::vector<double> out{0.0};
    double t = 0.0;
    const int samples = static_cast<int>(std::round(end / sample));
    for (int s = 0; s < samples; ++s) {
      for (int k = 0; k < per_sample; ++k) {
        const Eigen::VectorXd a1 = accel(t, q);
        const Eigen::VectorXd q2 = q + 0.5 * h * v, v2 = v + 0.5 * h * a1;
        const Eigen::VectorXd a2 = accel(t + 0.5 * h, q2);
        const Eigen::VectorXd q3 = q + 0.5 * h * v2, v3 = v + 0.5 * h * a2;
        const Eigen::VectorXd a3 = accel(t + 0.5 * h, q3);
        const Eigen::VectorXd q4 = q + h * v3, v4 = v + h * a3;
        const Eigen::VectorXd a4 = accel(t + h, q4);
        q += h / 6.0 * (v + 2 * v2 + 2 * v3 + v4);
        v += h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4);
        t += h;
      }
      out.push_back(tip * q);
    }
    return out;
  }
};

ReferenceBeam reference_beam(double ei, double rho_a, double length, double radius,
                             bool stiffening = true) {
  ReferenceBeam beam;
  beam.ei = ei;
  beam.rho_a = rho_a;
  beam.length = length;
  beam.radius = radius;
  beam.stiffening = stiffening;
  beam.assemble();
  return beam;
}

// The reference against the two analytic limits and Kane's divergence of the linear model.
TEST(FlexibleSpinUp, ReferenceBeamMatchesAnalyticLimits) {
  // Dimensionless beam EI = rho A = L = 1, r = 0.
  const ReferenceBeam beam = reference_beam(1.0, 1.0, 1.0, 0.0);
  // Static Euler load at Omega = 0: w_tip = 11 alpha L^4 rho A / (120 EI). Hermite cubics are
  // nodally exact for a consistent polynomial load.
  const Eigen::VectorXd w = beam.bending.ldlt().solve(-1.0 * beam.euler_load);
  EXPECT_NEAR(w[w.size() - 2], -11.0 / 120.0, 1e-10);
  // Also in the reduced time integration: a slow ramp (T_s 200 x the first period) follows
  // the quasi-static deflection at peak alpha = 2 Omega_s / T_s.
  {
    const double ramp = 200.0 * 2 * kPi / 3.516, spin = 1e-6;  // Omega^2 terms negligible
    const std::vector<double> tip = beam.spin_up(spin, ramp, ramp, ramp / 200.0);
    const double peak = *std::min_element(tip.begin(), tip.end());
    EXPECT_NEAR(peak / (-11.0 / 120.0 * 2 * spin / ramp), 1.0, 2e-3);
  }
  // Rotating chordwise frequencies: omega^2 = omega_flap^2 - Omega^2 (the chordwise equation is
  // the flapwise one plus the softening -rho A Omega^2 w), with the published flapwise table.
  const double gamma[] = {0, 1, 2, 3, 4, 5};
  const double flap[] = {3.5160, 3.6816, 4.1373, 4.7973, 5.5850, 6.4495};
  for (int k = 0; k < 6; ++k) {
    const double lambda = std::sqrt(beam.frequencies_squared(gamma[k])[0]);
    EXPECT_NEAR(lambda, std::sqrt(flap[k] * flap[k] - gamma[k] * gamma[k]), 2e-4)
        << "gamma " << gamma[k];
  }
  // Conventional linear model: K - Omega^2 M turns indefinite once Omega passes the first
  // chordwise frequency (3.516), and its spin-up diverges; the correct model stays bounded.
  const ReferenceBeam linear = reference_beam(1.0, 1.0, 1.0, 0.0, false);
  EXPECT_LT(linear.frequencies_squared(4.0)[0], 0.0);
  EXPECT_GT(beam.frequencies_squared(4.0)[0], 0.0);
  const double ramp = kKaneRampTimesOmegaC / 3.516, spin = kKaneSpinOverOmegaC * 3.516;
  const std::vector<double> correct = beam.spin_up(spin, ramp, 1.5 * ramp, ramp / 300.0);
  const std::vector<double> diverging = linear.spin_up(spin, ramp, 1.5 * ramp, ramp / 300.0);
  double correct_peak = 0.0;
  for (const double x : correct) correct_peak = std::max(correct_peak, std::abs(x));
  EXPECT_LT(std::abs(correct.back()), 0.5 * correct_peak);
  EXPECT_GT(std::abs(diverging.back()), 100.0 * correct_peak);
  std::printf(
      "reference (r = 0, EI = rho A = L = 1): peak |w_tip| %.4e, final %.4e; conventional "
      "linear at 1.5 T_s %.3e\n",
      correct_peak, correct.back(), diverging.back());
}

// ---------------------------------------------------------------------------------------
// The 3-D model: x along the beam, y chordwise (in the plane of rotation), z flapwise; spin
// about z through the origin. Columns of elements along x: hub (2, part 2, *MAT_RIGID, centred
// on the axis), then the cantilever: its root column (part 3, deformable) and the flexible
// part (part 1).
constexpr double kRho = 3000.0, kYoung = 7.0e10, kNu = 0.3;      // Kane's aluminium
constexpr double kLength = 1.0, kSlenderness = 100.0;            // L / r_g
const double kChord = std::sqrt(12.0) * kLength / kSlenderness;  // h: r_g = h / sqrt(12)
const double kFlapDepth = 2.0 * kChord;  // flap modes at twice the chordwise frequencies
// The beam's first element column stays deformable (part 3, the beam's own material): the
// joint through which the hub drives the flexible part; its nodes are shared with the hub and
// with the flexible part. So the cantilever (hub face to tip, kBeamElements columns) is
// uniform and the same in all runs.
constexpr int kBeamElements = 20, kHubColumns = 2, kLayerColumns = 1;
constexpr double kElementLength = kLength / kBeamElements;
constexpr int kColumns = kHubColumns + kBeamElements;
constexpr int kNy = 2, kNz = 1;
// Clamp radius: the hub's outer face.
constexpr double kClampRadius = 0.5 * kHubColumns * kElementLength;

int node_id(int i, int j, int k) {
  return 1 + i + (kColumns + 1) * (j + (kNy + 1) * k);
}

int column_part(int i) {
  if (i < kHubColumns) return 2;
  if (i < kHubColumns + kLayerColumns) return 3;
  return 1;
}

std::string geometry() {
  std::string s = "*NODE\n";
  for (int k = 0; k <= kNz; ++k)
    for (int j = 0; j <= kNy; ++j)
      for (int i = 0; i <= kColumns; ++i) {
        const double x = (i - 0.5 * kHubColumns) * kElementLength;
        const double y = kChord * (static_cast<double>(j) / kNy - 0.5);
        const double z = kFlapDepth * (static_cast<double>(k) / kNz - 0.5);
        s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", node_id(i, j, k), x, y, z);
      }
  s += "*ELEMENT_SOLID\n";
  int eid = 0;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kColumns; ++i) {
        s += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", ++eid, column_part(i), node_id(i, j, k),
                         node_id(i + 1, j, k), node_id(i + 1, j + 1, k), node_id(i, j + 1, k),
                         node_id(i, j, k + 1), node_id(i + 1, j, k + 1),
                         node_id(i + 1, j + 1, k + 1), node_id(i, j + 1, k + 1));
      }
  return s;
}

// Beam material card: elastic (deformable run, eigen analysis) or rigid with modes.
std::string deck(bool flexible, const std::string& extra, double end_time) {
  std::string s = "*KEYWORD\n" + geometry();
  s += "*PART\nbeam\n1,1,1\n*PART\nhub\n2,1,2\n*PART\nroot column\n3,1,3\n*SECTION_SOLID\n1,2\n";
  if (flexible) {
    s += fmt::format("*MAT_RIGID\n1,{:.17g},{:.17g},{}\n0,0,0\n", kRho, kYoung, kNu);
  } else {
    s += fmt::format("*MAT_ELASTIC\n1,{:.17g},{:.17g},{}\n", kRho, kYoung, kNu);
  }
  // Hub: translations fixed (CMO 1, CON1 7), tilt about x and y fixed (CON2 4: Kane's hub has
  // the spin as its only freedom), rotation about z prescribed. With the tilt free the hub
  // wobbled once spun up (a heavier hub went unstable at constant spin, 0.2 m tip swings), and
  // the lighter one kept a residual vibration of 4 % of the peak lag.
  s += fmt::format("*MAT_RIGID\n2,{:.17g},{:.17g},{}\n1,7,4\n", kRho, kYoung, kNu);
  s += fmt::format("*MAT_ELASTIC\n3,{:.17g},{:.17g},{}\n", kRho, kYoung, kNu);
  s += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n", end_time);
  return s + extra + "*END\n";
}

// Mode basis of the flexible part. The cantilever (root column + flexible part) is clamped to the
// driven hub, so the flexible part moves as a rigid motion plus the cantilever's deformation:
// its modes are the lowest in-plane clamped modes of the whole cantilever (parts 1 and 3,
// hub face fixed) restricted to the nodes of part 1, with their rigid content removed (the
// frame carries it) and orthonormalised by a Rayleigh-Ritz analysis of part 1 (Phi^T M Phi =
// I, Phi^T K Phi diagonal, as *PART_MODES expects of a mode database): Craig-Bampton's
// fixed-interface modes with a rigid interface. The part's free-free eigenmodes carry no
// bending moment at the root, where the cantilever's is largest: with the 12 in-plane ones
// among the lowest 40 FORM 0 peaked 9.2 % low and FORM 1 5.9 % low (measured), too close to
// tell the forms apart. K and M are the explicit solver's (modal::assemble_structural_matrices,
// the same call as the eigen analysis).
struct BeamModes {
  modal::ModeSet modes;
  double omega_c = 0.0;  // first chordwise frequency of the 3-D cantilever
};

constexpr int kClampedModes = 12;

Eigen::MatrixXd dense_stiffness(const modal::StructuralMatrices& sm) {
  Eigen::MatrixXd k = Eigen::MatrixXd(sm.stiffness);
  if (k.triangularView<Eigen::StrictlyLower>().toDenseMatrix().norm() == 0.0) {
    k = Eigen::MatrixXd(k.selfadjointView<Eigen::Upper>());
  }
  return k;
}

const BeamModes& beam_modes() {
  static const BeamModes result = [] {
    BeamModes out;
    const model::Model model = read(deck(false, "", 1e-3));
    // Clamped in-plane modes of the cantilever (parts 1 and 3).
    const modal::StructuralMatrices whole = modal::assemble_structural_matrices(model, {1, 3});
    const Eigen::MatrixXd kw = dense_stiffness(whole);
    const auto& wn = whole.state.nodes;
    std::vector<int> free_dofs;
    for (std::size_t i = 0; i < wn.size(); ++i) {
      if (std::abs(wn.x0.x[i] - kClampRadius) > 1e-9) {
        for (int d = 0; d < 3; ++d) free_dofs.push_back(static_cast<int>(3 * i) + d);
      }
    }
    const int nf = static_cast<int>(free_dofs.size());
    Eigen::MatrixXd kff(nf, nf);
    Eigen::VectorXd mff(nf);
    for (int a = 0; a < nf; ++a) {
      mff[a] = whole.mass[free_dofs[a]];
      for (int b = 0; b < nf; ++b) kff(a, b) = kw(free_dofs[a], free_dofs[b]);
    }
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> clamped(
        kff, Eigen::MatrixXd(mff.asDiagonal()));
    // Part 1 alone: its nodes, K and M.
    const modal::StructuralMatrices part = modal::assemble_structural_matrices(model, {1});
    const Eigen::MatrixXd k = dense_stiffness(part);
    const Eigen::VectorXd mass = part.mass;
    const auto& nodes = part.state.nodes;
    const std::size_t n = nodes.size();
    std::vector<int> whole_index(n, -1);  // free-DOF block of each part-1 node in `clamped`
    for (std::size_t i = 0; i < n; ++i) {
      for (int a = 0; a < nf; a += 3) {
        if (wn.id[static_cast<std::size_t>(free_dofs[a] / 3)] == nodes.id[i]) whole_index[i] = a;
      }
      EXPECT_GE(whole_index[i], 0);
    }
    std::vector<Eigen::VectorXd> basis;
    for (int m = 0; m < nf && static_cast<int>(basis.size()) < kClampedModes; ++m) {
      const Eigen::VectorXd shape = clamped.eigenvectors().col(m);
      double ez = 0.0, ey = 0.0, et = 0.0;
      for (int a = 0; a < nf; ++a) {
        const double e = mff[a] * shape[a] * shape[a];
        et += e;
        if (free_dofs[a] % 3 == 2) ez += e;
        if (free_dofs[a] % 3 == 1) ey += e;
      }
      if (ez > 0.01 * et) continue;  // flapwise or torsional
      if (basis.empty()) {
        EXPECT_GT(ey, 0.9 * et);  // the lowest in-plane mode is the first chordwise bending
        out.omega_c = std::sqrt(clamped.eigenvalues()[m]);
      }
      Eigen::VectorXd restricted(3 * static_cast<int>(n));
      for (std::size_t i = 0; i < n; ++i) {
        for (int d = 0; d < 3; ++d) restricted[3 * i + d] = shape[whole_index[i] + d];
      }
      basis.push_back(restricted);
    }
    // Remove rigid content (mass-orthonormal rigid modes of part 1 about its centre of mass).
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      centre += mass[3 * i] * Eigen::Vector3d(nodes.x0.x[i], nodes.x0.y[i], nodes.x0.z[i]);
      total += mass[3 * i];
    }
    centre /= total;
    Eigen::MatrixXd rigid = Eigen::MatrixXd::Zero(3 * static_cast<int>(n), 6);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d x =
          Eigen::Vector3d(nodes.x0.x[i], nodes.x0.y[i], nodes.x0.z[i]) - centre;
      for (int a = 0; a < 3; ++a) {
        rigid(static_cast<int>(3 * i) + a, a) = 1.0;
        rigid.block<3, 1>(static_cast<int>(3 * i), 3 + a) = Eigen::Vector3d::Unit(a).cross(x);
      }
    }
    for (int c = 0; c < 6; ++c) {  // Gram-Schmidt in the mass inner product
      for (int p = 0; p < c; ++p)
        rigid.col(c) -= rigid.col(p) * (rigid.col(p).cwiseProduct(mass).dot(rigid.col(c)));
      rigid.col(c) /= std::sqrt(rigid.col(c).cwiseProduct(mass).dot(rigid.col(c)));
    }
    const int nb = static_cast<int>(basis.size());
    Eigen::MatrixXd b(3 * static_cast<int>(n), nb);
    for (int c = 0; c < nb; ++c) {
      b.col(c) = basis[c] - rigid * (rigid.transpose() * basis[c].cwiseProduct(mass));
    }
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(
        b.transpose() * k * b, b.transpose() * mass.asDiagonal() * b);
    const Eigen::MatrixXd phi = b * ritz.eigenvectors();  // M-orthonormal
    modal::ModeSet& modes = out.modes;
    modes.node_ids.assign(nodes.id.begin(), nodes.id.end());
    modes.node_parts = part.node_parts;
    for (std::size_t i = 0; i < n; ++i) {
      modes.coordinates.insert(modes.coordinates.end(),
                               {nodes.x0.x[i], nodes.x0.y[i], nodes.x0.z[i]});
      modes.mass.push_back(mass[3 * i]);
    }
    for (int c = 0; c < nb; ++c) {
      modes.eigenvalues.push_back(ritz.eigenvalues()[c]);
      modes.generalized_mass.push_back(1.0);
      modes.residual.push_back(0.0);
      modes.rigid.push_back(0);
      modes.shapes.insert(modes.shapes.end(), phi.col(c).data(), phi.col(c).data() + phi.rows());
    }
    return out;
  }();
  return result;
}

std::string part_modes(int form, std::size_t count) {
  return fmt::format("*PART_MODES\n1,{},{},0,3,0\nbeam_modes.h5\n", count, form);
}

// Load curve 1: angular velocity of the spin-up, 400 samples, then constant.
std::string spin_up_cards(double spin, double ramp, double end) {
  std::string s = "*DEFINE_CURVE\n1\n";
  const int samples = 400;
  for (int k = 0; k <= samples; ++k) {
    const double t = ramp * k / samples;
    s += fmt::format("{:.17g},{:.17g}\n", t, spin_profile(spin, ramp, t));
  }
  s += fmt::format("{:.17g},{:.17g}\n", 2 * end + ramp, spin);
  s += "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n2,7,0,1,1.0\n";
  // Hub ends and tip on the centre line (history nodes: a flexible body reconstructs them
  // every cycle).
  s += fmt::format("*DATABASE_HISTORY_NODE\n{},{},{}\n", node_id(0, 1, 0),
                   node_id(kHubColumns, 1, 0), node_id(kColumns, 1, 0));
  return s;
}

struct TipHistory {
  std::vector<double> time, lag;  // chordwise tip deflection in the hub frame (+: ahead)
  double energy_ratio = 0.0, external_work = 0.0;
};

TipHistory run_spin_up(solver::Simulation& sim) {
  const auto& nodes = sim.state().nodes;
  const int ids[3] = {node_id(0, 1, 0), node_id(kHubColumns, 1, 0), node_id(kColumns, 1, 0)};
  std::size_t index[3] = {0, 0, 0};
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (nodes.id[i] == ids[k]) index[k] = i;
    }
  }
  const double tip_y0 = nodes.x0.y[index[2]];
  TipHistory history;
  while (!sim.finished()) {
    sim.cycle();
    if (sim.finished()) break;
    // Hub frame: origin at the hub centre, angle from the hub's end nodes.
    history.time.push_back(sim.state().time);
    history.lag.push_back(offset_across_hub_axis(nodes, index[0], index[1], index[2]) - tip_y0);
  }
  history.energy_ratio = sim.energy().ratio();
  history.external_work = sim.energy().external_work;
  return history;
}

// Reference sampled at `sample` s, linearly interpolated.
double interpolate(const std::vector<double>& values, double sample, double t) {
  const double s = t / sample;
  const std::size_t i = std::min(static_cast<std::size_t>(s), values.size() - 2);
  const double f = s - static_cast<double>(i);
  return (1 - f) * values[i] + f * values[i + 1];
}

struct Comparison {
  double peak = 0.0, peak_time = 0.0;  // most negative lag and when
  double final_amplitude = 0.0;        // max |lag| after the spin-up
  double rms_error = 0.0;              // RMS of (run - reference) over the run
  double max_error = 0.0;              // max |run - reference|
};

Comparison compare(const TipHistory& run, const std::vector<double>& reference, double sample,
                   double ramp) {
  Comparison c;
  double sum = 0.0;
  for (std::size_t i = 0; i < run.time.size(); ++i) {
    if (run.lag[i] < c.peak) {
      c.peak = run.lag[i];
      c.peak_time = run.time[i];
    }
    if (run.time[i] > ramp) c.final_amplitude = std::max(c.final_amplitude, std::abs(run.lag[i]));
    const double error = run.lag[i] - interpolate(reference, sample, run.time[i]);
    sum += error * error;
    c.max_error = std::max(c.max_error, std::abs(error));
  }
  c.rms_error = std::sqrt(sum / static_cast<double>(run.time.size()));
  return c;
}

// The problem at the 3-D beam's own chordwise frequency, and the reference curves.
struct SpinUpProblem {
  double omega_c = 0.0, ramp = 0.0, spin = 0.0, end = 0.0, sample = 0.0;
  std::vector<double> reference, conventional;
  double reference_peak = 0.0;   // most negative lag
  double reference_final = 0.0;  // max |w| after the spin-up
};

const SpinUpProblem& spin_up_problem() {
  static const SpinUpProblem problem = [] {
    SpinUpProblem p;
    // The reference gets the 3-D cantilever's chordwise frequency through an effective EI
    // (two ELFORM 2 hexahedra across the chord are stiffer than E b h^3 / 12).
    const double rho_a = kRho * kChord * kFlapDepth;
    const double ei_nominal = kYoung * kFlapDepth * kChord * kChord * kChord / 12.0;
    p.omega_c = beam_modes().omega_c;
    const double ei = rho_a * std::pow(kLength, 4) * std::pow(p.omega_c / (1.875104 * 1.875104), 2);
    p.ramp = kKaneRampTimesOmegaC / p.omega_c;
    p.spin = kKaneSpinOverOmegaC * p.omega_c;
    p.end = 4.0 / 3.0 * p.ramp;  // Kane's 20 s
    p.sample = p.ramp / 2000.0;
    p.reference =
        reference_beam(ei, rho_a, kLength, kClampRadius).spin_up(p.spin, p.ramp, p.end, p.sample);
    p.conventional = reference_beam(ei, rho_a, kLength, kClampRadius, false)
                         .spin_up(p.spin, p.ramp, p.end, p.sample);
    for (std::size_t i = 0; i < p.reference.size(); ++i) {
      p.reference_peak = std::min(p.reference_peak, p.reference[i]);
      if (static_cast<double>(i) * p.sample > p.ramp)
        p.reference_final = std::max(p.reference_final, std::abs(p.reference[i]));
    }
    std::printf(
        "beam: EI effective / nominal %.4f, omega_c %.2f rad/s, %zu modes; spin-up to %.1f "
        "rad/s in %.4f s, run to %.4f s\nreference: peak lag %.4e m, after spin-up |w| <= "
        "%.4e m; conventional linear at the end %.3e m\n",
        ei / ei_nominal, p.omega_c, beam_modes().modes.mode_count(), p.spin, p.ramp, p.end,
        p.reference_peak, p.reference_final, p.conventional.back());
    return p;
  }();
  return problem;
}

// run: 0 deformable beam, 1 FORM 0, 2 FORM 1.
Comparison run_and_compare(int run, double& energy_ratio) {
  const SpinUpProblem& p = spin_up_problem();
  const std::string cards = spin_up_cards(p.spin, p.ramp, p.end);
  solver::SimulationOptions options;
  options.write_fields = false;
  std::string text;
  if (run == 0) {
    text = deck(false, cards, p.end);
  } else {
    options.mode_loader = [](const std::filesystem::path&) { return beam_modes().modes; };
    text = deck(true, part_modes(run - 1, beam_modes().modes.mode_count()) + cards, p.end);
  }
  solver::Simulation sim(read(text), options);
  const TipHistory history = run_spin_up(sim);
  const Comparison c = compare(history, p.reference, p.sample, p.ramp);
  const char* names[3] = {"deformable", "FORM 0", "FORM 1"};
  std::printf(
      "%-10s peak lag %.4e m at %.3f T_s (reference %.4e m: %+.2f %%), after spin-up "
      "|w| <= %.4e m (%.1f %% of the reference peak), at end %.4e m; RMS error %.2f %%, max "
      "error %.2f %% of the reference peak; energy ratio %.9f, %zu cycles\n",
      names[run], c.peak, c.peak_time / p.ramp, p.reference_peak,
      100 * (c.peak / p.reference_peak - 1), c.final_amplitude,
      100 * c.final_amplitude / std::abs(p.reference_peak), history.lag.back(),
      100 * c.rms_error / std::abs(p.reference_peak),
      100 * c.max_error / std::abs(p.reference_peak), history.energy_ratio, history.time.size());
  energy_ratio = history.energy_ratio;
  return c;
}

// The physics of the model first: the fully deformable beam (geometrically nonlinear
// hexahedra, same mesh, hub-driven) follows the 1-D reference. Measured: peak -0.6 %, RMS error
// 0.61 % and largest error 1.2 % of the peak over the run; after the spin-up at most 0.5 % of
// the peak (the reference: 0.4 %). Tolerances: peak 2 %, RMS 1.5 %, largest 3 %, afterwards
// 2 % of the peak: the 3-D beam is not Euler-Bernoulli (h/L =
// 1/29: shear and rotary inertia O(0.5 %)), is geometrically nonlinear (tip lag 6 % of L) and
// stretches (the reference is inextensible), and its effective EI comes from its first
// frequency only. A model without stiffening (the conventional linear curve) is off by 60 % at
// t = 0.43 T_s and diverges; doubling the hub radius (L/10) raises the reference peak by 3.7 %.
TEST(FlexibleSpinUp, KaneSpinUpDeformableBeamFollowsReference) {
  const SpinUpProblem& p = spin_up_problem();
  EXPECT_GT(std::abs(p.conventional.back()), 1e3 * std::abs(p.reference_peak));
  double ratio = 0.0;
  const Comparison c = run_and_compare(0, ratio);
  const double peak = std::abs(p.reference_peak);
  EXPECT_NEAR(c.peak, p.reference_peak, 0.02 * peak);
  EXPECT_LT(c.rms_error, 0.015 * peak);
  EXPECT_LT(c.max_error, 0.03 * peak);
  EXPECT_LT(c.final_amplitude, 0.02 * peak);
  // Energy: the prescribed motion's work (external) balances kinetic plus internal energy.
  EXPECT_NEAR(ratio, 1.0, 1e-6);
}

// The flexible beam (12 modes, FORM 0: inertia coupling and geometric stiffening) follows the
// reference as well; FORM 1 (uncoupled modes: no centrifugal load, softening, stiffening,
// Coriolis or Euler coupling) drifts from it once the spin is a sizeable fraction of omega_c
// and keeps a larger vibration afterwards. Measured (FORM 0 / FORM 1): peak +4.1 % / +2.1 %,
// RMS error 1.7 % / 5.2 %, largest error 4.4 % / 12.8 %, after the spin-up 0.6 % / 0.9 % of the
// peak. Tolerances for FORM 0: peak 6 %, RMS 3 %, largest 7 %, afterwards 2 % of the peak
// (the deformable run's plus the modal truncation to 12 in-plane cantilever modes and the
// first-order frame coupling, docs/flexible_bodies.md section 2). FORM 1's RMS error is
// asserted to be at least twice FORM 0's.
TEST(FlexibleSpinUp, KaneSpinUpFlexibleFormZeroFollowsReference) {
  const SpinUpProblem& p = spin_up_problem();
  const double peak = std::abs(p.reference_peak);
  double ratio0 = 0.0, ratio1 = 0.0;
  const Comparison form0 = run_and_compare(1, ratio0);
  EXPECT_NEAR(form0.peak, p.reference_peak, 0.06 * peak);
  EXPECT_LT(form0.rms_error, 0.03 * peak);
  EXPECT_LT(form0.max_error, 0.07 * peak);
  EXPECT_LT(form0.final_amplitude, 0.02 * peak);
  EXPECT_NEAR(ratio0, 1.0, 1e-6);
  const Comparison form1 = run_and_compare(2, ratio1);
  EXPECT_GT(form1.rms_error, 2.0 * form0.rms_error);
  EXPECT_NEAR(ratio1, 1.0, 1e-6);
}

}  // namespace
}  // namespace rf::test
