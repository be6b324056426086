// Discrete elements (*ELEMENT_DISCRETE springs and dampers) against closed-form mechanics:
//  - a point mass m on a spring K with the other end held oscillates at w = sqrt(K / m); the
//    central difference runs it at w_h = (2 / dt) asin(w dt / 2) (e.g. Hughes, The Finite
//    Element Method, section 9.1), and its stability limit is dt = 2 / w;
//  - with a parallel damper c the free vibration decays with the damping ratio
//    zeta = c / (2 m w): successive peaks shrink by exp(2 pi zeta / sqrt(1 - zeta^2));
//  - two free masses joined by a spring and a damper keep their total momentum exactly, swing
//    at w = sqrt(K (1/m1 + 1/m2)), and kinetic + spring energy + damper dissipation stays equal
//    to the initial kinetic energy;
//  - a rigid body of mass M hung on a spring oscillates at sqrt(K / M) (forces on body nodes
//    go to the body);
//  - bad input is refused with file, line, keyword and field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

// Node 1 at the origin (held: no mass), node 2 at `tip` with a point mass; a spring and/or a
// damper between them, and an initial velocity v0 of node 2 along the spring.
struct SpringMass {
  double k = 800.0, m = 2.0, c = 0.0;
  std::array<double, 3> tip{0.6, 0.0, 0.8};  // length 1, inclined
  double v0 = 1.0;
  double tssfac = 0.02;
  double end = 2.0;
  double offset = 0.0;
};

std::string spring_mass_deck(const SpringMass& s) {
  std::string deck = "*KEYWORD\n*NODE\n1,0.0,0.0,0.0\n";
  deck += fmt::format("2,{:.17g},{:.17g},{:.17g}\n", s.tip[0], s.tip[1], s.tip[2]);
  deck += fmt::format("*ELEMENT_MASS\n1,2,{:.17g}\n", s.m);
  deck += "*SECTION_DISCRETE\n1,0\n0.0,0.0\n";
  deck += fmt::format("*PART\nspring\n1,1,1\n*MAT_SPRING_ELASTIC\n1,{:.17g}\n", s.k);
  deck += fmt::format("*ELEMENT_DISCRETE\n{:>8}{:>8}{:>8}{:>8}{:>8}{:>16}{:>8}{:>16.9g}\n", 1, 1, 1,
                      2, 0, "1.0", 0, s.offset);
  if (s.c > 0.0) {
    deck += fmt::format("*PART\ndamper\n2,1,2\n*MAT_DAMPER_VISCOUS\n2,{:.17g}\n", s.c);
    deck += "*ELEMENT_DISCRETE\n2,2,1,2\n";
  }
  const double l = std::hypot(s.tip[0], s.tip[1], s.tip[2]);
  deck += fmt::format("*INITIAL_VELOCITY_NODE\n2,{:.17g},{:.17g},{:.17g}\n", s.v0 * s.tip[0] / l,
                      s.v0 * s.tip[1] / l, s.v0 * s.tip[2] / l);
  deck += fmt::format("*CONTROL_TIMESTEP\n0.0,{:.17g}\n*CONTROL_TERMINATION\n{:.17g},\n*END\n",
                      s.tssfac, s.end);
  return deck;
}

// Velocity of node 2 along the spring at every cycle: times of its downward zero crossings and
// the peaks of the elongation between them.
struct Trace {
  std::vector<double> down_crossings;
  std::vector<double> peaks;  // |elongation| extremes, one per half period
  double dt = 0.0;
  double max_balance_error = 0.0;  // |KE + spring + damper - KE0| / KE0
  double energy_ratio = 0.0;
};

