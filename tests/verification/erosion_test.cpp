// Element erosion (issue 17): elements deleted by their material's failure strain (FS, FAIL),
// by TDEL, and by *MAT_ADD_EROSION. References that do not come from the erosion code:
//  - the time of failure of a bar in uniaxial tension, from the kinematics of the pull and the
//    hardening law: the element goes when ln(L/L0) - sigma/E reaches FAIL with
//    sigma = SIGY + Ep FAIL (solids, shells, trusses);
//  - the work per volume of that path, sigma*^2/(2E) + SIGY FAIL + Ep FAIL^2/2 (the eroded
//    internal energy, up to the elastic volume change);
//  - stress criteria reached at sigma = E ln(L/L0) in elastic uniaxial stress;
//  - the element step L/c of a cube squeezed along one axis (nu = 0) against TDEL;
//  - conservation of momentum, angular momentum and energy when elements and nodes leave a
//    free body (what left is in the ledger).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/model_summary.hpp"
#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7800.0, kE = 2.0e11, kNu = 0.3, kSigy = 2.0e8, kEtan = 2.0e9;
constexpr double kEp = kE * kEtan / (kE - kEtan);
constexpr double kFail = 0.2;
constexpr double kPull = 0.1, kRamp = 0.1;  // m/s after a linear ramp of kRamp s

// Displacement of the pulled face at time t (the ramp of curve 1 to `speed` in `ramp` s), and
// its inverse.
double pulled(double t, double speed = kPull, double ramp = kRamp) {
  return t < ramp ? speed * t * t / (2.0 * ramp) : speed * (t - 0.5 * ramp);
}
double time_of_displacement(double u, double speed = kPull, double ramp = kRamp) {
  const double at_ramp_end = pulled(ramp, speed, ramp);
  return u < at_ramp_end ? std::sqrt(2.0 * ramp * u / speed) : u / speed + 0.5 * ramp;
}

// Analytic failure of a unit bar pulled in uniaxial stress: time and work per reference volume.
// The work is int sigma (V/V0) d eps along the path (elastic to SIGY/E, then linear hardening,
// d eps = (1 + Ep/E) d eps_p), with V/V0 = exp(volume_exponent(sigma, eps_p)): the element's
// own volume law (solids: elastic dilatation only; shells: fixed thickness; trusses: fixed
// area). Midpoint rule, 2 x 20000 points.
struct BarFailure {
  double time, work;
};
template <class VolumeExponent>
BarFailure bar_failure(double length, VolumeExponent volume_exponent) {
  const double stress = kSigy + kEp * kFail;
  const double strain = kFail + stress / kE;  // ln(L/L0) at failure
  const double time = time_of_displacement(length * (std::exp(strain) - 1.0));
  double work = 0.0;
  const int steps = 20000;
  const double ey = kSigy / kE;
  for (int i = 0; i < steps; ++i) {
    const double sigma = kE * (i + 0.5) * ey / steps;
    work += sigma * std::exp(volume_exponent(sigma, 0.0)) * ey / steps;
  }
  for (int i = 0; i < steps; ++i) {
    const double ep = (i + 0.5) * kFail / steps;
    const double sigma = kSigy + kEp * ep;
    work += sigma * std::exp(volume_exponent(sigma, ep)) * (1.0 + kEp / kE) * kFail / steps;
  }
  return {time, work};
}
// Solids: plastic flow keeps the volume, the elastic strain changes it by (1 - 2 nu) sigma / E.
BarFailure bar_failure(double length) {
  return bar_failure(length, [](double sigma, double) { return (1.0 - 2.0 * kNu) * sigma / kE; });
}

std::string pull_curve(double end_time, double speed = kPull, double ramp = kRamp) {
  // Free format (the comma): a shortest round-trip end time is wider than a 10-column field.
  return fmt::format("*DEFINE_CURVE\n1\n0,0\n{},{}\n1e9,{}\n*CONTROL_TERMINATION\n{},\n", ramp,
                     speed, speed, end_time);
}

// The cube pulled by the ramp of pull_curve.
std::string pulled_cube(const std::string& material, double end_time) {
  return cube_on_symmetry_planes(material, 1.0) + pull_curve(end_time) + "*END\n";
}

// Runs until the first erosion (or the end); returns the time of the cycle that deleted.
double run_to_erosion(solver::Simulation& sim) {
  while (!sim.finished()) {
    sim.cycle();
    if (!sim.erosion().events().empty()) return sim.erosion().events().front().time;
  }
  return -1.0;
}

TEST(Erosion, SolidInUniaxialTensionErodesAtTheFailureStrainWithItsWork) {
  const BarFailure expected = bar_failure(1.0);
  solver::Simulation sim(
      read(pulled_cube(fmt::format("*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{},{},{},{},{},{}\n", kRho,
                                   kE, kNu, kSigy, kEtan, kFail),
                       1.2 * expected.time)),
      {});
  const double step = sim.state().dt;
  const double time = run_to_erosion(sim);
  const auto& ledger = sim.erosion().ledger();
  std::printf("solid: eroded at %.6f s (analytic %.6f, step %.2e), work %.6e (analytic %.6e)\n",
              time, expected.time, step, ledger.internal_energy, expected.work);
  ASSERT_GT(time, 0.0) << "the element never eroded";
  EXPECT_NEAR(time, expected.time, 2e-3 * expected.time);
  EXPECT_NEAR(ledger.internal_energy / expected.work, 1.0, 5e-4);
  EXPECT_EQ(ledger.elements, 1);
  EXPECT_EQ(ledger.nodes, 8);  // every node lost its only element
  EXPECT_EQ(sim.state().hex_blocks[0].erosion.count, 1);
  // Nothing resists the pull any more: no internal energy left, the balance still closes.
  sim.run();
  // Left: the hourglass share of the element's work, which the hourglass column keeps too.
  EXPECT_LT(std::abs(sim.energy().internal()), 1e-7 * expected.work);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-3);
  for (const double f : sim.state().nodes.f_int.x) EXPECT_EQ(f, 0.0);
}

