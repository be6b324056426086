// Penalty joints between rigid bodies against closed-form mechanics:
//  - spherical joint: a rigid bar released at 60 degrees swings with the exact period of the
//    compound pendulum, T = 4 sqrt(I / (M g d)) K(sin(theta0 / 2)) (complete elliptic integral
//    of the first kind; e.g. Thornton & Marion, Classical Dynamics, ch. 4);
//  - revolute joint: the same period while a side load along the hinge axis is carried;
//  - cylindrical joint: a slider falls freely along the axis (z = -g t^2 / 2) and spins up
//    under a torque about the axis (w = T t / J), while a side load is carried;
//  - translational joint: the same slider falls freely and does not spin;
//  - universal joint: a Hooke (cross) joint between two shafts at 30 degrees turns the driven
//    shaft by tan(theta_B) = tan(theta_A) / cos(beta) (e.g. Shigley & Uicker, Theory of
//    Machines and Mechanisms, "the Hooke joint"; speed ratio between cos(beta) and
//    1 / cos(beta));
//  - locking joint: two free bodies locked together move as one body under a force and a
//    torque on one of them (a = F / (m_A + m_B), alpha = T / (J_A + J_B)).
// The reference masses, centres and inertias come from the test's own lumped-mass sums over
// the node grid (rho V / 8 per element node), not from the solver.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

constexpr double kRho = 7850.0, kG = 9.81, kTheta0 = std::numbers::pi / 3;

// Ground: a fixed rigid block 2 x 2 x 1 over [-0.05, 0.05]^2 x [0, 0.1]; node (1,1,0) sits at
// the origin (the pivot), (1,2,0) at (0, 0.05, 0), (1,1,1) at (0, 0, 0.1), (2,1,0) at
// (0.05, 0, 0).
Block ground() {
  Block b;
  b.nx = b.ny = 2;
  b.nz = 1;
  b.lx = b.ly = b.lz = 0.1;
  b.local = Eigen::Vector3d(-0.05, -0.05, 0.0);
  b.first_node = 1;
  b.first_element = 1;
  b.pid = 1;
  return b;
}

// Pendulum bar 0.1 x 0.1 x 1 hanging from the origin, turned by theta0 about y.
Block bar(double tilt) {
  Block b;
  b.nx = b.ny = 2;
  b.nz = 10;
  b.lx = b.ly = 0.1;
  b.lz = 1.0;
  b.local = Eigen::Vector3d(-0.05, -0.05, -1.0);
  b.tilt = tilt;
  b.first_node = 1001;
  b.first_element = 1001;
  b.pid = 2;
  return b;
}

std::string rigid_parts() {
  return "*PART\nground\n1,1,1\n*PART\nmoving\n2,1,2\n*SECTION_SOLID\n1,1\n"
         "*MAT_RIGID\n1,7850.0,2.1e11,0.3\n1.0,7,7\n*MAT_RIGID\n2,7850.0,2.1e11,0.3\n";
}

std::string gravity(char axis, double g, int curve) {
  return fmt::format("*DEFINE_CURVE\n{0}\n0.0,{1:.17g}\n100.0,{1:.17g}\n*LOAD_BODY_{2}\n{0}\n",
                     curve, g, axis);
}

// Lumped-mass sums of a block in its own (untilted) frame: mass, first moment about the
// origin along z, and the second moment about the y axis through the origin.
struct MassSums {
  double mass = 0, first_z = 0, second_y = 0, second_z = 0;
};
MassSums lumped_sums(const Block& b) {
  MassSums s;
  const double m_node = kRho * (b.lx / b.nx) * (b.ly / b.ny) * (b.lz / b.nz) / 8.0;
  for (int k = 0; k < b.nz; ++k)
    for (int j = 0; j < b.ny; ++j)
      for (int i = 0; i < b.nx; ++i)
        for (int c = 0; c < 8; ++c) {
          const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
          const Eigen::Vector3d p = Eigen::Vector3d(b.lx * (i + di) / b.nx, b.ly * (j + dj) / b.ny,
                                                    b.lz * (k + dk) / b.nz) +
                                    b.local;
          s.mass += m_node;
          s.first_z += m_node * p.z();
          s.second_y += m_node * (p.x() * p.x() + p.z() * p.z());
          s.second_z += m_node * (p.x() * p.x() + p.y() * p.y());
        }
  return s;
}