Trace run_trace(const std::string& deck, double kinetic0) {
  solver::Simulation sim(read(deck), {});
  const auto& nodes = sim.state().nodes;
  const std::int32_t tip = 1;  // dense index of node 2
  const double x0 = nodes.x0.x[tip], y0 = nodes.x0.y[tip], z0 = nodes.x0.z[tip];
  const double l0 = std::hypot(x0, y0, z0);
  auto elongation = [&] { return std::hypot(nodes.x.x[tip], nodes.x.y[tip], nodes.x.z[tip]) - l0; };
  auto axial_velocity = [&] {
    return (nodes.v.x[tip] * x0 + nodes.v.y[tip] * y0 + nodes.v.z[tip] * z0) / l0;
  };
  Trace trace;
  double t_prev = 0.0, v_prev = axial_velocity(), peak = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    const double t = sim.state().time, v = axial_velocity();
    peak = std::max(peak, std::abs(elongation()));
    if ((v_prev > 0.0) != (v > 0.0) && sim.state().cycle > 1) {
      // Velocities are half-step values: v^{n+1/2} belongs to t^n + dt / 2.
      const double tv_prev = t_prev - 0.5 * sim.state().dt_prev, tv = t - 0.5 * sim.state().dt;
      if (v_prev > 0.0)
        trace.down_crossings.push_back(tv_prev + (tv - tv_prev) * v_prev / (v_prev - v));
      trace.peaks.push_back(peak);
      peak = 0.0;
    }
    double spring = 0.0, damper = 0.0;
    for (const auto& block : sim.state().discrete_blocks) {
      spring += block.spring_energy;
      damper += block.damper_energy;
    }
    trace.max_balance_error =
        std::max(trace.max_balance_error,
                 std::abs(sim.energy().kinetic + spring + damper - kinetic0) / kinetic0);
    t_prev = t;
    v_prev = v;
  }
  trace.dt = sim.state().dt;
  trace.energy_ratio = sim.energy().ratio();
  return trace;
}

double period_of(const Trace& trace) {
  const auto& c = trace.down_crossings;
  EXPECT_GE(c.size(), 3u);
  if (c.size() < 2) return 0.0;
  return (c.back() - c.front()) / static_cast<double>(c.size() - 1);
}

TEST(Discrete, SpringMassOscillatesAtSqrtKOverM) {
  const SpringMass s;
  const double w = std::sqrt(s.k / s.m);
  const Trace trace = run_trace(spring_mass_deck(s), 0.5 * s.m * s.v0 * s.v0);
  const double period = period_of(trace);
  // The scheme's own frequency at this step, and the physical one it converges to.
  const double dt = 0.02 * 2.0 / w;
  const double w_h = 2.0 / dt * std::asin(0.5 * w * dt);
  std::printf(
      "spring-mass: period %.9f s, exact %.9f s (ratio %.3g - 1), central difference "
      "%.9f s; energy error %.3g\n",
      period, 2 * std::numbers::pi / w, period * w / (2 * std::numbers::pi) - 1.0,
      2 * std::numbers::pi / w_h, trace.max_balance_error);
  EXPECT_NEAR(trace.dt, dt, 1e-12 * dt);  // TSSFAC x 2 sqrt(m / K), the node 1 held
  EXPECT_NEAR(period * w / (2 * std::numbers::pi), 1.0, 2e-4);
  EXPECT_NEAR(period * w_h / (2 * std::numbers::pi), 1.0, 2e-5);
  // Kinetic + spring energy (the springs' work, summed as the internal energy is) equals the
  // initial kinetic energy to round-off: the half-step balance of the central difference.
  EXPECT_LT(trace.max_balance_error, 1e-10);
  EXPECT_NEAR(trace.energy_ratio, 1.0, 1e-9);
}

TEST(Discrete, TheStepFromTheSpringIsStableAtTheLimit) {
  SpringMass s;
  s.tssfac = 0.98;  // w dt = 1.96: just inside the limit 2
  s.end = 20.0;
  const double w = std::sqrt(s.k / s.m);
  const Trace trace = run_trace(spring_mass_deck(s), 0.5 * s.m * s.v0 * s.v0);
  const double dt = 0.98 * 2.0 / w;
  const double w_h = 2.0 / dt * std::asin(0.5 * w * dt);
  const double period = period_of(trace);
  std::printf(
      "spring-mass at TSSFAC 0.98: period %.6f s vs central-difference %.6f s, largest "
      "elongation %.6g (v0 / w = %.6g)\n",
      period, 2 * std::numbers::pi / w_h, *std::max_element(trace.peaks.begin(), trace.peaks.end()),
      s.v0 / w);
  // Bounded after about 90 periods (growth would be exponential past the limit).
  EXPECT_LT(*std::max_element(trace.peaks.begin(), trace.peaks.end()), 20.0 * s.v0 / w);
  // 2.3 steps per period: the linearly interpolated crossings are good to a few 1e-3.
  EXPECT_NEAR(period * w_h / (2 * std::numbers::pi), 1.0, 5e-3);
}