// A shell in membrane tension: every layer reaches FAIL together; the element goes when the last
// layer does. Same law, same analytic time (side 1 m, thickness 10 mm).
TEST(Erosion, ShellInUniaxialTensionErodesWhenItsLayersHaveFailed) {
  const double side = 1.0, thick = 0.01;
  std::string deck = "*KEYWORD\n";
  deck += fmt::format("*NODE\n1,0,0,0\n2,{0},0,0\n3,{0},{0},0\n4,0,{0},0\n", side);
  deck += "*ELEMENT_SHELL\n1,1,1,2,3,4\n";
  deck += fmt::format(
      "*PART\nsheet\n1,1,1,0,1\n*SECTION_SHELL\n1,2,0.8333333,3\n{0},{0},{0},{0}\n"
      "*HOURGLASS\n1,4,0.05\n",
      thick);
  deck += fmt::format("*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{},{},{},{},{},{}\n", kRho, kE, kNu,
                      kSigy, kEtan, kFail);
  deck +=
      "*BOUNDARY_SPC_NODE\n1,0,1,1,1,1,1,1\n4,0,1,0,1,1,1,1\n2,0,0,0,1,1,1,1\n"
      "3,0,0,0,1,1,1,1\n";
  deck += "*BOUNDARY_PRESCRIBED_MOTION_NODE\n2,1,0,1,1.0\n3,1,0,1,1.0\n";
  // Pulled at 1 m/s: the same strain path as the bar, 100 times faster in time.
  deck += fmt::format("*DEFINE_CURVE\n1,0,1.0,{}\n0,0\n{},{}\n1e9,{}\n", side / 1.0, kRamp, kPull,
                      kPull);
  // The curve scaled by SFO = side: the pull is kPull * side per second, so the strain follows
  // the unit bar's path in time.
  // A shell keeps its thickness (ISTUPD 0): its volume follows the in-plane strains,
  // ln(V/V0) = eps_x + eps_y = (1 - nu) sigma / E + eps_p / 2.
  const BarFailure unit =
      bar_failure(1.0, [](double sigma, double ep) { return (1.0 - kNu) * sigma / kE + 0.5 * ep; });
  deck += fmt::format("*CONTROL_TERMINATION\n{},\n*END\n", 1.2 * unit.time);
  solver::Simulation sim(read(deck), {});
  const double time = run_to_erosion(sim);
  const auto& ledger = sim.erosion().ledger();
  const double volume = side * side * thick;
  std::printf("shell: eroded at %.6f s (analytic %.6f), work %.6e (analytic %.6e)\n", time,
              unit.time, ledger.internal_energy, unit.work * volume);
  ASSERT_GT(time, 0.0) << "the shell never eroded";
  EXPECT_NEAR(time, unit.time, 2e-3 * unit.time);
  EXPECT_NEAR(ledger.internal_energy / (unit.work * volume), 1.0, 1e-3);
  EXPECT_EQ(sim.state().shell_blocks[0].erosion.count, 1);
}

// A truss (ELFORM 3) with *MAT_003 FS: one stress point, deleted when it reaches FS.
TEST(Erosion, TrussErodesAtItsFailureStrain) {
  const BarFailure unit = bar_failure(1.0);
  std::string deck = "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*ELEMENT_BEAM\n1,1,1,2\n";
  deck += "*PART\ntruss\n1,1,1\n*SECTION_BEAM\n1,3\n1e-4\n";
  // *MAT_003 with BETA 1 (isotropic): the same linear law as the 024 card.
  deck += fmt::format("*MAT_PLASTIC_KINEMATIC\n1,{},{},{},{},{},1.0\n0,0,{}\n", kRho, kE, kNu,
                      kSigy, kEtan, kFail);
  deck += "*BOUNDARY_SPC_NODE\n1,0,1,1,1,0,0,0\n2,0,0,1,1,0,0,0\n";
  deck += "*BOUNDARY_PRESCRIBED_MOTION_NODE\n2,1,0,1,1.0\n";
  deck += pull_curve(1.2 * unit.time) + "*END\n";
  solver::Simulation sim(read(deck), {});
  const double time = run_to_erosion(sim);
  // The truss keeps its area A (no lateral contraction): ln(V/V0) = ln(L/L0).
  const double work =
      bar_failure(1.0, [](double sigma, double ep) { return sigma / kE + ep; }).work;
  std::printf("truss: eroded at %.6f s (analytic %.6f), work %.6e (analytic %.6e)\n", time,
              unit.time, sim.erosion().ledger().internal_energy, work * 1e-4);
  ASSERT_GT(time, 0.0) << "the truss never eroded";
  EXPECT_NEAR(time, unit.time, 2e-3 * unit.time);
  EXPECT_NEAR(sim.erosion().ledger().internal_energy / (work * 1e-4), 1.0, 1e-3);
}

// *MAT_ADD_EROSION stress criteria on an elastic cube in uniaxial stress: sigma = E ln(L/L0),
// so each criterion is met at a known stretch.
struct StressCriterion {
  const char* name;
  std::string card;       // the *MAT_ADD_EROSION cards after MID
  double failure_stress;  // uniaxial stress at which the element must go
};

class AddErosionCriteria : public ::testing::TestWithParam<StressCriterion> {};

TEST_P(AddErosionCriteria, ElementGoesWhenTheUniaxialStressMeetsTheCriterion) {
  const StressCriterion& c = GetParam();
  const double strain = c.failure_stress / kE;
  const double expected = time_of_displacement(std::exp(strain) - 1.0);
  const std::string material =
      fmt::format("*MAT_ELASTIC\n1,{},{},{}\n*MAT_ADD_EROSION\n1{}\n", kRho, kE, kNu, c.card);
  solver::Simulation sim(read(pulled_cube(material, 1.5 * expected)), {});
  const double step = sim.state().dt;
  const double time = run_to_erosion(sim);
  std::printf("%s: eroded at %.6f s (analytic %.6f, step %.1e)\n", c.name, time, expected, step);
  ASSERT_GT(time, 0.0);
  // The criterion is checked once per step: the deletion falls within one step after the
  // analytic instant (plus the lateral-inertia wobble of one element, below 1e-3).
  EXPECT_GE(time, expected * (1.0 - 1e-3));
  EXPECT_LE(time, expected * (1.0 + 1e-3) + step);
}

