// Deformable <-> rigid switching through the whole deck path. References that do not come from
// the switching code: the conservation of linear and angular momentum, the kinetic energy of
// the non-rigid motion computed here from the nodal masses and velocities (a least-squares
// rigid fit, independent of the solver's body construction), and the objectivity of stress
// (a stress carried through a rigid rotation Q must come back as Q s Q^T).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include "deck_builder.hpp"
#include "sensor/sensor.hpp"
#include "switching/part_switching.hpp"

namespace rf::test {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Linear momentum, angular momentum about the origin, kinetic energy and the kinetic energy of
// the best rigid fit (same P and H) of the free nodes of the state.
struct NodalMomenta {
  double mass = 0.0, kinetic = 0.0, rigid_kinetic = 0.0;
  Vector3d p = Vector3d::Zero(), h = Vector3d::Zero(), centre = Vector3d::Zero(),
           omega = Vector3d::Zero();
};

std::string read_deck_text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

NodalMomenta nodal_momenta(const solver::State& s) {
  NodalMomenta m;
  const auto& n = s.nodes;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Vector3d x(n.x.x[i], n.x.y[i], n.x.z[i]), v(n.v.x[i], n.v.y[i], n.v.z[i]);
    m.mass += n.mass[i];
    m.centre += n.mass[i] * x;
    m.p += n.mass[i] * v;
    m.h += x.cross(n.mass[i] * v);
    m.kinetic += 0.5 * n.mass[i] * v.squaredNorm();
  }
  m.centre /= m.mass;
  Matrix3d inertia = Matrix3d::Zero();
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Vector3d r = Vector3d(n.x.x[i], n.x.y[i], n.x.z[i]) - m.centre;
    inertia += n.mass[i] * (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose());
  }
  m.omega = inertia.inverse() * (m.h - m.centre.cross(m.p));
  m.rigid_kinetic = 0.5 * m.p.squaredNorm() / m.mass + 0.5 * m.omega.dot(inertia * m.omega);
  return m;
}

// A free elastic block 1.2 x 0.8 x 0.4 (3 x 2 x 2 elements, centred on the origin) spinning
// about z at w while translating and stretching along x: the stretch is motion no rigid body
// can carry.
std::string spinning_block_deck(int elform, int ihq, const std::string& switching) {
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
  std::string deck =
      "*KEYWORD\n" + mesh.keyword_text() + elastic_part(1000.0, 1e7, 0.3, elform, ihq);
  deck += "*INITIAL_VELOCITY_NODE\n";
  const double w = 10.0;
  for (int k = 0; k <= mesh.nz; ++k)
    for (int j = 0; j <= mesh.ny; ++j)
      for (int i = 0; i <= mesh.nx; ++i) {
        double x, y, z;
        mesh.coordinates(i, j, k, x, y, z);
        const Vector3d v = Vector3d(1.0, 0.5, 0.2) + Vector3d(0, 0, w).cross(Vector3d(x, y, z)) +
                           Vector3d(0.8 * x, 0.0, 0.0);
        deck +=
            fmt::format("{},{:.17g},{:.17g},{:.17g}\n", mesh.node_id(i, j, k), v.x(), v.y(), v.z());
      }
  deck += switching;
  deck += "*CONTROL_TERMINATION\n0.2\n*END\n";
  return deck;
}

const char* const kPairedTimeSwitch =
    "*DEFORMABLE_TO_RIGID_AUTOMATIC\n"
    "10,0,0.05,0.06,0,0,20,1\n"
    "0,0,0,0.01,1,0\n"
    "1\n"
    "*DEFORMABLE_TO_RIGID_AUTOMATIC\n"
    "20,0,0.12,0,0,0,10,-1\n"
    "0,0,0,0,0,1\n"
    "1\n";