double elliptic_k(double k) {  // K(k) = pi / (2 AGM(1, sqrt(1 - k^2)))
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int n = 0; n < 40; ++n) {
    const double a1 = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = a1;
  }
  return std::numbers::pi / (2.0 * a);
}

double pendulum_period() {
  const MassSums s = lumped_sums(bar(0.0));
  const double d = -s.first_z / s.mass;  // centre of mass below the pivot
  return 4.0 * std::sqrt(s.second_y / (s.mass * kG * d)) * elliptic_k(std::sin(kTheta0 / 2));
}

std::int32_t dense(const solver::Simulation& sim, model::Id id) {
  const auto& ids = sim.state().nodes.id;
  return static_cast<std::int32_t>(std::find(ids.begin(), ids.end(), id) - ids.begin());
}

// Runs the pendulum and returns the period from the times at which the bar's tip crosses
// x = 0 (twice per period), with the largest tip excursion along y.
struct Swing {
  double period = 0.0, max_y = 0.0, max_gap = 0.0, energy_ratio = 0.0;
};
Swing swing(const std::string& joint_cards, const std::string& extra_loads) {
  const Block g = ground(), b = bar(kTheta0);
  const double period = pendulum_period();
  std::string deck = "*KEYWORD\n" + g.text() + b.text() + rigid_parts() + joint_cards +
                     gravity('Z', kG, 1) + extra_loads;
  deck += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n1.0e-3\n*END\n",
                      2.3 * period);
  solver::Simulation sim(read(deck), {});
  const std::int32_t tip = dense(sim, b.node(1, 1, 0));
  const auto& x = sim.state().nodes.x;
  std::vector<double> crossings;
  double t_prev = 0.0, x_prev = x.x[tip];
  Swing s;
  while (!sim.finished()) {
    sim.cycle();
    const double t = sim.state().time, xt = x.x[tip];
    if ((x_prev < 0.0) != (xt < 0.0) && t > 0.0) {
      crossings.push_back(t_prev + (t - t_prev) * x_prev / (x_prev - xt));
    }
    s.max_y = std::max(s.max_y, std::abs(x.y[tip]));
    for (const auto& j : sim.joints().joints) s.max_gap = std::max(s.max_gap, j.gap);
    t_prev = t;
    x_prev = xt;
  }
  EXPECT_GE(crossings.size(), 4u);
  if (crossings.size() >= 2) {
    s.period =
        2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  }
  s.energy_ratio = sim.energy().ratio();
  return s;
}

TEST(Joint, SphericalPendulumSwingsWithTheExactLargeAmplitudePeriod) {
  const Block g = ground(), b = bar(kTheta0);
  const Swing s = swing(
      fmt::format("*CONSTRAINED_JOINT_SPHERICAL\n{},{}\n", g.node(1, 1, 0), b.node(1, 1, b.nz)),
      "");
  const double period = pendulum_period();
  std::printf(
      "spherical pendulum: period %.6f s vs exact %.6f s (ratio %.6f), largest gap "
      "%.3g m, energy ratio %.9f\n",
      s.period, period, s.period / period, s.max_gap, s.energy_ratio);
  EXPECT_NEAR(s.period / period, 1.0, 2e-3) << "period " << s.period << " vs " << period;
  EXPECT_LT(s.max_gap, 1e-3);  // the penalty spring gives way by less than 1 mm on a 1 m bar
  EXPECT_LT(s.max_y, 1e-9);    // nothing pushes the swing out of its plane
  // The joints' dashpots take a little energy; the ledger (spring energy and losses are
  // internal energy) still closes.
  EXPECT_NEAR(s.energy_ratio, 1.0, 1e-6);
}

