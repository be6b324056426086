// *MAT_3-PARAMETER_BARLAT (036) on shells. References that do not come from our code:
//  - Barlat and Lian, Int. J. Plasticity 5 (1989) 51-66: the yield function (eq. 4), its
//    coefficients a, c, h from R00 and R90 in closed form and p from R45 through the paper's
//    45-degree relation R45 = 2 M sigma^M / ((df/ds_xx + df/ds_yy) sigma_45) - 1, written here
//    again (with finite-difference derivatives) and solved by bisection;
//  - the definition of the Lankford coefficient (plastic width / thickness strain ratio in
//    uniaxial tension, thickness strain from plastic incompressibility), measured on the
//    material's response and on a shell element;
//  - the analytic yield stresses in uniaxial tension at an angle theta and in equi-biaxial
//    tension, (2 / f(unit stress state))^(1/M) sigma_y;
//  - von Mises for M = 2, R = 1 (the same run with *MAT_024 and the same hardening);
//  - the hardening laws as the LS-DYNA manual states them (linear, k (e0 + eps)^n, curve);
//  - energy: work of the prescribed motion = kinetic + elastic strain energy + plastic work
//    sum V int sigma_y d eps_p.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "deck_builder.hpp"
#include "material/barlat.hpp"
#include "material/plastic_setup.hpp"
#include "model/error.hpp"
#include "shell_builder.hpp"

