// *MAT_JOHNSON_COOK with *EOS_LINEAR_POLYNOMIAL through the whole deck path. References that do
// not come from the material code:
//  - the Johnson-Cook law (A + B eps^N)(1 + C ln rate*)(1 - T*^M) evaluated at the plastic
//    strain measured from the kinematics (ln L/L0 minus the elastic strain), at the imposed rate;
//  - the adiabatic temperature rise: the plastic work integral of the measured stress over the
//    measured plastic strain, divided by rho CP;
//  - the EOS pressure polynomial at mu from the element's geometry, and (with energy terms) the
//    energy equation dE = -p dV integrated by an independent RK4 in the test;
//  - the work balance (energy ratio 1) of every run, and the stress work of the element kernel
//    against the internal energy the material carries.
// Constants: OFHC copper of Johnson & Cook (1983), Table 1: A 90 MPa, B 292 MPa, N 0.31, C 0.025,
// M 1.09, TM 1356 K, CP 383 J/(kg K), rho 8960 kg/m^3; G 46 GPa, K 137 GPa (bulk modulus as C1).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <numbers>

#include "deck_builder.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 8960.0, kG = 4.6e10, kK = 1.37e11;
constexpr double kA = 9.0e7, kB = 2.92e8, kN = 0.31, kM = 1.09, kTm = 1356.0, kTr = 293.0;
constexpr double kCp = 383.0;

double hardening(double eps) {
  return kA + kB * std::pow(std::max(eps, 0.0), kN);
}

// *MAT_JOHNSON_COOK (MID 1) + *EOS_LINEAR_POLYNOMIAL (EOSID 1, C1 = K).
std::string jc_material(double c, double epso, int vp, double tm, double cp,
                        const std::string& card3_tail = "-1e20,1") {
  return fmt::format(
      "*MAT_JOHNSON_COOK\n1,{},{},0,0,0,{}\n{},{},{},{},{},{},{},{}\n{},{}\n"
      "*EOS_LINEAR_POLYNOMIAL\n1,0,{}\n0,1\n",
      kRho, kG, vp, kA, kB, kN, c, kM, tm, kTr, epso, cp, card3_tail, kK);
}

// One unit cube on the symmetry planes with every node's motion prescribed (as in
// plasticity_test.cpp): face x = 1 moves with curve 1, faces y = 1 and z = 1 with curve 2.
std::string prescribed_deck(const std::string& material, const std::string& curves, double end_time,
                            int elform = 1) {
  BoxMesh mesh;
  std::string deck = "*KEYWORD\n" + mesh.keyword_text();
  deck +=
      fmt::format("*PART\ncube\n1,1,1,1,1\n*SECTION_SOLID\n1,{}\n*HOURGLASS\n1,4,0.1\n", elform);
  deck += material;
  std::vector<int> x0, x1, y0, y1, z0, z1;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= 1; ++i) {
        const int id = mesh.node_id(i, j, k);
        (i ? x1 : x0).push_back(id);
        (j ? y1 : y0).push_back(id);
        (k ? z1 : z0).push_back(id);
      }
  deck += node_set(1, x0) + node_set(2, x1) + node_set(3, y0) + node_set(4, y1) + node_set(5, z0) +
          node_set(6, z1);
  deck += "*BOUNDARY_SPC_SET\n1,0,1,0,0\n3,0,0,1,0\n5,0,0,0,1\n";
  deck += "*BOUNDARY_PRESCRIBED_MOTION_SET\n2,1,0,1,1.0\n4,2,0,2,1.0\n6,3,0,2,1.0\n";
  deck += curves;
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", end_time);
  return deck;
}

// Velocity curves for the side stretches x = exp(ax e(t)), y = z = exp(al e(t)), e' = rate(t).
std::string stretch_curves(const std::function<double(double)>& rate, double end, double ax,
                           double al) {
  const int n = 2000;
  std::string c1 = "*DEFINE_CURVE\n1\n", c2 = "*DEFINE_CURVE\n2\n";
  double e = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double t = end * i / n;
    if (i > 0) {
      const double t0 = end * (i - 1) / n;
      e += 0.5 * (rate(t0) + rate(t)) * (t - t0);
    }
    const double r = rate(t);
    c1 += fmt::format("{:.17g},{:.17g}\n", t, ax * r * std::exp(ax * e));
    c2 += fmt::format("{:.17g},{:.17g}\n", t, al * r * std::exp(al * e));
  }
  return c1 + "1e9,0\n" + c2 + "1e9,0\n";
}