INSTANTIATE_TEST_SUITE_P(
    Erosion, AddErosionCriteria,
    ::testing::Values(
        StressCriterion{"principal stress", ",0,0,0,0,0,1,1\n0,3e8,0,0,0,0,0,0\n", 3e8},
        StressCriterion{"von Mises", ",0,0,0,0,0,1,1\n0,0,2.5e8,0,0,0,0,0\n", 2.5e8},
        // Tension cut-off: p = -sigma/3 <= MNPRES.
        StressCriterion{"minimum pressure", ",0,0,0,0,0,1,1\n-1e8,0,0,0,0,0,0,0\n", 3e8},
        // Both at once (NCS 2): the later of the two, sigma = 3.5e8.
        StressCriterion{"two criteria at once", ",0,0,0,0,0,1,2\n0,3.5e8,2e8,0,0,0,0,0\n", 3.5e8},
        // Exclusion number 1234: SIGVM = 1234 is off, SIGP1 acts.
        StressCriterion{"exclusion number", ",1234,0,0,0,0,1,1\n0,2e8,1234,0,0,0,0,0\n", 2e8}),
    [](const ::testing::TestParamInfo<StressCriterion>& info) {
      std::string name = info.param.name;
      for (char& ch : name)
        if (ch == ' ') ch = '_';
      return name;
    });

// Tuler-Butcher (*MAT_ADD_EROSION SIGTH, IMPULSE): the element goes when
// int_0^t max(0, sigma_1 - SIGTH)^2 dt reaches IMPULSE. The elastic cube in uniaxial stress has
// sigma_1 = E ln(L/L0) on the known pull u(t), so the failure time comes from a quadrature of that
// law (Simpson, 2 x 10^5 intervals), not from the solver's stresses. The evaluation once per step
// with the stress at its end may fail it up to one step early.
TEST(Erosion, TulerButcherImpulseFailsTheElementAtTheIntegratedStressImpulse) {
  constexpr double kThreshold = 1e8, kImpulse = 5e14;
  auto excess_squared = [](double t) {
    const double sigma = kE * std::log(1.0 + pulled(t));
    const double x = std::max(0.0, sigma - kThreshold);
    return x * x;
  };
  // Bisection on the quadrature from 0 to t.
  auto impulse_until = [&](double t) {
    const int n = 200000;
    const double h = t / n;
    double sum = excess_squared(0.0) + excess_squared(t);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * excess_squared(i * h);
    return sum * h / 3.0;
  };
  double lo = 0.0, hi = 0.2;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (impulse_until(mid) < kImpulse ? lo : hi) = mid;
  }
  const double expected = 0.5 * (lo + hi);
  const std::string material = fmt::format(
      "*MAT_ELASTIC\n1,{},{},{}\n*MAT_ADD_EROSION\n1,0,0,0,0,0,1,1\n"
      "0,0,0,0,0,{},{},0\n",
      kRho, kE, kNu, kThreshold, kImpulse);
  solver::Simulation sim(read(pulled_cube(material, 1.5 * expected)), {});
  const double step = sim.state().dt;
  const double time = run_to_erosion(sim);
  std::printf("Tuler-Butcher: eroded at %.6f s (analytic %.6f, step %.1e, stress there %.4g)\n",
              time, expected, step, kE * std::log(1.0 + pulled(expected)));
  ASSERT_GT(time, 0.0) << "the element never eroded";
  EXPECT_GE(time, expected * (1.0 - 1e-3) - step);
  EXPECT_LE(time, expected * (1.0 + 1e-3) + step);
  ASSERT_EQ(sim.erosion().events().size(), 1u);
  EXPECT_NE(sim.erosion().events().front().criterion.find("stress impulse"), std::string::npos)
      << sim.erosion().events().front().criterion;
  // A threshold above the largest stress of the run: nothing accumulates, nothing fails.
  const std::string high =
      fmt::format("*MAT_ELASTIC\n1,{},{},{}\n*MAT_ADD_EROSION\n1,0,0,0,0,0,1,1\n0,0,0,0,0,{},1,0\n",
                  kRho, kE, kNu, 2.0 * kE * std::log(1.0 + pulled(1.5 * expected)));
  solver::Simulation quiet(read(pulled_cube(high, 1.5 * expected)), {});
  EXPECT_LT(run_to_erosion(quiet), 0.0);
}

// TDEL: a cube (nu = 0) squeezed along x; its step is L/c with c = sqrt(E/rho), so it is deleted
// when L falls to c TDEL.
TEST(Erosion, ElementGoesWhenItsStepFallsBelowTdel) {
  const double c = std::sqrt(kE / kRho);
  const double tdel = 0.8 / c;  // L = 0.8
  // Squeezed at 20 m/s after a 1 ms ramp: L = 0.8 at t = 0.2 / 20 + 0.5 ms.
  std::string deck = cube_on_symmetry_planes(
      fmt::format("*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{},{},0.0,1e12,0,0,{:.17g}\n"
                  "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n",
                  kRho, kE, tdel),
      -1.0);
  deck += "*DEFINE_CURVE\n1\n0,0\n1e-3,20\n1e9,20\n*CONTROL_TERMINATION\n0.02\n*END\n";
  const double expected = 0.2 / 20.0 + 0.5e-3;
  solver::Simulation sim(read(deck), {});
  const double step = sim.state().dt;
  const double time = run_to_erosion(sim);
  std::printf("TDEL: eroded at %.6f s (analytic %.6f, step %.1e)\n", time, expected, step);
  ASSERT_GT(time, 0.0);
  EXPECT_GE(time, expected - 1e-9);
  EXPECT_LE(time, expected + 1.01 * step);
  ASSERT_FALSE(sim.erosion().events().empty());
  EXPECT_NE(sim.erosion().events().front().criterion.find("TDEL"), std::string::npos);
}