TEST(PartSwitching, SpinningBlockSwitchedRigidAndBackConservesMomentaAndRotatesStress) {
  for (const int ihq : {4, 6}) {
    SCOPED_TRACE(fmt::format("IHQ {}", ihq));
    solver::Simulation sim(read(spinning_block_deck(1, ihq, kPairedTimeSwitch)), {});
    const NodalMomenta start = nodal_momenta(sim.state());
    // Up to the switch: the free block vibrates, its stress is not zero.
    double elastic_dt = 0.0;
    while (sim.state().time < 0.05) {
      elastic_dt = sim.state().dt;
      sim.cycle();
    }
    const NodalMomenta before = nodal_momenta(sim.state());
    const std::vector<double> stress_before = sim.state().hex_blocks[0].stress;
    double stress_scale = 0.0;
    for (double s : stress_before) stress_scale = std::max(stress_scale, std::abs(s));
    ASSERT_GT(stress_scale, 1e3);  // a real stress state is carried through the rigid phase
    sim.cycle();                   // switches first
    ASSERT_EQ(sim.switch_events().size(), 1u);
    const auto& to_rigid = sim.switch_events()[0];
    EXPECT_TRUE(to_rigid.to_rigid);
    // The kinetic energy removed is the non-rigid part, computed here independently.
    const double non_rigid = before.kinetic - before.rigid_kinetic;
    ASSERT_GT(non_rigid, 1e-3 * before.kinetic);
    EXPECT_NEAR(to_rigid.kinetic_energy_before - to_rigid.kinetic_energy_after, non_rigid,
                1e-9 * before.kinetic);
    EXPECT_NEAR((to_rigid.momentum - before.p).norm(), 0.0, 1e-12 * before.p.norm());
    ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
    const Vector3d omega_body = sim.rigid_bodies().bodies[0].state.angular_velocity;
    EXPECT_NEAR((omega_body - before.omega).norm(), 0.0, 1e-6 * before.omega.norm());
    // Rigid phase: the step is DTMAX, larger than the elastic step.
    EXPECT_GT(sim.state().dt, 2.0 * elastic_dt);
    EXPECT_LE(sim.state().dt, 0.01 * (1 + 1e-12));
    const Matrix3d rotation_at_switch = switching::body_rotation(sim.rigid_bodies().bodies[0]);
    Matrix3d rotation_before_release;
    while (sim.switch_events().size() < 2 && !sim.finished()) {
      rotation_before_release = switching::body_rotation(sim.rigid_bodies().bodies[0]);
      sim.cycle();
    }
    // Released at the first cycle that started at t >= TIME1 = 0.12.
    EXPECT_GE(sim.switch_events()[1].time, 0.12);
    ASSERT_EQ(sim.switch_events().size(), 2u);
    const auto& to_deformable = sim.switch_events()[1];
    EXPECT_FALSE(to_deformable.to_rigid);
    EXPECT_NEAR(to_deformable.kinetic_energy_before, to_deformable.kinetic_energy_after,
                1e-12 * to_deformable.kinetic_energy_before);
    EXPECT_TRUE(sim.rigid_bodies().bodies.empty());
    // Released, the nodes carry the body's field; the body turned while rigid.
    const Matrix3d turned = rotation_before_release * rotation_at_switch.transpose();
    EXPECT_GT(std::acos(std::clamp((turned.trace() - 1.0) / 2.0, -1.0, 1.0)), 0.3);
    // Momenta of the whole run: constant to round-off through both switches.
    while (!sim.finished()) sim.cycle();
    const NodalMomenta end = nodal_momenta(sim.state());
    EXPECT_NEAR((end.p - start.p).norm(), 0.0, 1e-12 * start.p.norm());
    EXPECT_NEAR((end.h - start.h).norm(), 0.0, 1e-11 * start.h.norm());
    // Energy: kinetic + internal + removed = initial.
    const auto& e = sim.energy();
    EXPECT_NEAR(e.ratio(), 1.0, 1e-3);
    EXPECT_NEAR(e.switch_energy, non_rigid, 1e-9 * before.kinetic);
  }
}