TEST(Discrete, DamperDecaysWithTheDampingRatio) {
  SpringMass s;
  const double w = std::sqrt(s.k / s.m);
  const double zeta = 0.05;
  s.c = 2.0 * s.m * w * zeta;
  s.end = 1.5;
  const Trace trace = run_trace(spring_mass_deck(s), 0.5 * s.m * s.v0 * s.v0);
  // Peaks a whole period apart (every second half-period peak, skipping the first, which
  // starts at zero elongation).
  ASSERT_GE(trace.peaks.size(), 8u);
  const std::size_t first = 2, last = trace.peaks.size() - 2;
  const double periods = 0.5 * static_cast<double>(last - first);
  const double decrement = std::log(trace.peaks[first] / trace.peaks[last]) / periods;
  const double measured =
      decrement / std::sqrt(4 * std::numbers::pi * std::numbers::pi + decrement * decrement);
  const double period = period_of(trace);
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  std::printf(
      "damped: zeta %.6f (expected %.6f), damped period %.6f s (expected %.6f), "
      "energy error %.3g\n",
      measured, zeta, period, 2 * std::numbers::pi / wd, trace.max_balance_error);
  EXPECT_NEAR(measured / zeta, 1.0, 1e-2);
  // The damper acts with the half-step velocity: the period shifts by O(zeta w dt) = 2e-3.
  EXPECT_NEAR(period * wd / (2 * std::numbers::pi), 1.0, 2e-3);
  // Kinetic + spring + dissipated: the damper's share is accounted.
  EXPECT_LT(trace.max_balance_error, 1e-10);
  EXPECT_NEAR(trace.energy_ratio, 1.0, 1e-9);
}

// Two free masses, spring and damper between them, initial velocities in 3D.
TEST(Discrete, TwoFreeMassesKeepMomentumAndEnergy) {
  const double m1 = 1.0, m2 = 3.0, k = 500.0, c = 2.0;
  std::string deck =
      "*KEYWORD\n*NODE\n1,0.0,0.0,0.0\n2,0.3,0.4,1.2\n*ELEMENT_MASS\n1,1,1.0\n2,2,3.0\n"
      "*SECTION_DISCRETE_TITLE\nlink\n5,0\n*PART\nspring\n1,5,11\n*PART\ndamper\n2,5,12\n"
      "*MAT_S01\n11,500.0\n*MAT_S02\n12,2.0\n*ELEMENT_DISCRETE\n10,1,1,2\n20,2,2,1\n"
      "*INITIAL_VELOCITY_NODE\n1,2.0,0.5,-1.0\n2,0.0,0.0,0.3\n"
      "*CONTROL_TIMESTEP\n0.0,0.05\n*CONTROL_TERMINATION\n1.0\n*END\n";
  solver::Simulation sim(read(deck), {});
  const double p0[3] = {m1 * 2.0, m1 * 0.5, m1 * -1.0 + m2 * 0.3};
  const double ke0 = 0.5 * m1 * (4.0 + 0.25 + 1.0) + 0.5 * m2 * 0.09;
  double worst_momentum = 0.0, worst_balance = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    for (int a = 0; a < 3; ++a) {
      worst_momentum = std::max(worst_momentum, std::abs(sim.energy().momentum[a] - p0[a]));
    }
    double stored = 0.0;
    for (const auto& block : sim.state().discrete_blocks) {
      stored += block.spring_energy + block.damper_energy;
    }
    worst_balance = std::max(worst_balance, std::abs(sim.energy().kinetic + stored - ke0) / ke0);
  }
  const double damper = sim.state().discrete_blocks[1].damper_energy;
  std::printf(
      "two masses: momentum drift %.3g, energy balance error %.3g, damper dissipated "
      "%.6g of %.6g, step %.6g (limit 2 / sqrt(K (1/m1 + 1/m2)) = %.6g)\n",
      worst_momentum, worst_balance, damper, ke0, sim.state().dt,
      2.0 / std::sqrt(k * (1.0 / m1 + 1.0 / m2)));
  EXPECT_LT(worst_momentum, 1e-12);
  EXPECT_LT(worst_balance, 1e-10);
  EXPECT_GT(damper, 0.03 * ke0);  // the damper did take energy out (most of KE0 is drift)
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-9);
  // The smaller of the spring's and the damper's limits, times TSSFAC.
  const double spring_dt = 2.0 / std::sqrt(k * (1.0 / m1 + 1.0 / m2));
  const double damper_dt = 2.0 / (c * (1.0 / m1 + 1.0 / m2));
  EXPECT_NEAR(sim.state().dt, 0.05 * std::min(spring_dt, damper_dt), 1e-15);
}

