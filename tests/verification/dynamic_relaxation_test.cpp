// Dynamic relaxation (*CONTROL_DYNAMIC_RELAXATION, *DEFINE_CURVE SIDR) through the deck path.
// References that do not come from our code:
//  - Euler-Bernoulli: the static tip deflection of a cantilever under a tip load P is
//    P L^3 / (3 E I);
//  - Clapeyron's theorem: a linear elastic body brought to rest under a load stores half the
//    load's work, P d / 2 with d the deflection under the load;
//  - energy conservation in the free vibration that follows when a relaxation-only load
//    (SIDR 1) is gone: the strip swings to -d;
//  - a preload kept in the transient (SIDR 2) starts it in equilibrium (no motion), while the
//    same load applied suddenly would swing the tip between 0 and 2 d.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "app/run_log.hpp"
#include "deck_builder.hpp"
#include "model/error.hpp"
#include "shell_builder.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7800.0, kE = 2.0e11;
constexpr double kLength = 1.0, kWidth = 0.1, kThickness = 0.01, kLoad = 5.0;

ShellPlate strip() {
  ShellPlate p;
  p.nx = 10;
  p.ny = 1;
  p.lx = kLength;
  p.ly = kWidth;
  return p;
}

double beam_theory_deflection() {
  const double second_moment = kWidth * kThickness * kThickness * kThickness / 12.0;
  return kLoad * kLength * kLength * kLength / (3.0 * kE * second_moment);
}

// The clamped strip with a tip load in z on curve 1 (ramped over 0.05 s, then held; constant
// when `ramp` is false), whose SIDR is `sidr`, and a *CONTROL_DYNAMIC_RELAXATION card `control`
// (may be empty).
std::string cantilever_deck(int sidr, const std::string& control, double end_time,
                            bool ramp = true) {
  const ShellPlate p = strip();
  std::string deck = "*KEYWORD\n" + p.text() + shell_part(1, kThickness, kRho, kE, 0.0);
  deck += node_set(1, p.column(0)) + "*BOUNDARY_SPC_SET\n1,0,1,1,1,1,1,1\n";
  for (const int id : p.column(p.nx))
    deck += fmt::format("*LOAD_NODE_POINT\n{},3,1,{}\n", id, kLoad / 2);
  deck += fmt::format("*DEFINE_CURVE\n1,{}\n0,{}\n0.05,1\n10,1\n", sidr, ramp ? 0 : 1);
  deck += control;
  deck += fmt::format("*CONTROL_TERMINATION\n{},\n*END\n", end_time);
  return deck;
}

double tip_deflection(const solver::Simulation& sim) {
  const ShellPlate p = strip();
  double tip = 0.0;
  for (const int id : p.column(p.nx))
    tip += sim.state().nodes.x.z[static_cast<std::size_t>(id - 1)];
  return tip / 2.0;
}

// DRFCTR 0.998 damps the first mode (51 rad/s at a step near 1.8e-5 s) close to critically.
const std::string kControl = "*CONTROL_DYNAMIC_RELAXATION\n250,1e-6,0.998\n";

TEST(DynamicRelaxation, PreloadReachesStaticDeflectionAndStoresHalfTheLoadWork) {
  solver::Simulation sim(read(cantilever_deck(1, kControl, 0.15)), {});
  const auto& relaxation = sim.dynamic_relaxation();
  ASSERT_TRUE(relaxation.converged);
  EXPECT_GT(relaxation.cycles, 1000);
  EXPECT_LE(relaxation.kinetic_energy_ratio, 1e-6);
  // The transient starts at t = 0, at rest, in the relaxed shape.
  EXPECT_EQ(sim.state().time, 0.0);
  const double d0 = tip_deflection(sim);
  const double expected = beam_theory_deflection();
  RecordProperty("relaxed_tip_over_beam_theory", std::to_string(d0 / expected));
  RecordProperty("relaxation_cycles", std::to_string(relaxation.cycles));
  EXPECT_NEAR(d0 / expected, 1.0, 0.03) << "tip " << d0 << " beam theory " << expected;
  // Clapeyron: the stored energy is half the load's work on the tip deflection.
  const double stored = sim.energy().internal_work;
  EXPECT_NEAR(stored / (0.5 * kLoad * d0), 1.0, 2e-3) << "stored " << stored;
  EXPECT_EQ(sim.energy().kinetic, 0.0);
  // SIDR 1: the load is gone in the transient, so the strip swings freely from d0 to about -d0.
  double lowest = d0;
  while (!sim.finished()) {
    sim.cycle();
    lowest = std::min(lowest, tip_deflection(sim));
  }
  // Energy caps the swing at d0; the first mode holds about 97 % of the static shape of a
  // tip-loaded cantilever, and the higher modes shift the first minimum by a few per cent.
  RecordProperty("swing_over_relaxed_tip", std::to_string(-lowest / d0));
  EXPECT_LE(-lowest / d0, 1.0 + 1e-3);
  EXPECT_GE(-lowest / d0, 0.9);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 2e-3);
}

