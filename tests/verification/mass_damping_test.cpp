// Added masses (*ELEMENT_MASS, *ELEMENT_MASS_PART) and mass-proportional damping
// (*DAMPING_GLOBAL, *DAMPING_PART_MASS) against closed-form answers:
//  - a fixed-free bar with a tip mass M vibrates at w = beta c / L with beta tan(beta) = m / M
//    (m the bar's mass; e.g. Timoshenko, Vibration Problems in Engineering, longitudinal
//    vibration of a bar with a mass at its end);
//  - a bar whose density is raised uniformly (ELEMENT_MASS_PART) vibrates at pi c / (2 L)
//    times sqrt(m / (m + added));
//  - f = -d m v on a free body gives v(t) = v0 exp(-d t), on a spinning rigid body
//    L(t) = L0 exp(-d t); a damped mode decays as exp(-d t / 2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "deck_builder.hpp"
#include "model/error.hpp"
#include "shell_builder.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7850.0, kE = 210e9;
constexpr double kLength = 1.0, kSide = 0.05;
constexpr int kElements = 40;

BoxMesh bar_mesh() {
  BoxMesh mesh;
  mesh.nx = kElements;
  mesh.lx = kLength;
  mesh.ly = mesh.lz = kSide;
  return mesh;
}

double bar_mass() {
  return kRho * kLength * kSide * kSide;
}

// Fixed-free bar along x (nu = 0: one-dimensional), the face x = 0 held in x, with `extra`
// cards; initial axial velocity v0 sin(beta x / L), the first mode's shape, so that the first
// mode dominates.
std::string bar_deck(double beta, const std::string& extra, double end_time) {
  const BoxMesh mesh = bar_mesh();
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.0, 1, 4);
  deck += node_set(1, mesh.face_x(0)) + "*BOUNDARY_SPC_SET\n1,0,1,0,0,0,0,0\n";
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k <= mesh.nz; ++k)
    for (int j = 0; j <= mesh.ny; ++j)
      for (int i = 0; i <= mesh.nx; ++i) {
        const double x = kLength * i / mesh.nx;
        deck += fmt::format("{},{:.17g},0,0\n", mesh.node_id(i, j, k),
                            1.0 * std::sin(beta * x / kLength));
      }
  deck += extra;
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*END\n", end_time);
  return deck;
}