// A rigid block of mass M (MAT_RIGID) hangs from a held node on a spring: the spring force
// goes to the body, which oscillates at sqrt(K / M); the step comes from the body's mass.
TEST(Discrete, SpringOnARigidBodyMovesTheBody) {
  BoxMesh mesh;
  mesh.nx = mesh.ny = mesh.nz = 2;
  mesh.lx = mesh.ly = mesh.lz = 0.1;
  const double rho = 1000.0, k = 1.0e4;
  const double mass = rho * 0.1 * 0.1 * 0.1;  // 1 kg
  std::string deck = "*KEYWORD\n" + mesh.keyword_text();
  deck += fmt::format(
      "*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,1\n*MAT_RIGID\n1,{:.17g},2.1e11,0.3\n", rho);
  // Anchor 0.5 above the block's top centre (node (1,1,2) of the mesh).
  deck += "*NODE\n900,0.05,0.05,0.6\n";
  deck += fmt::format(
      "*SECTION_DISCRETE\n2,0\n*PART\nspring\n2,2,2\n*MAT_SPRING_ELASTIC\n2,{:.17g}\n"
      "*ELEMENT_DISCRETE\n500,2,900,{}\n",
      k, mesh.node_id(1, 1, 2));
  deck += "*INITIAL_VELOCITY\n0\n0.0,0.0,-0.5\n";
  deck += "*CONTROL_TIMESTEP\n0.0,0.02\n*CONTROL_TERMINATION\n0.5\n*END\n";
  solver::Simulation sim(read(deck), {});
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
  std::vector<double> crossings;
  double t_prev = 0.0, v_prev = sim.rigid_bodies().bodies[0].state.velocity.z();
  while (!sim.finished()) {
    sim.cycle();
    const double v = sim.rigid_bodies().bodies[0].state.velocity.z();
    const double t = sim.state().time;
    if (v_prev < 0.0 && v >= 0.0) {
      const double a = t_prev - 0.5 * sim.state().dt_prev, b = t - 0.5 * sim.state().dt;
      crossings.push_back(a + (b - a) * v_prev / (v_prev - v));
    }
    t_prev = t;
    v_prev = v;
  }
  ASSERT_GE(crossings.size(), 3u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double expected = 2 * std::numbers::pi * std::sqrt(mass / k);
  std::printf("rigid body on a spring: period %.6f s vs %.6f s, step %.6g\n", period, expected,
              sim.state().dt);
  EXPECT_NEAR(period / expected, 1.0, 1e-3);
  EXPECT_NEAR(sim.state().dt, 0.02 * 2.0 * std::sqrt(mass / k), 1e-12);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-9);
}

// OFFSET: a spring with a positive offset pulls at time zero, F = K OFFSET.
TEST(Discrete, OffsetGivesTensionAtTimeZero) {
  SpringMass s;
  s.offset = 0.01;
  s.v0 = 0.0;
  s.end = 1e-3;
  solver::Simulation sim(read(spring_mass_deck(s)), {});
  const auto& block = sim.state().discrete_blocks.at(0);  // forces at t = 0
  EXPECT_NEAR(block.axial_force[0], s.k * s.offset, 1e-9 * s.k * s.offset);
  sim.cycle();
  // The mass starts moving towards the held node.
  const auto& v = sim.state().nodes.v;
  EXPECT_LT(v.x[1] * s.tip[0] + v.z[1] * s.tip[2], 0.0);
}