// A switch of one part must leave every other family's forces alone: a spring-mass oscillator,
// not connected to the switched block and in control of the step, follows exactly the path it
// follows in the same run without the switch. (The switch cycle once re-assembled the
// hexahedra's forces only, so the spring's node lost its force for that cycle.)
TEST(PartSwitching, SwitchOfOnePartLeavesSpringsElsewhereUntouched) {
  // Node 2001 held, node 2002 (1 kg) on a 2e7 N/m spring (step limit 2 sqrt(m/k) = 4.5e-4 s,
  // below the block's), plucked along x.
  const std::string others =
      "*NODE\n2001,0.0,0.0,-2.0\n2002,0.5,0.0,-2.0\n*ELEMENT_MASS\n1,2002,1.0\n"
      "*SECTION_DISCRETE\n3,0\n*PART\nspring\n3,3,3\n*MAT_SPRING_ELASTIC\n3,2.0e7\n"
      "*ELEMENT_DISCRETE\n3001,3,2001,2002\n*BOUNDARY_SPC_NODE\n2001,0,1,1,1,0,0,0\n"
      "*INITIAL_VELOCITY_NODE\n2002,1.5,0.0,0.0\n";
  auto run = [&](const std::string& switching) {
    std::string deck = spinning_block_deck(1, 4, switching);
    deck.insert(deck.find("*CONTROL_TERMINATION"), others);
    auto sim = std::make_unique<solver::Simulation>(read(deck), solver::SimulationOptions{});
    sim->run();
    return sim;
  };
  const auto with_switch = run(kPairedTimeSwitch);
  const auto without = run("");
  ASSERT_EQ(with_switch->switch_events().size(), 2u);
  ASSERT_EQ(with_switch->state().cycle, without->state().cycle);  // the spring sets the step
  const auto& a = with_switch->state().nodes;
  const auto& b = without->state().nodes;
  double scale = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a.id[i] < 2000) continue;  // the block's own nodes move differently
    for (const auto* pair : {&a.v, &b.v}) {
      scale = std::max(scale, std::abs(pair->x[i]) + std::abs(pair->y[i]) + std::abs(pair->z[i]));
    }
    largest = std::max({largest, std::abs(a.v.x[i] - b.v.x[i]), std::abs(a.v.y[i] - b.v.y[i]),
                        std::abs(a.v.z[i] - b.v.z[i]), std::abs(a.x.z[i] - b.x.z[i]),
                        std::abs(a.x.x[i] - b.x.x[i])});
  }
  ASSERT_GT(scale, 0.1);
  EXPECT_LE(largest, 1e-12 * scale);
}

// Objectivity: a stress frozen at the switch returns as Q s Q^T, Q the rotation the body made
// while rigid. The body's turn is imposed here directly (Q = Rz(0.7) Rx(0.4)), so the check
// is of the bookkeeping alone, against a rotation computed by hand.
TEST(PartSwitching, FrozenStressReturnsRotatedByTheBodyRotation) {
  const model::Model model = read(spinning_block_deck(1, 4, ""));
  const solver::NodeIndex index(model);
  solver::State state = solver::build_state(model, index);
  solver::RigidSystem rigid = solver::build_rigid_system(model, index, state);
  auto& block = state.hex_blocks[0];
  for (std::size_t k = 0; k < block.stress.size(); ++k) block.stress[k] = std::sin(1.0 + k);
  for (std::size_t k = 0; k < block.hourglass_state.size(); ++k) {
    block.hourglass_state[k] = std::cos(2.0 + k);
  }
  const std::vector<double> frozen = block.stress, hourglass = block.hourglass_state;
  ASSERT_EQ(hourglass.size(), 12 * block.size());
  switching::PartSwitcher switcher(model, state);
  model::PartSwitch part;
  part.pid = 1;
  switcher.to_rigid({part}, 0.0, state, rigid);
  ASSERT_EQ(rigid.bodies.size(), 1u);
  EXPECT_TRUE(block.rigid);
  EXPECT_GT(switcher.frozen_energy(), 0.0);
  const Matrix3d q =
      (Eigen::AngleAxisd(0.7, Vector3d::UnitZ()) * Eigen::AngleAxisd(0.4, Vector3d::UnitX()))
          .toRotationMatrix();
  rigid.bodies[0].state.rotation = q * rigid.bodies[0].state.rotation;
  switcher.to_deformable({part}, 1.0, state, rigid);
  EXPECT_FALSE(block.rigid);
  EXPECT_TRUE(rigid.bodies.empty());
  EXPECT_EQ(switcher.frozen_energy(), 0.0);
  double worst = 0.0;
  for (std::size_t p = 0; p < frozen.size() / 6; ++p) {
    const double* s = &frozen[p * 6];
    Matrix3d m;
    m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    const Matrix3d expected = q * m * q.transpose();
    const double* r = &block.stress[p * 6];
    const double got[6] = {r[0], r[1], r[2], r[3], r[4], r[5]};
    const double want[6] = {expected(0, 0), expected(1, 1), expected(2, 2),
                            expected(0, 1), expected(1, 2), expected(2, 0)};
    for (int c = 0; c < 6; ++c) worst = std::max(worst, std::abs(got[c] - want[c]));
  }
  EXPECT_LT(worst, 1e-14);
  for (std::size_t k = 0; k < hourglass.size(); k += 3) {  // IHQ 4: global vectors
    const Vector3d want = q * Vector3d(hourglass[k], hourglass[k + 1], hourglass[k + 2]);
    EXPECT_NEAR(block.hourglass_state[k], want.x(), 1e-14);
    EXPECT_NEAR(block.hourglass_state[k + 1], want.y(), 1e-14);
    EXPECT_NEAR(block.hourglass_state[k + 2], want.z(), 1e-14);
  }
}

