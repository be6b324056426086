// Shells through the whole deck path (reader, state, rotations, kernels, time loop). References
// that do not come from our code:
//  - Euler-Bernoulli cantilever: static tip deflection P L^3 / (3 E I) and first frequency
//    f1 = (1.8751^2 / 2 pi) sqrt(E I / (rho A L^4));
//  - conservation of linear and angular momentum (spin I omega of the nodes included) and of
//    energy for a free structure;
//  - a rigid rotation of a rigid shell part carrying a deformable one that is attached to it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cantilever_strip.hpp"
#include "deck_builder.hpp"
#include "model/error.hpp"
#include "shell_builder.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7800.0, kE = 2.0e11;

TEST(ShellDeck, CantileverStaticTipDeflectionMatchesBeamTheory) {
  const CantileverStrip strip;
  const double load = 5.0;  // total tip load in z, N
  const double expected = load * std::pow(strip.length, 3) / (3.0 * strip.ei());
  solver::Simulation sim(read(strip.deck(2) + strip.static_tip_load(load, 3)), {});
  sim.run();
  const double tip = strip.tip_displacement(sim, 2);
  RecordProperty("tip_deflection_ratio", std::to_string(tip / expected));
  EXPECT_NEAR(tip / expected, 1.0, 0.03) << "tip " << tip << " beam theory " << expected;
  // The hourglass energy stays a small part of the strain energy in this bending problem.
  EXPECT_LT(std::abs(sim.energy().hourglass), 0.05 * std::abs(sim.energy().internal_work));
}

TEST(ShellDeck, CantileverFirstFrequencyMatchesBeamTheory) {
  const CantileverStrip strip;
  const double f1 = strip.first_frequency();
  solver::Simulation sim(read(strip.deck(2) + strip.first_mode_velocity()), {});
  const double f = strip.run_and_measure_frequency(sim);
  RecordProperty("frequency_ratio", std::to_string(f / f1));
  EXPECT_NEAR(f / f1, 1.0, 0.02) << "f " << f << " beam theory " << f1;
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 2e-3);
}

// Two plates joined at a right angle (an L section), free in space, thrown with a translation,
// a spin about a skew axis and a local kick that makes them vibrate. Returns {initial, final}.
std::pair<solver::EnergyAccount, solver::EnergyAccount> tumble(bool warping_correction) {
  ShellPlate a;
  a.nx = 4;
  a.ny = 4;
  a.lx = 0.4;
  a.ly = 0.4;
  ShellPlate b = a;
  b.first_node = 100;
  b.first_element = 100;
  b.pid = 2;
  b.place = [](double u, double v) { return Eigen::Vector3d(u, 0.0, v); };
  // Plate b shares plate a's edge v = 0 (y = 0): its nodes with v index 0 are a's nodes.
  std::string nodes = a.nodes_text() + "*NODE\n";
  for (int j = 1; j <= b.ny; ++j)
    for (int i = 0; i <= b.nx; ++i) {
      const Eigen::Vector3d x = b.position(i, j);
      nodes += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", b.node_id(i, j), x.x(), x.y(), x.z());
    }
  std::string elements = a.elements_text() + "*ELEMENT_SHELL\n";
  int eid = b.first_element;
  auto bid = [&](int i, int j) { return j == 0 ? a.node_id(i, 0) : b.node_id(i, j); };
  for (int j = 0; j < b.ny; ++j)
    for (int i = 0; i < b.nx; ++i)
      elements += fmt::format("{},2,{},{},{},{}\n", eid++, bid(i, j), bid(i + 1, j),
                              bid(i + 1, j + 1), bid(i, j + 1));
  std::string deck = "*KEYWORD\n" + nodes + elements + shell_part(1, 0.004, 2700.0, 7.0e10, 0.3) +
                     shell_part(2, 0.004, 2700.0, 7.0e10, 0.3);
  deck += "*INITIAL_VELOCITY_GENERATION\n0,1,20.0,1.0,-2.0,0.5\n0.1,0.2,0.0,1.0,1.0,1.0\n";
  deck += fmt::format("*INITIAL_VELOCITY_NODE\n{},0,0,3.0\n{},0,0,-3.0,0,0,20.0\n", a.node_id(4, 4),
                      a.node_id(2, 3));
  if (warping_correction) deck += "*CONTROL_SHELL\n20,0,-1,0,2,1\n";
  deck += "*CONTROL_TERMINATION\n0.02\n*END\n";
  solver::Simulation sim(read(deck), {});
  const solver::EnergyAccount e0 = sim.energy();
  sim.run();
  return {e0, sim.energy()};
}