// *MAT_SPRING_NONLINEAR_ELASTIC: a straight curve through the origin with slope K is the linear
// spring (same period); a bilinear curve gives the interpolated force at an OFFSET and the
// first segment's slope below the curve's start.
TEST(Discrete, NonlinearSpringFollowsItsCurve) {
  SpringMass s;
  std::string deck = spring_mass_deck(s);
  const std::string linear = "*MAT_SPRING_ELASTIC\n1,800\n";
  const std::size_t at = deck.find(linear);
  ASSERT_NE(at, std::string::npos);
  deck.replace(at, linear.size(),
               "*MAT_SPRING_NONLINEAR_ELASTIC\n1,7\n*DEFINE_CURVE\n7\n-1.0,-800.0\n1.0,800.0\n");
  const Trace trace = run_trace(deck, 0.5 * s.m * s.v0 * s.v0);
  const double w = std::sqrt(s.k / s.m);
  EXPECT_NEAR(period_of(trace) * w / (2 * std::numbers::pi), 1.0, 2e-4);
  EXPECT_LT(trace.max_balance_error, 1e-10);
  for (const auto& [offset, force] :
       {std::pair{0.02, 5.0 + 95.0 / 0.09 * 0.01}, std::pair{-0.01, -5.0}}) {
    SpringMass p;
    p.offset = offset;
    p.v0 = 0.0;
    p.end = 1e-3;
    std::string bilinear = spring_mass_deck(p);
    bilinear.replace(bilinear.find(linear), linear.size(),
                     "*MAT_S04\n1,7\n*DEFINE_CURVE\n7\n0.0,0.0\n0.01,5.0\n0.1,100.0\n");
    solver::Simulation sim(read(bilinear), {});
    EXPECT_NEAR(sim.state().discrete_blocks.at(0).axial_force[0], force, 1e-9 * std::abs(force))
        << "offset " << offset;
  }
}

TEST(Discrete, GlstatReportsSpringAndDamperEnergy) {
  SpringMass s;
  const double w = std::sqrt(s.k / s.m);
  s.c = 2.0 * s.m * w * 0.05;
  s.end = 0.5;
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_discrete_glstat";
  std::filesystem::remove_all(dir);
  {
    solver::Simulation sim(
        read(spring_mass_deck(s)),
        solver::SimulationOptions{.output_directory = dir, .write_fields = false});
    sim.run();
  }
  std::ifstream in(dir / "glstat.csv");
  std::string header, line, last;
  std::getline(in, header);
  // Columns by name (later versions append columns, docs/output.md).
  std::vector<std::string> names;
  {
    std::stringstream cells(header);
    for (std::string cell; std::getline(cells, cell, ',');) names.push_back(cell);
  }
  auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  ASSERT_LT(column("damper_energy"), names.size()) << header;
  while (std::getline(in, line)) last = line;
  std::vector<double> values;
  std::stringstream row(last);
  for (std::string cell; std::getline(row, cell, ',');) values.push_back(std::stod(cell));
  ASSERT_GE(values.size(), 23u);
  ASSERT_EQ(values.size(), names.size());
  const double kinetic = values[column("kinetic_energy")];
  const double internal = values[column("internal_energy")];
  const double spring = values[column("spring_energy")], damper = values[column("damper_energy")];
  const double ke0 = 0.5 * s.m * s.v0 * s.v0;
  std::printf("glstat: kinetic %.6g internal %.6g spring %.6g damper %.6g (initial %.6g)\n",
              kinetic, internal, spring, damper, ke0);
  // Both are part of the internal energy, which they make up here entirely.
  EXPECT_NEAR(spring + damper, internal, 1e-10 * ke0);
  EXPECT_NEAR(kinetic + spring + damper, ke0, 1e-10 * ke0);
  EXPECT_GT(damper, 0.2 * ke0);
}