// Two separate blocks: deformable part 1 at the origin, *MAT_RIGID part 2 two metres away,
// moving and spinning differently. Part 1 is merged into part 2's body (LRB) at t = 0.05.
std::string two_block_deck(const std::string& switching) {
  BoxMesh a;
  a.nx = a.ny = a.nz = 2;
  std::string deck = "*KEYWORD\n" + a.keyword_text(1) + elastic_part(1000.0, 1e7, 0.3, 1, 4);
  // Part 2: one hexahedron [2, 3] x [0, 1] x [0, 0.5], nodes 101..108, element 101.
  deck += "*NODE\n";
  const double xs[2] = {2.0, 3.0}, ys[2] = {0.0, 1.0}, zs[2] = {0.0, 0.5};
  const int order[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                           {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int k = 0; k < 8; ++k) {
    deck +=
        fmt::format("{},{},{},{}\n", 101 + k, xs[order[k][0]], ys[order[k][1]], zs[order[k][2]]);
  }
  deck += "*ELEMENT_SOLID\n101,2,101,102,103,104,105,106,107,108\n";
  deck += "*PART\nrigid\n2,1,2\n*MAT_RIGID\n2,3000.0,1e7,0.3\n";
  // ID STYP(2: part) OMEGA VX VY VZ / XC YC ZC NX NY NZ: the rigid block spins about z.
  deck += "*INITIAL_VELOCITY_GENERATION\n2,2,3.0,-1.0,0.5,0.0\n2.5,0.5,0.25,0,0,1\n";
  deck += "*INITIAL_VELOCITY_GENERATION\n1,2,0.0,4.0,0.3,0.2\n0.5,0.5,0.5,0,0,1\n";
  return deck + switching + "*CONTROL_TERMINATION\n0.15\n*END\n";
}

TEST(PartSwitching, MergeIntoMovingLeadRigidBodyConservesMomenta) {
  const std::string merge = "*DEFORMABLE_TO_RIGID_AUTOMATIC\n11,0,0.05\n0,0,0,0.004,1,0\n1,2\n";
  solver::Simulation sim(read(two_block_deck(merge)), {});
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);
  const auto total = [&] {
    // Free nodes plus bodies, at the same time levels (x^n, v^{n-1/2}).
    Vector3d p = Vector3d::Zero(), h = Vector3d::Zero();
    const auto& s = sim.state();
    const auto& rigid = sim.rigid_bodies();
    for (std::size_t i = 0; i < s.nodes.size(); ++i) {
      if (rigid.is_rigid(static_cast<std::int32_t>(i))) continue;
      const Vector3d x(s.nodes.x.x[i], s.nodes.x.y[i], s.nodes.x.z[i]);
      const Vector3d v(s.nodes.v.x[i], s.nodes.v.y[i], s.nodes.v.z[i]);
      p += s.nodes.mass[i] * v;
      h += x.cross(s.nodes.mass[i] * v);
    }
    for (const auto& b : rigid.bodies) {
      p += b.state.mass * b.state.velocity;
      h += b.state.centre.cross(b.state.mass * b.state.velocity) + b.state.angular_momentum;
    }
    return std::pair{p, h};
  };
  sim.cycle();
  const auto [p0, h0] = total();
  const double mass_rigid = sim.rigid_bodies().bodies[0].state.mass;
  EXPECT_NEAR(mass_rigid, 3000.0 * 0.5, 1e-9);
  while (sim.switch_events().empty()) sim.cycle();
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 1u);  // merged into part 2's body
  const auto& body = sim.rigid_bodies().bodies[0];
  EXPECT_EQ(body.id, 2);
  ASSERT_EQ(body.parts.size(), 2u);
  EXPECT_NEAR(body.state.mass, 1500.0 + 1000.0 * 1.0, 1e-9);
  while (!sim.finished()) sim.cycle();
  const auto [p1, h1] = total();
  EXPECT_NEAR((p1 - p0).norm(), 0.0, 1e-12 * p0.norm());
  EXPECT_NEAR((h1 - h0).norm(), 0.0, 1e-11 * h0.norm());
  // Energy: what the merge removed is reported, the balance closes.
  EXPECT_GT(sim.energy().switch_energy, 0.0);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
}