std::function<double(double)> ramped(double r, double ramp) {
  return [r, ramp](double t) { return t < ramp ? r * t / ramp : r; };
}

struct Sample {
  double time;
  double log_strain;  // ln(x / X) of the face x = 1
  double stress;      // sigma_xx - sigma_yy
  double pressure;    // -tr(sigma) / 3
  double volume;      // x y z of the corner node (the element's volume)
  double eps_p, temperature, energy, relative_volume;
};

void run(const std::string& deck, const std::function<void(const Sample&)>& sample,
         double ratio_tolerance = 1e-3) {
  solver::Simulation sim(read(deck), {});
  const auto& nodes = sim.state().nodes;
  std::size_t tip = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.x0.x[i] > 0.5 && nodes.x0.y[i] > 0.5 && nodes.x0.z[i] > 0.5) tip = i;
  while (!sim.finished()) {
    sim.cycle();
    const auto& block = sim.state().hex_blocks[0];
    auto value = [&](const char* name) {
      const auto* h = element::find_history(block, name);
      EXPECT_NE(h, nullptr) << name;
      return h ? h->values[0] : 0.0;
    };
    const double* s = block.stress.data();
    sample({sim.state().time, std::log(nodes.x.x[tip]), s[0] - s[1], -(s[0] + s[1] + s[2]) / 3.0,
            nodes.x.x[tip] * nodes.x.y[tip] * nodes.x.z[tip], value("effective_plastic_strain"),
            value("temperature"), value("internal_energy"), value("relative_volume")});
  }
  std::printf("energy ratio %.9f\n", sim.energy().ratio());
  EXPECT_NEAR(sim.energy().ratio(), 1.0, ratio_tolerance);
}

double kinematic_plastic_strain(const Sample& s) {
  return s.log_strain - s.stress / (3.0 * kG);
}

// Isothermal (CP 0), rate-free (C 0) isochoric extension to ln(L/L0) = 0.6: the stress is
// A + B eps^N at the kinematic plastic strain, the history is that plastic strain.
class JohnsonCookIsothermal : public ::testing::TestWithParam<int> {};