double momentum_scale(const double (&v)[3]) {
  return std::abs(v[0]) + std::abs(v[1]) + std::abs(v[2]);
}

// With the Belytschko-Wong-Chiang correction the element forces and moments are in balance for
// warped elements too (sum x f + m = 0), so the central difference keeps the angular momentum
// (spins of the nodes included) to round-off.
TEST(ShellDeck, FreeTumblingStructureConservesMomentaAndEnergy) {
  const auto [e0, e] = tumble(true);
  const double p_scale = momentum_scale(e0.momentum);
  const double l_scale = momentum_scale(e0.angular_momentum);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(e.momentum[k], e0.momentum[k], 1e-10 * p_scale) << k;
    EXPECT_NEAR(e.angular_momentum[k], e0.angular_momentum[k], 1e-9 * l_scale) << k;
  }
  EXPECT_GT(e.internal_work, 1e-4 * e0.kinetic);  // it does deform
  EXPECT_NEAR(e.ratio(), 1.0, 2e-3);
  RecordProperty("energy_ratio", std::to_string(e.ratio()));
}

// Without it (BWC 2, LS-DYNA's default) the plain Belytschko-Tsay element computes its forces as
// if the element were flat; once it warps, its moments are not quite in balance and the angular
// momentum drifts slowly (as in LS-DYNA). The drift stays small for this mildly warped case.
TEST(ShellDeck, FreeTumblingWithoutWarpingCorrectionDriftsLittle) {
  const auto [e0, e] = tumble(false);
  const double p_scale = momentum_scale(e0.momentum);
  const double l_scale = momentum_scale(e0.angular_momentum);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(e.momentum[k], e0.momentum[k], 1e-10 * p_scale) << k;
    EXPECT_NEAR(e.angular_momentum[k], e0.angular_momentum[k], 1e-4 * l_scale) << k;
  }
  EXPECT_NEAR(e.ratio(), 1.0, 2e-3);
}

// A rigid shell part (*MAT_RIGID, 2 x 2 shells) carrying a deformable 4 x 2 shell plate through
// three shared nodes. Returns the deck; `spin` throws both as a rigid rotation about z.
std::string rigid_and_soft_deck(double omega, const ShellPlate& rigid, const ShellPlate& soft) {
  std::string nodes = rigid.nodes_text() + "*NODE\n";
  for (int j = 0; j <= soft.ny; ++j)
    for (int i = 1; i <= soft.nx; ++i) {
      const Eigen::Vector3d x = soft.position(i, j);
      nodes += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", soft.node_id(i, j), x.x(), x.y(), x.z());
    }
  auto sid = [&](int i, int j) { return i == 0 ? rigid.node_id(rigid.nx, j) : soft.node_id(i, j); };
  std::string elements = rigid.elements_text() + "*ELEMENT_SHELL\n";
  int eid = soft.first_element;
  for (int j = 0; j < soft.ny; ++j)
    for (int i = 0; i < soft.nx; ++i)
      elements += fmt::format("{},2,{},{},{},{}\n", eid++, sid(i, j), sid(i + 1, j),
                              sid(i + 1, j + 1), sid(i, j + 1));
  std::string deck = "*KEYWORD\n" + nodes + elements;
  deck += "*PART\nrigid\n1,1,1\n*SECTION_SHELL\n1,2,0.8333,2\n0.005,0.005,0.005,0.005\n";
  deck += "*MAT_RIGID\n1,7800.0,2.0e11,0.3\n";
  deck += shell_part(2, 0.002, 7800.0, 2.0e11, 0.3);
  if (omega != 0.0) {
    deck += fmt::format("*INITIAL_VELOCITY_GENERATION\n1,2,{},0,0,0\n0.1,0.1,0,0,0,1\n", omega);
    deck += fmt::format("*INITIAL_VELOCITY_GENERATION\n2,2,{},0,0,0\n0.1,0.1,0,0,0,1\n", omega);
  }
  // Out-of-plane kick at the free end: bending must pass moments into the rigid body. The card
  // replaces the node's velocities (the last initial velocity of a node wins), so it carries the
  // node's share of the rigid spin, omega e_z x (x - c) and the nodal spin omega e_z, plus the
  // kick 0.5 e_z: the kick alone would also stop the node in the plane, a 0.5 omega m/s in-plane
  // impact at one node instead of the out-of-plane kick.
  const Eigen::Vector3d kicked = soft.position(soft.nx, 1);
  deck += fmt::format("*INITIAL_VELOCITY_NODE\n{},{:.17g},{:.17g},0.5,0,0,{:.17g}\n",
                      soft.node_id(soft.nx, 1), -omega * (kicked.y() - 0.1),
                      omega * (kicked.x() - 0.1), omega);
  return deck;
}