// Reader and build errors: each names the file, line, keyword and field.
TEST(DiscreteInput, BadCardsAreInputErrors) {
  const std::string nodes = "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*ELEMENT_MASS\n1,2,1.0\n";
  const std::string end = "*CONTROL_TERMINATION\n0.01\n*END\n";
  auto expect_error = [&](const std::string& cards, const std::string& keyword,
                          const std::string& field, const std::string& words) {
    try {
      solver::Simulation sim(read(nodes + cards + end), {});
      ADD_FAILURE() << "expected an input error at " << keyword << " " << field;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
      EXPECT_NE(what.find(keyword), std::string::npos) << what;
      EXPECT_NE(what.find(field), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  };
  const std::string part = "*PART\ns\n1,1,1\n";
  const std::string section = "*SECTION_DISCRETE\n1,0\n";
  const std::string spring = "*MAT_SPRING_ELASTIC\n1,100.0\n";
  const std::string element = "*ELEMENT_DISCRETE\n1,1,1,2\n";
  // Missing section and material.
  expect_error(part + spring + element, "*PART", "SECID", "not defined");
  expect_error(part + section + element, "*PART", "MID", "not defined");
  // Non-positive stiffness and damping constant; the unsupported rate curve.
  expect_error(part + section + "*MAT_SPRING_ELASTIC\n1,0.0\n" + element, "*MAT_SPRING_ELASTIC",
               "K", "positive");
  expect_error(part + section + "*MAT_DAMPER_VISCOUS\n1,-2.0\n" + element, "*MAT_DAMPER_VISCOUS",
               "DC", "positive");
  expect_error(part + section + "*MAT_SPRING_NONLINEAR_ELASTIC\n1,3,4\n" + element,
               "*MAT_SPRING_NONLINEAR_ELASTIC", "LCR", "not supported");
  expect_error(part + section + "*MAT_SPRING_NONLINEAR_ELASTIC\n1,3\n" + element,
               "*MAT_SPRING_NONLINEAR_ELASTIC", "LCD", "not defined");
  // Torsional springs, clearance, deflection limits.
  expect_error(part + "*SECTION_DISCRETE\n1,1\n" + spring + element, "*SECTION_DISCRETE", "DRO",
               "torsional");
  expect_error(part + "*SECTION_DISCRETE\n1,0,0.0,0.0,0.5\n" + spring + element,
               "*SECTION_DISCRETE", "CL", "not supported");
  expect_error(part + "*SECTION_DISCRETE\n1,0\n0.0,0.2\n" + spring + element, "*SECTION_DISCRETE",
               "TDL", "not supported");
  // Orientation vectors, a repeated node, an undefined node, coincident nodes.
  expect_error(part + section + spring + "*ELEMENT_DISCRETE\n1,1,1,2,3\n", "*ELEMENT_DISCRETE",
               "VID", "not supported");
  expect_error(part + section + spring + "*ELEMENT_DISCRETE\n1,1,1,1\n", "*ELEMENT_DISCRETE", "N2",
               "repeats N1");
  expect_error(part + section + spring + "*ELEMENT_DISCRETE\n1,1,1,7\n", "*ELEMENT_DISCRETE", "N2",
               "not defined");
  expect_error("*NODE\n3,1,0,0\n" + part + section + spring + "*ELEMENT_DISCRETE\n1,1,2,3\n",
               "*ELEMENT_DISCRETE", "N2", "coincide");
  // A field that is not a number, with its line.
  expect_error(part + section + spring + "*ELEMENT_DISCRETE\n1,1,1,2,0,abc\n", "*ELEMENT_DISCRETE",
               "S", "abc");
  // A solid material on a discrete part, a spring material on a solid part.
  expect_error("*PART\ns\n1,1,1\n" + section + "*MAT_ELASTIC\n1,7800,2e11,0.3\n" + element, "*PART",
               "MID", "*MAT_SPRING_ELASTIC");
  expect_error(
      "*NODE\n3,0,1,0\n4,0,0,1\n5,1,1,0\n6,1,0,1\n7,0,1,1\n8,1,1,1\n"
      "*ELEMENT_SOLID\n1,1,1,2,5,3,4,6,8,7\n*PART\ns\n1,1,1\n*SECTION_SOLID\n1,1\n" +
          spring,
      "*PART", "MID", "serves only *ELEMENT_DISCRETE");
  // A discrete element in a part whose section is a *SECTION_SOLID.
  expect_error("*PART\ns\n1,1,1\n*SECTION_SOLID\n1,1\n" + spring + element, "*ELEMENT_DISCRETE",
               "PID", "not a *SECTION_DISCRETE");
}

}  // namespace
}  // namespace rf::test
