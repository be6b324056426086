// Part switching of shell and beam parts (docs/switching.md, "Shells and beams"). References that
// do not come from the switching code: conservation of linear momentum and of angular momentum
// H = sum m x × v + sum I w (the nodal rotary inertia I of the rotational degrees of freedom
// included), the kinetic energy of the non-rigid part of the nodal field (translations and
// rotations) computed here by a rigid fit with the same momenta, the lumped-mass inertia of a
// rectangular plate in closed form, and the objectivity of the element forces: forces and moments
// computed from the frozen state after a rigid rotation Q must be Q times those before.
#include <gtest/gtest.h>

#include <unistd.h>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "deck_builder.hpp"
#include "element/beam_block.hpp"
#include "element/shell_block.hpp"
#include "model/error.hpp"
#include "restart_decks.hpp"
#include "rigid/rigid_body.hpp"
#include "shell_builder.hpp"
#include "solver/build_state.hpp"
#include "solver/rigid_bodies.hpp"
#include "switching/part_switching.hpp"

namespace rf::test {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Momenta of the free nodes, rotations included: P = sum m v, H = sum x × m v + sum I w about the
// origin, T = sum m v^2 / 2 + sum I w^2 / 2, and the rigid fit with the same P and H: inertia
// J = sum m (r^2 1 - r r^T) + sum I 1 about the centre of mass, omega = J^-1 (H - c × P),
// T_rigid = P^2 / 2M + omega . J omega / 2 (the least kinetic energy any motion with these
// momenta has; the rest is the non-rigid part of the field).
struct Momenta {
  double mass = 0.0, kinetic = 0.0, rigid_kinetic = 0.0, rotary = 0.0;
  Vector3d p = Vector3d::Zero(), h = Vector3d::Zero(), centre = Vector3d::Zero(),
           omega = Vector3d::Zero();
  Matrix3d inertia = Matrix3d::Zero();
};

Momenta momenta_of(const solver::State& s) {
  Momenta m;
  const auto& n = s.nodes;
  const auto& rot = s.rotations;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Vector3d x(n.x.x[i], n.x.y[i], n.x.z[i]), v(n.v.x[i], n.v.y[i], n.v.z[i]);
    m.mass += n.mass[i];
    m.centre += n.mass[i] * x;
    m.p += n.mass[i] * v;
    m.h += x.cross(n.mass[i] * v);
    m.kinetic += 0.5 * n.mass[i] * v.squaredNorm();
  }
  for (std::size_t r = 0; r < rot.size(); ++r) {
    const Vector3d w(rot.w.x[r], rot.w.y[r], rot.w.z[r]);
    m.h += rot.inertia[r] * w;
    m.kinetic += 0.5 * rot.inertia[r] * w.squaredNorm();
    m.rotary += rot.inertia[r];
  }
  m.centre /= m.mass;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Vector3d r = Vector3d(n.x.x[i], n.x.y[i], n.x.z[i]) - m.centre;
    m.inertia += n.mass[i] * (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose());
  }
  m.inertia += m.rotary * Matrix3d::Identity();
  m.omega = m.inertia.inverse() * (m.h - m.centre.cross(m.p));
  m.rigid_kinetic = 0.5 * m.p.squaredNorm() / m.mass + 0.5 * m.omega.dot(m.inertia * m.omega);
  return m;
}

// Paired CODE 0 sets on part 1: rigid at 0.05 s (step DTMAX), deformable again at 0.15 s.
std::string paired_switch(double dtmax) {
  return fmt::format(
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,0.05,0.06,0,0,20,1\n0,0,0,{},1,0\n1\n"
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,0,0.15,0,0,0,10,-1\n0,0,0,0,0,1\n1\n",
      dtmax);
}
const std::string kPairedSwitch = paired_switch(0.01);

// The initial field of both free parts: translation v0, spin w about an oblique axis, and a
// non-rigid part: a stretch along x, a bending velocity v_z = 2 (x^2 - 1/12) with the matching
// rotation rate -4x about y, and a twist rate 3x about x.
const Vector3d kV0(1.0, 0.5, 0.2), kSpin(6.0, 3.0, 10.0);
std::string node_velocity(int id, const Vector3d& x, bool rotations, const Vector3d& spin = kSpin) {
  const Vector3d v =
      kV0 + spin.cross(x) + Vector3d(0.8 * x.x(), 0.0, 2.0 * (x.x() * x.x() - 1.0 / 12.0));
  const Vector3d w = spin + Vector3d(3.0 * x.x(), -4.0 * x.x(), 0.0);
  if (!rotations) return fmt::format("{},{:.17g},{:.17g},{:.17g}\n", id, v.x(), v.y(), v.z());
  return fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", id, v.x(), v.y(),
                     v.z(), w.x(), w.y(), w.z());
}

// A free 1 x 0.5 m plate, 8 x 4 ELFORM 2 shells (t 0.02 m, NIP 3, IHQ 4), centred on the origin
// in the x-y plane, rho 1000, E 1e7, nu 0.3.
ShellPlate free_plate() {
  ShellPlate plate;
  plate.nx = 8;
  plate.ny = 4;
  plate.lx = 1.0;
  plate.ly = 0.5;
  plate.place = [](double u, double v) { return Vector3d(u - 0.5, v - 0.25, 0.0); };
  return plate;
}