// *CONTROL_TIMESTEP ERODE with *CONTROL_TERMINATION DTMIN 0.5: TSMIN is half the first step,
// so an element of a family ERODE names goes when its step L/c (nu = 0, no bulk viscosity) has
// halved, at L = 0.5; the same element of a family it does not name stops the run there ("time
// step collapsed"). Squeezed at 20 m/s after a 1 ms ramp: L = 0.5 at t = 0.5 / 20 + 0.5 ms.
struct ErodeCase {
  const char* name;
  const char* family;
  int erode;
  bool erodes;
};

std::string squeezed(const std::string& family, int erode) {
  const std::string elastic = fmt::format("*MAT_ELASTIC\n1,{},{},0.0\n", kRho, kE);
  std::string deck;
  if (family == "solid") {
    deck = cube_on_symmetry_planes(elastic, -1.0);
  } else if (family == "shell") {
    deck = "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n*ELEMENT_SHELL\n1,1,1,2,3,4\n";
    deck += "*PART\nsheet\n1,1,1\n*SECTION_SHELL\n1,2,0.8333333,2\n0.01,0.01,0.01,0.01\n" + elastic;
    deck +=
        "*BOUNDARY_SPC_NODE\n1,0,1,1,1,1,1,1\n2,0,0,1,1,1,1,1\n3,0,0,0,1,1,1,1\n"
        "4,0,1,0,1,1,1,1\n*BOUNDARY_PRESCRIBED_MOTION_NODE\n2,1,0,1,-1.0\n3,1,0,1,-1.0\n";
  } else {
    deck = "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*ELEMENT_BEAM\n1,1,1,2\n";
    deck += "*PART\ntruss\n1,1,1\n*SECTION_BEAM\n1,3\n1e-4\n" + elastic;
    deck += "*BOUNDARY_SPC_NODE\n1,0,1,1,1,0,0,0\n2,0,0,1,1,0,0,0\n";
    deck += "*BOUNDARY_PRESCRIBED_MOTION_NODE\n2,1,0,1,-1.0\n";
  }
  deck += "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n";
  deck += fmt::format("*CONTROL_TIMESTEP\n0,0.9,0,0,0,0,{}\n", erode);
  return deck + "*DEFINE_CURVE\n1\n0,0\n1e-3,20\n1e9,20\n*CONTROL_TERMINATION\n0.05,0,0.5\n*END\n";
}

class ErodeBelowMinimumStep : public ::testing::TestWithParam<ErodeCase> {};

TEST_P(ErodeBelowMinimumStep, ElementOfANamedFamilyGoesOthersStopTheRun) {
  const ErodeCase& k = GetParam();
  const double expected = 0.5 / 20.0 + 0.5e-3;
  solver::Simulation sim(read(squeezed(k.family, k.erode)), {});
  const double step = sim.state().dt;
  if (!k.erodes) {
    try {
      sim.run();
      FAIL() << "the run went on below TSMIN";
    } catch (const SolverError& e) {
      EXPECT_NE(std::string(e.what()).find("collapsed"), std::string::npos) << e.what();
    }
    EXPECT_GE(sim.state().time, expected - 1.01 * step);
    EXPECT_LE(sim.state().time, expected + 1.01 * step);
    return;
  }
  const double time = run_to_erosion(sim);
  std::printf("%s: eroded at %.6f s (analytic %.6f, step %.1e)\n", k.name, time, expected, step);
  ASSERT_GT(time, 0.0);
  EXPECT_GE(time, expected - 1e-9);
  EXPECT_LE(time, expected + 1.01 * step);
  ASSERT_FALSE(sim.erosion().events().empty());
  EXPECT_NE(sim.erosion().events().front().criterion.find("ERODE"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Erosion, ErodeBelowMinimumStep,
                         ::testing::Values(ErodeCase{"solid_1", "solid", 1, true},
                                           ErodeCase{"solid_111", "solid", 111, true},
                                           ErodeCase{"solid_10", "solid", 10, false},
                                           ErodeCase{"shell_10", "shell", 10, true},
                                           ErodeCase{"shell_1", "shell", 1, false},
                                           ErodeCase{"truss_100", "truss", 100, true},
                                           ErodeCase{"truss_11", "truss", 11, false}),
                         [](const auto& info) { return std::string(info.param.name); });

// A free block of two elements, moving and spinning, deleted whole by FAILTM: every node is
// removed, and what moved leaves with the ledger: momentum, angular momentum and kinetic energy
// before = ledger after (exactly, up to round-off), and the balance closes.
TEST(Erosion, FreeBodyDeletedByFailureTimeHandsItsMotionToTheLedger) {
  Block block;
  block.nx = 2;
  block.lx = 2.0;
  std::string deck = "*KEYWORD\n" + block.text();
  deck += elastic(1, kRho, 2e9, 0.3, 4);
  // FAILTM (card 2, eighth field) = 20 ms, about ten steps in.
  deck += "*MAT_ADD_EROSION\n1,0,0,0,0,0,1,1\n0,0,0,0,0,0,0,0.02\n";
  deck += "*INITIAL_VELOCITY_GENERATION\n1,2,30.0,3,-2,1\n1.0,0.5,0.5,0,0,1\n";
  deck += "*CONTROL_TIMESTEP\n0,0.5\n*CONTROL_TERMINATION\n0.05\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.cycle();
  ASSERT_TRUE(sim.erosion().events().empty());
  const auto before = sim.energy();
  std::array<double, 3> momentum{}, angular{};
  for (int k = 0; k < 3; ++k) {
    momentum[k] = before.momentum[k];
    angular[k] = before.angular_momentum[k];
  }
  const double kinetic = before.kinetic;
  const double time = run_to_erosion(sim);
  ASSERT_GT(time, 0.0);
  EXPECT_GE(time, 0.02);
  const auto& l = sim.erosion().ledger();
  EXPECT_EQ(l.elements, 2);
  EXPECT_EQ(l.nodes, 12);
  const double scale_p = std::hypot(momentum[0], momentum[1], momentum[2]);
  const double scale_h = std::hypot(angular[0], angular[1], angular[2]);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(l.momentum[k], momentum[k], 1e-12 * scale_p) << k;
    EXPECT_NEAR(l.angular_momentum[k], angular[k], 1e-10 * scale_h) << k;
  }
  // What the block held went to the ledger's two accounts (kinetic, strain), except the work of
  // its hourglass and bulk viscosity forces, which stays in those columns.
  const double artificial = sim.energy().hourglass + sim.energy().bulk_viscosity;
  EXPECT_NEAR(l.kinetic_energy + l.internal_energy + artificial, kinetic, 1e-6 * kinetic);
  sim.run();
  EXPECT_EQ(sim.energy().kinetic, 0.0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(sim.energy().momentum[k], 0.0);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-9);
}

// A bar flying apart: its two halves move away from each other unevenly; elements in the middle
// stretch, yield and reach FS; the halves then fly free. Momentum (with what left in the ledger)
// and energy (kinetic + internal + eroded) are conserved.
TEST(Erosion, BarTornApartConservesMomentumAndEnergy) {
  Block block;
  block.nx = 8;
  block.lx = 0.8;
  block.ly = block.lz = 0.1;
  std::string deck = "*KEYWORD\n" + block.text();
  deck += "*PART\nbar\n1,1,1,0,1\n*SECTION_SOLID\n1,1\n*HOURGLASS\n1,4,0.1\n";
  deck += fmt::format("*MAT_PLASTIC_KINEMATIC\n1,{},{},{},{},{},1.0\n0,0,0.02\n", kRho, kE, kNu,
                      kSigy, kEtan);
  // Left half at -20 m/s, right half at +60 m/s (nodes x < 0.4 and x > 0.4; the middle plane
  // at +20 m/s): a net momentum along x, and a sideways drift of the right half.
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= 8; ++i) {
        const double vx = i < 4 ? -20.0 : (i == 4 ? 20.0 : 60.0);
        deck += fmt::format("{},{},{},0\n", block.node(i, j, k), vx, i > 4 ? 5.0 : 0.0);
      }
  deck += "*CONTROL_TIMESTEP\n0,0.5\n*CONTROL_TERMINATION\n6e-3\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.cycle();
  std::array<double, 3> momentum{};
  for (int k = 0; k < 3; ++k) momentum[k] = sim.energy().momentum[k];
  sim.run();
  const auto& l = sim.erosion().ledger();
  const auto* eps = element::find_history(sim.state().hex_blocks[0], "effective_plastic_strain");
  double largest = 0.0;
  for (const double e : eps->values) largest = std::max(largest, e);
  std::printf("torn bar: largest plastic strain %.4f, enabled %d\n", largest,
              int(sim.state().hex_blocks[0].erosion.enabled));
  std::printf("torn bar: %lld elements and %lld nodes eroded, ratio %.12f, eroded work %.4e J\n",
              static_cast<long long>(l.elements), static_cast<long long>(l.nodes),
              sim.energy().ratio(), l.internal_energy);
  EXPECT_GE(l.elements, 1);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(sim.energy().momentum[k] + l.momentum[k], momentum[k], 1e-9 * 2000.0) << k;
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
  EXPECT_GT(l.internal_energy, 0.0);
}