// jntforc.csv: at the bottom of the swing the pivot holds the bar's weight and its centripetal
// force, R = M g + M w^2 d with w^2 = 2 M g d (1 - cos theta0) / I_O (energy conservation; the
// angular acceleration and so the horizontal reaction vanish there). The file reports the force
// on body B (the bar) in global axes.
TEST(Joint, JntforcReportsThePivotReactionOfThePendulum) {
  const Block g = ground(), b = bar(kTheta0);
  const double period = pendulum_period();
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_jntforc_test";
  std::filesystem::remove_all(dir);
  const double output_dt = 1e-3;
  std::string deck =
      "*KEYWORD\n" + g.text() + b.text() + rigid_parts() +
      fmt::format("*CONSTRAINED_JOINT_SPHERICAL_ID\n3,pivot\n{},{}\n", g.node(1, 1, 0),
                  b.node(1, 1, b.nz)) +
      gravity('Z', kG, 1) + fmt::format("*DATABASE_JNTFORC\n{:.17g}\n", output_dt) +
      fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n1.0e-3\n*END\n",
                  0.3 * period);
  const MassSums m = lumped_sums(bar(0.0));
  const double d = -m.first_z / m.mass;
  const double w2 = 2.0 * m.mass * kG * d * (1.0 - std::cos(kTheta0)) / m.second_y;
  const double expected = m.mass * kG + m.mass * w2 * d;
  double bottom_time = 0.0;
  {
    solver::Simulation sim(
        read(deck), solver::SimulationOptions{.output_directory = dir, .write_fields = false});
    const std::int32_t tip = dense(sim, b.node(1, 1, 0));
    const auto& x = sim.state().nodes.x;
    double x_prev = x.x[tip], t_prev = 0.0;
    while (!sim.finished() && bottom_time == 0.0) {
      sim.cycle();
      if ((x_prev < 0.0) != (x.x[tip] < 0.0)) {
        bottom_time = t_prev + (sim.state().time - t_prev) * x_prev / (x_prev - x.x[tip]);
      }
      x_prev = x.x[tip];
      t_prev = sim.state().time;
    }
    sim.run();
  }
  ASSERT_GT(bottom_time, 0.0);
  std::ifstream in(dir / "jntforc.csv");
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header,
            "time,joint,force_x,force_y,force_z,force_resultant,moment_x,moment_y,moment_z,"
            "moment_resultant,stiffness,phi,theta,psi,moment_phi,moment_theta,moment_psi,"
            "stiffness_elastic_energy,stiffness_dissipated_energy");
  // The rows within 2 ms of the bottom, averaged (the penalty spring rings at a few kHz).
  double sum_z = 0.0, sum_x = 0.0, sum_y = 0.0, largest_moment = 0.0;
  int near = 0, rows = 0;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 19u) << line;
    // No *CONSTRAINED_JOINT_STIFFNESS names this joint: its columns are zero.
    for (std::size_t c = 10; c < 19; ++c) EXPECT_EQ(v[c], 0.0) << c;
    ++rows;
    EXPECT_EQ(v[1], 3.0);
    EXPECT_NEAR(v[5], std::hypot(v[2], v[3], v[4]), 1e-9 * (1.0 + v[5]));
    largest_moment = std::max(largest_moment, v[9]);
    if (std::abs(v[0] - bottom_time) <= 2e-3) {
      sum_x += v[2];
      sum_y += v[3];
      sum_z += v[4];
      ++near;
    }
  }
  ASSERT_GT(near, 0);
  const double fz = sum_z / near, fx = sum_x / near, fy = sum_y / near;
  std::printf(
      "jntforc: pivot force at the bottom %.6g N (expected M g + M w^2 d = %.6g N, static "
      "M g = %.6g N), horizontal %.3g N, %d rows\n",
      fz, expected, m.mass * kG, std::hypot(fx, fy), rows);
  EXPECT_NEAR(fz / expected, 1.0, 1e-2);
  EXPECT_LT(std::hypot(fx, fy), 2e-2 * expected);
  EXPECT_LT(largest_moment, 1e-9 * expected);  // one pair: no moment about N1
  EXPECT_NEAR(rows, 0.3 * period / output_dt, 2.0);
}

