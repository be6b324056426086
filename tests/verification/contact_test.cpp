// Penalty contact (*CONTACT_AUTOMATIC_*) through the whole deck path, against references that
// do not come from the solver: 1D elastic wave theory for a bar dropped flat on a rigid plate
// (contact stress rho c v0, contact time 2 L / c, rebound at v0) and for two equal bars
// colliding head-on (velocities exchange), the Coulomb block on an inclined plane
// (x = g (sin a - mu cos a) t^2 / 2, friction dissipation mu N x, sticking when tan a < mu),
// conservation of momentum and energy, and thread-count determinism.
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "contact/contact.hpp"
#include "contact_fixture.hpp"
#include "deck_builder.hpp"

namespace rf::test {
namespace {

using Eigen::Vector3d;

// A rigid part held fixed (CMO 1, CON1 = CON2 = 7). Its E and PR give the contact stiffness.
std::string fixed_rigid(int pid, double rho, double e, double nu) {
  return fmt::format(
      "*PART\npart {0}\n{0},{0},{0}\n*SECTION_SOLID\n{0},1\n*MAT_RIGID\n{0},{1:.17g},{2:.17g},"
      "{3:.17g}\n1.0,7,7\n",
      pid, rho, e, nu);
}

std::string velocity(int pid, const Vector3d& v) {
  return fmt::format("*INITIAL_VELOCITY_GENERATION\n{},2,0,{:.17g},{:.17g},{:.17g}\n0,0,0,0,0,0\n",
                     pid, v.x(), v.y(), v.z());
}

std::string termination(double t_end) {
  return fmt::format("*CONTROL_TERMINATION\n{:.17g},\n", t_end);
}

// Momentum and mass of the nodes with user IDs in [first, last].
struct PartMotion {
  double mass = 0.0;
  Vector3d momentum = Vector3d::Zero();
  Vector3d centre = Vector3d::Zero();
  Vector3d velocity() const { return momentum / mass; }
};
PartMotion motion(const solver::State& state, int first, int last) {
  PartMotion m;
  const auto& n = state.nodes;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (n.id[i] < first || n.id[i] > last) continue;
    m.mass += n.mass[i];
    m.momentum += n.mass[i] * Vector3d(n.v.x[i], n.v.y[i], n.v.z[i]);
    m.centre += n.mass[i] * Vector3d(n.x.x[i], n.x.y[i], n.x.z[i]);
  }
  m.centre /= m.mass;
  return m;
}

std::filesystem::path fresh_directory(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("rigidflex_contact_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

// ---------------------------------------------------------------------------------------
// 1. An elastic bar (nu = 0: one-dimensional) dropped flat on a fixed rigid plate at v0.
// Wave theory: the contact stress is rho c v0 (force rho c A v0), the bar stays in contact
// for 2 L / c and leaves at v0. The penalty spring adds compliance: the duration is a few per
// cent longer and a little energy stays in the bar as vibration.

constexpr double kRho = 1000.0, kE = 1e7, kLength = 0.1, kWidth = 0.02, kV0 = 1.0;

// `gap`: the bar starts this far above the plate (default a tenth of an element); `t_end`:
// termination (default the fall plus 1.5 contact times).
std::string bar_drop_deck(int nz, const std::string& extra = "", double gap = -1.0,
                          double t_end = -1.0) {
  if (gap < 0.0) gap = 0.1 * kLength / nz;
  Block bar;
  bar.nx = bar.ny = 2;
  bar.nz = nz;
  bar.lx = bar.ly = kWidth;
  bar.lz = kLength;
  bar.local = Vector3d(0, 0, gap);
  Block plate;
  plate.nx = plate.ny = 4;
  plate.nz = 1;
  plate.lx = plate.ly = 2 * kWidth;
  plate.lz = 0.01;
  plate.local = Vector3d(-0.5 * kWidth, -0.5 * kWidth, -0.01);
  plate.first_node = 100001;
  plate.first_element = 100001;
  plate.pid = 2;
  const double c = std::sqrt(kE / kRho);
  return "*KEYWORD\n" + bar.text() + plate.text() + elastic(1, kRho, kE, 0.0) +
         fixed_rigid(2, kRho, kE, 0.0) + velocity(1, Vector3d(0, 0, -kV0)) +
         "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n7,drop\n1,2,3,3\n0,0,0,0,0\n10,10\n" + extra +
         termination(t_end > 0.0 ? t_end : gap / kV0 + 3.0 * kLength / c);
}

TEST(Contact, BarDroppedOnRigidPlateReboundsAsWaveTheoryPredicts) {
  const double c = std::sqrt(kE / kRho);
  const double contact_time = 2.0 * kLength / c;
  const double area = kWidth * kWidth;
  const auto dir = fresh_directory("drop");
  auto simulation = std::make_unique<solver::Simulation>(
      read(bar_drop_deck(40, "*DATABASE_RCFORC\n1e-5\n")),
      solver::SimulationOptions{.output_directory = dir, .write_fields = false});
  solver::Simulation& sim = *simulation;
  const PartMotion start = motion(sim.state(), 1, 99999);
  EXPECT_NEAR(start.mass, kRho * area * kLength, 1e-9 * start.mass);
  const double ke0 = 0.5 * start.mass * kV0 * kV0;
  ASSERT_EQ(sim.contacts().interfaces.size(), 1u);
  const auto& contact = sim.contacts().interfaces[0];
  EXPECT_EQ(contact.id, 7);
  double first = -1.0, last = -1.0, peak = 0.0, impulse = 0.0, worst_ratio = 0.0;
  double previous_force = 0.0, previous_time = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    const double t = sim.state().time;
    const double fz = contact.slave_force[2];  // on the bar, from the plate
    // Trapezoidal impulse of the force history (independent of the solver's momentum sums).
    impulse += 0.5 * (fz + previous_force) * (t - previous_time);
    previous_force = fz;
    previous_time = t;
    if (fz > 1e-3 * kRho * c * area * kV0) {
      if (first < 0.0) first = t;
      last = t;
    }
    peak = std::max(peak, fz);
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  const PartMotion end = motion(sim.state(), 1, 99999);
  // Contact force rho c A v0 while the wave runs (peak within 6 per cent).
  EXPECT_NEAR(peak, kRho * c * area * kV0, 0.06 * kRho * c * area * kV0);
  // Contact time 2 L / c, up to 10 per cent longer for the penalty spring.
  EXPECT_GT(last - first, 0.98 * contact_time);
  EXPECT_LT(last - first, 1.10 * contact_time);
  // Rebound at v0 less the energy left vibrating in the bar (under 3 per cent).
  EXPECT_GT(end.velocity().z(), 0.97 * kV0);
  EXPECT_LT(end.velocity().z(), 1.0 * kV0);
  // Symmetric problem: no sideways motion, up to the bilinear segments' corner normals (a node
  // on the edge between two segments takes the lower-numbered one: measured 1.1e-3 v0).
  EXPECT_NEAR(end.velocity().x(), 0.0, 3e-3 * kV0);
  EXPECT_NEAR(end.velocity().y(), 0.0, 3e-3 * kV0);
  // Momentum transferred = impulse of the contact force history (trapezoid: 1 per cent).
  EXPECT_NEAR(end.momentum.z() - start.momentum.z(), impulse, 0.01 * std::abs(impulse));
  // Energy: balanced to round-off with contact energy counted; after separation the contact
  // energy (penalty work lost) is small against the impact energy.
  EXPECT_LT(worst_ratio, 1e-9);
  EXPECT_LT(std::abs(sim.energy().contact_energy), 2e-3 * ke0);
  EXPECT_GT(sim.energy().kinetic, 0.94 * ke0);
  simulation.reset();  // closes the output files
  // rcforc.csv: slave and master resultants opposite.
  std::string header;
  std::ifstream in(dir / "rcforc.csv");
  std::getline(in, header);
  EXPECT_EQ(header,
            "time,contact,slave_fx,slave_fy,slave_fz,master_fx,master_fy,master_fz,"
            "contact_nodes");
  int rows = 0;
  double best = 0.0;
  for (std::string line; std::getline(in, line); ++rows) {
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) v.push_back(std::stod(f));
    ASSERT_EQ(v.size(), 9u);
    EXPECT_EQ(v[1], 7.0);
    EXPECT_EQ(v[4], -v[7]);
    best = std::max(best, v[4]);
  }
  EXPECT_GT(rows, 100);
  EXPECT_NEAR(best, kRho * c * area * kV0, 0.06 * kRho * c * area * kV0);
}

// The queries part switching uses (CODE 2/4): the resultant force of a contact by ID and the
// OFFSET proximity test, before and during the impact.
TEST(Contact, SwitchingQueriesSeeForceAndProximity) {
  const int nz = 20;
  const double gap = 0.1 * kLength / nz;  // the bar starts this far above the plate
  solver::Simulation sim(read(bar_drop_deck(nz)), {});
  const auto& contacts = sim.contacts();
  const auto& state = sim.state();
  EXPECT_EQ(contact::resultant_force(contacts, 7), 0.0);
  EXPECT_EQ(contact::resultant_force(contacts, 8), -1.0);  // no contact 8
  // Bar (part 1, slave side) and plate (part 2, master side): within 1.5 gaps, not within 0.5.
  for (const std::vector<model::Id> parts : {std::vector<model::Id>{1}, {2}}) {
    EXPECT_TRUE(contact::within_offset(contacts, 7, 1.5 * gap, parts, state));
    EXPECT_FALSE(contact::within_offset(contacts, 7, 0.5 * gap, parts, state));
  }
  EXPECT_FALSE(contact::within_offset(contacts, 7, 1.5 * gap, {3}, state));  // not a side
  EXPECT_FALSE(contact::within_offset(contacts, 8, 1.5 * gap, {1}, state));
  sim.cycle();  // the search grid is built from now on
  EXPECT_TRUE(contact::within_offset(contacts, 7, 1.5 * gap, {1}, state));
  EXPECT_FALSE(contact::within_offset(contacts, 7, 0.5 * gap, {1}, state));
  while (!sim.finished() && contact::resultant_force(contacts, 7) == 0.0) sim.cycle();
  // The first contact force: the gap closed at v0.
  EXPECT_NEAR(state.time, gap / kV0, 2.0 * state.dt);
  EXPECT_GT(contact::resultant_force(contacts, 7), 0.0);
  EXPECT_TRUE(contact::within_offset(contacts, 7, 1e-9, {2}, state));
}

// The drop with one SINGLE_SURFACE contact over all parts: the bar must not contact itself
// (its edge nodes lie next to its own faces), and the impact is the same as above.
TEST(Contact, SingleSurfaceDropFindsOnlyTheImpact) {
  std::string deck = bar_drop_deck(40);
  const std::string s2s = "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n7,drop\n1,2,3,3\n";
  ASSERT_NE(deck.find(s2s), std::string::npos);
  deck.replace(deck.find(s2s), s2s.size(), "*CONTACT_AUTOMATIC_SINGLE_SURFACE_ID\n7,drop\n0,0,5\n");
  solver::Simulation sim(read(deck), {});
  const PartMotion start = motion(sim.state(), 1, 99999);
  const double ke0 = 0.5 * start.mass * kV0 * kV0;
  const double c = std::sqrt(kE / kRho);
  double worst_ratio = 0.0;
  std::int64_t early_contacts = 0;
  const auto& contact = sim.contacts().interfaces[0];
  while (!sim.finished()) {
    sim.cycle();
    if (sim.state().time < 0.9 * 0.1 * kLength / 40 / kV0) early_contacts += contact.active_nodes;
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  const PartMotion end = motion(sim.state(), 1, 99999);
  EXPECT_EQ(early_contacts, 0);  // no self-contact while falling
  EXPECT_GT(end.velocity().z(), 0.97 * kV0);
  EXPECT_LT(end.velocity().z(), 1.0 * kV0);
  EXPECT_LT(worst_ratio, 1e-9);
  EXPECT_LT(std::abs(sim.energy().contact_energy), 2e-3 * ke0);
  EXPECT_EQ(contact.active_nodes, 0);
  (void)c;
}

// The drop with the bar raised to 27-node hexahedra (*CHANGE_P-ORDER 2): contact on the
// sub-quadrilaterals of the GLL face grid gives the same wave-theory rebound.
TEST(Contact, QuadraticHexahedraBarReboundsAsWaveTheoryPredicts) {
  solver::Simulation sim(read(bar_drop_deck(20, "*CHANGE_P-ORDER\nP,1,2\n")), {});
  // The bar's nodes: the deck's (below the plate's IDs) and those the elevation added (above).
  const auto bar = [&] {
    PartMotion m = motion(sim.state(), 1, 100000);
    const PartMotion added = motion(sim.state(), 100051, 1 << 30);  // plate: 100001..100050
    m.mass += added.mass;
    m.momentum += added.momentum;
    return m;
  };
  ASSERT_LT(sim.state().nodes.id.back(), 1 << 30);
  ASSERT_GT(sim.state().generated_node_count, 0);
  const PartMotion start = bar();
  const double ke0 = 0.5 * start.mass * kV0 * kV0;
  // 2 x 2 faces of 2 x 2 sub-quads on the bar's ends, the plate's faces unchanged.
  EXPECT_EQ(sim.contacts().interfaces[0].sides[0].segments.size(),
            std::size_t{2 * 16 + 4 * 2 * 20 * 4});
  double worst_ratio = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  const PartMotion end = bar();
  EXPECT_NEAR(start.mass, kRho * kWidth * kWidth * kLength, 1e-9 * start.mass);
  EXPECT_GT(end.velocity().z(), 0.97 * kV0);
  EXPECT_LT(end.velocity().z(), 1.0 * kV0);
  EXPECT_LT(worst_ratio, 1e-9);
  EXPECT_LT(std::abs(sim.energy().contact_energy), 1e-2 * ke0);
}

// Part switching on contact (*DEFORMABLE_TO_RIGID_AUTOMATIC CODE 4 / CODE 2, paired): the bar
// flies rigid, turns deformable when it comes within OFFSET of the plate (before any contact
// force), rebounds elastically, and turns rigid again once the contact force is zero after the
// delay TIME3. References: the switch times from the kinematics (gap - OFFSET) / v0 and the
// wave-theory contact (2 L / c); the rebound at v0 less the vibration energy the rigid switch
// removes; the energy balance with the switch energy.
TEST(Contact, SwitchingPairTurnsBarDeformableBeforeImpactAndRigidAfter) {
  const double c = std::sqrt(kE / kRho);
  const double gap = 0.004, offset = 0.001;
  const double delay = 4e-3;  // covers the last 1 mm of flight and the 2 ms contact
  const std::string switching =
      "*DEFORMABLE_TO_RIGID\n1\n*CONTROL_TIMESTEP\n2e-5\n" +
      fmt::format(
          "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,4,0,0,{:.17g},7,20,1\n0,0,0,0,0,1,{:.17g}\n1\n",
          delay, offset) +
      // Rigid again: the bar is still within OFFSET of the plate as it leaves, so set 10 must
      // wait (TIME3 of set 20) until it is farther away, as with rigid walls.
      "*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,2,0,0,2e-3,7,10,-1\n0,0,0,2e-5,1,0\n1\n";
  const double t_end = gap / kV0 + 2.0 * kLength / c + 4e-3;
  solver::Simulation sim(read(bar_drop_deck(40, switching, gap, t_end)), {});
  const PartMotion start = motion(sim.state(), 1, 99999);
  const double ke0 = 0.5 * start.mass * kV0 * kV0;
  double first_force = -1.0, last_force = -1.0, worst_ratio = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    if (contact::resultant_force(sim.contacts(), 7) > 0.0) {
      if (first_force < 0.0) first_force = sim.state().time;
      last_force = sim.state().time;
    }
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  const auto& events = sim.switch_events();
  ASSERT_EQ(events.size(), 3u);  // rigid at the start, deformable, rigid
  EXPECT_TRUE(events[0].to_rigid);
  EXPECT_FALSE(events[1].to_rigid);
  EXPECT_EQ(events[1].swset, 10);
  EXPECT_TRUE(events[2].to_rigid);
  EXPECT_EQ(events[2].swset, 20);
  // Deformable when the gap has closed to OFFSET, before the first contact force.
  EXPECT_NEAR(events[1].time, (gap - offset) / kV0, 2.5e-5);
  EXPECT_LT(events[1].time, first_force);
  EXPECT_NEAR(first_force, gap / kV0, 5e-5);
  // The contact lasts about 2 L / c; rigid again after the delay, with the force zero.
  EXPECT_NEAR(last_force - first_force, 2.0 * kLength / c, 0.1 * 2.0 * kLength / c);
  EXPECT_GE(events[2].time, events[1].time + delay);
  EXPECT_GT(events[2].time, last_force);
  const PartMotion end = motion(sim.state(), 1, 99999);
  EXPECT_GT(end.velocity().z(), 0.95 * kV0);
  EXPECT_LT(end.velocity().z(), 1.0 * kV0);
  EXPECT_LT(worst_ratio, 1e-9);
  EXPECT_LT(sim.energy().switch_energy, 0.05 * ke0);
}

// The same drop gives bit-identical results on 1 and 2 threads.
TEST(Contact, ResultsDoNotDependOnThreadCount) {
  const auto finals = contact_runs_on_1_and_2_threads([] { return read(bar_drop_deck(20)); });
  ASSERT_EQ(finals[0].size(), finals[1].size());
  for (std::size_t i = 0; i < finals[0].size(); ++i) ASSERT_EQ(finals[0][i], finals[1][i]) << i;
}

// ---------------------------------------------------------------------------------------
// 2. Two equal elastic bars (same material and length: equal impedance), one at v0, one at
// rest, colliding head-on. 1D wave theory: after 2 L / c the moving bar stops and the other
// leaves at v0 (the velocities exchange); momentum is conserved exactly.

TEST(Contact, EqualBarsHeadOnExchangeVelocities) {
  const double c = std::sqrt(kE / kRho);
  const int nz = 40;
  const double gap = 0.1 * kLength / nz;
  Block left;
  left.nx = left.ny = 2;
  left.nz = nz;
  left.lx = left.ly = kWidth;
  left.lz = kLength;
  Block right = left;
  right.local = Vector3d(0, 0, kLength + gap);
  right.first_node = 100001;
  right.first_element = 100001;
  right.pid = 2;
  const std::string deck = "*KEYWORD\n" + left.text() + right.text() + elastic(1, kRho, kE, 0.0) +
                           elastic(2, kRho, kE, 0.0) + velocity(1, Vector3d(0, 0, kV0)) +
                           "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n1,2,3,3\n0,0,0,0,0\n10,10\n" +
                           termination(gap / kV0 + 2.6 * kLength / c);
  solver::Simulation sim(read(deck), {});
  const PartMotion a0 = motion(sim.state(), 1, 99999);
  const PartMotion b0 = motion(sim.state(), 100001, 199999);
  double worst_ratio = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    worst_ratio = std::max(worst_ratio, std::abs(sim.energy().ratio() - 1.0));
  }
  const PartMotion a = motion(sim.state(), 1, 99999);
  const PartMotion b = motion(sim.state(), 100001, 199999);
  EXPECT_NEAR(a.velocity().z(), 0.0, 0.03 * kV0);
  EXPECT_NEAR(b.velocity().z(), kV0, 0.03 * kV0);
  // Contact forces are equal and opposite: momentum conserved to round-off.
  const double p0 = a0.momentum.z() + b0.momentum.z();
  EXPECT_NEAR(a.momentum.z() + b.momentum.z(), p0, 1e-12 * std::abs(p0));
  EXPECT_LT(worst_ratio, 1e-9);
  EXPECT_EQ(sim.contacts().interfaces[0].active_nodes, 0);  // separated
}

// ---------------------------------------------------------------------------------------
// 3. A block on a fixed rigid plane inclined at angle a, gravity -z, Coulomb friction mu
// (FS = FD). Sliding (tan a > mu): x(t) = g (sin a - mu cos a) t^2 / 2 down the slope, and
// the contact dissipates mu m g cos a x. Sticking (tan a < mu): it stays.

struct InclineResult {
  double along = 0.0;  // displacement of the centre of mass down the slope
  double normal = 0.0;
  double contact_energy = 0.0;
  double mass = 0.0;
  double ratio_error = 0.0;
};

InclineResult slide(double angle, double mu, double t_end) {
  Block plate;
  plate.nx = 12;
  plate.ny = 2;
  plate.nz = 1;
  plate.lx = 0.24;
  plate.ly = 0.04;
  plate.lz = 0.01;
  plate.local = Vector3d(-0.03, -0.01, -0.01);
  plate.tilt = angle;
  plate.first_node = 100001;
  plate.first_element = 100001;
  plate.pid = 2;
  Block block;
  block.nx = block.ny = block.nz = 2;
  block.lx = block.ly = block.lz = 0.02;
  block.tilt = angle;
  const std::string deck =
      "*KEYWORD\n" + block.text() + plate.text() + elastic(1, kRho, kE, 0.3) +
      fixed_rigid(2, kRho, kE, 0.3) +
      "*LOAD_BODY_Z\n99,1.0\n*DEFINE_CURVE\n99\n0,9.81\n1e3,9.81\n" +
      fmt::format("*CONTACT_AUTOMATIC_NODES_TO_SURFACE\n1,2,3,3\n{0},{0},0,0,20\n\n", mu) +
      // A free block of 2 x 2 x 2 elements needs TSSFAC <= 0.55 (docs/verification.md).
      "*CONTROL_TIMESTEP\n0,0.5\n" + termination(t_end);
  solver::Simulation sim(read(deck), {});
  const PartMotion start = motion(sim.state(), 1, 99999);
  InclineResult r;
  while (!sim.finished()) {
    sim.cycle();
    r.ratio_error = std::max(r.ratio_error, std::abs(sim.energy().ratio() - 1.0));
  }
  const PartMotion end = motion(sim.state(), 1, 99999);
  const Vector3d down(std::cos(angle), 0.0, -std::sin(angle));
  const Vector3d normal(std::sin(angle), 0.0, std::cos(angle));
  r.along = (end.centre - start.centre).dot(down);
  r.normal = (end.centre - start.centre).dot(normal);
  r.contact_energy = sim.energy().contact_energy;
  r.mass = start.mass;
  return r;
}

TEST(Contact, BlockSlidesDownInclineWithCoulombFriction) {
  const double angle = std::numbers::pi / 6.0, mu = 0.3, g = 9.81, t = 0.15;
  const InclineResult r = slide(angle, mu, t);
  const double expected = 0.5 * g * (std::sin(angle) - mu * std::cos(angle)) * t * t;
  EXPECT_NEAR(r.along, expected, 0.03 * expected);
  EXPECT_LT(std::abs(r.normal), 1e-4);  // stays on the plane (penalty penetration is tiny)
  // Friction dissipation mu N x (plus the damped settling and stored penalty energy, small).
  const double dissipated = mu * r.mass * g * std::cos(angle) * expected;
  EXPECT_NEAR(r.contact_energy, dissipated, 0.06 * dissipated);
  EXPECT_LT(r.ratio_error, 1e-9);
}

TEST(Contact, BlockSticksOnInclineFlatterThanFrictionAngle) {
  const double angle = 10.0 * std::numbers::pi / 180.0, mu = 0.3, t = 0.1;
  const InclineResult r = slide(angle, mu, t);
  // Without friction it would slide g sin a t^2 / 2 = 8.5 mm; it creeps only by the elastic
  // tangential spring.
  EXPECT_LT(std::abs(r.along), 1e-5);
}

}  // namespace
}  // namespace rf::test