// Times at which the velocity of `node` (x component) crosses zero downwards, linearly
// interpolated between cycles; the period is the mean spacing.
struct Crossings {
  std::vector<double> times;
  double period() const {
    return (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  }
};

Crossings velocity_crossings(solver::Simulation& sim, int node_index) {
  Crossings c;
  const auto& v = sim.state().nodes.v.x;
  double t_prev = sim.state().time, v_prev = v[node_index];
  while (!sim.finished()) {
    sim.cycle();
    const double t = sim.state().time, vi = v[node_index];
    if (v_prev > 0.0 && vi <= 0.0)
      c.times.push_back(t_prev + (t - t_prev) * v_prev / (v_prev - vi));
    t_prev = t;
    v_prev = vi;
  }
  return c;
}

int tip_node_index(const solver::Simulation& sim) {
  const auto& ids = sim.state().nodes.id;
  const model::Id tip = bar_mesh().node_id(kElements, 0, 0);
  return static_cast<int>(std::find(ids.begin(), ids.end(), tip) - ids.begin());
}

// beta tan(beta) = ratio, first root in (0, pi/2), by bisection.
double first_root(double ratio) {
  double lo = 1e-9, hi = std::numbers::pi / 2 - 1e-12;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mid * std::tan(mid) < ratio ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

const double kWaveSpeed = std::sqrt(kE / kRho);

TEST(ElementMass, TipMassBarVibratesAtTheClassicalFrequency) {
  const double tip_mass = bar_mass();  // M = m: beta tan(beta) = 1
  const double beta = first_root(bar_mass() / tip_mass);
  const double period = 2.0 * std::numbers::pi * kLength / (beta * kWaveSpeed);
  const BoxMesh mesh = bar_mesh();
  std::string masses = "*ELEMENT_MASS\n";
  int eid = 1000;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j)
      masses += fmt::format("{},{},{:.17g}\n", ++eid, mesh.node_id(kElements, j, k), tip_mass / 4);
  solver::Simulation sim(read(bar_deck(beta, masses, 4.5 * period)), {});
  double total = 0.0;
  for (const double m : sim.state().nodes.mass) total += m;
  EXPECT_NEAR(total, bar_mass() + tip_mass, 1e-12 * total);
  EXPECT_NEAR(sim.state().added_mass, tip_mass, 1e-12 * tip_mass);
  const Crossings c = velocity_crossings(sim, tip_node_index(sim));
  ASSERT_GE(c.times.size(), 4u);
  std::printf("tip-mass bar: period %.6g s vs beta %.6f: %.6g s (ratio %.6f)\n", c.period(), beta,
              period, c.period() / period);
  // 40 one-point elements: the discrete frequency is within a few 1e-4 of the continuum's.
  EXPECT_NEAR(c.period() / period, 1.0, 2e-3) << "beta " << beta;
  // Without the mass the bar would vibrate at pi c / (2 L): a 1.83x shorter period.
  EXPECT_GT(c.period(), 1.5 * 4.0 * kLength / kWaveSpeed);
}

class ElementMassPart : public testing::TestWithParam<std::string> {};

TEST_P(ElementMassPart, UniformlyAddedMassLowersTheFrequencyBySqrtTwo) {
  // Doubling the density: w1 = pi c / (2 L sqrt(2)).
  const double beta = std::numbers::pi / 2;
  const double period = 4.0 * kLength * std::sqrt(2.0) / kWaveSpeed;
  solver::Simulation sim(read(bar_deck(beta, GetParam(), 4.5 * period)), {});
  double total = 0.0;
  for (const double m : sim.state().nodes.mass) total += m;
  EXPECT_NEAR(total, 2.0 * bar_mass(), 1e-12 * total);
  const Crossings c = velocity_crossings(sim, tip_node_index(sim));
  ASSERT_GE(c.times.size(), 4u);
  std::printf("doubled density: period ratio %.6f\n", c.period() / period);
  EXPECT_NEAR(c.period() / period, 1.0, 2e-3);
}

INSTANTIATE_TEST_SUITE_P(
    Mass, ElementMassPart,
    testing::Values(fmt::format("*ELEMENT_MASS_PART\n1,{:.17g}\n", 7850.0 * 0.0025),
                    fmt::format("*ELEMENT_MASS_PART\n1,0.0,{:.17g}\n", 2 * 7850.0 * 0.0025),
                    fmt::format("*SET_PART_LIST\n5\n1\n*ELEMENT_MASS_PART_SET\n5,{:.17g}\n",
                                7850.0 * 0.0025)));

TEST(ElementMassPart, FinalMassBelowThePartsMassIsAnInputError) {
  const std::string deck = bar_deck(1.0, "*ELEMENT_MASS_PART\n1,0.0,1.0\n", 1e-4);
  try {
    solver::Simulation sim(read(deck), {});
    FAIL() << "expected an input error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("FINMASS"), std::string::npos) << e.what();
  }
}

// A free block moving at v0 under damping d: v(t) = v0 exp(-d t). The explicit force
// -d m v^{n-1/2} gives (1 - d dt)^n = exp(-d t) (1 + O(d^2 dt t)): with d dt ~ 4e-4 the
// relative error at d t = 1 is ~2e-4.
std::string moving_block(const std::string& part_cards, const std::string& damping,
                         double end_time) {
  BoxMesh mesh;
  mesh.nx = mesh.ny = mesh.nz = 3;
  mesh.lx = mesh.ly = mesh.lz = 0.03;
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + part_cards + damping;
  deck += "*INITIAL_VELOCITY\n0\n3.0,-2.0,1.0\n";
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n0,0.9\n", end_time);
  deck += "*DATABASE_GLSTAT\n1e-4\n*END\n";
  return deck;
}

TEST(DampingGlobal, FreeBlockSlowsDownExponentiallyAndTheLedgerCloses) {
  const double d = 50.0, end = 0.02;  // d t = 1
  solver::Simulation sim(
      read(moving_block(elastic_part(kRho, kE, 0.3, 1, 1), "*DAMPING_GLOBAL\n0,50.0\n", end)), {});
  const double ke0 = sim.energy().kinetic;
  sim.run();
  const double decay = std::exp(-d * sim.state().time);
  const double mass = kRho * 0.03 * 0.03 * 0.03;
  EXPECT_NEAR(sim.energy().momentum[0] / (mass * 3.0), decay, 1e-3 * decay);
  EXPECT_NEAR(sim.energy().momentum[1] / (mass * -2.0), decay, 1e-3 * decay);
  // The energy damping removed is booked: kinetic energy fell by (1 - e^-2) and the ratio
  // still closes.
  const double removed = ke0 - sim.energy().kinetic - sim.energy().internal_work;
  std::printf("damped free block: v/v0 %.9f vs exp(-d t) %.9f, energy ratio %.12f\n",
              sim.energy().momentum[0] / (mass * 3.0), decay, sim.energy().ratio());
  EXPECT_NEAR(-sim.energy().damping_work, removed, 1e-9 * ke0);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-9);
  EXPECT_NEAR(sim.energy().kinetic / ke0, decay * decay, 2e-3 * decay * decay);
}