TEST(Joint, RevoluteHingeCarriesASideLoadAlongItsAxis) {
  const Block g = ground(), b = bar(kTheta0);
  // RPS 10 (w dt0 = 1): the hinge's two pairs are only 5 cm apart, and the side load's moment
  // about the pivot (0.5 m arm) loads them twentyfold.
  const std::string joint =
      fmt::format("*CONSTRAINED_JOINT_REVOLUTE_ID\n7,hinge\n{},{},{},{},,,10.0\n", g.node(1, 1, 0),
                  b.node(1, 1, b.nz), g.node(1, 2, 0), b.node(1, 2, b.nz));
  // A spherical joint would let this load along y tilt the swing plane by atan(5 / 9.81) = 27
  // degrees: the tip would move 0.45 m sideways. The hinge gives way by F / k only.
  const Swing s = swing(joint, gravity('Y', 5.0, 2));
  std::printf("revolute pendulum: period ratio %.6f, tip off the plane %.4g m, gap %.3g m\n",
              s.period / pendulum_period(), s.max_y, s.max_gap);
  EXPECT_NEAR(s.period / pendulum_period(), 1.0, 2e-3);
  EXPECT_LT(s.max_y, 0.03);  // measured 0.018 m
  EXPECT_NEAR(s.energy_ratio, 1.0, 1e-6);
}

// A slider block coincident with the ground block, joined along the vertical axis through
// N1 = (0,0,0), N3 = (0,0,0.1); gravity along -z, a side load along x and a torque about z.
struct Slide {
  double drop = 0.0, expected_drop = 0.0, spin = 0.0, expected_spin = 0.0, side = 0.0;
};
Slide slide(const char* type, int pairs) {
  const Block g = ground();
  Block s = ground();
  s.first_node = 1001;
  s.first_element = 1001;
  s.pid = 2;
  std::string nodes = fmt::format("{},{},{},{}", g.node(1, 1, 0), s.node(1, 1, 0), g.node(1, 1, 1),
                                  s.node(1, 1, 1));
  if (pairs == 3) nodes += fmt::format(",{},{}", g.node(2, 1, 0), s.node(2, 1, 0));
  const double torque = 2.0, end = 0.05;
  std::string deck = "*KEYWORD\n" + g.text() + s.text() + rigid_parts() +
                     fmt::format("*CONSTRAINED_JOINT_{}\n{}\n", type, nodes) + gravity('Z', kG, 1) +
                     gravity('X', 3.0, 2) +
                     fmt::format(
                         "*DEFINE_CURVE\n3\n0.0,1.0\n100.0,1.0\n"
                         "*LOAD_RIGID_BODY\n2,7,3,{:.17g}\n",
                         torque) +
                     fmt::format(
                         "*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n1.0e-4\n"
                         "*END\n",
                         end);
  solver::Simulation sim(read(deck), {});
  sim.run();
  const auto& body = sim.rigid_bodies().bodies;
  const auto it = std::find_if(body.begin(), body.end(), [](const auto& b) { return b.id == 2; });
  EXPECT_NE(it, body.end());
  const MassSums m = lumped_sums(s);
  const double centre_z0 = m.first_z / m.mass;
  Slide r;
  const double t = sim.state().time;
  // The body sits at t^n (previous_centre) with its velocities at t^{n+1/2} (the last cycle
  // advanced them once more); central differences fall exactly as -g t^2 / 2.
  const double dt = sim.state().dt_prev > 0.0 ? sim.state().dt_prev : sim.state().dt;
  r.drop = centre_z0 - it->state.previous_centre.z();
  r.expected_drop = 0.5 * kG * t * t;
  r.side = std::abs(it->state.previous_centre.x()) + std::abs(it->state.previous_centre.y());
  r.spin = it->state.angular_velocity.z();
  r.expected_spin = torque * (t + 0.5 * dt) / m.second_z;  // J_zz about the axis
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
  std::printf("%s slider: drop ratio %.9f, spin %.6g (expected %.6g), side %.3g m\n", type,
              r.drop / r.expected_drop, r.spin, r.expected_spin, r.side);
  return r;
}

TEST(Joint, CylindricalSliderFallsFreelyAndTurnsAboutTheAxis) {
  const Slide r = slide("CYLINDRICAL", 2);
  EXPECT_NEAR(r.drop / r.expected_drop, 1.0, 1e-3);
  // The torque acts from t = 0 (first half step on t^0): w = T t / J up to one step.
  EXPECT_NEAR(r.spin / r.expected_spin, 1.0, 5e-3);
  EXPECT_LT(r.side, 1e-4);
}

TEST(Joint, TranslationalSliderFallsFreelyAndDoesNotTurn) {
  const Slide r = slide("TRANSLATIONAL", 3);
  EXPECT_NEAR(r.drop / r.expected_drop, 1.0, 1e-3);
  EXPECT_LT(std::abs(r.spin), 1e-3 * r.expected_spin);
  EXPECT_LT(r.side, 1e-4);
}