// *DEFORMABLE_TO_RIGID at the start with *DEFORMABLE_TO_RIGID_INERTIA: the body takes the
// card's mass, and moves as a free rigid body (constant momentum and centre velocity).
TEST(PartSwitching, SwitchedAtStartWithInertiaCard) {
  const std::string at_start =
      "*DEFORMABLE_TO_RIGID\n1\n"
      "*DEFORMABLE_TO_RIGID_INERTIA\n1\n1.0,1.0,1.0,2000.0\n400.0,0,0,400.0,0,400.0\n"
      "*CONTROL_TIMESTEP\n0.004\n";
  solver::Simulation sim(read(two_block_deck(at_start)), {});
  ASSERT_EQ(sim.rigid_bodies().bodies.size(), 2u);
  ASSERT_EQ(sim.switch_events().size(), 1u);
  EXPECT_EQ(sim.switch_events()[0].swset, 0);
  const solver::RigidBody* switched = nullptr;
  for (const auto& b : sim.rigid_bodies().bodies) {
    if (b.id == 1) switched = &b;
  }
  ASSERT_NE(switched, nullptr);
  EXPECT_DOUBLE_EQ(switched->state.mass, 2000.0);
  // Momentum of the part's nodes (4, 0.3, 0.2 m/s on 1000 kg of lumped mass) is kept.
  EXPECT_NEAR(switched->state.velocity.x(), 4.0 * 1000.0 / 2000.0, 1e-12);
  const Vector3d v0 = switched->state.velocity;
  while (!sim.finished()) sim.cycle();
  for (const auto& b : sim.rigid_bodies().bodies) {
    if (b.id == 1) EXPECT_NEAR((b.state.velocity - v0).norm(), 0.0, 1e-12);
  }
}

// NRBF: a nodal rigid body on the top face of block 1 is deleted when block 2 switches rigid
// (NRBF = 1; it shares no node with block 2) and made again when block 2 switches back
// (NRBF = 2). Momenta are conserved through all of it.
TEST(PartSwitching, NodalRigidBodiesDeletedAndActivatedByNrbf) {
  std::string deck = two_block_deck(
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n31,0,0.02,0,0,0,32,1\n1,0,0,0.004,1,0\n2\n"
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n32,0,0.06,0,0,0,31,-1\n2,0,0,0,0,1\n2\n");
  // Part 2 deformable instead of *MAT_RIGID, and the nodal rigid body.
  deck.replace(deck.find("*PART\nrigid\n2,1,2\n"), 18, "*PART\nsoft\n2,1,1\n");
  BoxMesh a;
  a.nx = a.ny = a.nz = 2;
  std::vector<int> top;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) top.push_back(a.node_id(i, j, 2));
  deck.insert(deck.find("*CONTROL_TERMINATION"),
              node_set(5, top) + "*CONSTRAINED_NODAL_RIGID_BODY\n50,0,5\n");
  solver::Simulation sim(read(deck), {});
  auto nodal_count = [&] {
    int n = 0;
    for (const auto& b : sim.rigid_bodies().bodies) n += b.nodal ? 1 : 0;
    return n;
  };
  ASSERT_EQ(nodal_count(), 1);
  const NodalMomenta start = nodal_momenta(sim.state());
  while (sim.switch_events().empty()) sim.cycle();
  sim.cycle();
  EXPECT_EQ(nodal_count(), 0);
  while (sim.switch_events().size() < 2) sim.cycle();
  EXPECT_EQ(nodal_count(), 1);
  while (!sim.finished()) sim.cycle();
  // Free nodes carry the velocities of their bodies: nodal sums are the totals.
  const NodalMomenta end = nodal_momenta(sim.state());
  EXPECT_NEAR((end.p - start.p).norm(), 0.0, 1e-12 * start.p.norm());
  EXPECT_NEAR((end.h - start.h).norm(), 0.0, 1e-11 * start.h.norm());
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-3);
}

