// Part switching driven by a rigid wall: an elastic ball dropped on a fixed *RIGIDWALL_PLANAR
// with a paired *DEFORMABLE_TO_RIGID_AUTOMATIC pair, CODE 1 (wall force zero: rigid) and
// CODE 3 (wall force nonzero or within OFFSET: deformable). References that do not come from
// the solver: the momentum balance (wall impulse minus weight), the energy balance with the
// strain energy from the element stresses, the gravity work from the centre-of-mass height and
// the non-rigid kinetic energy computed here from the nodal field, and Hertz's elastic sphere
// on a rigid plane for the contact time and the rebound.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>

#include "ball_drop_support.hpp"

namespace rf::test {
namespace {

// The drop: ball of radius 0.1 m, 0.01 m above the wall, moving down at 1 m/s under gravity.
// OFFSET is what makes the ball deformable *before* it touches: CODE 3 on the force alone sees
// the force of the last cycle, when the rigid ball has already hit the wall, and a constraint
// wall stops a rigid body plastically (measured with OFFSET 0: rebound 0.31 of the impact speed
// instead of 0.95).
struct BallDrop {
  double rho = 1000.0, young = 1e6, poisson = 0.3, g = 9.81, v0 = 1.0, gap = 0.01;
  double dtmax = 1e-3;        // DTMAX of the rigid set: the step of the rigid phases
  double time3_rigid = 5e-3;  // TIME3 of set 10: the ball leaves the OFFSET zone meanwhile
  double time3 = 0.02;        // TIME3 of set 20: covers the approach inside the OFFSET zone
  double offset = 3e-3;       // OFFSET of set 20: more than a rigid step travels (~1.1 mm)
  double end_time = 0.09;
};

std::string ball_drop_deck(const BallMesh& ball, const BallDrop& p) {
  std::string deck =
      "*KEYWORD\n" + ball.keyword_text() + elastic_part(p.rho, p.young, p.poisson, 1, 6) +
      fmt::format("*INITIAL_VELOCITY_GENERATION\n1,2,0,0,0,{:.17g}\n0,0,0,0,0,0\n", -p.v0) +
      fmt::format("*LOAD_BODY_Z\n9,1.0\n*DEFINE_CURVE\n9\n0,{0:.17g}\n1e3,{0:.17g}\n", p.g) +
      "*RIGIDWALL_PLANAR\n0\n0,0,0,0,0,1\n";
  // Set 10 (PAIRED 1, armed first; CODE 1): rigid while wall 1 pushes nothing, step DTMAX.
  deck +=
      fmt::format("*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,1,0,0,{:.17g},1,20,1\n0,0,0,{:.17g},1,0\n1\n",
                  p.time3_rigid, p.dtmax);
  // Set 20 (PAIRED -1; CODE 3): deformable once the wall pushes or a node of the ball is within
  // OFFSET of it; DTMAX 0 lifts the cap.
  deck += fmt::format(
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,3,0,0,{:.17g},1,10,-1\n0,0,0,0,0,1,{:.17g}\n1\n", p.time3,
      p.offset);
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", p.end_time);
  return deck;
}

TEST(SwitchingWall, BallMeshHasPositiveJacobiansAndTheSphereVolume) {
  const BallMesh ball;
  const BallMesh::Numbered mesh = ball.numbered();
  const int m = ball.m;
  EXPECT_EQ(mesh.elements.size(),
            static_cast<std::size_t>(8 * m * m * m + 24 * m * m * ball.layers));
  // Every corner of every hexahedron, from the connectivity the deck gets: positive, and no
  // flattened corner (a cube's corner is 1; measured 0.71).
  const double worst = smallest_scaled_jacobian(mesh);
  // Volume through the solver's lumped masses, which sum to rho V of the trilinear elements.
  solver::Simulation sim(
      read("*KEYWORD\n" + ball.keyword_text() + elastic_part(1000.0, 1e6, 0.3, 1, 6) +
           "*CONTROL_TERMINATION\n1e-3,\n*END\n"),
      {});
  double mass = 0.0;
  for (const double mi : sim.state().nodes.mass) mass += mi;
  const double sphere = 1000.0 * 4.0 / 3.0 * std::numbers::pi * std::pow(ball.radius, 3);
  std::printf(
      "ball mesh: %zu hexahedra, %zu nodes, smallest scaled corner Jacobian %.4f, mass "
      "%.5f = %.4f of the sphere's\n",
      mesh.elements.size(), mesh.nodes.size(), worst, mass, mass / sphere);
  EXPECT_GT(worst, 0.7);
  // Inscribed in the sphere (nodes on it, flat facets between): a little less than its volume.
  EXPECT_LT(mass, sphere);
  EXPECT_GT(mass, 0.95 * sphere);
  double farthest = 0.0;
  for (const auto& x : mesh.nodes) farthest = std::max(farthest, x.norm());
  EXPECT_NEAR(farthest, ball.radius, 1e-15);
}

// The acceptance test: rigid in flight, deformable while the wall pushes, rigid again
// after the rebound; TIME3 respected; a larger step in the rigid phases.
TEST(SwitchingWall, BallDropRigidInFlightDeformableOnTheWallRigidAfterRebound) {
  BallMesh ball;
  const BallDrop p;
  ball.centre = Vector3d(0, 0, ball.radius + p.gap);
  solver::Simulation sim(read(ball_drop_deck(ball, p)), {});
  const auto& walls = sim.rigid_walls();
  const NodalField start = nodal_field(sim.state());
  const double mass = start.mass;
  const Vector3d p0 = total_momentum(sim);

  double lowest = std::numeric_limits<double>::infinity();
  double force_impulse = 0.0, t_previous = 0.0;  // sum F^n dt_avg^n from the force query
  double max_momentum_error = 0.0, max_ratio_error = 0.0;
  double rigid_dt_min = std::numeric_limits<double>::infinity(), elastic_dt_max = 0.0;
  double first_contact = -1.0, last_contact = -1.0, peak_force = 0.0;
  double v_in = 0.0, v_out = 0.0;  // centre velocity before the first and after the last push
  double non_rigid_removed = 0.0;  // this test's own fit, at each switch to rigid
  bool pushed_while_rigid = false, zero_force_inside_delay = false;
  bool offset_reached_inside_delay = false;
  // Energy terms at the last full cycle (positions at t^{n+1}, velocities at t^{n+1/2}).
  double kinetic_end = 0.0, gravity_work = 0.0, strain_end = 0.0, internal_end = 0.0;
  std::size_t events_seen = 0;
  bool was_rigid = false;
  while (!sim.finished()) {
    const NodalField before = nodal_field(sim.state());
    const double t_n = sim.state().time;
    sim.cycle();
    // Switches of this cycle happened at its start, on the state `before` describes.
    for (; events_seen < sim.switch_events().size(); ++events_seen) {
      if (sim.switch_events()[events_seen].to_rigid) {
        non_rigid_removed += before.kinetic - before.rigid_kinetic;
      }
    }
    const bool rigid = !sim.rigid_bodies().bodies.empty();
    const double step = sim.finished() ? sim.state().dt : sim.state().dt_prev;  // dt^{n+1/2}
    // The step of a cycle that switched to rigid was chosen before the switch; the last one
    // is shortened to land on the end time.
    const bool last_step = t_n + step >= p.end_time * (1.0 - 1e-12);
    if (rigid && was_rigid && !last_step) rigid_dt_min = std::min(rigid_dt_min, step);
    was_rigid = rigid;
    if (!rigid) elastic_dt_max = std::max(elastic_dt_max, step);

    // Wall force at t^n acts over dt_avg^n = (t^{n+1} - t^{n-1}) / 2.
    const double force = contact::wall_normal_force(walls, 1);
    force_impulse += force * 0.5 * (t_n + step - t_previous);
    t_previous = t_n;
    const double vz = total_momentum(sim).z() / mass;
    if (force > 0.0) {
      if (first_contact < 0.0) first_contact = t_n;
      last_contact = t_n;
      peak_force = std::max(peak_force, force);
      pushed_while_rigid |= rigid;
    } else if (first_contact < 0.0) {
      v_in = vz;
    } else if (v_out == 0.0) {
      v_out = vz;
    }
    // Momentum: the wall's impulse minus the weight's, to round-off, every cycle.
    const double t_half = half_step_time(sim);
    const double momentum_z = total_momentum(sim).z() - p0.z();
    max_momentum_error =
        std::max(max_momentum_error, std::abs(momentum_z - (force_impulse - mass * p.g * t_half)));
    max_ratio_error = std::max(max_ratio_error, std::abs(sim.energy().ratio() - 1.0));
    lowest = std::min(lowest, lowest_z(sim.state()));
    // Set 10 (CODE 1) would fire at any zero-force cycle, set 20 (CODE 3) whenever the ball
    // is within OFFSET: inside the other's delay they must not.
    const auto& events = sim.switch_events();
    if (events.size() == 2 && t_n > events[1].time && t_n < events[1].time + p.time3 &&
        force == 0.0) {
      zero_force_inside_delay = true;
    }
    if (events.size() == 3 && t_n > events[2].time && t_n < events[2].time + p.time3_rigid &&
        lowest_z(sim.state()) < p.offset) {
      offset_reached_inside_delay = true;
    }
    if (!sim.finished()) {
      const NodalField now = nodal_field(sim.state());
      // Gravity's work up to t^{n+1/2}: the centre's drop to (z^n + z^{n+1}) / 2.
      const double z_half = now.centre.z() - 0.5 * sim.state().dt_prev * now.p.z() / mass;
      gravity_work = mass * p.g * (start.centre.z() - z_half);
      kinetic_end = now.kinetic;
      strain_end = elastic_strain_energy(sim.state());
      internal_end = sim.energy().internal();
    }
  }

  // Sequence: rigid at the start (force zero), deformable before it touches (OFFSET), rigid
  // once the wall lets go; then it flies off and nothing else fires.
  const auto& events = sim.switch_events();
  expect_rigid_deformable_rigid(events, first_contact, last_contact);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_FALSE(pushed_while_rigid);
  // TIME3: set 10 waited out set 20's delay although the force was zero inside it (the
  // approach through the OFFSET zone), and fired at the first zero-force cycle after contact.
  EXPECT_TRUE(zero_force_inside_delay);
  EXPECT_GE(events[2].time, events[1].time + p.time3);
  EXPECT_GE(events[1].time, events[0].time + p.time3_rigid);
  // Likewise set 20 waited out set 10's delay while the rebounding ball was still within
  // OFFSET of the wall (without it the pair would switch back at once).
  EXPECT_TRUE(offset_reached_inside_delay);
  // The force of a cycle decides at the start of the next: the first zero-force cycle after
  // the last push is the one after it, and set 10 fires at the start of the cycle after that.
  EXPECT_LE(events[2].time, last_contact + 2.0 * elastic_dt_max * (1 + 1e-12));
  // Rigid phases run at DTMAX, 4.3 times the elastic step.
  EXPECT_DOUBLE_EQ(rigid_dt_min, p.dtmax);
  EXPECT_GT(rigid_dt_min, 4.0 * elastic_dt_max);
  // No node behind the wall, beyond round-off of the 0.1 m ball.
  EXPECT_GE(lowest, -1e-15);

  // Momentum over the contact equals the wall impulse (force query integrated here, and the
  // wall's own sum) less the weight's impulse, every cycle: measured 6.5e-15 of M v0.
  const double wall_impulse = walls.walls[0].normal_impulse;
  const double contact_time = last_contact - first_contact;
  EXPECT_NEAR(force_impulse, wall_impulse, 1e-12 * mass * p.v0);
  EXPECT_LT(max_momentum_error, 1e-12 * mass * p.v0);

  // Energy. The solver's ratio (total = KE + internal work + switch energy) / (KE0 + external
  // work) is an identity of the scheme: 1 to round-off (measured 1.1e-14) because the removed
  // non-rigid energy is counted; without it the ratio would end 9 % low.
  const auto& e = sim.energy();
  EXPECT_LT(max_ratio_error, 1e-12);
  const double ratio_without_switch =
      (e.total() - e.switch_energy) / (e.initial_total + e.external_work);
  EXPECT_LT(ratio_without_switch, 0.95);
  EXPECT_NEAR(e.switch_energy, non_rigid_removed, 1e-12 * start.kinetic);
  EXPECT_GT(e.switch_energy, 0.02 * start.kinetic);
  ASSERT_FALSE(sim.rigid_bodies().bodies.empty());
  // Balances from terms not taken from the solver's work sums: nodal kinetic energy, gravity's
  // work from the centre's drop, the non-rigid energy this test's own fit found at the switch.
  // The wall's dissipation (constraint impacts are plastic) and the hourglass energy are the
  // solver's. (1) With the solver's internal energy: measured 1.7e-5 of KE0, the O(dt^2 g)
  // difference between sum f . d^n and M g dz where the step jumps between 0.23 and 1 ms.
  // (2) With the strain energy of the frozen stresses instead, 1/2 s : C^-1 : s: measured
  // 2.3e-3 of KE0: the hypoelastic stress update is not exactly path independent through 10 %
  // compression (internal work and stress energy differ by 1.5 % at the deepest point).
  const double supplied = start.kinetic + gravity_work + e.rigidwall_work;
  // The bulk viscosity's dissipation (LS-DYNA's default, on here) is the solver's too.
  const double dissipated = e.hourglass + e.bulk_viscosity;
  const double with_internal = kinetic_end + internal_end + dissipated + non_rigid_removed;
  const double with_strain = kinetic_end + strain_end + dissipated + non_rigid_removed;
  EXPECT_NEAR(with_internal, supplied, 1e-4 * start.kinetic);
  EXPECT_NEAR(with_strain, supplied, 5e-3 * start.kinetic);
  EXPECT_NEAR(e.frozen_energy, strain_end, 1e-12 * start.kinetic);

  // Hertz: elastic sphere (mass M, radius R) on a rigid plane at v: contact time
  // 2.87 (M^2 / (R E*^2 v))^(1/5), E* = E / (1 - nu^2); rebound at v (no loss). Measured: 3.5 %
  // shorter on this 864-element faceted ball at 10 % compression; restitution 0.95, the loss
  // being the constraint impacts (wall work, 2.5 % of the impact energy) and the vibration the
  // ball still has when it leaves (removed or frozen at the switch): loose bounds.
  const double e_star = p.young / (1.0 - p.poisson * p.poisson);
  const double hertz_time =
      2.87 * std::pow(mass * mass / (ball.radius * e_star * e_star * std::abs(v_in)), 0.2);
  const double hertz_force =
      4.0 / 3.0 * e_star * std::sqrt(ball.radius) *
      std::pow(15.0 * mass * v_in * v_in / (16.0 * e_star * std::sqrt(ball.radius)), 0.6);
  const double restitution = -v_out / v_in;
  std::printf(
      "ball drop: mass %.5f, v_in %.5f, v_out %.5f (restitution %.4f), contact %.5f s (Hertz "
      "%.5f), peak force %.1f (Hertz %.1f), wall impulse %.6f (momentum error %.2g of M v0), "
      "wall work %.4f, switch energy %.5f (own fit %.5f), frozen strain %.5f, hourglass %.3g, "
      "KE0 %.5f, balance with internal work %.2g, with stress energy %.2g of KE0, max |ratio - 1| "
      "%.2g (%.4f without switch energy), steps: rigid %.3g, elastic <= %.4g, "
      "lowest node %.2g\n",
      mass, v_in, v_out, restitution, contact_time, hertz_time, peak_force, hertz_force,
      wall_impulse, max_momentum_error / (mass * p.v0), e.rigidwall_work, e.switch_energy,
      non_rigid_removed, strain_end, e.hourglass, start.kinetic,
      (with_internal - supplied) / start.kinetic, (with_strain - supplied) / start.kinetic,
      max_ratio_error, ratio_without_switch, rigid_dt_min, elastic_dt_max, lowest);
  EXPECT_NEAR(contact_time, hertz_time, 0.1 * hertz_time);
  EXPECT_GT(restitution, 0.9);
  EXPECT_LT(restitution, 1.0);
}

// The contrast that shows what the delays do: without set 20's TIME3 set 10 makes the ball rigid
// again in the very next cycle (the force is still zero on the approach), and without set 10's
// TIME3 set 20 makes the rebounding ball deformable again at once (it is still within OFFSET).
TEST(SwitchingWall, WithoutTheDelaysThePairSwitchesBackInTheNextCycle) {
  for (const bool delay_after_rigid : {true, false}) {
    BallMesh ball;
    BallDrop p;
    ball.centre = Vector3d(0, 0, ball.radius + p.gap);
    if (delay_after_rigid) {
      p.time3 = 0.0;  // set 10 keeps its 5 ms, set 20 has none
    } else {
      p.time3_rigid = 0.0;
    }
    const std::size_t undone = delay_after_rigid ? 2 : 3;  // the event that undoes the previous
    solver::Simulation sim(read(ball_drop_deck(ball, p)), {});
    const double elastic_dt = sim.state().dt;
    while (!sim.finished() && sim.switch_events().size() <= undone) sim.cycle();
    const auto& events = sim.switch_events();
    ASSERT_GT(events.size(), undone);
    EXPECT_EQ(events[undone].swset, events[undone - 2].swset);
    EXPECT_EQ(events[undone].to_rigid, !events[undone - 1].to_rigid);
    EXPECT_LE(events[undone].time - events[undone - 1].time, elastic_dt * (1 + 1e-9));
  }
}

// *LOAD_BODY acts on a rigid body at its centre and on free nodes directly; switching moves
// nodes between the two. Bug found with the ball: a body made by switching took gravity twice
// (its nodes kept their nodal body force), and nodes of a nodal rigid body deleted by NRBF = 1
// took none. Reference: in free fall the momentum of everything is P0 - M g t, every cycle.
// Block 1 (2 x 2 x 2, nodal rigid body on its top face) and block 2 fall side by side; block 2
// is made rigid at 0.02 s (NRBF = 1 deletes the nodal body) and deformable at 0.06 s (NRBF = 2
// makes it again) by paired CODE 0 sets; a second run makes block 2 rigid from the start
// (*DEFORMABLE_TO_RIGID).
TEST(SwitchingGravity, BodyForceActsOnceOnSwitchedAndReleasedNodes) {
  constexpr double g = 9.81;
  BoxMesh a;
  a.nx = a.ny = a.nz = 2;
  std::vector<int> top;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) top.push_back(a.node_id(i, j, 2));
  std::string common =
      "*KEYWORD\n" + a.keyword_text(1) + elastic_part(1000.0, 1e7, 0.3, 1, 4) + "*NODE\n";
  const double xs[2] = {2.0, 3.0}, ys[2] = {0.0, 1.0}, zs[2] = {0.0, 0.5};
  const int order[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                           {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int k = 0; k < 8; ++k) {
    common +=
        fmt::format("{},{},{},{}\n", 101 + k, xs[order[k][0]], ys[order[k][1]], zs[order[k][2]]);
  }
  common +=
      "*ELEMENT_SOLID\n101,2,101,102,103,104,105,106,107,108\n"
      "*PART\nsoft\n2,1,2,0,1\n*MAT_ELASTIC\n2,1000.0,1e7,0.3\n" +
      node_set(5, top) + "*CONSTRAINED_NODAL_RIGID_BODY\n50,0,5\n" +
      "*INITIAL_VELOCITY_GENERATION\n1,2,2.0,0.5,0.0,1.0\n1,1,1,0,0,1\n" +
      "*INITIAL_VELOCITY_GENERATION\n2,2,0.0,0.0,0.3,-0.5\n0,0,0,0,0,1\n" +
      fmt::format("*LOAD_BODY_Z\n9,1.0\n*DEFINE_CURVE\n9\n0,{0}\n1,{0}\n", g) +
      "*CONTROL_TERMINATION\n0.1,\n";
  const std::string paired =
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n31,0,0.02,0,0,0,32,1\n1,0,0,0.004,1,0\n2\n"
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n32,0,0.06,0,0,0,31,-1\n2,0,0,0,0,1\n2\n";
  const std::string at_start = "*DEFORMABLE_TO_RIGID\n2\n";
  for (const auto& switching : {paired, at_start}) {
    solver::Simulation sim(read(common + switching + "*END\n"), {});
    double mass = 0.0;
    for (const double m : sim.state().nodes.mass) mass += m;
    const Vector3d p0 = total_momentum(sim);
    double worst = 0.0;
    while (!sim.finished()) {
      sim.cycle();
      const double expected = p0.z() - mass * g * half_step_time(sim);
      worst = std::max(worst, std::abs(total_momentum(sim).z() - expected));
    }
    std::printf(
        "free fall with switching (%zu switches): worst |P_z - (P0 - M g t)| = %.2g M g T\n",
        sim.switch_events().size(), worst / (mass * g * 0.1));
    EXPECT_EQ(sim.switch_events().size(), switching == paired ? 2u : 1u);
    EXPECT_LT(worst, 1e-12 * mass * g * 0.1);
  }
}

}  // namespace
}  // namespace rf::test