std::string shell_plate_deck(const std::string& switching, double end_time,
                             const std::string& velocities = "", const Vector3d& spin = kSpin) {
  const ShellPlate plate = free_plate();
  std::string deck = "*KEYWORD\n" + plate.text() + shell_part(1, 0.02, 1000.0, 1e7, 0.3, 3, 4);
  if (velocities.empty()) {
    deck += "*INITIAL_VELOCITY_NODE\n";
    for (int j = 0; j <= plate.ny; ++j)
      for (int i = 0; i <= plate.nx; ++i)
        deck += node_velocity(plate.node_id(i, j), plate.position(i, j), true, spin);
  } else {
    deck += velocities;
  }
  return deck + switching + fmt::format("*CONTROL_TERMINATION\n{},\n*END\n", end_time);
}

// A free straight beam along x from -0.5 to 0.5 m, 8 resultant beams (ELFORM 2; A 5e-3, ISS
// 1e-6, ITT 4e-6, J 2e-6), nodes 1..9; or (elform 1) integrated beams of a 0.1 x 0.05
// rectangle.
std::string beam_deck(const std::string& switching, double end_time, int elform = 2,
                      const Vector3d& spin = kSpin) {
  std::string deck = "*KEYWORD\n*NODE\n";
  for (int k = 0; k <= 8; ++k) deck += fmt::format("{},{:.17g},0,0\n", k + 1, -0.5 + k / 8.0);
  deck += "*ELEMENT_BEAM\n";
  for (int k = 0; k < 8; ++k) deck += fmt::format("{},1,{},{}\n", k + 1, k + 1, k + 2);
  deck += "*PART\nbeam\n1,1,1\n*MAT_ELASTIC\n1,1000.0,1.0e7,0.3\n";
  deck += elform == 2 ? "*SECTION_BEAM\n1,2,0.8333\n5.0e-3,1.0e-6,4.0e-6,2.0e-6\n"
                      : "*SECTION_BEAM\n1,1,0.8333,2,0\n0.1,0.1,0.05,0.05\n";
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= 8; ++k) {
    deck += node_velocity(k + 1, Vector3d(-0.5 + k / 8.0, 0, 0), true, spin);
  }
  return deck + switching + fmt::format("*CONTROL_TERMINATION\n{},\n*END\n", end_time);
}

double largest_magnitude(const std::vector<double>& values) {
  double s = 0.0;
  for (const double v : values) s = std::max(s, std::abs(v));
  return s;
}

