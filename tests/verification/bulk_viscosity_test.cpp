// Artificial bulk viscosity (*CONTROL_BULK_VISCOSITY; docs/theory.md, docs/verification.md).
//
// A piston drives one end of a bar at speed v in uniaxial strain (every node held laterally),
// so a plane compression shock runs down the bar. Reference: the Rankine-Hugoniot jump
// conditions across a steady shock, which hold whatever smooths the front,
//   mass      lambda = 1 - v / U           (lambda = V / V0 behind the front, U shock speed)
//   momentum  p = rho0 U v                 (p = -sigma_xx behind the front)
// closed by the material: the hypoelastic update integrates sigma_xx = M ln lambda in uniaxial
// strain (M = lambda_L + 2 mu, the constrained modulus), so rho0 U v = -M ln(1 - v / U); for a
// weak shock U -> c = sqrt(M / rho0) and p -> rho0 c v. Checked: the plateau pressure, the
// front position U t, the width of the front in elements and the overshoot behind it as Q1, Q2
// vary, and the energy balance with an independent stored energy
//   W(lambda) = M (lambda ln lambda - lambda + 1) V0 per element
// (the work of sigma_xx = M ln lambda along the uniaxial path): kinetic + stored + bulk
// viscosity energy = work of the piston.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "deck_builder.hpp"
#include "shock_profile.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7850.0, kE = 210e9, kNu = 0.3, kLength = 1.0;
constexpr int kElements = 200;
constexpr double kH = kLength / kElements;

double constrained_modulus() {
  return kE * (1.0 - kNu) / ((1.0 + kNu) * (1.0 - 2.0 * kNu));
}
double wave_speed() {
  return std::sqrt(constrained_modulus() / kRho);
}

double shock_speed(double v) {
  return shock::speed(v, wave_speed());
}

struct ShockRun {
  double time = 0.0;
  std::vector<double> pressure;  // -sigma_xx per element (mean over its stress points)
  std::vector<double> ratio;     // V / V0 per element
  double kinetic = 0.0, internal = 0.0, hourglass = 0.0, bulk = 0.0, external = 0.0;
};

// `control`: the *CONTROL_BULK_VISCOSITY card text ("" for LS-DYNA's defaults).
ShockRun run_shock(int elform, double v, const std::string& control, double front_fraction) {
  BoxMesh mesh;
  mesh.nx = kElements;
  mesh.lx = kLength;
  mesh.ly = mesh.lz = kH;
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, kNu, elform, 1);
  std::vector<int> all;
  for (int i = 1; i <= mesh.node_count(); ++i) all.push_back(i);
  deck += node_set(1, mesh.face_x(0)) + node_set(2, all);
  deck += "*BOUNDARY_SPC_SET\n2,0,0,1,1\n";
  deck += fmt::format("*BOUNDARY_PRESCRIBED_MOTION_SET\n1,1,0,1,{:.17g}\n", v);
  deck += "*DEFINE_CURVE\n1\n0.0,1.0\n1.0,1.0\n";
  deck += control;
  const double end = front_fraction * kLength / shock_speed(v);
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", end);
  solver::Simulation sim(read(deck), {});
  while (!sim.finished()) sim.cycle();

  ShockRun out;
  out.time = sim.state().time;
  const auto& block = sim.state().hex_blocks[0];
  const int points = block.points_per_element();
  for (std::size_t e = 0; e < block.size(); ++e) {
    double s = 0.0;
    for (int p = 0; p < points; ++p) s += block.stress[(e * points + p) * 6];
    out.pressure.push_back(-s / points);
    out.ratio.push_back(block.volume[e] / block.volume0[e]);
  }
  const solver::EnergyAccount& en = sim.energy();
  out.kinetic = en.kinetic;
  out.internal = en.internal();
  out.hourglass = en.hourglass;
  out.bulk = en.bulk_viscosity;
  out.external = en.external_work;
  return out;
}

double plateau(const ShockRun& r, double front, double a, double b) {
  return shock::plateau(r.pressure, kH, front, a, b);
}
double front_position(const ShockRun& r, double p) {
  return shock::front_position(r.pressure, kH, p);
}
double front_width(const ShockRun& r, double p) {
  return shock::front_width(r.pressure, p);
}
double overshoot(const ShockRun& r, double p) {
  return shock::overshoot(r.pressure, p);
}

double stored_energy(const ShockRun& r) {
  const double m = constrained_modulus(), v0 = kH * kH * kH;
  double w = 0.0;
  for (double l : r.ratio) w += m * (l * std::log(l) - l + 1.0) * v0;
  return w;
}

class BulkViscosityShock : public ::testing::TestWithParam<int> {};