// Johnson-Cook fracture: a cube in uniaxial stress (triaxiality 1/3, D4 = D5 = 0) fails when
// its plastic strain reaches eps_f = D1 + D2 exp(D3 / 3); the damage then is 1.
TEST(Erosion, JohnsonCookFractureAtTheFailureStrainOfUniaxialStress) {
  const double a = 2e8, b = 5e8, d1 = 0.05, d2 = 0.3, d3 = -1.5;
  const double fracture = d1 + d2 * std::exp(d3 / 3.0);
  const double stress = a + b * fracture;  // N = 1
  const double expected = time_of_displacement(std::exp(fracture + stress / kE) - 1.0);
  const std::string material =
      fmt::format("*MAT_JOHNSON_COOK\n1,{},{},{},{}\n{},{},1.0\n0,-1e12,1,0,{},{},{},0\n0\n", kRho,
                  kE / (2.0 * (1.0 + kNu)), kE, kNu, a, b, d1, d2, d3);
  solver::Simulation sim(read(pulled_cube(material, 1.2 * expected)), {});
  const double step = sim.state().dt;
  const double time = run_to_erosion(sim);
  const auto* damage = element::find_history(sim.state().hex_blocks[0], "damage");
  const auto* eps = element::find_history(sim.state().hex_blocks[0], "effective_plastic_strain");
  std::printf(
      "Johnson-Cook fracture: eroded at %.6f s (analytic %.6f, step %.1e), eps_p %.5f "
      "(eps_f %.5f), damage %.5f\n",
      time, expected, step, eps->values[0], fracture, damage->values[0]);
  ASSERT_GT(time, 0.0);
  EXPECT_NEAR(time, expected, 2e-3 * expected);
  EXPECT_NEAR(eps->values[0], fracture, 2e-3 * fracture);
  EXPECT_GE(damage->values[0], 1.0);
  EXPECT_NE(sim.erosion().events().front().criterion.find("Johnson-Cook"), std::string::npos);
}