TEST(DampingPartMass, DirectionScalesDampOnlyTheChosenDirection) {
  // Part damping from a curve (d = SF * 25 = 50), FLAG 1: only x is damped.
  const std::string damping =
      "*DEFINE_CURVE\n7\n0.0,25.0\n1.0,25.0\n*DAMPING_PART_MASS\n1,7,2.0,1\n1.0,0.0,0.0\n";
  solver::Simulation sim(read(moving_block(elastic_part(kRho, kE, 0.3, 1, 1), damping, 0.02)), {});
  sim.run();
  const double mass = kRho * 0.03 * 0.03 * 0.03;
  const double decay = std::exp(-50.0 * sim.state().time);
  EXPECT_NEAR(sim.energy().momentum[0] / (mass * 3.0), decay, 1e-3 * decay);
  EXPECT_NEAR(sim.energy().momentum[1] / (mass * -2.0), 1.0, 1e-12);
  EXPECT_NEAR(sim.energy().momentum[2] / (mass * 1.0), 1.0, 1e-12);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-9);
}

TEST(DampingGlobal, RigidBodyIsDampedAtItsCentreOfMass) {
  // *MAT_RIGID block, translating and spinning about z through its centre: v and the spin
  // both decay as exp(-d t).
  const std::string rigid =
      "*PART\nrigid block\n1,1,1\n*SECTION_SOLID\n1,1\n*MAT_RIGID\n1,7850.0,2.1e11,0.3\n";
  BoxMesh mesh;
  mesh.nx = mesh.ny = mesh.nz = 3;
  mesh.lx = mesh.ly = mesh.lz = 0.03;
  std::string deck = "*KEYWORD\n" + mesh.keyword_text() + rigid + "*DAMPING_GLOBAL\n0,50.0\n";
  deck += "*INITIAL_VELOCITY_GENERATION\n1,2,100.0,3.0,0.0,0.0\n0.015,0.015,0.015,0.0,0.0,1.0\n";
  deck += "*CONTROL_TERMINATION\n0.02\n*CONTROL_TIMESTEP\n1e-5\n*END\n";
  solver::Simulation sim(read(deck), {});
  const double ke0 = sim.energy().kinetic;
  const double lz0 = sim.energy().angular_momentum[2];
  ASSERT_GT(std::abs(lz0), 0.0);
  sim.run();
  const double decay = std::exp(-50.0 * sim.state().time);
  const double mass = kRho * 0.03 * 0.03 * 0.03;
  EXPECT_NEAR(sim.energy().momentum[0] / (mass * 3.0), decay, 2e-3 * decay);
  // L_z about the origin = (x_c x M v_c)_z + J w_z; v_c is along x and x_c moves along x, so
  // the first term is -y_c M v_x and decays like v_x too.
  EXPECT_NEAR(sim.energy().angular_momentum[2] / lz0, decay, 2e-3 * decay);
  // The rigid rotation update conserves energy only to O((w dt)^2) per step under a moment
  // (the same for *LOAD_RIGID_BODY moments): measured 2.8e-9 and 1.8e-8 here.
  EXPECT_NEAR(-sim.energy().damping_work, ke0 - sim.energy().kinetic, 1e-8 * ke0);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-7);
}

// Mass-weighted damping of every DOF, the spins of shell nodes included: on a free body the
// damping forces and moments are -d times the momentum density, so the angular momentum about
// any fixed point, the nodal spins' J w included, decays as dH/dt = -d H whatever the body does
// (the internal forces and moments conserve H). A shell plate spinning about its normal: its
// nodal rotary inertia holds a tenth of H (J = m (A0/4 + t^2/12), scaled as the kernels scale
// it), which undamped spins would keep.
TEST(DampingGlobal, SpinningShellPlateLosesAngularMomentumAsExpMinusDt) {
  const double d = 50.0, end = 0.02, omega = 40.0, size = 0.1;
  ShellPlate plate;
  plate.nx = plate.ny = 4;
  plate.lx = plate.ly = size;
  std::string deck = "*KEYWORD\n" + plate.text() + shell_part(1, 0.002, kRho, kE, 0.3);
  deck += fmt::format("*DAMPING_GLOBAL\n0,{}\n*INITIAL_VELOCITY_NODE\n", d);
  for (int j = 0; j <= plate.ny; ++j) {
    for (int i = 0; i <= plate.nx; ++i) {
      const Eigen::Vector3d r = plate.position(i, j) - Eigen::Vector3d(size / 2, size / 2, 0.0);
      deck += fmt::format("{},{:.17g},{:.17g},0,0,0,{:.17g}\n", plate.node_id(i, j), -omega * r.y(),
                          omega * r.x(), omega);
    }
  }
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n0,0.9\n*END\n", end);
  solver::Simulation sim(read(deck), {});
  const double h0 = sim.energy().angular_momentum[2];
  double spin_share = 0.0;
  const solver::RotationalState& rot = sim.state().rotations;
  for (std::size_t r = 0; r < rot.size(); ++r) spin_share += rot.inertia[r] * rot.w.z[r];
  spin_share /= h0;
  const double ke0 = sim.energy().kinetic;
  sim.run();
  const double decay = std::exp(-d * sim.state().time);
  std::printf(
      "spinning shell plate: spins hold %.3f of H; H/H0 %.9f vs exp(-d t) %.9f; energy ratio "
      "%.12f\n",
      spin_share, sim.energy().angular_momentum[2] / h0, decay, sim.energy().ratio());
  ASSERT_GT(spin_share, 0.05);  // the spins matter: without their damping H/H0 would be off by
                                // about spin_share (1 - decay)
  // The explicit lag (forces at t^{n+1} from v^{n+1/2}) and the first half step: 1e-3, as the
  // translating block above.
  EXPECT_NEAR(sim.energy().angular_momentum[2] / h0, decay, 1e-3 * decay);
  // The work of the damping forces and moments is booked: the energy balance closes.
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-9);
  EXPECT_NEAR(-sim.energy().damping_work, ke0 - sim.energy().kinetic - sim.energy().internal_work,
              1e-8 * ke0);
}