TEST_P(BulkViscosityShock, JumpConditionsFrontAndEnergyWithDefaultCoefficients) {
  const int elform = GetParam();
  const double v = 0.05 * wave_speed();  // strain about 5 %: a weak but not linear shock
  const double u = shock_speed(v);
  const ShockRun r = run_shock(elform, v, "", 0.6);
  const double p_rh = kRho * u * v;
  const double front = u * r.time;
  const double p = plateau(r, front, 0.2, 0.7);
  EXPECT_NEAR(p, p_rh, 0.005 * p_rh) << "plateau pressure vs Rankine-Hugoniot rho0 U v";
  EXPECT_GT(std::abs(p - kRho * wave_speed() * v), 0.01 * p_rh)
      << "the nonlinear jump (U > c) must be resolved, not only the acoustic limit";
  EXPECT_NEAR(front_position(r, p), front, 0.5 * kH) << "front position vs U t";
  const double width = front_width(r, p);
  EXPECT_GT(width, 2.0);
  EXPECT_LT(width, 10.0) << "the defaults spread this weak shock over several elements";
  EXPECT_LT(overshoot(r, p), 0.01);
  // Energy: the piston's work is kinetic + stored + dissipated.
  const double stored = stored_energy(r);
  std::printf(
      "ELFORM %d: p/p_rh - 1 %.2e, front - U t %.3f elements, width %.2f, overshoot "
      "%.1e, internal/stored - 1 %.1e, balance %.1e, bulk/external %.4f\n",
      elform, p / p_rh - 1.0, (front_position(r, p) - front) / kH, width, overshoot(r, p),
      r.internal / stored - 1.0, (r.kinetic + stored + r.hourglass + r.bulk) / r.external - 1.0,
      r.bulk / r.external);
  EXPECT_NEAR(r.internal, stored, 2e-3 * stored) << "internal energy vs stored energy";
  EXPECT_GT(r.bulk, 0.0);
  EXPECT_NEAR(r.kinetic + stored + r.hourglass + r.bulk, r.external, 1e-3 * r.external)
      << "energy balance with the viscous dissipation";
}

INSTANTIATE_TEST_SUITE_P(Elform, BulkViscosityShock, ::testing::Values(1, 2));

TEST(BulkViscosityCoefficients, FrontSpreadsAndRingingFallsAsTheyGrow) {
  const double v = 0.05 * wave_speed();
  const double u = shock_speed(v);
  const double p_rh = kRho * u * v;
  struct Case {
    double q1, q2;
    double width = 0.0, over = 0.0, bulk = 0.0;
  };
  std::vector<Case> cases{{0.0, 0.0}, {0.5, 0.02}, {1.5, 0.06}, {4.0, 0.2}};
  for (Case& c : cases) {
    const ShockRun r =
        run_shock(1, v, fmt::format("*CONTROL_BULK_VISCOSITY\n{},{}\n", c.q1, c.q2), 0.6);
    const double front = u * r.time;
    const double p = plateau(r, front, 0.2, 0.7);
    EXPECT_NEAR(p, p_rh, 0.01 * p_rh) << "Q1 " << c.q1 << ": jump independent of the viscosity";
    c.width = front_width(r, p);
    c.over = overshoot(r, p);
    c.bulk = r.bulk;
    std::printf("Q1 %g Q2 %g: p/p_rh %.5f width %.3f overshoot %.5f bulk/ext %.5f\n", c.q1, c.q2,
                p / p_rh, c.width, c.over, r.bulk / r.external);
    const double stored = stored_energy(r);
    EXPECT_NEAR(r.kinetic + stored + r.hourglass + r.bulk, r.external, 3e-3 * r.external)
        << "Q1 " << c.q1;
  }
  // Without viscosity the scheme rings behind the front (Gibbs-like overshoot of tens of %).
  EXPECT_EQ(cases[0].bulk, 0.0);
  EXPECT_GT(cases[0].over, 0.2);
  // More viscosity: a wider front, less ringing (none left with the defaults), more dissipation.
  for (std::size_t k = 1; k < cases.size(); ++k) {
    EXPECT_GT(cases[k].width, cases[k - 1].width) << "Q1 " << cases[k].q1;
    EXPECT_LT(cases[k].over, cases[k - 1].over + 1e-4) << "Q1 " << cases[k].q1;
    EXPECT_GT(cases[k].bulk, cases[k - 1].bulk) << "Q1 " << cases[k].q1;
  }
  EXPECT_LT(cases[1].over, 0.25 * cases[0].over);
  EXPECT_LT(cases[2].over, 0.01);
}

}  // namespace
}  // namespace rf::test