struct RigidAndSoft {
  ShellPlate rigid, soft;
  RigidAndSoft() {
    rigid.nx = 2;
    rigid.ny = 2;
    rigid.lx = 0.2;
    rigid.ly = 0.2;
    soft = rigid;
    soft.nx = 4;
    soft.lx = 0.4;
    soft.first_node = 100;
    soft.first_element = 100;
    soft.pid = 2;
    soft.place = [](double u, double v) { return Eigen::Vector3d(0.2 + u, v, 0.0); };
  }
};

// The kicked plate bends against the rigid body: its moments at the shared nodes turn the body
// (nonzero angular velocity about the shared edge), and the structure conserves momentum,
// angular momentum (the nodal spins included) and energy.
TEST(ShellDeck, RigidShellBodyTakesTheMomentsOfAttachedShells) {
  const RigidAndSoft m;
  std::string deck = rigid_and_soft_deck(0.0, m.rigid, m.soft);
  // With the warping correction the bent (warped) elements stay in moment balance.
  deck += "*CONTROL_SHELL\n20,0,-1,0,2,1\n*CONTROL_TERMINATION\n0.1\n*END\n";
  solver::Simulation sim(read(deck), {});
  const auto e0 = sim.energy();
  sim.run();
  const auto& e = sim.energy();
  const double p_scale = std::abs(e0.momentum[2]);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(e.momentum[k], e0.momentum[k], 1e-9 * p_scale) << k;
    EXPECT_NEAR(e.angular_momentum[k], e0.angular_momentum[k],
                1e-6 * (std::abs(e0.angular_momentum[0]) + std::abs(e0.angular_momentum[1])))
        << k;
  }
  EXPECT_NEAR(e.ratio(), 1.0, 2e-3);
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
  const auto& w = sim.rigid_bodies().bodies.front().state.angular_velocity;
  EXPECT_GT(std::abs(w.x()) + std::abs(w.y()), 1e-3)
      << "the plate's moments did not reach the body";
  EXPECT_LT(std::abs(e.hourglass), 0.1 * e0.kinetic);
}

// The same structure thrown as a rigid spin about z (5 rad/s) with the kick on top: after
// 0.25 s (1.25 rad) the angular momentum about z and the energy are conserved and the far corner
// of the plate is where the rigid rotation of the whole about its centre of mass puts it (the
// out-of-plane kick moves it in the plane only to second order), at the default TSSFAC 0.9.
// (Issue 16: this test once failed at t = 0.072 s because the deck's kick card replaced the
// node's spin velocity, an in-plane impact of 2.5 m/s at one node; that open defect is
// InPlaneImpactOnShellStripStaysBounded below and docs/elements.md.)
TEST(ShellDeck, SpinningRigidShellBodyCarriesDeformableShells) {
  const RigidAndSoft m;
  const double omega = 5.0;
  std::string deck = rigid_and_soft_deck(omega, m.rigid, m.soft);
  const double end = 0.25;
  deck += fmt::format("*CONTROL_TERMINATION\n{},\n*END\n", end);
  solver::Simulation sim(read(deck), {});
  const auto& state0 = sim.state().nodes;
  double mass = 0.0;
  Eigen::Vector2d com = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < state0.size(); ++i) {
    mass += state0.mass[i];
    com += state0.mass[i] * Eigen::Vector2d(state0.x0.x[i], state0.x0.y[i]);
  }
  com /= mass;
  const Eigen::Vector2d com_velocity(-omega * (com.y() - 0.1), omega * (com.x() - 0.1));
  const auto e0 = sim.energy();
  sim.run();
  const auto& e = sim.energy();
  EXPECT_NEAR(e.angular_momentum[2], e0.angular_momentum[2],
              1e-6 * std::abs(e0.angular_momentum[2]));
  EXPECT_NEAR(e.ratio(), 1.0, 2e-3);
  const auto& x = sim.state().nodes;
  const std::size_t corner = static_cast<std::size_t>(std::distance(
      x.id.begin(), std::find(x.id.begin(), x.id.end(), m.soft.node_id(m.soft.nx, 0))));
  const double t = sim.state().time;
  const Eigen::Vector2d r0 = Eigen::Vector2d(0.6, 0.0) - com;
  const Eigen::Vector2d expected = com + t * com_velocity + Eigen::Rotation2Dd(omega * t) * r0;
  EXPECT_NEAR(x.x.x[corner], expected.x(), 2e-3 * r0.norm());
  EXPECT_NEAR(x.x.y[corner], expected.y(), 2e-3 * r0.norm());
}