// A projectile perforates an erodible plate (contact with the faces erosion uncovers): no
// supports, so the momentum of projectile + plate + what left with removed nodes is the
// projectile's initial momentum, and the energy balance closes with the contact and eroded
// energies.
TEST(Erosion, ProjectilePerforatesAnErodiblePlateWithMomentumAndEnergyKept) {
  Block plate;
  plate.nx = plate.ny = 6;
  plate.nz = 2;
  plate.lx = plate.ly = 0.06;
  plate.lz = 0.01;
  plate.local = Eigen::Vector3d(-0.03, -0.03, -0.01);
  plate.pid = 1;
  Block bullet;
  bullet.nx = bullet.ny = bullet.nz = 2;
  bullet.lx = bullet.ly = 0.012;
  bullet.lz = 0.02;
  bullet.local = Eigen::Vector3d(-0.006, -0.006, 0.0005);
  bullet.first_node = 1000;
  bullet.first_element = 1000;
  bullet.pid = 2;
  std::string deck = "*KEYWORD\n" + plate.text() + bullet.text();
  deck += "*PART\nplate\n1,1,1,0,1\n*SECTION_SOLID\n1,1\n*HOURGLASS\n1,4,0.05\n";
  deck += fmt::format("*MAT_PLASTIC_KINEMATIC\n1,{},{},{},{},{},1.0\n0,0,0.25\n", kRho, kE, kNu,
                      kSigy, kEtan);
  deck += fmt::format(
      "*PART\nbullet\n2,2,2,0,2\n*SECTION_SOLID\n2,1\n*HOURGLASS\n2,4,0.05\n"
      "*MAT_ELASTIC\n2,{},{},{}\n",
      3.0 * kRho, 3.0 * kE, kNu);
  deck += "*INITIAL_VELOCITY_GENERATION\n2,2,0,0,0,-600\n0,0,0,0,0,0\n";
  deck += "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n2,1,3,3\n0\n1,1\n";
  deck += "*CONTROL_TIMESTEP\n0,0.6\n*CONTROL_TERMINATION\n1.2e-4\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.cycle();
  std::array<double, 3> momentum{};
  for (int k = 0; k < 3; ++k) momentum[k] = sim.energy().momentum[k];
  double worst_ratio = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  const auto& l = sim.erosion().ledger();
  double bullet_vz = 0.0, bullet_mass = 0.0;
  const auto& nodes = sim.state().nodes;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.id[i] < 1000) continue;
    bullet_vz += nodes.mass[i] * nodes.v.z[i];
    bullet_mass += nodes.mass[i];
  }
  std::printf(
      "perforation: %lld elements and %lld nodes eroded, bullet %.1f m/s, worst |ratio - 1| "
      "%.2e, eroded work %.4e J, contact energy %.4e J\n",
      static_cast<long long>(l.elements), static_cast<long long>(l.nodes), bullet_vz / bullet_mass,
      worst_ratio, l.internal_energy, sim.energy().contact_energy);
  EXPECT_GE(l.elements, 4);
  const double scale = std::abs(momentum[2]);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(sim.energy().momentum[k] + l.momentum[k], momentum[k], 1e-9 * scale) << k;
  // Every cycle: the work balance closes with the eroded and contact energies (measured 9e-16).
  EXPECT_LT(worst_ratio, 1e-8);
}

// --- Strain criteria (MXEPS, MNEPS, EFFEPS, EPSSH)
// -------------------------------------------------- Every node is prescribed, so the deformation
// is homogeneous and known in closed form, and so are the principal logarithmic strains e1 >= e2 >=
// e3 that the criteria read:
//  - solid in simple shear x = X + gamma Y: e = (g, 0, -g), g = asinh(gamma / 2);
//  - shell stretched equi-biaxially by 1 + u: e = (b, b, -2 b), b = ln(1 + u) (the thickness
//    strain volume-preserving, as documented);
//  - shell turned 45 degrees in its plane, stretched along x with y held (plane strain):
//    e = (b, 0, -b), the element's own axes see shear (tensor xy = b/2 at small strain);
//  - truss stretched by 1 + u: e = (b, -b/2, -b/2).
// Each criterion equals factor x base (base = g or b); the element goes at base = limit / factor.
enum class Strain { kMax, kMin, kEffective, kShear };
constexpr double kStrainLimit = 0.1;
// Every node is prescribed, so inertia plays no part: pulled ten times faster than the bars
// above (a strain increment per step of 0.2 % of the limit).
constexpr double kStrainPull = 1.0, kStrainRamp = 0.01;
std::string strain_pull_curve(double end_time) {
  return pull_curve(end_time, kStrainPull, kStrainRamp);
}

std::string strain_card(Strain c) {
  switch (c) {
    case Strain::kMax:
      return fmt::format("*MAT_ADD_EROSION\n1\n0,0,0,{}\n", kStrainLimit);
    case Strain::kMin:
      return fmt::format("*MAT_ADD_EROSION\n1,0,0,{}\n", -kStrainLimit);
    case Strain::kEffective:
      return fmt::format("*MAT_ADD_EROSION\n1,0,0,0,{}\n", kStrainLimit);
    case Strain::kShear:
      return fmt::format("*MAT_ADD_EROSION\n1\n0,0,0,0,{}\n", kStrainLimit);
  }
  return "";
}

// Factors of (max, min, effective, shear) for the strain triples above.
constexpr double kRoot3 = 1.7320508075688772;
constexpr double kPlaneStrainFactors[4] = {1.0, 1.0, 2.0 / kRoot3, 1.0};  // (b, 0, -b)
constexpr double kBiaxialFactors[4] = {1.0, 2.0, 2.0, 1.5};               // (b, b, -2b)
constexpr double kTrussFactors[4] = {1.0, 0.5, 1.0, 0.75};                // (b, -b/2, -b/2)

std::string elastic_card() {
  return fmt::format("*MAT_ELASTIC\n1,{},{},{}\n", kRho, kE, kNu);
}

// One solid (ELFORM 1, 2 hexahedron or ELFORM 10 tetrahedron) of unit height in simple shear:
// the nodes at y = 1 move along x by the pull, those at y = 0 are held, y and z held everywhere.
std::string sheared_solid(int elform, Strain c, double end_time) {
  std::string deck = "*KEYWORD\n";
  std::vector<int> all, top, bottom;
  if (elform == 10) {
    deck += "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n*ELEMENT_SOLID\n1,1,1,2,3,4\n";
    all = {1, 2, 3, 4};
    top = {3};
    bottom = {1, 2, 4};
  } else {
    BoxMesh mesh;
    deck += mesh.keyword_text();
    for (int k = 0; k <= 1; ++k)
      for (int j = 0; j <= 1; ++j)
        for (int i = 0; i <= 1; ++i) {
          all.push_back(mesh.node_id(i, j, k));
          (j == 1 ? top : bottom).push_back(mesh.node_id(i, j, k));
        }
  }
  deck += fmt::format("*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,{}\n", elform) + elastic_card() +
          strain_card(c);
  deck += node_set(1, all) + node_set(2, top) + node_set(3, bottom);
  deck += "*BOUNDARY_SPC_SET\n1,0,0,1,1\n3,0,1,0,0\n*BOUNDARY_PRESCRIBED_MOTION_SET\n2,1,0,1,1.0\n";
  return deck + strain_pull_curve(end_time) + "*END\n";
}

