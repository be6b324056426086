// Part switching driven by contact (CODE 2 and 4 of *DEFORMABLE_TO_RIGID_AUTOMATIC): the elastic
// ball of the rigid-wall test dropped on a fixed *MAT_RIGID plate, with a penalty
// *CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID between them. Set 10 (CODE 2, PAIRED 1) makes the ball
// rigid while the contact force is zero, set 20 (CODE 4, PAIRED -1) deformable when the force is
// nonzero or a node of the ball comes within OFFSET of the plate. References that do not come
// from the solver: the momentum balance (contact impulse on the ball minus the weight's), the
// energy ratio with every term counted, Hertz's elastic sphere for the contact time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "ball_drop_support.hpp"

namespace rf::test {
namespace {

struct ContactDrop {
  double rho = 1000.0, young = 1e6, poisson = 0.3, g = 9.81, v0 = 1.0, gap = 0.01;
  double dtmax = 1e-3, time3_rigid = 5e-3, time3 = 0.02, offset = 3e-3, end_time = 0.09;
  int code_rigid = 2, code_deformable = 4;
  double penalty_scale = 10.0;  // SFS = SFM
};

// A fixed rigid plate of 8 x 8 x 1 hexahedra, 0.4 x 0.4 x 0.05 m, top face at z = 0; node IDs
// from 5001, element IDs from 5001, part 2.
std::string rigid_plate() {
  std::string s = "*NODE\n";
  const int n = 8;
  auto id = [&](int i, int j, int k) { return 5001 + i + (n + 1) * (j + (n + 1) * k); };
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", id(i, j, k), -0.2 + 0.4 * i / n,
                         -0.2 + 0.4 * j / n, -0.05 + 0.05 * k);
      }
  s += "*ELEMENT_SOLID\n";
  int eid = 5001;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      s += fmt::format("{},2,{},{},{},{},{},{},{},{}\n", eid++, id(i, j, 0), id(i + 1, j, 0),
                       id(i + 1, j + 1, 0), id(i, j + 1, 0), id(i, j, 1), id(i + 1, j, 1),
                       id(i + 1, j + 1, 1), id(i, j + 1, 1));
    }
  // Same elastic constants as the ball: they set the penalty stiffness (SOFT = 0).
  s += "*PART\nplate\n2,2,2\n*SECTION_SOLID\n2,1\n*MAT_RIGID\n2,1000.0,1e6,0.3\n1.0,7,7\n";
  return s;
}

std::string contact_drop_deck(const BallMesh& ball, const ContactDrop& p) {
  std::string deck =
      "*KEYWORD\n" + ball.keyword_text() + elastic_part(p.rho, p.young, p.poisson, 1, 6) +
      rigid_plate() +
      fmt::format("*INITIAL_VELOCITY_GENERATION\n1,2,0,0,0,{:.17g}\n0,0,0,0,0,0\n", -p.v0) +
      fmt::format("*LOAD_BODY_Z\n9,1.0\n*DEFINE_CURVE\n9\n0,{0:.17g}\n1e3,{0:.17g}\n", p.g) +
      // Contact 7: ball nodes (part 1) on the plate's segments (part 2).
      fmt::format(
          "*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID\n7,ball on plate\n1,2,3,3\n"
          "0,0,0,0,0,0,0,0\n{0:.17g},{0:.17g},0,0\n",
          p.penalty_scale);
  deck += fmt::format(
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,{},0,0,{:.17g},7,20,1\n0,0,0,{:.17g},1,0\n1\n",
      p.code_rigid, p.time3_rigid, p.dtmax);
  deck += fmt::format(
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,{},0,0,{:.17g},7,10,-1\n0,0,0,0,0,1,{:.17g}\n1\n",
      p.code_deformable, p.time3, p.offset);
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", p.end_time);
  return deck;
}

// Momentum of the ball alone (the plate is fixed): free nodes of part 1 plus its body.
Vector3d ball_momentum(const solver::Simulation& sim, std::size_t ball_nodes) {
  Vector3d p = Vector3d::Zero();
  const auto& n = sim.state().nodes;
  const auto& rigid = sim.rigid_bodies();
  for (std::size_t i = 0; i < ball_nodes; ++i) {
    if (rigid.is_rigid(static_cast<std::int32_t>(i))) continue;
    p += n.mass[i] * Vector3d(n.v.x[i], n.v.y[i], n.v.z[i]);
  }
  for (const auto& b : rigid.bodies) {
    if (b.parts.size() == 1 && b.parts.front() == 1) p += b.state.mass * b.state.velocity;
  }
  return p;
}