// Hooke (cross) joint. Shaft A turns about the global z axis (its centre of mass is on the axis,
// *MAT_RIGID CON1 7, CON2 4: only the turn about z is free); shaft B lies along b = (sin beta,
// 0, cos beta) and turns about b in a revolute joint to the fixed ground. The cross sits at the
// origin: arm u_A = x on A (N1 -> N3), arm u_B = y on B (N2 -> N4). The joint nodes are extra
// nodes of the bodies. With u_A = (cos tA, sin tA, 0) and u_B = cos tB y + sin tB (b x y),
// u_A . u_B = 0 gives tan tB = tan tA / cos beta: the kinematics, independent of the masses.
TEST(Joint, UniversalJointDrivesAnInclinedShaftWithTheHookeJointLaw) {
  const double beta = std::numbers::pi / 6, omega = 2.0 * std::numbers::pi;
  Block g = ground();
  g.local = Eigen::Vector3d(1.0, 1.0, 0.0);  // out of the way of the shafts
  Block a;
  a.nx = a.ny = 2;
  a.nz = 4;
  a.lx = a.ly = 0.2;
  a.lz = 0.8;
  a.local = Eigen::Vector3d(-0.1, -0.1, -1.0);
  a.first_node = 1001;
  a.first_element = 1001;
  a.pid = 2;
  Block b = a;
  b.lx = b.ly = 0.1;
  b.local = Eigen::Vector3d(-0.05, -0.05, 0.2);
  b.tilt = beta;
  b.first_node = 2001;
  b.first_element = 2001;
  b.pid = 3;
  const Eigen::Vector3d axis_b(std::sin(beta), 0.0, std::cos(beta));
  std::string deck = "*KEYWORD\n" + g.text() + a.text() + b.text();
  deck += "*NODE\n9001,0,0,0\n9002,0,0,0\n9003,0.1,0,0\n9004,0,0.1,0\n";
  for (int k = 0; k < 2; ++k) {  // the hinge of B: two points on its axis, ground and shaft
    const Eigen::Vector3d p = (0.5 + 0.5 * k) * axis_b;
    deck += fmt::format("{},{:.17g},{:.17g},{:.17g}\n{},{:.17g},{:.17g},{:.17g}\n", 9005 + 2 * k,
                        p.x(), p.y(), p.z(), 9006 + 2 * k, p.x(), p.y(), p.z());
  }
  deck +=
      "*PART\nground\n1,1,1\n*PART\nshaft A\n2,1,2\n*PART\nshaft B\n3,1,3\n*SECTION_SOLID\n1,1\n"
      "*MAT_RIGID\n1,7850.0,2.1e11,0.3\n1.0,7,7\n*MAT_RIGID\n2,7850.0,2.1e11,0.3\n1.0,7,4\n"
      "*MAT_RIGID\n3,7850.0,2.1e11,0.3\n"
      "*CONSTRAINED_EXTRA_NODES_NODE\n2,9001\n2,9003\n3,9002\n3,9004\n1,9005\n3,9006\n1,9007\n"
      "3,9008\n"
      "*CONSTRAINED_JOINT_UNIVERSAL_ID\n1,cross\n9001,9002,9003,9004\n"
      "*CONSTRAINED_JOINT_REVOLUTE_ID\n2,hinge of B\n9005,9006,9007,9008\n";
  // Both shafts start on the law: at tA = 0, d tB / d tA = 1 / cos(beta).
  deck += fmt::format(
      "*INITIAL_VELOCITY_GENERATION\n2,2,{:.17g},0,0,0\n0,0,0,0,0,1\n"
      "*INITIAL_VELOCITY_GENERATION\n3,2,{:.17g},0,0,0\n0,0,0,{:.17g},0,{:.17g}\n",
      omega, omega / std::cos(beta), axis_b.x(), axis_b.z());
  deck += "*CONTROL_TERMINATION\n1.0,0\n*CONTROL_TIMESTEP\n2.5e-4\n*END\n";
  solver::Simulation sim(read(deck), {});
  const std::int32_t n1 = dense(sim, 9001), n2 = dense(sim, 9002), n3 = dense(sim, 9003),
                     n4 = dense(sim, 9004);
  const auto& x = sim.state().nodes.x;
  auto at = [&](std::int32_t i) { return Eigen::Vector3d(x.x[i], x.y[i], x.z[i]); };
  const Eigen::Vector3d e1 = Eigen::Vector3d::UnitY(), e2 = axis_b.cross(e1);
  const auto& bodies = sim.rigid_bodies().bodies;
  auto body = [&](model::Id id) {
    return std::find_if(bodies.begin(), bodies.end(), [id](const auto& r) { return r.id == id; });
  };
  double worst = 0.0, turned = 0.0, previous = 0.0, ratio_min = 1e9, ratio_max = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    const Eigen::Vector3d arm_a = at(n3) - at(n1), arm_b = (at(n4) - at(n2)).normalized();
    const double theta_a = std::atan2(arm_a.y(), arm_a.x());
    const double theta_b = std::atan2(arm_b.dot(e2), arm_b.dot(e1));
    const double expected = std::atan2(std::sin(theta_a), std::cos(theta_a) * std::cos(beta));
    worst = std::max(worst, std::abs(std::remainder(theta_b - expected, 2.0 * std::numbers::pi)));
    turned += std::remainder(theta_a - previous, 2.0 * std::numbers::pi);
    previous = theta_a;
    const double ratio =
        body(3)->state.angular_velocity.dot(axis_b) / body(2)->state.angular_velocity.z();
    ratio_min = std::min(ratio_min, ratio);
    ratio_max = std::max(ratio_max, ratio);
  }
  std::printf(
      "universal joint, beta 30 deg: shaft A turned %.4f rev; driven angle off the Hooke law by "
      "at most %.3g rad; speed ratio %.6f .. %.6f (law: cos beta %.6f .. 1/cos beta %.6f); "
      "largest gap %.3g m; energy ratio %.9f\n",
      turned / (2.0 * std::numbers::pi), worst, ratio_min, ratio_max, std::cos(beta),
      1.0 / std::cos(beta), sim.joints().joints[0].gap, sim.energy().ratio());
  EXPECT_GT(turned, 0.9 * 2.0 * std::numbers::pi);  // a whole turn goes through every phase
  // Measured 8.5e-5 rad at dt 0.25 ms (1.45e-3 at 1 ms: the penalty compliance falls as dt^2).
  // A joint that did not hold the cross would leave B coasting: 0.1 rad off within a turn.
  EXPECT_LT(worst, 3e-4);
  EXPECT_NEAR(ratio_min / std::cos(beta), 1.0, 1e-3);
  EXPECT_NEAR(ratio_max * std::cos(beta), 1.0, 1e-3);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
}