namespace rf::test {
namespace {

constexpr double kE = 2.0e11, kNu = 0.3, kRho = 7800.0;
constexpr double kPi = std::numbers::pi;

// --- The paper's formulas, written independently of material/barlat.hpp ---------------------

struct Coefficients {
  double a, c, h, p;
};

// f of Barlat and Lian (1989), eq. (4): s_xy the tensor shear stress.
double paper_f(const Coefficients& k, double m, double sxx, double syy, double sxy) {
  const double k1 = (sxx + k.h * syy) / 2.0;
  const double k2 = std::sqrt(std::pow((sxx - k.h * syy) / 2.0, 2) + k.p * k.p * sxy * sxy);
  return k.a * std::pow(std::abs(k1 + k2), m) + k.a * std::pow(std::abs(k1 - k2), m) +
         k.c * std::pow(std::abs(2.0 * k2), m);
}

// Yield stress of uniaxial tension at theta to the rolling direction, over sigma_y.
double uniaxial_ratio(const Coefficients& k, double m, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return std::pow(2.0 / paper_f(k, m, c * c, s * s, c * s), 1.0 / m);
}

// The paper's identification: a, c, h closed form; p by bisection on its R45 relation.
Coefficients paper_coefficients(double r0, double r45, double r90, double m) {
  Coefficients k;
  k.a = 2.0 - 2.0 * std::sqrt(r0 / (1.0 + r0) * r90 / (1.0 + r90));
  k.c = 2.0 - k.a;
  k.h = std::sqrt(r0 / (1.0 + r0) * (1.0 + r90) / r90);
  auto r45_of = [&](double p) {
    Coefficients q = k;
    q.p = p;
    const double s45 = uniaxial_ratio(q, m, kPi / 4.0);  // sigma_y = 1
    const double e = 1e-6 * s45, x = s45 / 2.0;
    const double dfx = (paper_f(q, m, x + e, x, x) - paper_f(q, m, x - e, x, x)) / (2.0 * e);
    const double dfy = (paper_f(q, m, x, x + e, x) - paper_f(q, m, x, x - e, x)) / (2.0 * e);
    return 2.0 * m / ((dfx + dfy) * s45) - 1.0;
  };
  double lo = 1e-2, hi = 1e2;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (r45_of(mid) < r45 ? lo : hi) = mid;
  }
  k.p = std::sqrt(lo * hi);
  return k;
}

// --- Material parameters through the reader ----------------------------------------------------

std::string barlat_card(const std::string& card1, const std::string& card2,
                        const std::string& axes = "0,0,0,0,0,0,0,0\n0,0,0,0,0,0,0,0\n",
                        const std::string& card3 = "0,0,0,0,0,0,0,0\n") {
  return "*MAT_3-PARAMETER_BARLAT\n" + card1 + "\n" + card2 + "\n" + card3 + axes;
}

material::BarlatParameters parameters_of(const std::string& material_text) {
  const model::Model model = read("*KEYWORD\n" + material_text + "*END\n");
  return material::make_barlat_parameters(model, model.materials.at(1));
}

// --- A material point in uniaxial (or equi-biaxial) stress -------------------------------------

struct PointPath {
  double r = 0.0;              // plastic width / thickness strain ratio, total
  double stress = 0.0;         // loading-direction stress at the end
  double eps = 0.0;            // effective plastic strain at the end
  double max_law_error = 0.0;  // max |sigma_0 / sigma_y(eps) - 1| along the path (theta = 0)
};

// Strain-driven along the element x axis; the rolling direction is at -theta from it (so the
// load is at theta to rolling). Uniaxial: the other stresses vanish; biaxial: s_yy = s_xx,
// s_xy = 0. The transverse strains are found by Newton (finite-difference Jacobian) each step.
PointPath drive(const material::BarlatParameters& p, double theta, double total, int steps,
                bool biaxial = false) {
  const material::ElasticConstants m = material::make_elastic(kRho, kE, kNu);
  const double cs = std::cos(-theta), sn = std::sin(-theta);
  double s[3] = {0, 0, 0}, eps = 0.0, ep[3] = {0, 0, 0}, y[2] = {0, 0};
  PointPath out;
  const double dt = 1.0;
  for (int k = 0; k < steps; ++k) {
    const double de = total / steps;
    auto step = [&](const double x[2], double so[3], double& e) {
      const double d[3] = {de, x[0], x[1]};
      for (int i = 0; i < 3; ++i) so[i] = s[i];
      e = eps;
      material::BarlatMaterial::plane_stress_update(m, p, cs, sn, d, dt, so, &e);
    };
    auto residual = [&](const double so[3], double r[2]) {
      r[0] = biaxial ? so[1] - so[0] : so[1];
      r[1] = so[2];
    };
    double so[3], e, r[2];
    for (int it = 0; it < 40; ++it) {
      step(y, so, e);
      residual(so, r);
      if (std::abs(r[0]) + std::abs(r[1]) < 1e-7 * (std::abs(so[0]) + 1.0)) break;
      double J[2][2];
      const double h = 1e-10;
      for (int j = 0; j < 2; ++j) {
        double yy[2] = {y[0], y[1]}, s2[3], e2, r2[2];
        yy[j] += h;
        step(yy, s2, e2);
        residual(s2, r2);
        J[0][j] = (r2[0] - r[0]) / h;
        J[1][j] = (r2[1] - r[1]) / h;
      }
      const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      const double d0 = (J[1][1] * r[0] - J[0][1] * r[1]) / det;
      const double d1 = (-J[1][0] * r[0] + J[0][0] * r[1]) / det;
      y[0] -= d0;
      y[1] -= d1;
    }
    step(y, so, e);
    // Plastic strain increments: total minus elastic (isotropic compliance, engineering shear).
    const double ds[3] = {so[0] - s[0], so[1] - s[1], so[2] - s[2]};
    ep[0] += de - (ds[0] - kNu * ds[1]) / kE;
    ep[1] += y[0] - (ds[1] - kNu * ds[0]) / kE;
    ep[2] += y[1] - ds[2] * 2.0 * (1.0 + kNu) / kE;
    for (int i = 0; i < 3; ++i) s[i] = so[i];
    eps = e;
    if (eps > 0.0) {
      double slope = 0.0;
      out.max_law_error = std::max(
          out.max_law_error, std::abs(s[0] / material::barlat::yield_stress(p, eps, &slope) - 1.0));
    }
  }
  out.r = ep[1] / -(ep[0] + ep[1]);
  out.stress = s[0];
  out.eps = eps;
  return out;
}

// A BCC-like steel sheet (M = 6) and an FCC-like aluminium sheet (M = 8).
struct Sheet {
  double m, r0, r45, r90;
};
const Sheet kSheets[] = {{6.0, 1.8, 1.4, 2.1}, {8.0, 0.7, 0.5, 0.65}};

std::string linear_sheet(const Sheet& sh) {
  return barlat_card("1,7800,2e11,0.3,1,2e9,2e8,0",
                     fmt::format("{},{},{},{},0,0,0,0", sh.m, sh.r0, sh.r45, sh.r90));
}

TEST(BarlatPoint, CoefficientsFollowThePaper) {
  for (const Sheet& sh : kSheets) {
    const material::BarlatParameters p = parameters_of(linear_sheet(sh));
    const Coefficients ref = paper_coefficients(sh.r0, sh.r45, sh.r90, sh.m);
    EXPECT_NEAR(p.a, ref.a, 1e-12);
    EXPECT_NEAR(p.c, ref.c, 1e-12);
    EXPECT_NEAR(p.h, ref.h, 1e-12);
    EXPECT_NEAR(p.p / ref.p, 1.0, 1e-5) << "M " << sh.m;
  }
}

TEST(BarlatPoint, UniaxialTensionGivesTheLankfordCoefficientsAndYieldRatios) {
  double worst_r = 0.0, worst_stress = 0.0;
  for (const Sheet& sh : kSheets) {
    const material::BarlatParameters p = parameters_of(linear_sheet(sh));
    const Coefficients ref = paper_coefficients(sh.r0, sh.r45, sh.r90, sh.m);
    const double expected_r[] = {sh.r0, sh.r45, sh.r90};
    for (int i = 0; i < 3; ++i) {
      const double theta = i * kPi / 4.0;
      const PointPath path = drive(p, theta, 0.05, 100);
      double slope = 0.0;
      const double sy = material::barlat::yield_stress(p, path.eps, &slope);
      EXPECT_NEAR(path.r / expected_r[i], 1.0, 1e-3) << "M " << sh.m << " theta " << 45 * i;
      EXPECT_NEAR(path.stress / sy / uniaxial_ratio(ref, sh.m, theta), 1.0, 1e-4)
          << "M " << sh.m << " theta " << 45 * i;
      EXPECT_GT(path.eps, 0.03);
      worst_r = std::max(worst_r, std::abs(path.r / expected_r[i] - 1.0));
      worst_stress = std::max(worst_stress,
                              std::abs(path.stress / sy / uniaxial_ratio(ref, sh.m, theta) - 1.0));
    }
    // The 90-degree ratio in closed form: sigma_90 / sigma_0 = 1 / h.
    EXPECT_NEAR(uniaxial_ratio(ref, sh.m, kPi / 2.0), 1.0 / ref.h, 1e-12);
  }
  RecordProperty("worst_r_error", fmt::format("{:.2g}", worst_r));
  RecordProperty("worst_yield_ratio_error", fmt::format("{:.2g}", worst_stress));
}

TEST(BarlatPoint, EquibiaxialYieldStressIsTheAnalyticOne) {
  for (const Sheet& sh : kSheets) {
    const material::BarlatParameters p = parameters_of(linear_sheet(sh));
    const Coefficients ref = paper_coefficients(sh.r0, sh.r45, sh.r90, sh.m);
    const PointPath path = drive(p, 0.0, 0.03, 100, true);
    double slope = 0.0;
    const double sy = material::barlat::yield_stress(p, path.eps, &slope);
    const double expected = std::pow(2.0 / paper_f(ref, sh.m, 1.0, 1.0, 0.0), 1.0 / sh.m);
    EXPECT_NEAR(path.stress / sy / expected, 1.0, 1e-4) << "M " << sh.m;
    RecordProperty(fmt::format("biaxial_error_m{}", sh.m),
                   fmt::format("{:.2g}", path.stress / sy / expected - 1.0));
    EXPECT_GT(path.eps, 0.01);
  }
}

TEST(BarlatPoint, QuadraticIsotropicCaseIsVonMises) {
  const material::BarlatParameters p = parameters_of(linear_sheet({2.0, 1.0, 1.0, 1.0}));
  EXPECT_NEAR(p.p, 1.0, 1e-6);
  material::barlat::Surface sf;
  const double states[][3] = {{1, 0, 0}, {0.3, -0.7, 0.2}, {2, 1, -0.5}, {-1, -1, 0}, {0, 0, 1}};
  for (const auto& s : states) {
    material::barlat::surface(p, s, false, sf);
    const double vm = std::sqrt(s[0] * s[0] - s[0] * s[1] + s[1] * s[1] + 3.0 * s[2] * s[2]);
    EXPECT_NEAR(sf.phi / vm, 1.0, 1e-6);
  }
}

// Stress against effective plastic strain in uniaxial tension along the rolling direction
// equals the hardening law, for HR 1, 2 and 3.
TEST(BarlatPoint, HardeningRulesAreTheManualsLaws) {
  const std::string c2 = "6,1.5,1.0,2.0,0,0,0,0";
  // HR 1: sigma_y = 200 MPa + Ep eps, Ep = E Et / (E - Et).
  {
    const material::BarlatParameters p =
        parameters_of(barlat_card("1,7800,2e11,0.3,1,2e9,2e8,0", c2));
    const double ep = kE * 2e9 / (kE - 2e9);
    EXPECT_NEAR(p.modulus / ep, 1.0, 1e-12);
    const PointPath path = drive(p, 0.0, 0.2, 200);
    EXPECT_LT(path.max_law_error, 1e-6);
    EXPECT_NEAR(path.stress / (2e8 + ep * path.eps), 1.0, 1e-6);
  }
  // HR 2 with E0: sigma = k (E0 + eps)^n.
  {
    const material::BarlatParameters p =
        parameters_of(barlat_card("1,7800,2e11,0.3,2,5e8,0.22,0", "6,1.5,1.0,2.0,0,0.01,0,0"));
    const PointPath path = drive(p, 0.0, 0.2, 200);
    EXPECT_LT(path.max_law_error, 1e-6);
    EXPECT_NEAR(path.stress / (5e8 * std::pow(0.01 + path.eps, 0.22)), 1.0, 1e-6);
  }
  // HR 2, E0 = 0, SPI = 0: e0 where the elastic line meets the power law, E e0 = k e0^n.
  {
    const material::BarlatParameters p =
        parameters_of(barlat_card("1,7800,2e11,0.3,2,5e8,0.22,0", c2));
    EXPECT_NEAR(kE * p.e0 / (5e8 * std::pow(p.e0, 0.22)), 1.0, 1e-10);
  }
  // HR 2, SPI > 0.02: SPI is the initial yield stress.
  {
    const material::BarlatParameters p =
        parameters_of(barlat_card("1,7800,2e11,0.3,2,5e8,0.22,0", "6,1.5,1.0,2.0,0,0,2.5e8,0"));
    double slope = 0.0;
    EXPECT_NEAR(material::barlat::yield_stress(p, 0.0, &slope) / 2.5e8, 1.0, 1e-12);
  }
  // HR 3: curve with SFA/SFO scale factors applied (stress in MPa scaled by 1e6).
  {
    const material::BarlatParameters p =
        parameters_of(barlat_card("1,7800,2e11,0.3,3,0,0,0", "6,1.5,1.0,2.0,7,0,0,0") +
                      "*DEFINE_CURVE\n7,0,1.0,1e6\n0,200\n0.05,260\n0.2,330\n1.0,400\n");
    const PointPath path = drive(p, 0.0, 0.25, 250);
    EXPECT_LT(path.max_law_error, 1e-6);
    // eps in [0.2, 1]: 330 + (400 - 330) (eps - 0.2) / 0.8 MPa.
    EXPECT_NEAR(path.stress / (1e6 * (330.0 + 70.0 * (path.eps - 0.2) / 0.8)), 1.0, 1e-6);
  }
}

// --- One shell element in uniaxial tension ------------------------------------------------------

constexpr double kSide = 0.01, kThick = 0.001;

// Part `pid` (nodes 10 pid + 1..4, element pid) pulled along x at 0.2 m/s after a ramp; node 1
// fixed, node 4 free in y, nodes 2 and 3 free in y; all nodes stay in the plane (z and
// rotations fixed). y offset keeps parts apart.
std::string pulled_element(int pid, double y0, const std::string& material) {
  const int n = 10 * pid;
  std::string s = fmt::format("*NODE\n{},0,{},0\n{},{},{},0\n{},{},{},0\n{},0,{},0\n", n + 1, y0,
                              n + 2, kSide, y0, n + 3, kSide, y0 + kSide, n + 4, y0 + kSide);
  s += fmt::format("*ELEMENT_SHELL\n{0},{0},{1},{2},{3},{4}\n", pid, n + 1, n + 2, n + 3, n + 4);
  s += fmt::format(
      "*PART\npart {0}\n{0},{0},{0},0,{0}\n*SECTION_SHELL\n{0},2,0.8333333,2\n"
      "{1},{1},{1},{1}\n*HOURGLASS\n{0},4,0.05\n",
      pid, kThick);
  s += material;
  s += fmt::format(
      "*BOUNDARY_SPC_NODE\n{},0,1,1,1,1,1,1\n{},0,1,0,1,1,1,1\n{},0,0,0,1,1,1,1\n"
      "{},0,0,0,1,1,1,1\n",
      n + 1, n + 4, n + 2, n + 3);
  s +=
      fmt::format("*BOUNDARY_PRESCRIBED_MOTION_NODE\n{0},1,0,1,1.0\n{1},1,0,1,1.0\n", n + 2, n + 3);
  return s;
}

std::string pull_controls(double end_time) {
  return fmt::format("*DEFINE_CURVE\n1\n0,0\n2e-4,0.2\n1,0.2\n*CONTROL_TERMINATION\n{},\n",
                     end_time);
}

struct ElementResult {
  double r, stress, eps, sy;
};

ElementResult measure(const solver::Simulation& sim, std::size_t block, int pid,
                      const material::BarlatParameters* p) {
  const auto& nodes = sim.state().nodes;
  auto at = [&](int id) {
    for (std::size_t i = 0; i < nodes.id.size(); ++i)
      if (nodes.id[i] == id) return i;
    return std::size_t{0};
  };
  const int n = 10 * pid;
  const double len = nodes.x.x[at(n + 2)] - nodes.x.x[at(n + 1)];
  const double width = 0.5 * ((nodes.x.y[at(n + 4)] - nodes.x.y[at(n + 1)]) +
                              (nodes.x.y[at(n + 3)] - nodes.x.y[at(n + 2)]));
  const auto& b = sim.state().shell_blocks[block];
  const double sxx = 0.5 * (b.stress[0] + b.stress[element::kShellStress]);
  const double syy = 0.5 * (b.stress[1] + b.stress[element::kShellStress + 1]);
  const double el = std::log(len / kSide), ew = std::log(width / kSide);
  const double pl = el - (sxx - kNu * syy) / kE, pw = ew - (syy - kNu * sxx) / kE;
  ElementResult r{pw / -(pl + pw), sxx, 0.0, 0.0};
  const material::HistoryArray* h = element::find_history(b, "effective_plastic_strain");
  if (h) r.eps = h->values[0];
  if (p) {
    double slope = 0.0;
    r.sy = material::barlat::yield_stress(*p, r.eps, &slope);
  }
  return r;
}

void uniaxial_at_three_angles(int elform) {
  const Sheet sh = kSheets[0];
  const Coefficients ref = paper_coefficients(sh.r0, sh.r45, sh.r90, sh.m);
  const double expected_r[] = {sh.r0, sh.r45, sh.r90};
  std::string deck = "*KEYWORD\n";
  for (int i = 0; i < 3; ++i) {
    // AOPT 2: rolling direction A at -theta from the pulling direction x.
    const double theta = i * kPi / 4.0;
    const std::string axes = fmt::format("0,0,0,{:.17g},{:.17g},0,0,0\n0,0,0,0,0,0,0,0\n",
                                         std::cos(theta), -std::sin(theta));
    std::string mat = barlat_card(fmt::format("{},7800,2e11,0.3,1,2e9,2e8,0", i + 1),
                                  fmt::format("{},{},{},{},0,0,0,0", sh.m, sh.r0, sh.r45, sh.r90),
                                  axes, "2,0,0,0,0,0,0,0\n");
    deck += pulled_element(i + 1, 0.05 * i, mat);
  }
  deck += pull_controls(3e-3) + "*END\n";
  if (elform == 16) deck = fully_integrated(deck);
  solver::Simulation sim(read(deck), {});
  ASSERT_EQ(sim.state().shell_blocks[0].elform, elform);
  sim.run();
  const material::BarlatParameters& p = sim.state().shell_blocks[0].barlat;
  for (int i = 0; i < 3; ++i) {
    const ElementResult r = measure(sim, static_cast<std::size_t>(i), i + 1, &p);
    const double ratio = r.stress / r.sy / uniaxial_ratio(ref, sh.m, i * kPi / 4.0);
    ::testing::Test::RecordProperty(fmt::format("r_ratio_{}", 45 * i),
                                    fmt::format("{:.5f}", r.r / expected_r[i]));
    ::testing::Test::RecordProperty(fmt::format("yield_ratio_{}", 45 * i),
                                    fmt::format("{:.5f}", ratio));
    EXPECT_NEAR(r.r / expected_r[i], 1.0, 0.01) << "theta " << 45 * i << " R " << r.r;
    EXPECT_NEAR(ratio, 1.0, 0.005) << "theta " << 45 * i;
    EXPECT_GT(r.eps, 0.03);
  }
}

TEST(BarlatShell, UniaxialTensionOfAShellAtZero45And90DegreesToRolling) {
  uniaxial_at_three_angles(2);
}

// The same with fully integrated shells (ELFORM 16: Barlat at each of the 4 x 2 points, the
// material axes of the element).
TEST(BarlatShell, UniaxialTensionOfAFullyIntegratedShellAtThreeAngles) {
  uniaxial_at_three_angles(16);
}

TEST(BarlatShell, QuadraticIsotropicBarlatEqualsPiecewiseLinearPlasticity) {
  std::string deck = "*KEYWORD\n";
  deck += pulled_element(1, 0.0, barlat_card("1,7800,2e11,0.3,1,2e9,2e8,0", "2,1,1,1,0,0,0,0"));
  deck += pulled_element(2, 0.05, "*MAT_PIECEWISE_LINEAR_PLASTICITY\n2,7800,2e11,0.3,2e8,2e9\n");
  deck += pull_controls(2e-3) + "*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  const auto& b = sim.state().shell_blocks;
  ASSERT_EQ(b.size(), 2u);
  for (std::size_t c = 0; c < b[0].stress.size(); ++c)
    EXPECT_NEAR(b[0].stress[c], b[1].stress[c], 1e-6 * 2e8) << "component " << c;
  const double e0 = element::find_history(b[0], "effective_plastic_strain")->values[0];
  const double e1 = element::find_history(b[1], "effective_plastic_strain")->values[0];
  EXPECT_GT(e0, 0.02);
  EXPECT_NEAR(e0, e1, 1e-6 * e1);
}

// Work of the prescribed motion = kinetic + elastic strain energy + plastic work (sum of V int
// sigma_y d eps_p over the points, accumulated cycle by cycle from the material history).
TEST(BarlatShell, PlasticWorkClosesTheEnergyBalance) {
  const Sheet sh = kSheets[1];
  const std::string axes = "0,0,0,0.6,0.8,0,0,0\n0,0,0,0,0,0,0,0\n";
  std::string deck =
      "*KEYWORD\n" +
      pulled_element(1, 0.0,
                     barlat_card("1,7800,2e11,0.3,1,2e9,2e8,0",
                                 fmt::format("{},{},{},{},0,0,0,0", sh.m, sh.r0, sh.r45, sh.r90),
                                 axes, "2,0,0,0,0,0,0,0\n")) +
      pull_controls(2e-3) + "*END\n";
  solver::Simulation sim(read(deck), {});
  const auto& b = sim.state().shell_blocks[0];
  const material::BarlatParameters& p = b.barlat;
  const std::size_t points = static_cast<std::size_t>(b.points_per_element());
  std::vector<double> before(points, 0.0);
  double plastic_work = 0.0;
  while (!sim.finished()) {
    const auto& h = element::find_history(b, "effective_plastic_strain")->values;
    for (std::size_t q = 0; q < points; ++q) before[q] = h[q];
    const double area_before = b.area[0];
    sim.cycle();
    const auto& after = element::find_history(b, "effective_plastic_strain")->values;
    for (std::size_t q = 0; q < points; ++q) {
      // int sigma_y d eps over the step (trapezoid; exact for the linear law).
      double slope = 0.0;
      const double s0 = material::barlat::yield_stress(p, before[q], &slope);
      const double s1 = material::barlat::yield_stress(p, after[q], &slope);
      const double volume = 0.5 * (area_before + b.area[0]) * kThick * b.weight[q] / 2.0;
      plastic_work += 0.5 * (s0 + s1) * (after[q] - before[q]) * volume;
    }
  }
  double elastic = 0.0;
  const material::ElasticConstants m = material::make_elastic(kRho, kE, kNu);
  for (std::size_t q = 0; q < points; ++q) {
    const double* s = &b.stress[element::kShellStress * q];
    const double w =
        0.5 * ((s[0] * s[0] + s[1] * s[1] - 2.0 * kNu * s[0] * s[1]) / kE + s[2] * s[2] / m.shear +
               (s[3] * s[3] + s[4] * s[4]) / (b.shear_factor * m.shear));
    elastic += w * b.area[0] * kThick * b.weight[q] / 2.0;
  }
  const auto& en = sim.energy();
  const double stored = en.kinetic + elastic + plastic_work + en.hourglass;
  RecordProperty("energy_ratio", fmt::format("{:.5f}", stored / en.external_work));
  ASSERT_GT(plastic_work, 0.5 * en.external_work);  // mostly plastic
  EXPECT_NEAR(stored / en.external_work, 1.0, 0.01)
      << "external " << en.external_work << " kinetic " << en.kinetic << " elastic " << elastic
      << " plastic " << plastic_work << " hourglass " << en.hourglass;
  EXPECT_NEAR(en.kinetic + en.internal_work, en.external_work, 0.01 * en.external_work);
}

}  // namespace
}  // namespace rf::test