// CODE 5: the example's DEF2RIG control turns on when switch 10 has seen the bar's stress
// above 100 MPa for TIMWIN = 10 us; the block must become rigid at the next cycle start.
TEST(PartSwitching, SensorControlledSetFiresWhenTheControlTurnsOn) {
  const auto model = io::read_deck(std::string(RIGIDFLEX_EXAMPLES) + "/sensor_def2rig.k");
  solver::Simulation sim(model, {});
  double crossing = -1.0, dt = 0.0;
  while (!sim.finished() && sim.switch_events().empty()) {
    dt = sim.state().dt;
    sim.cycle();
    if (crossing < 0.0 && sensor::sensor_value(sim.sensors(), 1) > 100.0) {  // MPa: mm, t, s
      crossing = sim.state().time;
    }
  }
  ASSERT_GT(crossing, 0.0);
  ASSERT_EQ(sim.switch_events().size(), 1u);
  const auto& event = sim.switch_events()[0];
  EXPECT_EQ(event.swset, 10);
  EXPECT_TRUE(event.to_rigid);
  EXPECT_GE(event.time, crossing + 1e-5 - 1e-12);
  EXPECT_LE(event.time, crossing + 1e-5 + 2.0 * dt);
}

// A block that hits a rigid wall is made rigid mid-impact (its compressive stresses frozen),
// rests and slides on the wall as a rigid body, and is released there. The released elements'
// first kick must respect their own stable step (not the rigid phase's DTMAX): the run ends
// normally with the energy balance closed (switch energy and wall work included), and no node
// ends behind the wall.
TEST(PartSwitching, ReleasedWhileOnARigidWallStaysStable) {
  solver::Simulation sim(
      io::read_deck(std::string(RIGIDFLEX_TEST_DECKS) + "/rigidwall_switching_block.k"), {});
  double rigid_dt = 0.0;
  while (!sim.finished()) {
    if (!sim.rigid_bodies().bodies.empty()) rigid_dt = std::max(rigid_dt, sim.state().dt);
    sim.cycle();
  }
  ASSERT_EQ(sim.switch_events().size(), 2u);
  EXPECT_DOUBLE_EQ(rigid_dt, 0.005);  // DTMAX of the rigid phase
  EXPECT_LT(sim.state().dt, 0.5 * rigid_dt);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
  const auto& z = sim.state().nodes.x.z;
  EXPECT_GE(*std::min_element(z.begin(), z.end()), -0.30 - 1e-9);
}

// RWF = 1 deletes the rigid walls when the set fires (remark 4: all of them), RWF = 2 brings
// them back: with the wall deleted at 0.02 s the falling block passes the wall's plane.
TEST(PartSwitching, RwfDeletesAndActivatesRigidWalls) {
  std::string deck =
      read_deck_text_of(std::string(RIGIDFLEX_TEST_DECKS) + "/rigidwall_switching_block.k");
  // Set 10 (rigid at 0.05 s) gets RWF = 1; set 20 (released at 0.12 s) RWF = 2.
  const std::string card10 = "         0         0         0     0.005         1         0";
  const std::string card20 = "         0         0         0         0         0         1";
  deck.replace(deck.find(card10), card10.size(),
               "         0         0         1     0.005         1         0");
  deck.replace(deck.find(card20), card20.size(),
               "         0         0         2         0         0         1");
  // Make set 10 fire before the impact (0.0325 s): at 0.02 s.
  const std::string time10 = "        10         0      0.05      0.06";
  deck.replace(deck.find(time10), time10.size(), "        10         0      0.02      0.06");
  solver::Simulation sim(read(deck), {});
  while (sim.switch_events().empty()) sim.cycle();
  sim.cycle();
  EXPECT_FALSE(sim.rigid_walls().walls[0].active);
  while (sim.switch_events().size() < 2) sim.cycle();
  EXPECT_TRUE(sim.rigid_walls().walls[0].active);
  // While the wall was deleted the rigid block fell through its plane (z = -0.3).
  const auto& z = sim.state().nodes.x.z;
  EXPECT_LT(*std::min_element(z.begin(), z.end()), -0.35);
}

}  // namespace
}  // namespace rf::test