TEST(SwitchingContact, BallDeformableBeforeImpactOnTheRigidPlateRigidAfterRebound) {
  BallMesh ball;
  const ContactDrop p;
  ball.centre = Vector3d(0, 0, ball.radius + p.gap);
  const std::size_t ball_nodes = ball.numbered().nodes.size();
  solver::Simulation sim(read(contact_drop_deck(ball, p)), {});
  double mass = 0.0;
  for (std::size_t i = 0; i < ball_nodes; ++i) mass += sim.state().nodes.mass[i];
  const Vector3d p0 = ball_momentum(sim, ball_nodes);
  const double ke0 = 0.5 * mass * p.v0 * p.v0;

  double impulse = 0.0, t_previous = 0.0;
  double max_momentum_error = 0.0, max_ratio_error = 0.0;
  double first_contact = -1.0, last_contact = -1.0, v_in = 0.0, v_out = 0.0;
  double contact_energy_peak = 0.0;
  bool pushed_while_rigid = false;
  while (!sim.finished()) {
    const double t_n = sim.state().time;
    // The contact force of t^n (computed at the end of the last cycle, on the ball's nodes)
    // acts in this cycle's velocity update over dt_avg^n.
    const double fz = sim.contacts().interfaces.front().slave_force[2];
    sim.cycle();
    const bool rigid = sim.rigid_bodies().is_rigid(0);
    const double step = sim.finished() ? sim.state().dt : sim.state().dt_prev;
    impulse += fz * 0.5 * (t_n + step - t_previous);
    t_previous = t_n;
    const double vz = ball_momentum(sim, ball_nodes).z() / mass;
    if (fz != 0.0) {
      if (first_contact < 0.0) first_contact = t_n;
      last_contact = t_n;
      pushed_while_rigid |= rigid;
    } else if (first_contact < 0.0) {
      v_in = vz;
    } else if (v_out == 0.0) {
      v_out = vz;
    }
    const double momentum_z = ball_momentum(sim, ball_nodes).z() - p0.z();
    max_momentum_error = std::max(
        max_momentum_error, std::abs(momentum_z - (impulse - mass * p.g * half_step_time(sim))));
    max_ratio_error = std::max(max_ratio_error, std::abs(sim.energy().ratio() - 1.0));
    contact_energy_peak = std::max(contact_energy_peak, sim.energy().contact_energy);
  }
  expect_rigid_deformable_rigid(sim.switch_events(), first_contact, last_contact);
  EXPECT_FALSE(pushed_while_rigid);
  // Momentum of the ball = contact impulse - weight impulse, every cycle (measured 6.5e-15).
  EXPECT_LT(max_momentum_error, 1e-12 * mass * p.v0);
  // Energy: kinetic + internal + switch + contact energy = KE0 + external work (measured
  // 8e-15: the balance is an identity of the scheme with every term counted).
  EXPECT_LT(max_ratio_error, 1e-12);
  // Contact energy: stored penalty energy at the deepest point, (almost) all returned.
  const auto& e = sim.energy();
  const double e_star = p.young / (1.0 - p.poisson * p.poisson);
  const double hertz_time =
      2.87 * std::pow(mass * mass / (ball.radius * e_star * e_star * std::abs(v_in)), 0.2);
  const double contact_time = last_contact - first_contact;
  const double restitution = -v_out / v_in;
  std::printf(
      "contact drop: mass %.5f, v_in %.5f, v_out %.5f (restitution %.4f), contact %.5f s (Hertz "
      "%.5f), impulse %.6f, momentum error %.2g of M v0, contact energy peak %.4g end %.4g (KE0 "
      "%.4g), switch energy %.4g, max |ratio - 1| %.2g\n",
      mass, v_in, v_out, restitution, contact_time, hertz_time, impulse,
      max_momentum_error / (mass * p.v0), contact_energy_peak, e.contact_energy, ke0,
      e.switch_energy, max_ratio_error);
  // The penalty springs hold energy during the contact (measured peak 37 % of KE0 with
  // SFS = SFM = 10) and give it back at separation (0.16 % left).
  EXPECT_LT(std::abs(e.contact_energy), 0.01 * ke0);
  EXPECT_GT(contact_energy_peak, 0.05 * ke0);
  // Hertz (elastic sphere on a rigid plane) with the penalty springs in series: measured 7 %
  // longer with SFS = SFM = 10; with the default scale 1 the springs are softer than the ball
  // and the contact lasts 1.6 times Hertz's time (0.049 s).
  EXPECT_NEAR(contact_time, hertz_time, 0.1 * hertz_time);
  EXPECT_GT(contact_time, hertz_time);
  // Restitution 0.96: the vibration the ball still has when it is made rigid is removed
  // (switch energy).
  EXPECT_GT(restitution, 0.9);
  EXPECT_LT(restitution, 1.0);
}

}  // namespace
}  // namespace rf::test