// Runs the deck with the paired sets through both switches and checks the conservation laws;
// `unswitched` is the same deck without the sets, whose energy ratio (the central difference's
// own energy measure for this fast spin) the switched run must match.
double check_paired_switch(const std::string& deck, const std::string& unswitched, bool shells) {
  double ratio_error = 1.0;
  solver::Simulation sim(read(deck), {});
  const Momenta start = momenta_of(sim.state());
  EXPECT_GT(start.rotary, 0.0);
  while (sim.state().time < 0.05) sim.cycle();
  const Momenta before = momenta_of(sim.state());
  const double stress_scale = shells ? largest_magnitude(sim.state().shell_blocks[0].stress)
                                     : largest_magnitude(sim.state().beam_blocks[0].resultant);
  EXPECT_GT(stress_scale, 0.0);
  const double internal_before = sim.energy().internal();
  sim.cycle();  // switches first
  if (sim.switch_events().size() != 1u) {
    ADD_FAILURE() << "no switch to rigid";
    return ratio_error;
  }
  const auto& to_rigid = sim.switch_events()[0];
  EXPECT_TRUE(to_rigid.to_rigid);
  // The kinetic energy removed is the non-rigid part of the field (rotations included).
  const double non_rigid = before.kinetic - before.rigid_kinetic;
  EXPECT_GT(non_rigid, 1e-3 * before.kinetic);
  const double removed = to_rigid.kinetic_energy_before - to_rigid.kinetic_energy_after;
  EXPECT_NEAR(removed, non_rigid, 1e-10 * before.kinetic);
  EXPECT_NEAR((to_rigid.momentum - before.p).norm(), 0.0, 1e-13 * before.p.norm());
  EXPECT_NEAR((to_rigid.angular_momentum - before.h).norm(), 0.0, 1e-13 * before.h.norm());
  if (sim.rigid_bodies().bodies.size() != 1u) {
    ADD_FAILURE() << "not one body";
    return ratio_error;
  }
  const auto& body = sim.rigid_bodies().bodies[0];
  EXPECT_NEAR(body.state.mass, before.mass, 1e-13 * before.mass);
  // The body's inertia is the one of the fit (rotary inertia included), at the switch.
  // (After one step the body has turned: compare the invariant eigenvalues.)
  const Eigen::SelfAdjointEigenSolver<Matrix3d> want(before.inertia),
      got(rigid::global_inertia(body.state));
  EXPECT_NEAR((want.eigenvalues() - got.eigenvalues()).norm(), 0.0,
              1e-12 * want.eigenvalues().norm());
  EXPECT_GT(sim.energy().frozen_energy, 0.0);
  std::printf(
      "[ measured ] %s: KE %.6g J, non-rigid %.6g J, removed - non-rigid %.3g J, frozen "
      "%.6g J, internal %.6g J\n",
      shells ? "shells" : "beams", before.kinetic, non_rigid, removed - non_rigid,
      sim.energy().frozen_energy, internal_before);
  // Rigid phase: every rotational node turns with the body.
  sim.cycle();
  {
    const auto& rot = sim.state().rotations;
    const Vector3d w = sim.rigid_bodies().bodies[0].state.angular_velocity;
    for (std::size_t r = 0; r < rot.size(); ++r) {
      EXPECT_EQ(rot.w.x[r], w.x());
      EXPECT_EQ(rot.w.y[r], w.y());
      EXPECT_EQ(rot.w.z[r], w.z());
    }
    EXPECT_LE(sim.state().dt, 0.01 * (1 + 1e-12));
  }
  Matrix3d first = switching::body_rotation(sim.rigid_bodies().bodies[0]), last = first;
  while (sim.switch_events().size() < 2 && !sim.finished()) {
    last = switching::body_rotation(sim.rigid_bodies().bodies[0]);
    sim.cycle();
  }
  if (sim.switch_events().size() != 2u) {
    ADD_FAILURE() << "not released";
    return ratio_error;
  }
  const Matrix3d turned = last * first.transpose();
  EXPECT_GT(std::acos(std::clamp((turned.trace() - 1.0) / 2.0, -1.0, 1.0)), 1.0);
  const auto& released = sim.switch_events()[1];
  EXPECT_FALSE(released.to_rigid);
  // Released with the body's momenta at its present attitude: the nodes carry its kinetic
  // energy M v^2 / 2 + L . J^-1 L / 2.
  const double release_change = released.kinetic_energy_before - released.kinetic_energy_after;
  EXPECT_LT(std::abs(release_change), 1e-12 * released.kinetic_energy_before);
  EXPECT_TRUE(sim.rigid_bodies().bodies.empty());
  const Momenta after = momenta_of(sim.state());
  // Through both switches and the deformable phases: constant to round-off.
  while (!sim.finished()) sim.cycle();
  const Momenta end = momenta_of(sim.state());
  const double dp = (end.p - start.p).norm() / start.p.norm();
  const double dh_release = (after.h - before.h).norm() / start.h.norm();
  const double dh = (end.h - start.h).norm() / start.h.norm();
  EXPECT_LT(dp, 1e-13);
  EXPECT_LT(dh_release, 1e-12);
  EXPECT_LT(dh, 1e-12);
  const auto& e = sim.energy();
  EXPECT_NEAR(e.switch_energy, non_rigid, 1e-10 * before.kinetic);
  std::printf(
      "[ measured ] %s: |dP|/|P| %.3g, |dH|/|H| %.3g (release %.3g), release KE change "
      "%.3g of %.6g J, energy ratio - 1 %.3g, %lld cycles\n",
      shells ? "shells" : "beams", dp, dh, dh_release, release_change,
      released.kinetic_energy_before, e.ratio() - 1.0, static_cast<long long>(sim.state().cycle));
  solver::Simulation reference(read(unswitched), {});
  reference.run();
  std::printf("[ measured ] %s: energy ratio - 1 without the switches %.3g\n",
              shells ? "shells" : "beams", reference.energy().ratio() - 1.0);
  return e.ratio() - 1.0;
}

// The frozen strain energy (element/switch_state.hpp, from the stresses or resultants) against
// the work-based internal energy at the switch, for the parts without the rigid spin and with
// TSSFAC 0.05: the work sum pairs kinetic energies at half steps with strains at whole steps, so
// at one instant it differs from the strain energy by O((omega dt)^2) of the vibration's energy.
const char* const kSmallSteps = "*CONTROL_TIMESTEP\n0,0.05\n";
void check_frozen_energy(const std::string& deck, const char* what, double tolerance) {
  solver::Simulation sim(read(deck), {});
  while (sim.state().time < 0.05) sim.cycle();
  const double internal = sim.energy().internal();
  sim.cycle();
  ASSERT_EQ(sim.switch_events().size(), 1u);
  const double frozen = sim.energy().frozen_energy;
  std::printf("[ measured ] %s: frozen energy %.6g J, internal energy (work) %.6g J, ratio %.6f\n",
              what, frozen, internal, frozen / internal);
  EXPECT_NEAR(frozen, internal, tolerance * internal);
}

TEST(ShellSwitching, FrozenEnergyIsTheStrainEnergyAtTheSwitch) {
  check_frozen_energy(
      shell_plate_deck(std::string(kPairedSwitch) + kSmallSteps, 0.25, "", Vector3d::Zero()),
      "shells", 0.03);
}

TEST(BeamSwitching, FrozenEnergyIsTheStrainEnergyAtTheSwitch) {
  const std::string sets = std::string(kPairedSwitch) + kSmallSteps;
  check_frozen_energy(beam_deck(sets, 0.25, 2, Vector3d::Zero()), "beams ELFORM 2", 0.02);
  check_frozen_energy(beam_deck(sets, 0.25, 1, Vector3d::Zero()), "beams ELFORM 1", 0.02);
}