// Two free bodies locked together (coincident blocks, three pairs off one line); a force along
// x and a moment about z act on body B only. Locked, the pair is one rigid body of twice the
// mass and twice the inertia about the common centre: body A follows at a = F / 2m and
// alpha = T / 2J.
TEST(Joint, LockingJointMakesTwoBodiesMoveAsOne) {
  const Block g = ground();
  Block s = ground();
  s.first_node = 1001;
  s.first_element = 1001;
  s.pid = 2;
  const double force = 40.0, torque = 2.0, end = 0.05;
  const std::string deck =
      "*KEYWORD\n" + g.text() + s.text() +
      "*PART\nA\n1,1,1\n*PART\nB\n2,1,2\n*SECTION_SOLID\n1,1\n"
      "*MAT_RIGID\n1,7850.0,2.1e11,0.3\n*MAT_RIGID\n2,7850.0,2.1e11,0.3\n" +
      fmt::format("*CONSTRAINED_JOINT_LOCKING\n{},{},{},{},{},{}\n", g.node(1, 1, 0),
                  s.node(1, 1, 0), g.node(1, 1, 1), s.node(1, 1, 1), g.node(2, 1, 0),
                  s.node(2, 1, 0)) +
      fmt::format(
          "*DEFINE_CURVE\n3\n0.0,1.0\n100.0,1.0\n*LOAD_RIGID_BODY\n2,1,3,{:.17g}\n2,7,3,{:.17g}\n",
          force, torque) +
      fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n1.0e-4\n*END\n", end);
  solver::Simulation sim(read(deck), {});
  sim.run();
  const auto& bodies = sim.rigid_bodies().bodies;
  auto body = [&](model::Id id) {
    return std::find_if(bodies.begin(), bodies.end(), [id](const auto& r) { return r.id == id; });
  };
  const MassSums m = lumped_sums(g);
  const double t = sim.state().time;
  const double dt = sim.state().dt_prev > 0.0 ? sim.state().dt_prev : sim.state().dt;
  // Velocities are at t^{n+1/2}: the loads act from t = 0.
  const double expected_v = force * (t + 0.5 * dt) / (2.0 * m.mass);
  const double expected_w = torque * (t + 0.5 * dt) / (2.0 * m.second_z);
  const auto& a = body(1)->state;
  const auto& b = body(2)->state;
  std::printf(
      "locking joint: body A velocity %.6g (expected F t / 2m %.6g), spin %.6g (expected "
      "T t / 2J %.6g); B - A: velocity %.3g, spin %.3g; energy ratio %.9f\n",
      a.velocity.x(), expected_v, a.angular_velocity.z(), expected_w,
      (b.velocity - a.velocity).norm(), (b.angular_velocity - a.angular_velocity).norm(),
      sim.energy().ratio());
  // Measured: 1.6e-5 and 3.4e-4 off; B - A 1.9e-4 and 7.3e-4 of the motion (penalty ringing).
  EXPECT_NEAR(a.velocity.x() / expected_v, 1.0, 2e-3);
  EXPECT_NEAR(a.angular_velocity.z() / expected_w, 1.0, 2e-3);
  EXPECT_LT((b.velocity - a.velocity).norm(), 2e-3 * expected_v);
  EXPECT_LT((b.angular_velocity - a.angular_velocity).norm(), 3e-3 * expected_w);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-6);
}