// One shell (NIP 3): equi-biaxial stretch of the unit square, or the unit square turned 45
// degrees stretched along x in plane strain (node velocities proportional to X). Rotations and
// z held.
std::string stretched_shell(bool turned, Strain c, double end_time, int elform = 2) {
  const double h = std::sqrt(0.5);
  std::string deck = "*KEYWORD\n*NODE\n";
  deck += turned ? fmt::format("1,0,0,0\n2,{0},{1},0\n3,{2},0,0\n4,{0},{0},0\n", h, -h, 2.0 * h)
                 : "1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n";
  deck += fmt::format(
      "*ELEMENT_SHELL\n1,1,1,2,3,4\n*PART\nsheet\n1,1,1\n*SECTION_SHELL\n1,{},0.8333333,3\n",
      elform);
  deck += "0.01,0.01,0.01,0.01\n" + elastic_card() + strain_card(c);
  if (turned) {
    deck +=
        "*BOUNDARY_SPC_NODE\n1,0,1,1,1,1,1,1\n2,0,0,1,1,1,1,1\n3,0,0,1,1,1,1,1\n"
        "4,0,0,1,1,1,1,1\n";
    deck += fmt::format("*BOUNDARY_PRESCRIBED_MOTION_NODE\n2,1,0,1,{0}\n3,1,0,1,{1}\n4,1,0,1,{0}\n",
                        h, 2.0 * h);
  } else {
    deck +=
        "*BOUNDARY_SPC_NODE\n1,0,1,1,1,1,1,1\n2,0,0,1,1,1,1,1\n3,0,0,0,1,1,1,1\n"
        "4,0,1,0,1,1,1,1\n";
    deck +=
        "*BOUNDARY_PRESCRIBED_MOTION_NODE\n2,1,0,1,1.0\n3,1,0,1,1.0\n3,2,0,1,1.0\n"
        "4,2,0,1,1.0\n";
  }
  return deck + strain_pull_curve(end_time) + "*END\n";
}

std::string stretched_truss(Strain c, double end_time) {
  std::string deck = "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*ELEMENT_BEAM\n1,1,1,2\n";
  deck += "*PART\ntruss\n1,1,1\n*SECTION_BEAM\n1,3\n1e-4\n" + elastic_card() + strain_card(c);
  deck += "*BOUNDARY_SPC_NODE\n1,0,1,1,1,0,0,0\n2,0,0,1,1,0,0,0\n";
  deck += "*BOUNDARY_PRESCRIBED_MOTION_NODE\n2,1,0,1,1.0\n";
  return deck + strain_pull_curve(end_time) + "*END\n";
}

struct StrainCase {
  const char* name;
  Strain criterion;
  int kind;  // 1, 2, 10: solid ELFORM; -1 biaxial shell; -2 turned shell; -3 truss; -4, -5:
             // -1, -2 with ELFORM 16 (fully integrated) shells
};

class StrainCriteria : public ::testing::TestWithParam<StrainCase> {};

TEST_P(StrainCriteria, ElementGoesWhenTheAnalyticStrainMeetsTheLimit) {
  StrainCase k = GetParam();
  const int elform = k.kind <= -4 ? 16 : 2;
  if (k.kind <= -4) k.kind += 3;  // the ELFORM 2 case's geometry and reference
  const int which = static_cast<int>(k.criterion);
  double displacement = 0.0;  // of the pull when the criterion is met
  std::string text;
  if (k.kind > 0) {
    const double g = kStrainLimit / kPlaneStrainFactors[which];
    displacement = 2.0 * std::sinh(g);  // gamma = 2 sinh(g), unit height
  } else {
    const double* factors = k.kind == -1   ? kBiaxialFactors
                            : k.kind == -2 ? kPlaneStrainFactors
                                           : kTrussFactors;
    displacement = std::expm1(kStrainLimit / factors[which]);  // unit length
  }
  const double expected = time_of_displacement(displacement, kStrainPull, kStrainRamp);
  const double end = 1.2 * expected;
  if (k.kind > 0)
    text = sheared_solid(k.kind, k.criterion, end);
  else if (k.kind == -3)
    text = stretched_truss(k.criterion, end);
  else
    text = stretched_shell(k.kind == -2, k.criterion, end, elform);
  solver::Simulation sim(read(text), {});
  const double step = sim.state().dt;
  const double time = run_to_erosion(sim);
  std::printf("%s: eroded at %.6f s (analytic %.6f, step %.2e)\n", k.name, time, expected, step);
  ASSERT_GT(time, 0.0) << "the element never eroded";
  // The first cycle at or after the analytic time; the shells integrate the rate of
  // deformation (midpoint rule): second order in the step, and the turned shell's frame turns
  // with the shear it sees (0.1 % of the strain at 10 %).
  // The step grows with the length of a stretched shell or truss (L/c): the failing cycle's
  // step is at most the first one times 1 + u.
  const double tolerance = k.kind == -2 ? 2e-3 * expected : 1e-5 * expected;
  const double last_step = step * (k.kind > 0 ? 1.0 : 1.0 + displacement);
  EXPECT_GE(time, expected - tolerance);
  EXPECT_LE(time, expected + 1.01 * last_step + tolerance);
  ASSERT_FALSE(sim.erosion().events().empty());
  EXPECT_NE(sim.erosion().events().front().criterion.find("principal strains"), std::string::npos)
      << sim.erosion().events().front().criterion;
}