// The energy ratio after both switches (the run without switches keeps it to 1e-15): what is
// left is the rigid-body integrator's own error over the rigid phase (the body turns 1.2 rad at
// 12 rad/s, w dt = 0.12 per step at DTMAX 0.01), the exact kinetic energy L . J^-1 L / 2 drifting
// with the attitude error: second order in the step, 25 times smaller at DTMAX 0.002.
void expect_rigid_phase_error(double coarse, double fine) {
  EXPECT_LT(std::abs(coarse), 3e-5);
  EXPECT_LT(std::abs(fine), 1.5e-6);
  EXPECT_GT(std::abs(coarse), 10.0 * std::abs(fine));
}

// With the warping correction (*CONTROL_SHELL BWC 1) the element is in moment balance also when
// warped (shell_block.cpp, section 5), so the deformable phases conserve H to round-off too.
TEST(ShellSwitching, FreePlateSwitchedRigidAndBackConservesMomentaWithRotaryInertia) {
  const std::string bwc = "*CONTROL_SHELL\n20,0,-1,0,2,1\n";
  const double coarse = check_paired_switch(shell_plate_deck(kPairedSwitch + bwc, 0.25),
                                            shell_plate_deck(bwc, 0.25), true);
  const double fine = check_paired_switch(shell_plate_deck(paired_switch(0.002) + bwc, 0.25),
                                          shell_plate_deck(bwc, 0.25), true);
  expect_rigid_phase_error(coarse, fine);
}

// Fully integrated shells (ELFORM 16): the frozen energy of the 4 x NIP points is the strain
// energy at the switch, and the paired switch conserves the momenta as for ELFORM 2.
TEST(ShellSwitching, FullyIntegratedShellsFreezeTheirEnergyAndConserveMomenta) {
  check_frozen_energy(fully_integrated(shell_plate_deck(std::string(kPairedSwitch) + kSmallSteps,
                                                        0.25, "", Vector3d::Zero())),
                      "shells ELFORM 16", 0.03);
  const double coarse = check_paired_switch(fully_integrated(shell_plate_deck(kPairedSwitch, 0.25)),
                                            fully_integrated(shell_plate_deck("", 0.25)), true);
  EXPECT_LT(std::abs(coarse), 3e-5);
}

TEST(BeamSwitching, FreeBeamSwitchedRigidAndBackConservesMomentaWithRotaryInertia) {
  const double coarse =
      check_paired_switch(beam_deck(kPairedSwitch, 0.25), beam_deck("", 0.25), false);
  const double fine =
      check_paired_switch(beam_deck(paired_switch(0.002), 0.25), beam_deck("", 0.25), false);
  expect_rigid_phase_error(coarse, fine);
}

TEST(BeamSwitching, IntegratedBeamSwitchedRigidAndBackConservesMomenta) {
  const double coarse =
      check_paired_switch(beam_deck(kPairedSwitch, 0.25, 1), beam_deck("", 0.25, 1), false);
  const double fine =
      check_paired_switch(beam_deck(paired_switch(0.002), 0.25, 1), beam_deck("", 0.25, 1), false);
  expect_rigid_phase_error(coarse, fine);
}