// The deck that showed issue 16: the spinning structure above, but the kicked node's card
// replaces its velocities, so that node stops in the plane (an in-plane impact of 2.5 m/s,
// 0.23 J at one node, with the kick). The step used to follow the geometry of the hammered
// elements up and down and pump energy into their highest modes: the run stopped with the
// solver's instability message at t = 0.072 s (TSSFAC 0.9). With the step hysteresis
// (Simulation::select_time_step) it stays bounded: over 1 s the kinetic energy stays below 1.2
// times the initial total (measured 1.10: the half-step kinetic energy of modes near the step
// limit exceeds their share of the energy; a growing mode passes any bound), and the angular
// momentum about z and the energy balance hold.
TEST(ShellDeck, SpinningShellStructureHitInItsPlaneStaysStable) {
  const RigidAndSoft m;
  std::string deck = rigid_and_soft_deck(5.0, m.rigid, m.soft);
  deck += fmt::format("*INITIAL_VELOCITY_NODE\n{},0,0,0.5\n", m.soft.node_id(m.soft.nx, 1));
  // With the warping correction the warped elements stay in moment balance (angular momentum to
  // round-off, as in RigidShellBodyTakesTheMomentsOfAttachedShells).
  deck += "*CONTROL_SHELL\n20,0,-1,0,2,1\n*CONTROL_TERMINATION\n1.0\n*END\n";
  solver::Simulation sim(read(deck), {});
  const auto e0 = sim.energy();
  double max_kinetic = 0.0;
  sim.run([&](const solver::Simulation& s) {
    max_kinetic = std::max(max_kinetic, s.energy().kinetic);
  });
  const auto& e = sim.energy();
  EXPECT_LT(max_kinetic, 1.2 * e0.kinetic);
  EXPECT_NEAR(e.angular_momentum[2], e0.angular_momentum[2],
              1e-6 * std::abs(e0.angular_momentum[2]));
  EXPECT_NEAR(e.ratio(), 1.0, 2e-3);
  RecordProperty("max_kinetic_ratio", std::to_string(max_kinetic / e0.kinetic));
}

// OPEN (issue 16, docs/elements.md): the structure above without spin, one node of the free end
// given an in-plane velocity of 2.5 m/s. With the step hysteresis the motion stays bounded
// (kinetic energy 0.09-0.35 J against 0.244 J over 2 s, measured with the check below off), but
// the solver's instability check (internal energy below -5 % of the energy scale) stops the run
// at cycle 1: the impact puts its energy into the highest modes, and for a mode with
// omega dt > sqrt(2) the central difference books internal energy k x^n x^{n+1} / 2 < 0 while
// the step is stable (-0.038 J at cycle 1, kinetic 0.282 J, energy ratio 1). With the spin
// above, the larger energy scale keeps the check quiet. The check is a heuristic of
// Simulation::update_velocities, outside the shell work.
TEST(ShellDeck, DISABLED_InPlaneImpactOnShellStripStaysBounded) {
  const RigidAndSoft m;
  std::string deck = rigid_and_soft_deck(0.0, m.rigid, m.soft);
  // The last initial velocity of a node wins: this card replaces the kick.
  deck += fmt::format("*INITIAL_VELOCITY_NODE\n{},0,-2.5,0\n", m.soft.node_id(m.soft.nx, 1));
  deck += "*CONTROL_TERMINATION\n2.0\n*END\n";
  solver::Simulation sim(read(deck), {});
  const auto e0 = sim.energy();
  sim.run();
  EXPECT_LT(sim.energy().kinetic, 2.0 * e0.kinetic);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 2e-3);
}