TEST(DampingGlobal, DampedModeDecaysAtHalfTheDampingConstant) {
  // Mass-proportional damping d gives every mode the decay rate d / 2 (modal damping ratio
  // d / (2 w)); the fixed-free bar's first mode is excited alone.
  const double beta = std::numbers::pi / 2;
  const double period = 4.0 * kLength / kWaveSpeed;
  const double d = 200.0;
  // Mass damping alone is the subject: no bulk viscosity, which would add its own decay.
  solver::Simulation sim(
      read(bar_deck(beta, "*DAMPING_GLOBAL\n0,200.0\n*CONTROL_BULK_VISCOSITY\n0.0,0.0\n",
                    6.0 * period)),
      {});
  const int tip = tip_node_index(sim);
  // Maxima of the tip's displacement, where its velocity turns from positive to negative: the
  // amplitude ratio over n periods is exp(-d n T / 2).
  std::vector<std::pair<double, double>> peaks;
  const double x0 = sim.state().nodes.x0.x[tip];
  double v_prev = sim.state().nodes.v.x[tip];
  while (!sim.finished()) {
    sim.cycle();
    const double v = sim.state().nodes.v.x[tip];
    if (v_prev > 0.0 && v <= 0.0) {
      peaks.emplace_back(sim.state().time, sim.state().nodes.x.x[tip] - x0);
    }
    v_prev = v;
  }
  ASSERT_GE(peaks.size(), 4u);
  const auto& first = peaks.front();
  const auto& last = peaks.back();
  const double measured_rate = std::log(first.second / last.second) / (last.first - first.first);
  std::printf("damped bar mode: decay rate %.6g 1/s vs d/2 = %.6g (ratio %.6f)\n", measured_rate,
              0.5 * d, measured_rate / (0.5 * d));
  EXPECT_NEAR(measured_rate / (0.5 * d), 1.0, 1e-2);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-9);
}

TEST(DampingInput, BadCardsAreInputErrors) {
  const std::string base = moving_block(elastic_part(kRho, kE, 0.3, 1, 1), "", 1e-4);
  auto with = [&](const std::string& cards) {
    std::string deck = base;
    deck.insert(deck.find("*END"), cards);
    return deck;
  };
  auto expect_error = [&](const std::string& deck, const std::string& field) {
    try {
      solver::Simulation sim(read(deck), {});
      ADD_FAILURE() << "expected an input error at " << field;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  expect_error(with("*DAMPING_GLOBAL\n0,-1.0\n"), "VALDMP");
  expect_error(with("*DAMPING_GLOBAL\n9\n"), "LCID");       // undefined curve
  expect_error(with("*DAMPING_PART_MASS\n1,0\n"), "LCID");  // curve required
  expect_error(with("*DEFINE_CURVE\n7\n0,1\n1,1\n*DAMPING_PART_MASS\n4,7\n"), "PID");
  expect_error(with("*DEFINE_CURVE\n7\n0,1\n1,1\n*DAMPING_PART_MASS\n1,7,1.0,0,1\n"), "STRUC");
  expect_error(with("*ELEMENT_MASS\n1,99999,1.0\n"), "NID");
  expect_error(with("*ELEMENT_MASS\n1,1,-1.0\n"), "MASS");
  expect_error(with("*ELEMENT_MASS_PART\n1,1.0,2.0\n"), "FINMASS");
  expect_error(with("*ELEMENT_MASS_PART\n1,1.0,0.0,3\n"), "LCID");
}

}  // namespace
}  // namespace rf::test
