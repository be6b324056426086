// Every part switched rigid by *DEFORMABLE_TO_RIGID_AUTOMATIC with DTMAX 0 and no DTINIT
// (issue 22): the run keeps the step in force before the switch, says so once, and `check`
// warns up front. References independent of the solver: conservation of linear and angular
// momentum of the isolated system, and the kinetic energy of a free rigid body spinning about a
// principal axis, constant to round-off (Euler's equations with w parallel to a principal axis).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "deck_builder.hpp"

namespace rf::test {
namespace {

using Eigen::Vector3d;

// A free elastic block 1.2 x 0.8 x 0.4 centred on the origin, spinning about z (a principal
// axis by symmetry), translating and stretching along x; all of it switched rigid at t = 0.05 by
// a set without DTMAX; no *CONTROL_TIMESTEP.
std::string all_rigid_deck() {
  BoxMesh mesh;
  mesh.nx = 3;
  mesh.ny = 2;
  mesh.nz = 2;
  mesh.lx = 1.2;
  mesh.ly = 0.8;
  mesh.lz = 0.4;
  mesh.distort = [](double& x, double& y, double& z) {
    x -= 0.6;
    y -= 0.4;
    z -= 0.2;
  };
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(1000.0, 1e7, 0.3, 1, 4);
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= mesh.nz; ++k)
    for (int j = 0; j <= mesh.ny; ++j)
      for (int i = 0; i <= mesh.nx; ++i) {
        double x, y, z;
        mesh.coordinates(i, j, k, x, y, z);
        const Vector3d v = Vector3d(1.0, 0.5, 0.2) + Vector3d(0, 0, 10.0).cross(Vector3d(x, y, z)) +
                           Vector3d(0.8 * x, 0.0, 0.0);
        deck +=
            fmt::format("{},{:.17g},{:.17g},{:.17g}\n", mesh.node_id(i, j, k), v.x(), v.y(), v.z());
      }
  deck += "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,0.05\n0,0,0,0,1,0\n1\n";
  deck += "*CONTROL_TERMINATION\n0.2\n*END\n";
  return deck;
}

struct Momenta {
  Vector3d p = Vector3d::Zero(), h = Vector3d::Zero();
  double kinetic = 0.0;
};

// Free nodes plus rigid bodies (momenta about the origin; body kinetic energy 1/2 m v^2 +
// 1/2 w . L).
Momenta momenta(const solver::Simulation& sim) {
  Momenta m;
  const auto& s = sim.state();
  const auto& rigid = sim.rigid_bodies();
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    if (rigid.is_rigid(static_cast<std::int32_t>(i))) continue;
    const Vector3d x(s.nodes.x.x[i], s.nodes.x.y[i], s.nodes.x.z[i]);
    const Vector3d v(s.nodes.v.x[i], s.nodes.v.y[i], s.nodes.v.z[i]);
    m.p += s.nodes.mass[i] * v;
    m.h += x.cross(s.nodes.mass[i] * v);
    m.kinetic += 0.5 * s.nodes.mass[i] * v.squaredNorm();
  }
  for (const auto& b : rigid.bodies) {
    m.p += b.state.mass * b.state.velocity;
    m.h += b.state.centre.cross(b.state.mass * b.state.velocity) + b.state.angular_momentum;
    m.kinetic += 0.5 * b.state.mass * b.state.velocity.squaredNorm() +
                 0.5 * b.state.angular_velocity.dot(b.state.angular_momentum);
  }
  return m;
}

int held_step_notices(const solver::Simulation& sim) {
  int n = 0;
  for (const auto& w : sim.warnings()) {
    if (w.message.find("keeps the step in force before the switch") != std::string::npos) ++n;
  }
  return n;
}

TEST(PartSwitching, AllPartsRigidWithoutStepControlKeepTheStepBeforeTheSwitch) {
  const model::Model model = read(all_rigid_deck());
  // `check` (the reader) warns up front.
  int check_warnings = 0;
  for (const auto& w : model.warnings) {
    if (w.message.find("can make every deformable part rigid") != std::string::npos) {
      ++check_warnings;
    }
  }
  EXPECT_EQ(check_warnings, 1);

  solver::Simulation sim(model, {});
  const Momenta start = momenta(sim);
  double elastic_dt = 0.0;
  while (sim.switch_events().empty()) {
    elastic_dt = sim.state().dt;
    sim.cycle();
  }
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
  sim.cycle();
  const Momenta after_switch = momenta(sim);
  double max_energy_drift = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    // The held step, except the last one, cut to land on ENDTIM.
    if (sim.state().time + elastic_dt < 0.2) EXPECT_DOUBLE_EQ(sim.state().dt, elastic_dt);
    max_energy_drift =
        std::max(max_energy_drift, std::abs(momenta(sim).kinetic - after_switch.kinetic));
  }
  EXPECT_NEAR(sim.state().time, 0.2, 1e-12);
  EXPECT_EQ(held_step_notices(sim), 1);  // said once
  const Momenta end = momenta(sim);
  EXPECT_NEAR((end.p - start.p).norm(), 0.0, 1e-12 * start.p.norm());
  EXPECT_NEAR((end.h - start.h).norm(), 0.0, 1e-11 * start.h.norm());
  // Rigid phase: free rotation about a principal axis keeps the kinetic energy.
  EXPECT_LT(max_energy_drift, 1e-10 * after_switch.kinetic);
  // Whole run: kinetic + internal + removed by the switch = initial.
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-3);
}

// With DTINIT the old behaviour stands: DTINIT is the step once no deformable element is left,
// and nothing is said.
TEST(PartSwitching, AllPartsRigidWithDtinitUseDtinit) {
  std::string deck = all_rigid_deck();
  deck.insert(deck.find("*END"), "*CONTROL_TIMESTEP\n0.004\n");
  const model::Model model = read(deck);
  for (const auto& w : model.warnings) {
    EXPECT_EQ(w.message.find("can make every deformable part rigid"), std::string::npos);
  }
  solver::Simulation sim(model, {});
  while (sim.switch_events().empty()) sim.cycle();
  sim.cycle();
  EXPECT_DOUBLE_EQ(sim.state().dt, 0.004);
  while (!sim.finished()) sim.cycle();
  EXPECT_EQ(held_step_notices(sim), 0);
}

}  // namespace
}  // namespace rf::test