// Bad shell and beam input: errors name the keyword and field.
TEST(ShellDeck, BadInputNamesKeywordAndField) {
  const ShellPlate p;
  const std::string base = "*KEYWORD\n" + p.text() + "*CONTROL_TERMINATION\n0.001\n";
  auto expect_error = [&](const std::string& cards, const std::string& keyword,
                          const std::string& field) {
    try {
      solver::Simulation sim(read(base + cards + "*END\n"), {});
      ADD_FAILURE() << "expected an input error at " << keyword << " " << field;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(keyword), std::string::npos) << what;
      EXPECT_NE(what.find(field), std::string::npos) << what;
    }
  };
  const std::string mat = "*MAT_ELASTIC\n1,7800,2e11,0.3\n*PART\np\n1,1,1\n";
  expect_error(mat + "*SECTION_SHELL\n1,2,1,2\n0.0\n", "*SECTION_SHELL", "T1");
  expect_error(mat + "*SECTION_SHELL\n1,2,1,12\n0.01\n", "*SECTION_SHELL", "NIP");
  expect_error(mat + "*SECTION_SHELL\n1,7,1,2\n0.01\n", "*SECTION_SHELL", "ELFORM");
  expect_error(mat + "*SECTION_SHELL\n1,2,1,2\n0.01,,,,1\n", "*SECTION_SHELL", "NLOC");
  expect_error(mat + "*SECTION_SOLID\n1,1\n", "*ELEMENT_SHELL", "PID");
  expect_error(mat + "*SECTION_SHELL\n1,2,1,2\n0.01\n*CONTROL_SHELL\n20,0,-1,2\n", "*CONTROL_SHELL",
               "ISTUPD");
  expect_error(mat + "*SECTION_SHELL\n1,2,1,2\n0.01\n*CONTROL_TIMESTEP\n0,0.9,1\n",
               "*CONTROL_TIMESTEP", "ISDO");
  expect_error(mat + "*SECTION_SHELL\n1,2,1,2\n0.01\n*ELEMENT_SHELL\n9,1,1,2,3,4,5\n",
               "*ELEMENT_SHELL", "N5");
  expect_error(mat + "*SECTION_SHELL\n1,2,1,2\n0.01\n*ELEMENT_SHELL\n9,1,1,1,3,4\n",
               "*ELEMENT_SHELL", "N1");
  // Beams: zero length, an orientation node on the axis, unsupported releases.
  const std::string beam_part =
      "*MAT_ELASTIC\n2,7800,2e11,0.3\n*PART\nb\n2,2,2\n"
      "*SECTION_BEAM\n2,2\n1e-4,1e-8,1e-8,2e-8\n*SECTION_SHELL\n1,2,1,2\n0.01\n"
      "*MAT_ELASTIC\n1,7800,2e11,0.3\n*PART\np\n1,1,1\n";
  expect_error(beam_part + "*ELEMENT_BEAM\n20,2,1,1\n", "*ELEMENT_BEAM", "N2");
  expect_error(beam_part + "*NODE\n50,2.0,0,0\n*ELEMENT_BEAM\n20,2,1,2,50\n", "*ELEMENT_BEAM",
               "N3");
  expect_error(beam_part + "*ELEMENT_BEAM\n20,2,1,2,3,1\n", "*ELEMENT_BEAM", "RT1");
  expect_error(
      "*MAT_ELASTIC\n2,7800,2e11,0.3\n*PART\nb\n2,2,2\n*SECTION_BEAM\n2,2\n0,1e-8,1e-8\n"
      "*ELEMENT_BEAM\n20,2,1,2\n",
      "*SECTION_BEAM", "A");
}

}  // namespace
}  // namespace rf::test
