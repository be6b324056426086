// Decks written the way LS-PrePost writes them (tests/decks/real_style: _TITLE options, includes
// in folders found relative to the including file and through *INCLUDE_PATH, parameters in
// expressions by bare name, generated and general sets, an _ID card before every SPC card,
// *DEFINE_CURVE_FUNCTION), read end to end and run briefly. The references are conservation
// laws and closed-form integrals, not our own output:
//   impact_main.k: two equal free cubes, one at v0; the contact is internal, so the total
//     momentum stays rho V v0, and for equal elastic bodies it passes to the target (1D elastic
//     wave theory: the velocities exchange).
//   ramp_load.k: every node of a free cube pushed by F(t) = SFO * fRate * t; the cube's
//     momentum at T is N SFO fRate T^2 / 2; the other cube, held by the two SPC cards, stays.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "io/keyword/reader.hpp"
#include "solver/simulation.hpp"

namespace rf::test {
namespace {

using Eigen::Vector3d;

std::filesystem::path deck(const std::string& name) {
  return std::filesystem::path(RIGIDFLEX_TEST_DECKS) / "real_style" / name;
}

model::Model read_for_run(const std::string& name) {
  io::ReadOptions options;
  options.check_runnable = true;  // as `rigidflex check` and `run`
  return io::read_deck(deck(name), options);
}

// Mass and momentum of the nodes with IDs in [first, last].
struct Motion {
  double mass = 0.0;
  Vector3d momentum = Vector3d::Zero();
};
Motion motion(const solver::State& state, int first, int last) {
  Motion m;
  const auto& n = state.nodes;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (n.id[i] < first || n.id[i] > last) continue;
    m.mass += n.mass[i];
    m.momentum += n.mass[i] * Vector3d(n.v.x[i], n.v.y[i], n.v.z[i]);
  }
  return m;
}

constexpr double kRho = 7.85e-9, kSide = 20.0;  // steel, 20 mm cubes (props/steel.k, mesh/)

TEST(RealStyleDecks, ImpactDeckIsReadAsWritten) {
  const model::Model m = read_for_run("impact_main.k");
  EXPECT_EQ(m.files.size(), 4u);  // main, mesh/cubes.k, mesh/nodes.k, props/steel.k
  EXPECT_EQ(m.nodes.size(), 54u);
  EXPECT_EQ(m.solids.size(), 16u);
  EXPECT_DOUBLE_EQ(m.termination.endtim, 1.2e-4);
  EXPECT_DOUBLE_EQ(m.output.glstat_dt, 1.2e-4 / 40.0);  // TEnd/40 with tEnd defined
  EXPECT_DOUBLE_EQ(m.timestep.dtinit, 1.2e-7);          // &tend/1000
  ASSERT_EQ(m.contacts.size(), 1u);
  EXPECT_EQ(m.contacts[0].heading, "projectile on target");
  EXPECT_EQ(m.part_sets.at(1).parts, std::vector<model::Id>{1});
  // The one output request without a writer is the only warning.
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0].where.keyword, "*DATABASE_SLEOUT");
}

TEST(RealStyleDecks, ImpactConservesMomentumAndHandsItToTheTarget) {
  solver::Simulation sim(read_for_run("impact_main.k"), {});
  const double v0 = 1.0e4;
  const double mass = kRho * kSide * kSide * kSide;
  const Motion start = motion(sim.state(), 1, 27);
  EXPECT_NEAR(start.mass, mass, 1e-9 * mass);
  EXPECT_NEAR(start.momentum.x(), mass * v0, 1e-9 * mass * v0);
  while (!sim.finished()) sim.cycle();
  const Motion projectile = motion(sim.state(), 1, 27);
  const Motion target = motion(sim.state(), 101, 127);
  const Vector3d total = projectile.momentum + target.momentum;
  EXPECT_NEAR(total.x(), mass * v0, 1e-6 * mass * v0);
  EXPECT_NEAR(total.y(), 0.0, 1e-6 * mass * v0);
  EXPECT_NEAR(total.z(), 0.0, 1e-6 * mass * v0);
  // Equal elastic bodies exchange their velocities; the coarse mesh and the penalty spring
  // leave some momentum behind, but most of it must have passed.
  EXPECT_GT(target.momentum.x(), 0.9 * mass * v0);
}

TEST(RealStyleDecks, RampLoadGivesTheIntegratedMomentum) {
  const model::Model m = read_for_run("ramp_load.k");
  ASSERT_EQ(m.spcs.size(), 2u);  // one ID card before each SPC card
  EXPECT_EQ(m.node_sets.at(10).nodes.size(), 27u);
  EXPECT_EQ(m.node_sets.at(20).nodes.size(), 27u);
  ASSERT_TRUE(m.curves.at(5).function);
  solver::Simulation sim(m, {});
  while (!sim.finished()) sim.cycle();
  const double t = sim.state().time;
  EXPECT_NEAR(t, 1.0e-3, 1e-12);
  const double expected = 27.0 * 0.5 * 2000.0 * t * t / 2.0;
  const Motion loaded = motion(sim.state(), 1, 27);
  // Central differences integrate the linear ramp with an error of order dt / T (~0.2 %).
  EXPECT_NEAR(loaded.momentum.x(), expected, 5e-3 * expected);
  EXPECT_NEAR(loaded.momentum.y(), 0.0, 1e-9 * expected);
  const Motion held = motion(sim.state(), 101, 127);
  EXPECT_EQ(held.momentum.norm(), 0.0);
}

}  // namespace
}  // namespace rf::test