TEST_P(JohnsonCookIsothermal, StressFollowsTheLaw) {
  const double rate = 4.0, end = 0.155;
  const std::string deck =
      prescribed_deck(jc_material(0.0, 1.0, 0, 0.0, 0.0),
                      stretch_curves(ramped(rate, 0.005), end, 1.0, -0.5), end, GetParam());
  double worst = 0.0, worst_history = 0.0, max_eps = 0.0;
  int n = 0;
  run(deck, [&](const Sample& s) {
    const double eps = kinematic_plastic_strain(s);
    if (eps < 0.01) return;
    ++n;
    max_eps = std::max(max_eps, eps);
    worst = std::max(worst, std::abs(s.stress - hardening(eps)) / hardening(eps));
    worst_history = std::max(worst_history, std::abs(s.eps_p - eps) / eps);
    EXPECT_NEAR(s.temperature, kTr, 1e-12);
  });
  std::printf("JC isothermal: %d samples to eps_p %.3f: law %.2e, history %.2e\n", n, max_eps,
              worst, worst_history);
  ASSERT_GT(n, 100);
  EXPECT_GT(max_eps, 0.55);
  EXPECT_LT(worst, 1e-5);
  EXPECT_LT(worst_history, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(JohnsonCookUniaxial, JohnsonCookIsothermal, ::testing::Values(1, 2),
                         [](const auto& info) { return "elform" + std::to_string(info.param); });

// VP 0: the rate term 1 + C ln(rate / EPSO) with the total effective strain rate, which for this
// path equals the imposed log-strain rate. Two rates; C exaggerated (0.1) so that the factors
// (1.46 and 1.60) differ clearly.
TEST(JohnsonCookUniaxial, RateFactorAtTwoRates) {
  const double c = 0.1, epso = 0.01;
  for (const double rate : {1.0, 4.0}) {
    const double end = 0.62 / rate, ramp = 0.02 / rate;
    const std::string deck = prescribed_deck(
        jc_material(c, epso, 0, 0.0, 0.0), stretch_curves(ramped(rate, ramp), end, 1.0, -0.5), end);
    const double factor = 1.0 + c * std::log(rate / epso);
    double worst = 0.0;
    int n = 0;
    run(deck, [&](const Sample& s) {
      const double eps = kinematic_plastic_strain(s);
      if (s.time <= ramp * 1.01 || eps < 0.05) return;
      ++n;
      const double law = hardening(eps) * factor;
      worst = std::max(worst, std::abs(s.stress - law) / law);
    });
    std::printf("JC VP 0 rate %g: factor %.4f, %d samples, worst %.2e\n", rate, factor, n, worst);
    ASSERT_GT(n, 50);
    EXPECT_LT(worst, 1e-5);
  }
}

// VP 1: the rate is the plastic strain rate, solved with the return; the measured rate of the
// history variable gives the factor.
TEST(JohnsonCookUniaxial, ViscoplasticRateIsThePlasticRate) {
  const double c = 0.1, epso = 0.01, rate = 4.0, end = 0.155, ramp = 0.005;
  const std::string deck = prescribed_deck(jc_material(c, epso, 1, 0.0, 0.0),
                                           stretch_curves(ramped(rate, ramp), end, 1.0, -0.5), end);
  double worst = 0.0, previous_eps = 0.0, previous_time = 0.0;
  int n = 0;
  run(deck, [&](const Sample& s) {
    const double plastic_rate = (s.eps_p - previous_eps) / (s.time - previous_time);
    previous_eps = s.eps_p;
    previous_time = s.time;
    if (s.time <= 2.0 * ramp || s.eps_p < 0.05) return;
    ++n;
    const double law = hardening(s.eps_p) * (1.0 + c * std::log(plastic_rate / epso));
    worst = std::max(worst, std::abs(s.stress - law) / law);
  });
  std::printf("JC VP 1: %d samples, worst %.2e\n", n, worst);
  ASSERT_GT(n, 50);
  EXPECT_LT(worst, 1e-6);
}

// Adiabatic heating with thermal softening: the temperature rise equals the plastic work of the
// measured stress over the measured plastic strain divided by rho CP; the stress is the law with
// the softening factor of that temperature.
TEST(JohnsonCookUniaxial, AdiabaticTemperatureRiseIsPlasticWorkOverRhoCp) {
  const double rate = 4.0, end = 0.155;
  const std::string deck = prescribed_deck(
      jc_material(0.0, 1.0, 0, kTm, kCp), stretch_curves(ramped(rate, 0.005), end, 1.0, -0.5), end);
  // Two quadratures of the work: the rectangle rule with the stress at the end of each step
  // (the implicit return's), and the trapezoidal rule, which differs from it by at most
  // sum |d(sigma) d(eps)| / 2.
  double rectangle = 0.0, trapezoid = 0.0, bound = 0.0, last_eps = 0.0, last_stress = 0.0;
  double worst_law = 0.0, last_rise = 0.0, worst_rise = 0.0, worst_trapezoid = 0.0;
  run(deck, [&](const Sample& s) {
    const double eps = std::max(kinematic_plastic_strain(s), 0.0);
    if (eps > 0.0) {
      rectangle += s.stress * (eps - last_eps);
      trapezoid += 0.5 * (s.stress + last_stress) * (eps - last_eps);
      bound += 0.5 * std::abs((s.stress - last_stress) * (eps - last_eps));
    }
    last_eps = eps;
    last_stress = s.stress;
    if (eps < 0.02) return;
    const double rise = s.temperature - kTr;
    last_rise = rise;
    worst_rise = std::max(worst_rise, std::abs(rise - rectangle / (kRho * kCp)) / rise);
    worst_trapezoid =
        std::max(worst_trapezoid, std::abs(rise - trapezoid / (kRho * kCp)) - bound / (kRho * kCp));
    const double soft = 1.0 - std::pow((s.temperature - kTr) / (kTm - kTr), kM);
    worst_law = std::max(worst_law, std::abs(s.stress - hardening(eps) * soft) / s.stress);
  });
  std::printf(
      "JC adiabatic: rise %.3f K, vs work/(rho cp) worst %.2e (trapezoid beyond its "
      "bound %.2e K), law worst %.2e\n",
      last_rise, worst_rise, worst_trapezoid, worst_law);
  EXPECT_GT(last_rise, 40.0);
  EXPECT_LT(worst_rise, 1e-4);
  EXPECT_LT(worst_trapezoid, 1e-3);
  // The yield stress of a step uses the temperature at its start (staggered heating): one
  // step's heating is ~1e-3 K of ~50 K.
  EXPECT_LT(worst_law, 2e-4);
}

// Homogeneous volumetric compression and expansion of one element: pressure against the EOS
// polynomial at mu from the element's geometry; with energy terms, against an RK4 solution of
// dE/dV = -p(mu, E), and the internal energy history against it.
struct EosCase {
  std::string name;
  std::array<double, 7> c;
  double e0;
  double mu_end;  // final mu (negative: expansion)
};

class EosCompression : public ::testing::TestWithParam<EosCase> {};

double eos_pressure(const std::array<double, 7>& c, double mu, double e) {
  const double mu2 = mu > 0.0 ? mu * mu : 0.0;
  return c[0] + c[1] * mu + c[2] * mu2 + c[3] * mu * mu * mu + (c[4] + c[5] * mu + c[6] * mu2) * e;
}

TEST_P(EosCompression, PressureIsThePolynomialOfMuAndEnergy) {
  const EosCase& k = GetParam();
  // V = exp(-e(t)): every side shrinks (or grows) like exp(-e/3).
  const double ev = std::log(1.0 + k.mu_end), end = 0.05, rate = ev / end;
  std::string eos = fmt::format("*EOS_LINEAR_POLYNOMIAL\n1");
  for (double v : k.c) eos += fmt::format(",{:.17g}", v);
  eos += fmt::format("\n{:.17g},1\n", k.e0);
  const std::string mat =
      fmt::format("*MAT_JOHNSON_COOK\n1,{},{}\n{},{},{}\n0,-1e20,1\n", kRho, kG, kA, kB, kN) + eos;
  const std::string deck = prescribed_deck(
      mat, stretch_curves([rate](double) { return rate; }, end, -1.0 / 3.0, -1.0 / 3.0), end);
  // Reference energy: RK4 on dE/dV = -p(1/V - 1, E) from V = 1.
  auto reference_energy = [&](double v_end) {
    const int steps = 20000;
    double e = k.e0, v = 1.0;
    const double h = (v_end - 1.0) / steps;
    auto f = [&](double vv, double ee) { return -eos_pressure(k.c, 1.0 / vv - 1.0, ee); };
    for (int i = 0; i < steps; ++i) {
      const double k1 = f(v, e), k2 = f(v + h / 2, e + h / 2 * k1),
                   k3 = f(v + h / 2, e + h / 2 * k2), k4 = f(v + h, e + h * k3);
      e += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      v += h;
    }
    return e;
  };
  double worst_p = 0.0, worst_e = 0.0, worst_v = 0.0, last_mu = 0.0;
  const double scale = kK * std::abs(k.mu_end);
  int n = 0;
  run(deck, [&](const Sample& s) {
    const double mu = 1.0 / s.volume - 1.0;
    last_mu = mu;
    if (n++ % 10 != 0) return;
    const double e_ref = reference_energy(s.volume);
    worst_p = std::max(worst_p, std::abs(s.pressure - eos_pressure(k.c, mu, e_ref)) / scale);
    worst_e = std::max(worst_e, std::abs(s.energy - e_ref) / (scale * std::abs(k.mu_end)));
    worst_v = std::max(worst_v, std::abs(s.relative_volume - s.volume));
  });
  std::printf("EOS %s: mu %.4f, pressure %.2e, energy %.2e, volume %.2e\n", k.name.c_str(), last_mu,
              worst_p, worst_e, worst_v);
  EXPECT_NEAR(last_mu, k.mu_end, 2e-3);
  EXPECT_LT(worst_p, 1e-4);
  EXPECT_LT(worst_e, 1e-4);
  EXPECT_LT(worst_v, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(
    JohnsonCook, EosCompression,
    ::testing::Values(
        EosCase{"polynomial_compression", {1e8, kK, 2.0 * kK, 1.0 * kK, 0, 0, 0}, 0.0, 0.25},
        EosCase{"polynomial_expansion", {0, kK, 5.0 * kK, 1.0 * kK, 0, 0, 0}, 0.0, -0.05},
        EosCase{"energy_terms", {0, kK, 1.5 * kK, 0, 1.96, 0.5, 0.3}, 2e8, 0.2}),
    [](const auto& info) { return info.param.name; });

// ---- Taylor impact: a copper bar on a rigid wall, quarter model ----
//
// Bar of radius R and length L along z, its face z = 0 on the frictionless wall z = 0 (normal
// +z), moving at -V. Quarter cross-section meshed as an O-grid: an inner square block of n x n
// elements with side 0.55 R and an outer ring of 2n x m elements out to the circle (no element
// with a 180 degree corner); nz layers along the bar. Symmetry planes x = 0 and y = 0.
struct TaylorMesh {
  int n = 2, m = 2, nz = 16;
  double radius = 3.81e-3, length = 25.4e-3;
};

struct TaylorResult {
  double final_length = 0.0, foot_diameter = 0.0, energy_ratio = 0.0, kinetic_left = 0.0;
  double material_energy = 0.0, internal = 0.0, hourglass = 0.0, max_eps = 0.0;
  double max_temperature = 0.0, axis_eps = 0.0, axis_temperature = 0.0;
  int elements = 0;
};

std::string copper_card() {
  return jc_material(0.025, 1.0, 0, kTm, kCp, "-1e20,1");
}

std::string taylor_deck(const TaylorMesh& t, double velocity, double end_time,
                        const std::string& material, int eosid) {
  const int n = t.n, m = t.m;
  const double a = 0.55 * t.radius;
  // Cross-section nodes: inner (i, j) in [0, n]^2, ring (s, k) with s in [0, 2n] along the
  // square's outer edges (x = a from y = 0 up, then y = a from x = a down to 0), k in [1, m].
  std::vector<std::array<double, 2>> xy;
  std::map<std::pair<int, int>, int> inner, ring;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      inner[{i, j}] = static_cast<int>(xy.size());
      xy.push_back({a * i / n, a * j / n});
    }
  auto edge = [&](int s) -> std::pair<int, int> {  // inner node on the square's outer edge
    return s <= n ? std::pair<int, int>{n, s} : std::pair<int, int>{2 * n - s, n};
  };
  for (int s = 0; s <= 2 * n; ++s) {
    ring[{s, 0}] = inner[edge(s)];
    const double theta = 0.5 * std::numbers::pi * s / (2.0 * n);
    const auto e = xy[inner[edge(s)]];
    for (int k = 1; k <= m; ++k) {
      const double f = static_cast<double>(k) / m;
      ring[{s, k}] = static_cast<int>(xy.size());
      xy.push_back({(1 - f) * e[0] + f * t.radius * std::cos(theta),
                    (1 - f) * e[1] + f * t.radius * std::sin(theta)});
    }
  }
  std::vector<std::array<int, 4>> quads;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      quads.push_back({inner[{i, j}], inner[{i + 1, j}], inner[{i + 1, j + 1}], inner[{i, j + 1}]});
  for (int s = 0; s < 2 * n; ++s)
    for (int k = 0; k < m; ++k)
      quads.push_back({ring[{s, k}], ring[{s, k + 1}], ring[{s + 1, k + 1}], ring[{s + 1, k}]});
  const int per_layer = static_cast<int>(xy.size());
  auto id = [&](int node, int layer) { return 1 + node + per_layer * layer; };
  std::string deck = "*KEYWORD\n*NODE\n";
  std::vector<int> sym_x, sym_y;
  for (int layer = 0; layer <= t.nz; ++layer)
    for (int k = 0; k < per_layer; ++k) {
      deck += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", id(k, layer), xy[k][0], xy[k][1],
                          t.length * layer / t.nz);
      if (std::abs(xy[k][0]) < 1e-12) sym_x.push_back(id(k, layer));
      if (std::abs(xy[k][1]) < 1e-12) sym_y.push_back(id(k, layer));
    }
  deck += "*ELEMENT_SOLID\n";
  int eid = 0;
  for (int layer = 0; layer < t.nz; ++layer)
    for (const auto& q : quads) {
      // Counter-clockwise quads seen from +z: positive volume with the upper layer on top.
      deck += fmt::format("{},1,{},{},{},{},{},{},{},{}\n", ++eid, id(q[0], layer), id(q[1], layer),
                          id(q[2], layer), id(q[3], layer), id(q[0], layer + 1),
                          id(q[1], layer + 1), id(q[2], layer + 1), id(q[3], layer + 1));
    }
  deck += fmt::format("*PART\nbar\n1,1,1,{},1\n*SECTION_SOLID\n1,1\n*HOURGLASS\n1,1,0.1\n", eosid);
  deck += material;
  deck += node_set(1, sym_x) + node_set(2, sym_y);
  deck += "*BOUNDARY_SPC_SET\n1,0,1,0,0\n2,0,0,1,0\n";
  deck += fmt::format("*INITIAL_VELOCITY\n0\n0,0,{:.17g}\n", -velocity);
  deck += "*RIGIDWALL_PLANAR\n0\n0,0,0,0,0,1,0\n";
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", end_time);
  return deck;
}

TaylorResult run_taylor(const TaylorMesh& t, double velocity, double end_time,
                        const std::string& material = copper_card(), int eosid = 1) {
  solver::Simulation sim(read(taylor_deck(t, velocity, end_time, material, eosid)), {});
  const double kinetic0 = sim.energy().kinetic;
  while (!sim.finished()) sim.cycle();
  TaylorResult r;
  const auto& x = sim.state().nodes.x;
  double top = 0.0, foot = 0.0;
  for (std::size_t i = 0; i < x.z.size(); ++i) {
    top = std::max(top, x.z[i]);
    if (x.z[i] < 0.05 * t.length) foot = std::max(foot, std::hypot(x.x[i], x.y[i]));
  }
  const auto& block = sim.state().hex_blocks[0];
  r.elements = static_cast<int>(block.size());
  r.final_length = top;
  r.foot_diameter = 2.0 * foot;
  const auto& e = sim.energy();
  r.energy_ratio = e.ratio();
  r.kinetic_left = kinetic0 > 0.0 ? e.kinetic / kinetic0 : e.kinetic;
  r.internal = e.internal();
  r.hourglass = e.hourglass;
  const auto* energy = element::find_history(block, "internal_energy");
  const auto* eps = element::find_history(block, "effective_plastic_strain");
  const auto* temp = element::find_history(block, "temperature");
  // The element on the axis at the impact face (the first one: inner block, first layer).
  r.axis_eps = eps->values[0];
  r.axis_temperature = temp->values[0];
  for (std::size_t k = 0; k < block.size(); ++k) {
    r.material_energy += energy->values[k] * block.volume0[k] * 4.0;  // quarter model: x 4
    r.max_eps = std::max(r.max_eps, eps->values[k]);
    r.max_temperature = std::max(r.max_temperature, temp->values[k]);
  }
  r.internal *= 4.0;
  r.hourglass *= 4.0;
  std::printf(
      "Taylor %d elements: L %.3f mm, foot D %.3f mm, ratio %.5f, kinetic left %.3f, internal %.2f "
      "J, material %.2f J, hourglass %.2f J, max eps_p %.2f, max T %.0f, axis element eps_p %.2f "
      "T %.0f\n",
      r.elements, r.final_length * 1e3, r.foot_diameter * 1e3, r.energy_ratio, r.kinetic_left,
      r.internal, r.material_energy, r.hourglass, r.max_eps, r.max_temperature, r.axis_eps,
      r.axis_temperature);
  return r;
}

// Coarse mesh in ctest (seconds); the finer meshes by hand (DISABLED_ below, docs/verification.md).
TEST(JohnsonCookTaylor, CopperBarOnRigidWallConservesEnergy) {
  const double velocity = 190.0, end = 80e-6;
  const TaylorResult r = run_taylor(TaylorMesh{}, velocity, end);
  const double kinetic0 =
      0.5 * kRho * std::numbers::pi * 3.81e-3 * 3.81e-3 * 25.4e-3 * velocity * velocity;
  // Work balance: kinetic energy into internal (plastic) energy, the wall doing no work on a
  // frictionless fixed plane.
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-2);
  // The bar has come (nearly) to rest: at most a few per cent of the impact energy is left as
  // rebound and elastic vibration.
  EXPECT_LT(r.kinetic_left, 0.05);
  // The material's internal energy (EOS energy equation) is the kernel's stress work.
  EXPECT_NEAR(r.material_energy, r.internal, 0.02 * kinetic0);
  EXPECT_LT(r.hourglass, 0.05 * kinetic0);
  // Plausibility bounds only (a bar that neither rebounds elastically nor flattens); the
  // comparison with a published result is the steel bar below, the mesh study in
  // docs/verification.md.
  EXPECT_GT(r.final_length, 0.55 * 25.4e-3);
  EXPECT_LT(r.final_length, 0.75 * 25.4e-3);
  EXPECT_GT(r.foot_diameter, 1.4 * 7.62e-3);
  EXPECT_LT(r.foot_diameter, 2.1 * 7.62e-3);
}

// The 42CrMo4 steel bar of the DynELA v4 documentation (O. Pantale, "DynELA impact sample
// cases", Documentation/Samples-Impacts.tex of github.com/pantale/DynELA-v.-4.0, 2020), computed
// there with Abaqus/Explicit and DynELA: height 32.4 mm, radius 3.2 mm, 287 m/s on a frictionless
// rigid target, 80 us; Johnson-Cook E 206.9 GPa, nu 0.3, A 806 MPa, B 614 MPa, C 0.0089,
// n 0.168, m 1.1, rho 7830, Cp 460, Taylor-Quinney 0.9, rate 1/s, T0 20 C, Tm 1540 C. Abaqus 3D:
// L_f 26.55 mm, D_f 11.22 mm (axisymmetric 26.56, 11.16; DynELA 26.52, 11.18). Linear pressure
// from E and nu (no EOS; what Abaqus' elasticity gives), VP 1 (Abaqus' plastic strain rate) and
// CP = 460 / 0.9 (the heat fraction 0.9 on the same temperature rise).
std::string steel_card() {
  return "*MAT_JOHNSON_COOK\n1,7830,7.957692307692308e10,2.069e11,0.3,0,1\n"
         "806e6,614e6,0.168,0.0089,1.1,1540,20,1\n511.1111111111111,-1e20,1\n";
}
const TaylorMesh kSteelCoarse{2, 2, 20, 3.2e-3, 32.4e-3};

// Tolerances from the mesh study (DISABLED_MeshConvergence, docs/verification.md): this 240-element
// mesh gives L_f +2.9 % and D_f -5.1 % off Abaqus; 1920 and 6480 elements converge to
// L_f 27.19 mm (+2.4 %) and D_f 11.24 mm (+0.2 %). The bounds hold the coarse mesh to its
// measured error plus a margin. DISABLED_Sensitivity on this mesh: without heating D_f is
// -11.8 % (caught); without the rate term L_f +1.2 %, D_f -2.2 % (not caught here: the rate
// term is verified by the one-element tests above).
TEST(JohnsonCookTaylor, SteelBarMatchesTheAbaqusReference) {
  const TaylorResult r = run_taylor(kSteelCoarse, 287.0, 80e-6, steel_card(), 0);
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-2);
  EXPECT_NEAR(r.final_length, 26.55e-3, 0.035 * 26.55e-3);
  EXPECT_NEAR(r.foot_diameter, 11.22e-3, 0.06 * 11.22e-3);
}

// What the coarse steel bar's L_f and D_f do when a term of the law is dropped (the tolerances
// above must not admit these).
TEST(JohnsonCookTaylor, DISABLED_Sensitivity) {
  std::string isothermal = steel_card(), rate_free = steel_card();
  isothermal.replace(isothermal.find("511.1111111111111"), 17, "0");
  rate_free.replace(rate_free.find("0.0089"), 6, "0");
  run_taylor(kSteelCoarse, 287.0, 80e-6, isothermal, 0);
  run_taylor(kSteelCoarse, 287.0, 80e-6, rate_free, 0);
}

TEST(JohnsonCookTaylor, DISABLED_MeshConvergence) {
  for (const TaylorMesh& t : {TaylorMesh{2, 2, 16}, TaylorMesh{4, 4, 32}, TaylorMesh{6, 6, 48}})
    run_taylor(t, 190.0, 80e-6);
  for (const TaylorMesh& t :
       {kSteelCoarse, TaylorMesh{4, 4, 40, 3.2e-3, 32.4e-3}, TaylorMesh{6, 6, 60, 3.2e-3, 32.4e-3}})
    run_taylor(t, 287.0, 80e-6, steel_card(), 0);
}

}  // namespace
}  // namespace rf::test
