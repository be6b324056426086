// Bulk viscosity of shells (*CONTROL_BULK_VISCOSITY TYPE -1/-2; element/shell_block.cpp,
// section 10; docs/theory.md).
//
// A piston drives one end of a shell strip in its plane at speed v, every node held across the
// strip, out of the plane and in rotation, so a plane compression shock runs along the strip in
// uniaxial in-plane strain. Reference: the Rankine-Hugoniot jump conditions across a steady
// shock, which hold whatever smooths the front,
//   mass      lambda = 1 - v / U           (lambda = A / A0 behind the front, U shock speed)
//   momentum  p = rho0 U v                 (p = -sigma_xx behind the front)
// closed by the material: the hypoelastic plane-stress update integrates sigma_xx = E' ln lambda
// in this strain path (E' = E / (1 - nu^2), thickness constant), so rho0 U v = -E' ln(1 - v / U);
// for a weak shock U -> c = sqrt(E' / rho0), the plate wave speed. Checked: the plateau stress,
// the front position U t, the width of the front and the ringing behind it for TYPE 1 (no
// viscosity in shells, as in LS-DYNA), -1 and -2 (the same in RigidFlex) and growing Q1/Q2, and
// the energy balance with an independent stored energy
//   W(lambda) = E' (lambda ln lambda - lambda + 1) A0 t per element
// (the work of sigma_xx = E' ln lambda along the path): kinetic + stored + bulk viscosity energy
// = work of the piston.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "deck_builder.hpp"
#include "shell_builder.hpp"
#include "shock_profile.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7850.0, kE = 210e9, kNu = 0.3, kLength = 1.0, kThickness = 0.002;
constexpr int kElements = 200;
constexpr double kH = kLength / kElements;

double plane_modulus() {
  return kE / (1.0 - kNu * kNu);
}
double wave_speed() {
  return std::sqrt(plane_modulus() / kRho);
}

double shock_speed(double v) {
  return shock::speed(v, wave_speed());
}

struct ShockRun {
  double time = 0.0;
  std::vector<double> pressure;  // -sigma_xx per element along the strip (mean over its points)
  std::vector<double> ratio;     // A / A0 per element along the strip (triangles: per pair)
  std::vector<double> area0;
  double kinetic = 0.0, internal = 0.0, hourglass = 0.0, bulk = 0.0, external = 0.0;
};