// Objectivity of the frozen state: a deformed part (run deformable to 0.05 s), switched rigid,
// turned rigidly by a large rotation Q (2.5 rad about an oblique axis, imposed on the body and
// its nodes) and released. Its elements' forces and moments at the turned configuration, from
// the restored state with no increment, must be Q times those at the switch; the co-rotational
// stresses (shells) and resultants (beams) come back unchanged.
template <class Family>
void check_objectivity(const std::string& deck, Family family) {
  const model::Model model = read(deck);
  solver::Simulation sim(read(deck), {});
  while (sim.state().time < 0.05) sim.cycle();
  solver::State state = sim.state();  // deformed, between cycles: x^n
  const solver::NodeIndex index(model);
  solver::RigidSystem rigid = solver::build_rigid_system(model, index, state);
  auto& blocks = family(state);
  ASSERT_EQ(blocks.size(), 1u);
  const auto frozen = blocks[0];
  switching::PartSwitcher switcher(model, state);
  model::PartSwitch part;
  part.pid = 1;
  switcher.to_rigid({part}, state.time, state, rigid);
  ASSERT_EQ(rigid.bodies.size(), 1u);
  EXPECT_TRUE(blocks[0].rigid);
  // The imposed rigid motion.
  const Matrix3d q =
      Eigen::AngleAxisd(2.5, Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  auto& body = rigid.bodies[0];
  const Vector3d c = body.state.centre;
  auto& n = state.nodes;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Vector3d x = c + q * (Vector3d(n.x.x[i], n.x.y[i], n.x.z[i]) - c);
    n.x.x[i] = x.x();
    n.x.y[i] = x.y();
    n.x.z[i] = x.z();
  }
  body.state.rotation = q * body.state.rotation;
  switcher.to_deformable({part}, state.time, state, rigid);
  EXPECT_FALSE(blocks[0].rigid);
  EXPECT_TRUE(rigid.bodies.empty());

  const auto& rot = state.rotations;
  const element::RotationalView spins{rot.w.x.data(), rot.w.y.data(), rot.w.z.data()};
  auto forces = [&](auto block, const solver::NodalState& nodes) {
    if constexpr (std::is_same_v<decltype(block), element::ShellBlock>) {
      element::compute_shell_forces(block, solver::view_of(nodes), spins, 0.0);
    } else {
      element::compute_beam_forces(block, solver::view_of(nodes), spins, 0.0);
    }
    return block;
  };
  const auto at_switch = forces(frozen, sim.state().nodes);
  const auto released = forces(blocks[0], state.nodes);
  // Without turning what the block keeps in global axes (the beam frames): the same check on
  // the frozen block as it was, to show what the turn repairs.
  const auto unturned = forces(frozen, state.nodes);
  const double scale = largest_magnitude(at_switch.force);
  ASSERT_GT(scale, 0.0);
  double worst = 0.0, worst_unturned = 0.0;
  for (std::size_t k = 0; k + 2 < at_switch.force.size(); k += 3) {
    const Vector3d want =
        q * Vector3d(at_switch.force[k], at_switch.force[k + 1], at_switch.force[k + 2]);
    worst = std::max(
        worst,
        (Vector3d(released.force[k], released.force[k + 1], released.force[k + 2]) - want).norm());
    worst_unturned = std::max(
        worst_unturned,
        (Vector3d(unturned.force[k], unturned.force[k + 1], unturned.force[k + 2]) - want).norm());
  }
  EXPECT_LT(worst, 1e-10 * scale);
  auto state_of = [](const auto& block) -> const std::vector<double>& {
    if constexpr (std::is_same_v<std::decay_t<decltype(block)>, element::ShellBlock>) {
      return block.stress;
    } else {
      return block.resultant;
    }
  };
  const std::vector<double>& kept = state_of(frozen);
  const std::vector<double>& back = state_of(released);
  double stress_change = 0.0;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    stress_change = std::max(stress_change, std::abs(kept[k] - back[k]));
  }
  EXPECT_LT(stress_change, 1e-10 * largest_magnitude(kept));
  std::printf(
      "[ measured ] force error after Q: %.3g of the largest force %.3g (state not "
      "turned: %.3g); stress/resultant change %.3g of %.3g\n",
      worst / scale, scale, worst_unturned / scale, stress_change, largest_magnitude(kept));

  // The part continues as if it had been rotated: one step (dt = 2e-4 s) of the deformed part
  // with its velocities and spins from before the switch, against the same step of the released
  // part at the turned configuration with the turned velocities Q v and spins Q w. Forces and
  // moments must be Q times, the co-rotational stresses / resultants equal.
  const double dt = 2e-4;
  solver::NodalState moved = sim.state().nodes, turned_nodes = state.nodes;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const Vector3d v(moved.v.x[i], moved.v.y[i], moved.v.z[i]);
    const Vector3d x = Vector3d(moved.x.x[i], moved.x.y[i], moved.x.z[i]) + dt * v;
    const Vector3d xq = c + q * (x - c), vq = q * v;
    moved.x.x[i] = x.x();
    moved.x.y[i] = x.y();
    moved.x.z[i] = x.z();
    turned_nodes.x.x[i] = xq.x();
    turned_nodes.x.y[i] = xq.y();
    turned_nodes.x.z[i] = xq.z();
    turned_nodes.v.x[i] = vq.x();
    turned_nodes.v.y[i] = vq.y();
    turned_nodes.v.z[i] = vq.z();
  }
  const auto& w0 = sim.state().rotations.w;
  std::vector<double> wx(w0.x.size()), wy(w0.x.size()), wz(w0.x.size());
  for (std::size_t r = 0; r < wx.size(); ++r) {
    const Vector3d w = q * Vector3d(w0.x[r], w0.y[r], w0.z[r]);
    wx[r] = w.x();
    wy[r] = w.y();
    wz[r] = w.z();
  }
  const element::RotationalView spins_before{w0.x.data(), w0.y.data(), w0.z.data()};
  const element::RotationalView spins_turned{wx.data(), wy.data(), wz.data()};
  auto step = [&](auto block, const solver::NodalState& nodes, const element::RotationalView& w) {
    if constexpr (std::is_same_v<decltype(block), element::ShellBlock>) {
      element::compute_shell_forces(block, solver::view_of(nodes), w, dt);
    } else {
      element::compute_beam_forces(block, solver::view_of(nodes), w, dt);
    }
    return block;
  };
  const auto deformed = step(frozen, moved, spins_before);
  const auto continued = step(blocks[0], turned_nodes, spins_turned);
  double step_worst = 0.0, step_scale = largest_magnitude(deformed.force), state_worst = 0.0;
  for (std::size_t k = 0; k + 2 < deformed.force.size(); k += 3) {
    const Vector3d want =
        q * Vector3d(deformed.force[k], deformed.force[k + 1], deformed.force[k + 2]);
    step_worst = std::max(
        step_worst,
        (Vector3d(continued.force[k], continued.force[k + 1], continued.force[k + 2]) - want)
            .norm());
  }
  const std::vector<double>& a = state_of(deformed);
  const std::vector<double>& b = state_of(continued);
  for (std::size_t k = 0; k < a.size(); ++k)
    state_worst = std::max(state_worst, std::abs(a[k] - b[k]));
  EXPECT_LT(step_worst, 1e-9 * step_scale);
  EXPECT_LT(state_worst, 1e-9 * largest_magnitude(a));
  std::printf(
      "[ measured ] one step after the release vs the unrotated step: forces %.3g, "
      "stresses/resultants %.3g (relative)\n",
      step_worst / step_scale, state_worst / largest_magnitude(a));
}