TEST(DynamicRelaxation, RunLogSaysWhatThePhaseDid) {
  const model::Model model = read(cantilever_deck(1, kControl, 0.01));
  solver::Simulation sim(model, {});
  const auto path = std::filesystem::temp_directory_path() / "rigidflex_dr_d3hsp.txt";
  {
    app::RunLog log(path, false);
    log.model_summary(model, sim);
  }
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(path);
  EXPECT_NE(text.find("dynamic relaxation before the transient: DRTOL 1e-06, DRFCTR 0.998"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find(fmt::format("dynamic relaxation converged after {} cycles",
                                  sim.dynamic_relaxation().cycles)),
            std::string::npos)
      << text;
}

TEST(DynamicRelaxation, PreloadKeptInTheTransientStartsInEquilibrium) {
  // A SIDR 2 curve is evaluated again from t = 0 in the transient: a constant one (as for
  // gravity) keeps the load on.
  solver::Simulation sim(read(cantilever_deck(2, kControl, 0.1, false)), {});
  ASSERT_TRUE(sim.dynamic_relaxation().converged);
  const double d0 = tip_deflection(sim);
  double largest_change = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    largest_change = std::max(largest_change, std::abs(tip_deflection(sim) - d0));
  }
  // Applied suddenly, the load would move the tip by up to 2 d0; preloaded it stays.
  EXPECT_LT(largest_change, 0.01 * d0) << "largest change " << largest_change << " of " << d0;
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-3);
}

TEST(DynamicRelaxation, SidrCurveStartsTheRelaxationWithLsDynaDefaults) {
  // No control card: a curve flagged SIDR 1 alone starts the phase (NRCYCK 250, DRTOL 1e-3,
  // DRFCTR 0.995), which gets near the static deflection with its default tolerance.
  solver::Simulation sim(read(cantilever_deck(1, "", 0.001)), {});
  ASSERT_TRUE(sim.dynamic_relaxation().converged);
  EXPECT_NEAR(tip_deflection(sim) / beam_theory_deflection(), 1.0, 0.1);
}

TEST(DynamicRelaxation, IdrflgMinus999TurnsItOffAndRelaxationOnlyLoadsNeverAct) {
  solver::Simulation sim(
      read(cantilever_deck(1, "*CONTROL_DYNAMIC_RELAXATION\n0,0,0,0,0,0,0,-999\n", 0.02)), {});
  EXPECT_EQ(sim.dynamic_relaxation().cycles, 0);
  sim.run();
  EXPECT_EQ(tip_deflection(sim), 0.0);  // the SIDR 1 load is not applied in the transient
}

TEST(DynamicRelaxation, UnsupportedOptionsNameTheField) {
  const auto expect_error = [](const std::string& card, const std::string& field) {
    try {
      read(cantilever_deck(1, card, 0.01));
      ADD_FAILURE() << "no error for " << card;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("*CONTROL_DYNAMIC_RELAXATION"), std::string::npos) << what;
      EXPECT_NE(what.find(field), std::string::npos) << what;
    }
  };
  expect_error("*CONTROL_DYNAMIC_RELAXATION\n0,0,0,0,0,0,0,2\n", "IDRFLG");
  expect_error("*CONTROL_DYNAMIC_RELAXATION\n0,0,0,0,0,1\n", "IRELAL");
  expect_error("*CONTROL_DYNAMIC_RELAXATION\n0,0,1.5\n", "DRFCTR");
  expect_error("*CONTROL_DYNAMIC_RELAXATION\n0,2.0\n", "DRTOL");
  // Initial velocities before the relaxation (PHASE 1) are refused when the run relaxes.
  try {
    solver::Simulation sim(
        read(
            cantilever_deck(1, "*INITIAL_VELOCITY_GENERATION\n1,2,0,0,0,1\n0,0,0,0,0,0,1\n", 0.01)),
        {});
    ADD_FAILURE() << "no error for PHASE 1";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("PHASE"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rf::test