INSTANTIATE_TEST_SUITE_P(
    Erosion, StrainCriteria,
    ::testing::Values(
        StrainCase{"hex_MXEPS", Strain::kMax, 1}, StrainCase{"hex_MNEPS", Strain::kMin, 1},
        StrainCase{"hex_EFFEPS", Strain::kEffective, 1}, StrainCase{"hex_EPSSH", Strain::kShear, 1},
        StrainCase{"hex2_MXEPS", Strain::kMax, 2}, StrainCase{"hex2_EFFEPS", Strain::kEffective, 2},
        StrainCase{"tet_MNEPS", Strain::kMin, 10}, StrainCase{"tet_EPSSH", Strain::kShear, 10},
        StrainCase{"shell_MXEPS", Strain::kMax, -1}, StrainCase{"shell_MNEPS", Strain::kMin, -1},
        StrainCase{"shell_EFFEPS", Strain::kEffective, -1},
        StrainCase{"shell_EPSSH", Strain::kShear, -1},
        StrainCase{"turned_shell_MXEPS", Strain::kMax, -2},
        StrainCase{"turned_shell_EFFEPS", Strain::kEffective, -2},
        StrainCase{"shell16_MXEPS", Strain::kMax, -4},
        StrainCase{"shell16_EFFEPS", Strain::kEffective, -4},
        StrainCase{"turned_shell16_EFFEPS", Strain::kEffective, -5},
        StrainCase{"truss_MXEPS", Strain::kMax, -3}, StrainCase{"truss_MNEPS", Strain::kMin, -3},
        StrainCase{"truss_EFFEPS", Strain::kEffective, -3},
        StrainCase{"truss_EPSSH", Strain::kShear, -3}),
    [](const auto& info) { return std::string(info.param.name); });

// --- Bad input ----------------------------------------------------------------------------------

std::string cube_with(const std::string& extra) {
  BoxMesh mesh;
  return "*KEYWORD\n" + mesh.keyword_text() +
         fmt::format("*PART\ncube\n1,1,1,0,0\n*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,{},{},{}\n",
                     kRho, kE, kNu) +
         extra + "*CONTROL_TERMINATION\n1e-3\n*END\n";
}

TEST(ErosionDeck, UnsupportedCriteriaAndBadCardsAreErrorsNamingTheField) {
  // A positive MNEPS would fail every element at rest; negative MXEPS, EFFEPS, EPSSH are curves
  // in LS-DYNA (not supported).
  EXPECT_NE(simulation_error_of(cube_with("*MAT_ADD_EROSION\n1,0,0,0.1\n")).find("MNEPS"),
            std::string::npos);
  EXPECT_NE(simulation_error_of(cube_with("*MAT_ADD_EROSION\n1\n0,0,0,-2\n")).find("MXEPS"),
            std::string::npos);
  EXPECT_NE(simulation_error_of(cube_with("*MAT_ADD_EROSION\n1,0,0,0,-2\n")).find("EFFEPS"),
            std::string::npos);
  EXPECT_NE(simulation_error_of(cube_with("*MAT_ADD_EROSION\n1\n0,0,0,0,-2\n")).find("EPSSH"),
            std::string::npos);
  // Tuler-Butcher: a threshold without an impulse, a negative impulse or threshold.
  EXPECT_NE(simulation_error_of(cube_with("*MAT_ADD_EROSION\n1\n0,0,0,0,0,3e8\n")).find("SIGTH"),
            std::string::npos);
  EXPECT_NE(
      simulation_error_of(cube_with("*MAT_ADD_EROSION\n1\n0,0,0,0,0,1e8,-5\n")).find("IMPULSE"),
      std::string::npos);
  EXPECT_NE(
      simulation_error_of(cube_with("*MAT_ADD_EROSION\n1\n0,0,0,0,0,-1e8,5e14\n")).find("SIGTH"),
      std::string::npos);
  // ERODE values LS-DYNA does not define.
  EXPECT_NE(simulation_error_of(cube_with("*CONTROL_TIMESTEP\n0,0.9,0,0,0,0,2\n")).find("ERODE"),
            std::string::npos);
  // Beams other than trusses have no strain tensor at their section points.
  const std::string beam =
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*ELEMENT_BEAM\n1,1,1,2\n*PART\nbeam\n1,1,1\n"
      "*SECTION_BEAM\n1,1\n0.01,0.01,0.01,0.01\n" +
      elastic_card() + strain_card(Strain::kMax) + "*CONTROL_TERMINATION\n1e-3\n*END\n";
  EXPECT_NE(simulation_error_of(beam).find("trusses (beam ELFORM 3)"), std::string::npos)
      << simulation_error_of(beam);
  EXPECT_NE(
      simulation_error_of(cube_with("*MAT_ADD_EROSION\n1\n0,0,0,0,0,0,0,0\n7\n")).find("IDAM"),
      std::string::npos);
  EXPECT_NE(simulation_error_of(cube_with("*MAT_ADD_EROSION\n9\n0,3e8\n"))
                .find("material 9 is not defined"),
            std::string::npos);
  EXPECT_NE(
      simulation_error_of(cube_with("*MAT_ADD_EROSION\n1,0,0,0,0,0,1,3\n0,3e8,2e8\n")).find("NCS"),
      std::string::npos);
  EXPECT_NE(simulation_error_of(cube_with("*MAT_ADD_EROSION\n1\n0,0,-5\n")).find("SIGVM"),
            std::string::npos);
  EXPECT_NE(
      simulation_error_of(cube_with("*MAT_ADD_EROSION\n1,0,0,0,0,0,-50\n0,3e8\n")).find("NUMFIP"),
      std::string::npos);
}

}  // namespace
}  // namespace rf::test

namespace rf::test {
namespace {

// `rigidflex check` lists the criteria of every part that can erode.
TEST(ErosionDeck, CheckListsTheCriteriaOfErodibleParts) {
  const model::Model model = read(cube_with("*MAT_ADD_EROSION\n1,0,0,0,0,0,1,2\n0,3e8,2e8\n"));
  solver::Simulation sim(model, {});
  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  app::print_model_summary(model, sim, file);
  std::rewind(file);
  std::string text;
  for (int ch; (ch = std::fgetc(file)) != EOF;) text.push_back(static_cast<char>(ch));
  std::fclose(file);
  EXPECT_NE(text.find("erodes at: *MAT_ADD_EROSION SIGP1 3e+08, SIGVM 2e+08 (NCS 2, NUMFIP 1)"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace rf::test