TEST(ShellSwitching, FrozenStressesComeBackObjectiveAfterALargeRigidRotation) {
  check_objectivity(
      shell_plate_deck("", 0.25), [](solver::State & s) -> auto& { return s.shell_blocks; });
}

TEST(BeamSwitching, FrozenResultantsAndFramesComeBackObjectiveAfterALargeRigidRotation) {
  for (const int elform : {2, 1}) {
    SCOPED_TRACE(fmt::format("ELFORM {}", elform));
    check_objectivity(
        beam_deck("", 0.25, elform), [](solver::State & s) -> auto& { return s.beam_blocks; });
  }
}

// *DEFORMABLE_TO_RIGID at the start: the plate spinning about an oblique axis through its centre
// (*INITIAL_VELOCITY_GENERATION: translations and the nodal spins). Lumped masses on the
// (nx + 1) x (ny + 1) grid are the trapezoidal rule, exact for x^2:
//   sum m x^2 = M a^2 (1 + 2 / nx^2) / 12,   sum m y^2 = M b^2 (1 + 2 / ny^2) / 12,
// and the rotary inertia of the shell nodes (element/shell_block.hpp: m_I (A_e / 4 + t^2 / 12) per
// node share m_I) adds R = M (A_e / 4 + t^2 / 12) about every axis:
//   Ixx = sum m y^2 + R,  Iyy = sum m x^2 + R,  Izz = sum m (x^2 + y^2) + R,  products 0.
// The continuum plate has Ixx = M (b^2 + t^2) / 12 etc.; the lumped grid tends to it with
// 1 / n^2, and the A_e / 4 share of R is the rotary-inertia scaling of the shell (a numerical
// choice that keeps rotations off the step limit), which the body carries so that a switch
// conserves the nodes' spin I w exactly.
TEST(ShellSwitching, DeformableToRigidAtStartHasThePlateMassAndInertia) {
  const Vector3d axis = Vector3d(1.0, 1.0, 2.0).normalized();
  const double omega = 5.0;
  const std::string generation = fmt::format(
      "*INITIAL_VELOCITY_GENERATION\n1,2,{:.17g},1.0,-0.5,0.25\n0,0,0,{:.17g},{:.17g},{:.17g}\n",
      omega, axis.x(), axis.y(), axis.z());
  const std::string deck =
      shell_plate_deck("*DEFORMABLE_TO_RIGID\n1\n*CONTROL_TIMESTEP\n1.0e-3,0.9\n", 0.2, generation);
  solver::Simulation sim(read(deck), {});
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
  const auto& body = sim.rigid_bodies().bodies[0];
  const double a = 1.0, b = 0.5, t = 0.02, rho = 1000.0;
  const int nx = 8, ny = 4;
  const double mass = rho * t * a * b;
  const double ae = (a / nx) * (b / ny);
  const double sxx = mass * a * a * (1.0 + 2.0 / (nx * nx)) / 12.0;
  const double syy = mass * b * b * (1.0 + 2.0 / (ny * ny)) / 12.0;
  const double rotary = mass * (ae / 4.0 + t * t / 12.0);
  Matrix3d want = Matrix3d::Zero();
  want.diagonal() << syy + rotary, sxx + rotary, sxx + syy + rotary;
  EXPECT_NEAR(body.state.mass, mass, 1e-13 * mass);
  const Matrix3d got = rigid::global_inertia(body.state);
  EXPECT_NEAR((got - want).norm(), 0.0, 1e-12 * want.norm());
  EXPECT_NEAR(body.state.centre.norm(), 0.0, 1e-15);
  // The generated field is rigid: nothing is removed and the body spins at omega about the axis.
  ASSERT_EQ(sim.switch_events().size(), 1u);
  EXPECT_NEAR(sim.switch_events()[0].kinetic_energy_before,
              sim.switch_events()[0].kinetic_energy_after,
              1e-12 * sim.switch_events()[0].kinetic_energy_before);
  EXPECT_NEAR((body.state.angular_velocity - omega * axis).norm(), 0.0, 1e-12 * omega);
  std::printf(
      "[ measured ] body mass %.15g kg, Ixx %.10g Iyy %.10g Izz %.10g (rotary %.6g); "
      "|J - J_ref| / |J_ref| %.3g\n",
      body.state.mass, got(0, 0), got(1, 1), got(2, 2), rotary, (got - want).norm() / want.norm());
  // Free flight: the centre moves at the initial velocity, the angular momentum about the
  // origin is constant (the spin precesses: the axis is not principal).
  const Vector3d v0(1.0, -0.5, 0.25);
  auto h_of = [&] {
    const auto& s = sim.rigid_bodies().bodies[0].state;
    return Vector3d(s.centre.cross(s.mass * s.velocity) + s.angular_momentum);
  };
  const Vector3d h0 = h_of();
  sim.cycle();
  const Vector3d c1 = sim.rigid_bodies().bodies[0].state.centre;
  const double t1 = sim.state().time;
  while (sim.state().time < 0.15) sim.cycle();
  const auto& s = sim.rigid_bodies().bodies[0].state;
  EXPECT_NEAR((s.centre - c1 - v0 * (sim.state().time - t1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((s.velocity - v0).norm(), 0.0, 1e-13);
  EXPECT_NEAR((h_of() - h0).norm(), 0.0, 1e-12 * h0.norm());
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
}

// *DEFORMABLE_TO_RIGID_INERTIA for the shell part replaces its nodes' lumped masses and rotary
// inertias: body mass TM, inertia the card's about (XC, YC, ZC); the velocities carry the nodes'
// momenta: v_c = P / TM, w = J_card^-1 H with H = J_lumped w0 (the generated rigid spin w0 about
// the centre, J_lumped the closed form of the test above, rotary inertia included).
TEST(ShellSwitching, DeformableToRigidInertiaCardReplacesTheShellMasses) {
  const Vector3d axis = Vector3d(1.0, 1.0, 2.0).normalized();
  const double omega = 5.0;
  const std::string cards = fmt::format(
      "*INITIAL_VELOCITY_GENERATION\n1,2,{:.17g},1.0,-0.5,0.25\n0,0,0,{:.17g},{:.17g},{:.17g}\n"
      "*DEFORMABLE_TO_RIGID\n1\n*DEFORMABLE_TO_RIGID_INERTIA\n1\n0.0,0.0,0.0,12.0\n"
      "0.5,0.0,0.0,1.0,0.0,1.5\n*CONTROL_TIMESTEP\n1.0e-3,0.9\n",
      omega, axis.x(), axis.y(), axis.z());
  solver::Simulation sim(read(shell_plate_deck("", 0.01, cards)), {});
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
  const auto& body = sim.rigid_bodies().bodies[0].state;
  EXPECT_DOUBLE_EQ(body.mass, 12.0);
  Matrix3d card = Matrix3d::Zero();
  card.diagonal() << 0.5, 1.0, 1.5;
  EXPECT_NEAR((rigid::global_inertia(body) - card).norm(), 0.0, 1e-14);
  const double mass = 10.0, a = 1.0, b = 0.5, t = 0.02;
  const double rotary = mass * ((a / 8) * (b / 4) / 4.0 + t * t / 12.0);
  Matrix3d lumped = Matrix3d::Zero();
  const double sxx = mass * a * a * (1.0 + 2.0 / 64.0) / 12.0;
  const double syy = mass * b * b * (1.0 + 2.0 / 16.0) / 12.0;
  lumped.diagonal() << syy + rotary, sxx + rotary, sxx + syy + rotary;
  const Vector3d p = mass * Vector3d(1.0, -0.5, 0.25);
  EXPECT_NEAR((body.velocity - p / 12.0).norm(), 0.0, 1e-14);
  const Vector3d w = card.inverse() * (lumped * (omega * axis));
  EXPECT_NEAR((body.angular_velocity - w).norm(), 0.0, 1e-12 * w.norm());
}

// Trusses (ELFORM 3) have no rotations: a straight chain switched rigid has no inertia about its
// axis, which the body regularises (1e-6 of the largest moment, as for spot welds; the chain's
// H has no component along it); P and H conserved through both switches.
TEST(BeamSwitching, StraightTrussChainSwitchedRigidAndBack) {
  std::string deck = "*KEYWORD\n*NODE\n";
  for (int k = 0; k <= 8; ++k) deck += fmt::format("{},{:.17g},0,0\n", k + 1, -0.5 + k / 8.0);
  deck += "*ELEMENT_BEAM\n";
  for (int k = 0; k < 8; ++k) deck += fmt::format("{},1,{},{}\n", k + 1, k + 1, k + 2);
  deck += "*PART\ntruss\n1,1,1\n*MAT_ELASTIC\n1,1000.0,1.0e7,0.3\n*SECTION_BEAM\n1,3\n5.0e-3\n";
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= 8; ++k) {
    const double x = -0.5 + k / 8.0;
    const Vector3d v =
        kV0 + Vector3d(0.0, 0.0, 2.0).cross(Vector3d(x, 0, 0)) + Vector3d(0.8 * x, 0.0, 0.0);
    deck += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", k + 1, v.x(), v.y(), v.z());
  }
  deck += kPairedSwitch + "*CONTROL_TERMINATION\n0.25\n*END\n";
  solver::Simulation sim(read(deck), {});
  const Momenta start = momenta_of(sim.state());
  EXPECT_EQ(start.rotary, 0.0);
  while (sim.switch_events().empty()) sim.cycle();
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
  const Vector3d moments = sim.rigid_bodies().bodies[0].state.principal_inertia;
  EXPECT_NEAR(moments.x(), 1e-6 * moments.z(), 1e-9 * moments.z());  // the regularisation
  sim.run();
  ASSERT_EQ(sim.switch_events().size(), 2u);
  const Momenta end = momenta_of(sim.state());
  EXPECT_LT((end.p - start.p).norm(), 1e-13 * start.p.norm());
  EXPECT_LT((end.h - start.h).norm(), 1e-12 * start.h.norm());
  EXPECT_TRUE(std::isfinite(sim.energy().ratio()));
  std::printf("[ measured ] truss chain: |dP|/|P| %.3g, |dH|/|H| %.3g, energy ratio - 1 %.3g\n",
              (end.p - start.p).norm() / start.p.norm(), (end.h - start.h).norm() / start.h.norm(),
              sim.energy().ratio() - 1.0);
}

// Two solid parts sharing a face, switched by one set (two D2R cards, no LRB): each part is a
// group of its own and the second merges the body the first just made. The kinetic energy
// removed must be the non-rigid energy of the nodes, counted once (the first body's momenta
// were once counted twice: "before" exceeded the model's whole kinetic energy).
TEST(PartSwitching, TwoPartsSharingNodesInOneSetCountTheirMomentaOnce) {
  BoxMesh mesh;
  mesh.nx = 4;
  mesh.ny = 2;
  mesh.nz = 2;
  mesh.lx = 1.2;
  mesh.ly = 0.8;
  mesh.lz = 0.4;
  std::string deck = "*KEYWORD\n" +
                     mesh.keyword_text([](int i, int, int) { return i < 2 ? 1 : 2; }) +
                     elastic(1, 1000.0, 1e7, 0.3, 4) + elastic(2, 1000.0, 1e7, 0.3, 4);
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= mesh.nz; ++k)
    for (int j = 0; j <= mesh.ny; ++j)
      for (int i = 0; i <= mesh.nx; ++i) {
        double x, y, z;
        mesh.coordinates(i, j, k, x, y, z);
        deck += node_velocity(mesh.node_id(i, j, k), Vector3d(x - 0.6, y - 0.4, z - 0.2), false);
      }
  deck +=
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,0.05\n0,0,0,0.01,2,0\n1\n2\n"
      "*CONTROL_TERMINATION\n0.1\n*END\n";
  solver::Simulation sim(read(deck), {});
  while (sim.state().time < 0.05) sim.cycle();
  const Momenta before = momenta_of(sim.state());
  sim.cycle();
  ASSERT_EQ(sim.switch_events().size(), 1u);
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
  const auto& event = sim.switch_events()[0];
  EXPECT_NEAR(event.kinetic_energy_before, before.kinetic, 1e-12 * before.kinetic);
  EXPECT_NEAR(event.kinetic_energy_before - event.kinetic_energy_after,
              before.kinetic - before.rigid_kinetic, 1e-10 * before.kinetic);
  EXPECT_NEAR((event.momentum - before.p).norm(), 0.0, 1e-13 * before.p.norm());
  EXPECT_NEAR((event.angular_momentum - before.h).norm(), 0.0, 1e-13 * before.h.norm());
  // After one rigid step: the rigid body's L . w^{n+1/2} / 2 measure.
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-5);
}