TEST(JointInput, BadCardsAreInputErrors) {
  const Block g = ground(), b = bar(0.0);
  const std::string base = "*KEYWORD\n" + g.text() + b.text() + rigid_parts() +
                           "*CONTROL_TERMINATION\n0.01\n*CONTROL_TIMESTEP\n1.0e-3\n";
  auto expect_error = [&](const std::string& cards, const std::string& field) {
    try {
      solver::Simulation sim(read(base + cards + "*END\n"), {});
      ADD_FAILURE() << "expected an input error at " << field;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  const int pivot_a = g.node(1, 1, 0), pivot_b = b.node(1, 1, b.nz);
  // N2 not coincident with N1.
  expect_error(fmt::format("*CONSTRAINED_JOINT_SPHERICAL\n{},{}\n", pivot_a, b.node(0, 0, 0)),
               "N2");
  expect_error(fmt::format("*CONSTRAINED_JOINT_SPHERICAL\n{},999999\n", pivot_a), "N2");
  expect_error(fmt::format("*CONSTRAINED_JOINT_REVOLUTE\n{},{}\n", pivot_a, pivot_b), "N3");
  expect_error(fmt::format("*CONSTRAINED_JOINT_SPHERICAL\n{},{},5\n", pivot_a, pivot_b), "N3");
  expect_error(fmt::format("*CONSTRAINED_JOINT_SPHERICAL\n{},{},,,,,-1.0\n", pivot_a, pivot_b),
               "RPS");
  expect_error(fmt::format("*CONSTRAINED_JOINT_SPHERICAL_FAILURE\n{},{}\n", pivot_a, pivot_b),
               "FAILURE");
  // Universal: the arms N1 -> N3 (x) and N2 -> N4 (along x too) are not perpendicular.
  expect_error(fmt::format("*CONSTRAINED_JOINT_UNIVERSAL\n{},{},{},{}\n", pivot_a, pivot_b,
                           g.node(2, 1, 0), b.node(2, 1, b.nz)),
               "N4");
  expect_error(
      fmt::format("*CONSTRAINED_JOINT_UNIVERSAL\n{},{},{}\n", pivot_a, pivot_b, g.node(2, 1, 0)),
      "N4");
  // Locking: N5 on the axis N1 -> N3 leaves the turn about it free.
  expect_error(fmt::format("*NODE\n9101,0,0,0.2\n9102,0,0,0.2\n9103,0,0,0.1\n"
                           "*CONSTRAINED_JOINT_LOCKING\n{},{},{},9103,9101,9102\n",
                           pivot_a, pivot_b, g.node(1, 1, 1)),
               "N5");
}

}  // namespace
}  // namespace rf::test