// The strip as kElements quadrilaterals, or as 2 kElements triangles (each cell cut along a
// diagonal). `control`: the *CONTROL_BULK_VISCOSITY card ("" for LS-DYNA's defaults, TYPE 1);
// `hourglass_q`: Q1,Q2 on the part's *HOURGLASS card ("" blank).
ShockRun run_shock(double v, const std::string& control, bool triangles = false,
                   const std::string& hourglass_q = "") {
  ShellPlate plate;
  plate.nx = kElements;
  plate.ny = 1;
  plate.lx = kLength;
  plate.ly = kH;
  std::string deck = "*KEYWORD\n" + plate.nodes_text();
  if (triangles) {
    deck += "*ELEMENT_SHELL\n";
    for (int i = 0; i < kElements; ++i) {
      const int a = plate.node_id(i, 0), b = plate.node_id(i + 1, 0), c = plate.node_id(i + 1, 1),
                d = plate.node_id(i, 1);
      deck += fmt::format("{},1,{},{},{},{}\n{},1,{},{},{},{}\n", 2 * i + 1, a, b, c, c, 2 * i + 2,
                          a, c, d, d);
    }
  } else {
    deck += plate.elements_text();
  }
  std::string part = shell_part(1, kThickness, kRho, kE, kNu);
  if (!hourglass_q.empty()) {
    // HGID IHQ QM, then IBQ Q1 Q2 appended to the same card.
    const std::size_t card = part.find("*HOURGLASS\n");
    part.insert(part.find('\n', card + 11), ",0," + hourglass_q);
  }
  deck += part;
  std::vector<int> all;
  for (int i = 1; i <= plate.node_count(); ++i) all.push_back(i);
  deck += node_set(1, plate.column(0)) + node_set(2, all);
  deck += "*BOUNDARY_SPC_SET\n2,0,0,1,1,1,1,1\n";
  deck += fmt::format("*BOUNDARY_PRESCRIBED_MOTION_SET\n1,1,0,1,{:.17g}\n", v);
  deck += "*DEFINE_CURVE\n1\n0.0,1.0\n1.0,1.0\n";
  deck += control;
  const double end = 0.6 * kLength / shock_speed(v);
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", end);
  solver::Simulation sim(read(deck), {});
  while (!sim.finished()) sim.cycle();

  ShockRun out;
  out.time = sim.state().time;
  const auto& block = sim.state().shell_blocks.at(0);
  const int per_cell = triangles ? 2 : 1;
  const std::size_t points = static_cast<std::size_t>(block.points_per_element());
  const auto& x = sim.state().nodes.x;
  for (int i = 0; i < kElements; ++i) {
    double s = 0.0, area = 0.0, area0 = 0.0;
    for (int k = 0; k < per_cell; ++k) {
      const std::size_t e = static_cast<std::size_t>(per_cell * i + k);
      // Stresses are stored in the element's co-rotational frame, whose axis 1 runs along side
      // 1-2 (along the strip for the quadrilaterals and lower triangles, along the diagonal for
      // the upper triangles), e1 = (c, s), e2 = (-s, c): sigma_xx = c^2 s11 + s^2 s22 - 2 c s s12.
      const std::int32_t n1 = block.conn[4 * e], n2 = block.conn[4 * e + 1];
      const double angle = std::atan2(x.y[n2] - x.y[n1], x.x[n2] - x.x[n1]);
      const double c = std::cos(angle), sn = std::sin(angle);
      for (std::size_t p = 0; p < points; ++p) {
        const double* sp = &block.stress[(e * points + p) * 5];
        s += c * c * sp[0] + sn * sn * sp[1] - 2.0 * c * sn * sp[2];
      }
      area += block.area[e];
      area0 += block.area0[e];
    }
    out.pressure.push_back(-s / (per_cell * static_cast<double>(points)));
    out.ratio.push_back(area / area0);
    out.area0.push_back(area0);
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
  double w = 0.0;
  for (std::size_t e = 0; e < r.ratio.size(); ++e) {
    const double l = r.ratio[e];
    w += plane_modulus() * (l * std::log(l) - l + 1.0) * r.area0[e] * kThickness;
  }
  return w;
}

const double kSpeed = 0.05 * wave_speed();  // strain about 5 %: a weak but not linear shock

class ShellBulkViscosityShock : public ::testing::TestWithParam<bool> {};

TEST_P(ShellBulkViscosityShock, JumpFrontAndEnergyWithTypeMinus2Defaults) {
  const bool triangles = GetParam();
  const double u = shock_speed(kSpeed);
  const ShockRun r = run_shock(kSpeed, "*CONTROL_BULK_VISCOSITY\n1.5,0.06,-2\n", triangles);
  const double p_rh = kRho * u * kSpeed;
  const double front = u * r.time;
  const double p = plateau(r, front, 0.2, 0.7);
  const double stored = stored_energy(r);
  std::printf(
      "%s: p/p_rh - 1 %.2e, front - U t %.3f cells, width %.2f, overshoot %.1e, internal/stored "
      "- 1 %.1e, balance %.1e, bulk/external %.4f, hourglass/external %.1e\n",
      triangles ? "triangles" : "quadrilaterals", p / p_rh - 1.0,
      (front_position(r, p) - front) / kH, front_width(r, p), overshoot(r, p),
      r.internal / stored - 1.0, (r.kinetic + stored + r.hourglass + r.bulk) / r.external - 1.0,
      r.bulk / r.external, r.hourglass / r.external);
  EXPECT_NEAR(p, p_rh, 0.005 * p_rh) << "plateau stress vs Rankine-Hugoniot rho0 U v";
  EXPECT_GT(std::abs(p - kRho * wave_speed() * kSpeed), 0.01 * p_rh)
      << "the nonlinear jump (U > c) must be resolved, not only the acoustic limit";
  EXPECT_NEAR(front_position(r, p), front, 0.5 * kH) << "front position vs U t";
  const double width = front_width(r, p);
  EXPECT_GT(width, 2.0);
  EXPECT_LT(width, 10.0) << "the defaults spread this weak shock over several cells";
  if (!triangles) {
    EXPECT_LT(overshoot(r, p), 0.01);
  } else {
    // The triangles' length L_s = 2 A / max side is the cell size / sqrt(2) (the diagonal is the
    // longest side), so the same coefficients damp less per cell: the ringing is cut to a
    // fraction of the undamped mesh's, not removed.
    const ShockRun plain = run_shock(kSpeed, "", true);
    const double p_plain = plateau(plain, u * plain.time, 0.2, 0.7);
    std::printf("triangles: overshoot %.3f without viscosity (TYPE 1), %.3f with\n",
                overshoot(plain, p_plain), overshoot(r, p));
    EXPECT_LT(overshoot(r, p), 0.2 * overshoot(plain, p_plain));
    EXPECT_LT(overshoot(r, p), 0.06);
  }
  EXPECT_NEAR(r.internal, stored, 2e-3 * stored) << "internal energy vs stored energy";
  EXPECT_GT(r.bulk, 1e-3 * r.external);
  EXPECT_NEAR(r.kinetic + stored + r.hourglass + r.bulk, r.external, 1e-3 * r.external)
      << "energy balance with the viscous dissipation";
}

INSTANTIATE_TEST_SUITE_P(Shape, ShellBulkViscosityShock, ::testing::Values(false, true),
                         [](const auto& info) {
                           return std::string(info.param ? "Triangles" : "Quadrilaterals");
                         });

TEST(ShellBulkViscosity, TypeOneLeavesShellsUndampedAndMinusOneEqualsMinusTwo) {
  const double u = shock_speed(kSpeed);
  const double p_rh = kRho * u * kSpeed;
  // TYPE 1 (also LS-DYNA's default without the card): solids only.
  const ShockRun plain = run_shock(kSpeed, "");
  const double p = plateau(plain, u * plain.time, 0.2, 0.7);
  EXPECT_NEAR(p, p_rh, 0.02 * p_rh) << "the jump does not depend on the viscosity";
  EXPECT_EQ(plain.bulk, 0.0);
  EXPECT_GT(overshoot(plain, p), 0.2) << "without viscosity the scheme rings behind the front";
  // TYPE -1 differs from -2 in LS-DYNA only in its energy report; RigidFlex accounts both.
  const ShockRun minus1 = run_shock(kSpeed, "*CONTROL_BULK_VISCOSITY\n1.5,0.06,-1\n");
  const ShockRun minus2 = run_shock(kSpeed, "*CONTROL_BULK_VISCOSITY\n1.5,0.06,-2\n");
  EXPECT_EQ(minus1.pressure, minus2.pressure);
  EXPECT_EQ(minus1.bulk, minus2.bulk);
  EXPECT_GT(minus1.bulk, 0.0);
  // The part's *HOURGLASS Q1/Q2 override the control card's, as for solids: 0, 0 switches the
  // viscosity off for the part, which then rings like TYPE 1.
  const ShockRun off = run_shock(kSpeed, "*CONTROL_BULK_VISCOSITY\n1.5,0.06,-1\n", false, "0,0");
  EXPECT_EQ(off.bulk, 0.0);
  EXPECT_EQ(off.pressure, plain.pressure);
}

TEST(ShellBulkViscosity, FrontSpreadsAndRingingFallsAsTheCoefficientsGrow) {
  const double u = shock_speed(kSpeed);
  const double p_rh = kRho * u * kSpeed;
  struct Case {
    double q1, q2;
    double width = 0.0, over = 0.0, bulk = 0.0;
  };
  // The last case holds only with the viscous step (section 10): Q1 4 at the plain L_s / c
  // step would go unstable in the front.
  std::vector<Case> cases{{0.5, 0.02}, {1.5, 0.06}, {4.0, 0.2}};
  for (Case& c : cases) {
    const ShockRun r =
        run_shock(kSpeed, fmt::format("*CONTROL_BULK_VISCOSITY\n{},{},-2\n", c.q1, c.q2));
    const double p = plateau(r, u * r.time, 0.2, 0.7);
    EXPECT_NEAR(p, p_rh, 0.01 * p_rh) << "Q1 " << c.q1 << ": jump independent of the viscosity";
    c.width = front_width(r, p);
    c.over = overshoot(r, p);
    c.bulk = r.bulk;
    std::printf("Q1 %g Q2 %g: p/p_rh %.5f width %.3f overshoot %.5f bulk/ext %.5f\n", c.q1, c.q2,
                p / p_rh, c.width, c.over, r.bulk / r.external);
    EXPECT_NEAR(r.kinetic + stored_energy(r) + r.hourglass + r.bulk, r.external, 3e-3 * r.external)
        << "Q1 " << c.q1;
  }
  for (std::size_t k = 1; k < cases.size(); ++k) {
    EXPECT_GT(cases[k].width, cases[k - 1].width) << "Q1 " << cases[k].q1;
    EXPECT_LT(cases[k].over, cases[k - 1].over + 1e-4) << "Q1 " << cases[k].q1;
    EXPECT_GT(cases[k].bulk, cases[k - 1].bulk) << "Q1 " << cases[k].q1;
  }
}

}  // namespace
}  // namespace rf::test