namespace rf::test {
namespace {

// *CONTROL_CONTACT SLSFAC scales every SOFT = 0 segment stiffness: k = SLSFAC K A^2 / V with K
// the bulk modulus E / (3 (1 - 2 nu)), A the face area and V the element's volume (LS-DYNA
// Theory Manual, contact penalty method), here on the bar's faces (nu = 0: K = E / 3).
TEST(Contact, ControlContactSlsfacScalesThePenaltyStiffness) {
  const int nz = 4;
  solver::Simulation sim(read(bar_drop_deck(nz, "*CONTROL_CONTACT\n0.3\n")), {});
  const contact::ContactSurface& bar = sim.contacts().interfaces.at(0).sides[0];
  const auto& x = sim.state().nodes.x;
  const double bulk = kE / 3.0;
  const double volume = (kWidth / 2) * (kWidth / 2) * (kLength / nz);
  ASSERT_FALSE(bar.segments.empty());
  for (std::size_t s = 0; s < bar.segments.size(); ++s) {
    const auto& q = bar.segments[s];
    auto p = [&](int a) { return Eigen::Vector3d(x.x[q[a]], x.y[q[a]], x.z[q[a]]); };
    const double area = 0.5 * ((p(2) - p(0)).cross(p(3) - p(1))).norm();
    EXPECT_NEAR(bar.stiffness[s], 0.3 * bulk * area * area / volume, 1e-12 * bar.stiffness[s]);
  }
  // The default (no *CONTROL_CONTACT) is LS-DYNA's 0.1.
  solver::Simulation plain(read(bar_drop_deck(nz)), {});
  const contact::ContactSurface& bar0 = plain.contacts().interfaces.at(0).sides[0];
  for (std::size_t s = 0; s < bar0.segments.size(); ++s)
    EXPECT_NEAR(bar.stiffness[s] / bar0.stiffness[s], 3.0, 1e-12);
}

// *CONTROL_CONTACT PENOPT: a small cube (side c = 0.2 h, part 2, the slave part) pressed g into the
// top face of a cube of side h (part 1); its corner node 1001. The segment's stiffness is SLSFAC K1
// A^2 / V = 0.1 K1 h, the node's (its own bottom face, facing the segment) 0.1 K2 c: the pair takes
// the smaller (PENOPT 0, 1), the segment's (2) or the node's (3); force k g on the node (dt = 0: no
// stability cap). Once with the cube as stiff as the target (the node's is smaller) and once ten
// times stiffer (the segment's is smaller).
TEST(Contact, ControlContactPenoptChoosesWhoseStiffnessThePairTakes) {
  constexpr double h = 0.01, c = 0.2 * h, g = 1e-5, e1 = 1e7, nu = 0.3;
  const double bulk1 = e1 / (3.0 * (1.0 - 2.0 * nu));
  for (const double stiffer : {1.0, 10.0}) {
    for (const int penopt : {0, 1, 2, 3}) {
      SCOPED_TRACE(fmt::format("cube E x {}, PENOPT {}", stiffer, penopt));
      Block target;
      target.lx = target.ly = target.lz = h;
      Block cube;
      cube.lx = cube.ly = cube.lz = c;
      cube.local = Eigen::Vector3d(0.4 * h, 0.4 * h, h - g);
      cube.pid = 2;
      cube.first_node = cube.first_element = 1001;
      const std::string deck = "*KEYWORD\n" + target.text() + cube.text() +
                               elastic(1, 1000.0, e1, nu) + elastic(2, 1000.0, stiffer * e1, nu) +
                               fmt::format("*CONTROL_CONTACT\n0.1,0,0,0,{}\n", penopt) +
                               "*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID\n1\n2,1,3,3\n0\n1,1\n" +
                               "*CONTROL_TERMINATION\n1.0\n*END\n";
      ContactFixture f(deck);
      f.build();
      contact::compute_contact_forces(f.contacts, f.state, 0.0);
      const double k_segment = 0.1 * bulk1 * h, k_node = 0.1 * stiffer * bulk1 * c;
      const double k = penopt == 2 ? k_segment : penopt == 3 ? k_node : std::min(k_segment, k_node);
      EXPECT_EQ(f.contacts.interfaces[0].active_nodes, 4);  // the cube's bottom corners
      EXPECT_NEAR(f.force(1001).z(), k * g, 1e-9 * k * g);
    }
  }
}

// Fields that would change the physics are refused by name; those without effect are accepted.
TEST(Contact, ControlContactRefusesWhatWouldChangeThePhysics) {
  auto error_of = [](const std::string& control) {
    return simulation_error_of(bar_drop_deck(2, control));
  };
  EXPECT_EQ(error_of("*CONTROL_CONTACT\n0.1,0,2,1,1,1,1,0\n0,0,10,1,4,0,1,0\n"), "");
  EXPECT_NE(error_of("*CONTROL_CONTACT\n0.1,0,1,0,1,0,1,1\n").find("ENMASS"), std::string::npos);
  EXPECT_NE(error_of("*CONTROL_CONTACT\n0.1,0,1,0,4\n").find("PENOPT"), std::string::npos);
  EXPECT_NE(error_of("*CONTROL_CONTACT\n0.1,0,1,0,5\n").find("PENOPT"), std::string::npos);
  EXPECT_NE(error_of("*CONTROL_CONTACT\n0.1,1.0\n").find("RWPNAL"), std::string::npos);
  EXPECT_NE(error_of("*CONTROL_CONTACT\n0.1\n0\n0.3\n").find("SFRIC"), std::string::npos);
  EXPECT_NE(error_of("*CONTROL_CONTACT\n0.1\n0\n0\n1\n").find("IGNORE"), std::string::npos);
  EXPECT_NE(error_of("*CONTROL_CONTACT\n-1\n").find("SLSFAC"), std::string::npos);
}

}  // namespace
}  // namespace rf::test