// The restart tests' switching deck (restart_decks.hpp): shells and beams of parts 2 and 4, which
// share nodes with the deformable parts 1 and 3, become one body and are released again; the run
// with loads, plasticity and the attached deformable parts keeps its energy balance.
TEST(ShellSwitching, ShellsAndBeamsAttachedToDeformablePartsSwitchAndReturn) {
  solver::Simulation sim(read(restart_decks::shells_and_beams_switching(4e-5)), {});
  sim.run();
  ASSERT_EQ(sim.switch_events().size(), 2u);
  EXPECT_TRUE(sim.switch_events()[0].to_rigid);
  EXPECT_GE(sim.switch_events()[0].time, 8e-6);
  EXPECT_EQ(sim.switch_events()[0].parts, (std::vector<model::Id>{2, 4}));
  EXPECT_FALSE(sim.switch_events()[1].to_rigid);
  EXPECT_GE(sim.switch_events()[1].time, 2.6e-5);
  EXPECT_TRUE(sim.rigid_bodies().bodies.empty());
  const auto& e = sim.energy();
  std::printf(
      "[ measured ] switched shells and beams deck: energy ratio - 1 %.3g, switch energy "
      "%.3g of kinetic %.3g\n",
      e.ratio() - 1.0, e.switch_energy, e.kinetic);
  EXPECT_NEAR(e.ratio(), 1.0, 1e-6);
  // The switch to rigid removes the non-rigid part of the nodes' motion only (it once counted a
  // body made by the first of two parts sharing nodes twice: 269 J "removed" of 478 J).
  const auto& to_rigid = sim.switch_events()[0];
  EXPECT_LT(to_rigid.kinetic_energy_before - to_rigid.kinetic_energy_after,
            0.01 * to_rigid.kinetic_energy_before);
}

// *PART_MODES on a deformable shell part stays refused (flexible bodies of shells are not
// supported): the error names the file, line, keyword and field.
TEST(ShellSwitching, PartModesOnADeformableShellPartIsRefusedNamingTheCard) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("rigidflex_shell_modes_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string deck = shell_plate_deck(kPairedSwitch, 0.25);
  deck.insert(deck.rfind("*END"), "*PART_MODES\n1,10,0,0,3\nmodes.h5\n");
  const auto path = dir / "shell_modes.k";
  {
    std::ofstream out(path);
    out << deck;
  }
  std::size_t line = 1;
  for (std::size_t k = 0; k < deck.find("*PART_MODES"); ++k) line += deck[k] == '\n';
  try {
    solver::Simulation sim(io::read_deck(path), {});
    ADD_FAILURE() << "no error for *PART_MODES on a shell part";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(fmt::format("shell_modes.k:{}", line + 1)), std::string::npos)
        << message;
    EXPECT_NE(message.find("*PART_MODES"), std::string::npos) << message;
    EXPECT_NE(message.find("PID"), std::string::npos) << message;
    EXPECT_NE(message.find("is a deformable shell or beam part: *PART_MODES on it"),
              std::string::npos)
        << message;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rf::test
