// *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED against closed-form rigid-body mechanics. Body A is a
// fixed rigid cube, body B a rigid cube whose mass, inertia (isotropic, I) and initial angular
// velocity come from *PART_INERTIA, so every reference below uses the card's numbers only:
//  - torsional oscillator, moment k psi: period 2 pi sqrt(I / k), energy conserved;
//  - nonlinear (piecewise linear) curve under a slowly applied moment T: the angle where the
//    curve equals T;
//  - linear viscous damping c: logarithmic decrement 2 pi zeta / sqrt(1 - zeta^2),
//    zeta = c / (2 sqrt(k I)) (e.g. Thomson & Dahleh, Theory of Vibration, ch. 2);
//  - friction moment FM: constant deceleration FM / I until the body stops;
//  - stop angle with stiffness ES: contact lasts half a period of the stop spring,
//    pi sqrt(I / ES), and the body rebounds with its impact speed;
//  - angles of a rotation about a general axis: B = A R_x(phi) R_y(theta) R_z(psi), the
//    definition of docs/theory.md "Joint stiffness", checked against Rodrigues' formula;
//  - three stiffnesses at once under a general spin: the moments are the generalized forces of
//    the angles, so energy is conserved;
//  - bad input: errors with file, line, keyword and field.
#include <gtest/gtest.h>
#include <unistd.h>

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

constexpr double kPi = std::numbers::pi;
constexpr double kMass = 3.0, kInertia = 2.0;

struct Spec {
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();  // initial angular velocity of body B
  std::string curves;                               // *DEFINE_CURVE cards
  std::string card2 = "0,0,0,0,0,0";
  std::string card3 = "0.0,0.0,0.0,0.0,0.0,0.0";
  std::string card4 = "0.0,0.0,0.0,0.0,0.0,0.0";
  std::string extra;  // more keywords (loads, joints, output)
  std::string cid = "*DEFINE_COORDINATE_VECTOR\n1,1.0,0.0,0.0,0.0,1.0,0.0\n";
  int jid = 0;
  double end_time = 1.0;
  double dt = 1e-4;
};

Block cube(int first_node, int pid, double x) {
  Block b;
  b.first_node = first_node;
  b.first_element = pid;
  b.pid = pid;
  b.local = Eigen::Vector3d(x, 0.0, 0.0);
  return b;
}

std::string deck_of(const Spec& s) {
  std::string d = "*KEYWORD\n" + cube(1, 1, 0.0).text() + cube(11, 2, 2.0).text();
  d += "*PART\nground\n1,1,1\n*PART_INERTIA\nspinner\n2,1,2\n";
  d += fmt::format("2.5,0.5,0.5,{0:.17g},0,0\n{1:.17g},0.0,0.0,{1:.17g},0.0,{1:.17g}\n", kMass,
                   kInertia);
  d += fmt::format("0.0,0.0,0.0,{:.17g},{:.17g},{:.17g}\n", s.omega.x(), s.omega.y(), s.omega.z());
  d += "*SECTION_SOLID\n1,1\n*MAT_RIGID\n1,7850.0,2.1e11,0.3\n1.0,7,7\n"
       "*MAT_RIGID\n2,7850.0,2.1e11,0.3\n";
  d += s.cid + s.curves;
  d += fmt::format("*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n10,1,2,1,0,{}\n{}\n{}\n{}\n", s.jid,
                   s.card2, s.card3, s.card4);
  d += s.extra;
  d += fmt::format("*CONTROL_TERMINATION\n{:.17g},0\n*CONTROL_TIMESTEP\n{:.17g},0.9\n*END\n",
                   s.end_time, s.dt);
  return d;
}

// A straight line through the origin with slope `slope`, over +-`range`.
std::string line_curve(int id, double slope, double range) {
  return fmt::format("*DEFINE_CURVE\n{}\n{:.17g},{:.17g}\n{:.17g},{:.17g}\n", id, -range,
                     -slope * range, range, slope * range);
}

struct Sample {
  double t;
  std::array<double, 3> angle;
  std::array<double, 3> moment;
  Eigen::Vector3d omega;
  double elastic, dissipated;
};

// Runs the deck and samples body B and the joint stiffness after every cycle.
struct Trace {
  std::vector<Sample> samples;
  double energy_ratio = 0.0;
  double internal = 0.0, kinetic = 0.0;
};

Trace run(const Spec& s) {
  solver::Simulation sim(read(deck_of(s)), {});
  Trace r;
  const auto& j = sim.joint_stiffnesses().joints.at(0);
  const auto& body = sim.rigid_bodies().bodies.at(j.body_b);
  while (!sim.finished()) {
    sim.cycle();
    r.samples.push_back({sim.state().time, j.angle, j.moment, body.state.angular_velocity,
                         j.elastic, j.dissipated()});
  }
  r.energy_ratio = sim.energy().ratio();
  r.internal = sim.energy().internal();
  r.kinetic = sim.energy().kinetic;
  return r;
}

// Times at which component k of the angle crosses `level` upwards.
std::vector<double> upward_crossings(const Trace& r, int k, double level = 0.0) {
  std::vector<double> t;
  for (std::size_t i = 1; i < r.samples.size(); ++i) {
    const double a = r.samples[i - 1].angle[k] - level, b = r.samples[i].angle[k] - level;
    if (a < 0.0 && b >= 0.0) {
      t.push_back(r.samples[i - 1].t + (r.samples[i].t - r.samples[i - 1].t) * (-a) / (b - a));
    }
  }
  return t;
}

TEST(JointStiffness, TorsionalOscillatorHasThePeriodOfItsSpring) {
  const double k = 200.0, w0 = 0.5;
  const double period = 2.0 * kPi * std::sqrt(kInertia / k);
  Spec s;
  s.omega = Eigen::Vector3d(0.0, 0.0, w0);
  s.curves = line_curve(5, k, 10.0);
  s.card2 = "0,0,5,0,0,0";
  s.end_time = 3.2 * period;
  const Trace r = run(s);
  const auto up = upward_crossings(r, 2);
  ASSERT_GE(up.size(), 3u);
  const double measured = (up.back() - up.front()) / static_cast<double>(up.size() - 1);
  double largest = 0.0, largest_other = 0.0, energy_spread = 0.0;
  const double e0 = 0.5 * kInertia * w0 * w0;
  for (const Sample& x : r.samples) {
    largest = std::max(largest, std::abs(x.angle[2]));
    largest_other = std::max({largest_other, std::abs(x.angle[0]), std::abs(x.angle[1])});
    // Kinetic energy at the half step and the spring's at the full step: mean of the two.
    energy_spread = std::max(
        energy_spread, std::abs(0.5 * kInertia * x.omega.squaredNorm() + x.elastic - e0) / e0);
  }
  const double amplitude = w0 * std::sqrt(kInertia / k);
  std::printf(
      "torsional oscillator: period %.8f s vs 2 pi sqrt(I/k) = %.8f s (error %.2e), amplitude "
      "%.6f vs %.6f rad, energy ratio %.12f, largest |E - E0| / E0 %.2e\n",
      measured, period, measured / period - 1.0, largest, amplitude, r.energy_ratio, energy_spread);
  EXPECT_NEAR(measured / period, 1.0, 1e-5);
  EXPECT_NEAR(largest / amplitude, 1.0, 1e-3);
  EXPECT_LT(largest_other, 1e-12);  // nothing turns B about the other axes
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-6);
  EXPECT_LT(energy_spread, 1e-3);  // half-step kinetic energy: O(w dt) apart
}

// The moment of a nonlinear curve: a moment T about z applied slowly (ramped over 2 s, then
// held) with damping; at rest the curve's moment equals T. The curve's points (0, 0), (0.2, 100),
// (0.5, 160), (1, 200): T = 130 lies on the second segment, psi = 0.2 + 30 / 200 = 0.35.
TEST(JointStiffness, QuasiStaticMomentEqualsTheCurveAtTheAngle) {
  Spec s;
  s.curves =
      "*DEFINE_CURVE\n5\n-1.0,-200.0\n-0.5,-160.0\n-0.2,-100.0\n0.0,0.0\n0.2,100.0\n0.5,160.0\n"
      "1.0,200.0\n" +
      line_curve(6, 40.0, 100.0) + "*DEFINE_CURVE\n7\n0.0,0.0\n2.0,1.0\n100.0,1.0\n";
  s.card2 = "0,0,5,0,0,6";
  s.extra = "*LOAD_RIGID_BODY\n2,7,7,130.0\n";
  s.end_time = 5.0;
  const Trace r = run(s);
  const Sample& last = r.samples.back();
  std::printf("nonlinear curve: psi %.8f rad (curve inverse 0.35), moment %.8f (applied 130)\n",
              last.angle[2], last.moment[2]);
  EXPECT_NEAR(last.angle[2], 0.35, 1e-5);
  EXPECT_NEAR(last.moment[2], 130.0, 1e-3);
  EXPECT_LT(std::abs(last.omega.z()), 1e-4);
}

TEST(JointStiffness, LinearDampingDecaysWithTheLogarithmicDecrement) {
  const double k = 200.0, c = 4.0, w0 = 1.0;
  const double zeta = c / (2.0 * std::sqrt(k * kInertia));  // 0.1
  const double decrement = 2.0 * kPi * zeta / std::sqrt(1.0 - zeta * zeta);
  const double damped_period = 2.0 * kPi / (std::sqrt(k / kInertia) * std::sqrt(1 - zeta * zeta));
  Spec s;
  s.omega = Eigen::Vector3d(0.0, 0.0, w0);
  s.curves = line_curve(5, k, 10.0) + line_curve(6, c, 100.0);
  s.card2 = "0,0,5,0,0,6";
  s.end_time = 4.6 * damped_period;  // five peaks, the last 0.4 periods before the end
  const Trace r = run(s);
  std::vector<double> peaks;  // local maxima of psi
  for (std::size_t i = 1; i + 1 < r.samples.size(); ++i) {
    const double a = r.samples[i - 1].angle[2], b = r.samples[i].angle[2],
                 d = r.samples[i + 1].angle[2];
    if (b > a && b > d && b > 0.0) {
      // The parabola through the three samples for the peak value.
      peaks.push_back(b + 0.125 * (d - a) * (d - a) / (2.0 * b - a - d));
    }
  }
  ASSERT_GE(peaks.size(), 4u);
  const double measured =
      std::log(peaks.front() / peaks.back()) / static_cast<double>(peaks.size() - 1);
  const Sample& last = r.samples.back();
  const double e0 = 0.5 * kInertia * w0 * w0;
  std::printf(
      "damping: logarithmic decrement %.8f vs 2 pi zeta / sqrt(1 - zeta^2) = %.8f (error %.2e); "
      "dissipated %.6f of %.6f J, energy ratio %.12f\n",
      measured, decrement, measured / decrement - 1.0, last.dissipated, e0, r.energy_ratio);
  EXPECT_NEAR(measured / decrement, 1.0, 1e-4);
  // Energy: what is left plus what the dashpot took is the initial kinetic energy.
  const double left = 0.5 * kInertia * last.omega.squaredNorm() + last.elastic;
  EXPECT_NEAR((left + last.dissipated) / e0, 1.0, 2e-3);
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-6);
}

TEST(JointStiffness, FrictionMomentStopsASpinningBodyAtFmOverI) {
  const double fm = 10.0, es = 1.0e4, w0 = 8.0;
  const double deceleration = fm / kInertia;               // 5 rad/s^2
  const double stop_time = w0 / deceleration;              // 1.6 s
  const double stop_angle = 0.5 * w0 * w0 / deceleration;  // 6.4 rad, more than a turn
  Spec s;
  s.omega = Eigen::Vector3d(0.0, 0.0, w0);
  s.card3 = fmt::format("0.0,0.0,0.0,0.0,{:.17g},{:.17g}", es, fm);
  s.end_time = 2.0;
  s.dt = 2e-5;
  const Trace r = run(s);
  // Deceleration: least-squares slope of the angular velocity over 0.4..1.2 s, well within the
  // slip.
  double n = 0, st = 0, sw = 0, stt = 0, stw = 0;
  for (const Sample& x : r.samples) {
    if (x.t < 0.4 || x.t > 1.2) continue;
    n += 1;
    st += x.t;
    sw += x.omega.z();
    stt += x.t * x.t;
    stw += x.t * x.omega.z();
  }
  const double measured = -(n * stw - st * sw) / (n * stt - st * st);
  double stopped = -1.0;
  for (const Sample& x : r.samples) {
    if (x.omega.z() <= 0.0) {
      stopped = x.t;
      break;
    }
  }
  const Sample& last = r.samples.back();
  const double e0 = 0.5 * kInertia * w0 * w0;
  std::printf(
      "friction: deceleration %.8f vs FM/I = %.8f rad/s^2, stopped at %.6f s vs %.6f s, angle "
      "%.6f vs %.6f rad, dissipated %.6f of %.6f J, energy ratio %.12f\n",
      measured, deceleration, stopped, stop_time, last.angle[2], stop_angle, last.dissipated, e0,
      r.energy_ratio);
  EXPECT_NEAR(measured / deceleration, 1.0, 1e-6);
  EXPECT_NEAR(stopped, stop_time, 10.0 * s.dt);
  // After the stop it sticks: the friction spring holds it within FM / ES of the stop angle.
  EXPECT_NEAR(last.angle[2], stop_angle, 2.0 * fm / es + 1e-3);
  EXPECT_LT(std::abs(last.omega.z()), 2.0 * fm / std::sqrt(es * kInertia));
  EXPECT_NEAR(last.dissipated / e0, 1.0, 1e-3);
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-6);
}

TEST(JointStiffness, StopAngleReboundsAfterHalfAPeriodOfTheStopSpring) {
  const double es = 5.0e3, w0 = 2.0, stop_degrees = 30.0;
  const double stop = stop_degrees * kPi / 180.0;
  const double contact = kPi * std::sqrt(kInertia / es);  // 0.0628 s
  Spec s;
  s.omega = Eigen::Vector3d(0.0, 0.0, w0);
  s.card3 = fmt::format("0.0,0.0,0.0,0.0,{:.17g},0.0", es);
  s.card4 = fmt::format("0.0,0.0,0.0,0.0,0.0,{:.17g}", stop_degrees);
  s.end_time = stop / w0 + 2.0 * contact;
  s.dt = 1e-5;
  const Trace r = run(s);
  const auto in = upward_crossings(r, 2, stop);
  ASSERT_EQ(in.size(), 1u);
  double out = -1.0, largest = 0.0;
  for (std::size_t i = 1; i < r.samples.size(); ++i) {
    const double a = r.samples[i - 1].angle[2] - stop, b = r.samples[i].angle[2] - stop;
    largest = std::max(largest, r.samples[i].angle[2]);
    if (a > 0.0 && b <= 0.0) {
      out = r.samples[i - 1].t + (r.samples[i].t - r.samples[i - 1].t) * a / (a - b);
    }
  }
  ASSERT_GT(out, 0.0);
  const Sample& last = r.samples.back();
  const double overshoot = w0 * std::sqrt(kInertia / es);
  std::printf(
      "stop: contact %.8f s vs pi sqrt(I/ES) = %.8f s (error %.2e), reached at %.6f s (%.6f), "
      "overshoot %.6f vs %.6f rad, rebound %.8f vs %.8f rad/s, energy ratio %.12f\n",
      out - in[0], contact, (out - in[0]) / contact - 1.0, in[0], stop / w0, largest - stop,
      overshoot, last.omega.z(), -w0, r.energy_ratio);
  EXPECT_NEAR(in[0], stop / w0, 1e-6);
  EXPECT_NEAR((out - in[0]) / contact, 1.0, 1e-6);
  EXPECT_NEAR((largest - stop) / overshoot, 1.0, 1e-3);
  EXPECT_NEAR(last.omega.z() / -w0, 1.0, 1e-6);  // elastic: back with the impact speed
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-6);
}

Eigen::Matrix3d rx(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).matrix();
}
Eigen::Matrix3d ry(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).matrix();
}
Eigen::Matrix3d rz(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).matrix();
}

// Body B spins freely (no moment: all curves 0) about a fixed general axis n at w0; at time t
// it has turned by Rodrigues' R(n, w0 t). The local systems are a tilted one (CIDA = CIDB), so
// the relative rotation in A's axes is Q = A0^T R A0; the reported angles must rebuild it as
// R_x(phi) R_y(theta) R_z(psi), each of them nonzero.
TEST(JointStiffness, AnglesOfAGeneralRotationFollowTheCardanDefinition) {
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, 2.0, 3.0).normalized();
  const double w0 = 0.8;
  Spec s;
  s.omega = w0 * n;
  s.cid = "*DEFINE_COORDINATE_VECTOR\n1,1.0,1.0,0.0,-1.0,2.0,1.0\n";
  s.end_time = 0.9;
  s.dt = 1e-4;
  const Trace r = run(s);
  // A0: the system's axes as *DEFINE_COORDINATE_VECTOR defines them (x along X, z = x cross V).
  const Eigen::Vector3d x = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  const Eigen::Vector3d z = x.cross(Eigen::Vector3d(-1.0, 2.0, 1.0)).normalized();
  Eigen::Matrix3d a0;
  a0.col(0) = x;
  a0.col(1) = z.cross(x);
  a0.col(2) = z;
  double worst = 0.0;
  Sample at_end = r.samples.back();
  for (const Sample& sample : r.samples) {
    const Eigen::Matrix3d q = a0.transpose() * Eigen::AngleAxisd(w0 * sample.t, n).matrix() * a0;
    const Eigen::Matrix3d rebuilt = rx(sample.angle[0]) * ry(sample.angle[1]) * rz(sample.angle[2]);
    worst = std::max(worst, (rebuilt - q).cwiseAbs().maxCoeff());
  }
  std::printf(
      "angles at %.3f s: phi %.6f, theta %.6f, psi %.6f rad; largest |R_x R_y R_z - Q| %.2e\n",
      at_end.t, at_end.angle[0], at_end.angle[1], at_end.angle[2], worst);
  for (int k = 0; k < 3; ++k) EXPECT_GT(std::abs(at_end.angle[k]), 0.05) << k;
  EXPECT_LT(worst, 1e-9);
}

// Stiffness about all three angles and a general spin: the body tumbles through large angles
// of all three; conserved energy shows the moments are the generalized forces of the angles
// (a torque J^-T f; applying f about the joint axes directly would not conserve it).
TEST(JointStiffness, ThreeAxesUnderAGeneralSpinConserveEnergy) {
  Spec s;
  s.omega = Eigen::Vector3d(0.6, -0.5, 0.7);
  s.curves = line_curve(5, 3.0, 10.0) + line_curve(6, 5.0, 10.0) + line_curve(7, 2.0, 10.0);
  s.card2 = "5,6,7,0,0,0";
  s.end_time = 6.0;
  s.dt = 1e-4;
  const Trace r = run(s);
  const double e0 = 0.5 * kInertia * s.omega.squaredNorm();
  double spread = 0.0;
  std::array<double, 3> largest{};
  for (const Sample& x : r.samples) {
    spread =
        std::max(spread, std::abs(0.5 * kInertia * x.omega.squaredNorm() + x.elastic - e0) / e0);
    for (int k = 0; k < 3; ++k) largest[k] = std::max(largest[k], std::abs(x.angle[k]));
  }
  std::printf(
      "three axes: largest angles %.4f %.4f %.4f rad, largest |E - E0| / E0 %.2e, energy ratio "
      "%.12f\n",
      largest[0], largest[1], largest[2], spread, r.energy_ratio);
  for (int k = 0; k < 3; ++k) EXPECT_GT(largest[k], 0.2) << k;
  EXPECT_LT(spread, 1e-3);
  EXPECT_NEAR(r.energy_ratio, 1.0, 1e-6);
}

// jntforc.csv: a stiffness whose JID names a joint adds its angles, moments and energies to
// that joint's row. Body B turns on a revolute joint about z through its centre.
TEST(JointStiffness, JntforcReportsTheStiffnessOfItsJoint) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("rigidflex_jntstiff_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const double k = 200.0, w0 = 0.5;
  Spec s;
  s.omega = Eigen::Vector3d(0.0, 0.0, w0);
  s.curves = line_curve(5, k, 10.0);
  s.card2 = "0,0,5,0,0,0";
  s.jid = 4;
  // Nodes at the centre of B and 0.5 above it, one pair on each body (extra nodes).
  s.extra =
      "*NODE\n101,2.5,0.5,0.5\n102,2.5,0.5,0.5\n103,2.5,0.5,1.0\n104,2.5,0.5,1.0\n"
      "*CONSTRAINED_EXTRA_NODES_NODE\n1,101\n1,103\n2,102\n2,104\n"
      "*CONSTRAINED_JOINT_REVOLUTE_ID\n4,hinge\n101,102,103,104\n*DATABASE_JNTFORC\n0.01\n";
  s.end_time = 0.5;
  {
    solver::Simulation sim(read(deck_of(s)), solver::SimulationOptions{.output_directory = dir,
                                                                       .write_fields = false});
    sim.run();
  }
  std::ifstream in(dir / "jntforc.csv");
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header,
            "time,joint,force_x,force_y,force_z,force_resultant,moment_x,moment_y,moment_z,"
            "moment_resultant,stiffness,phi,theta,psi,moment_phi,moment_theta,moment_psi,"
            "stiffness_elastic_energy,stiffness_dissipated_energy");
  int rows = 0;
  double worst = 0.0;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 19u) << line;
    ++rows;
    EXPECT_EQ(v[1], 4.0);
    EXPECT_EQ(v[10], 10.0);
    // psi = (w0 / w) sin(w t), moment k psi, energy k psi^2 / 2.
    const double w = std::sqrt(k / kInertia);
    const double psi = w0 / w * std::sin(w * v[0]);
    worst = std::max(worst, std::abs(v[13] - psi));
    EXPECT_NEAR(v[16], k * v[13], 1e-9);
    EXPECT_NEAR(v[17], 0.5 * k * v[13] * v[13], 1e-9);
    EXPECT_NEAR(v[18], 0.0, 1e-9);
  }
  std::printf("jntforc: %d rows, largest |psi - psi_exact| %.2e rad\n", rows, worst);
  EXPECT_GE(rows, 40);
  EXPECT_LT(worst, 1e-3);
  std::filesystem::remove_all(dir);
}

std::string error_of(const Spec& s) {
  return simulation_error_of(deck_of(s));
}

void expect_error(const std::string& message, const std::string& field, const std::string& words) {
  EXPECT_NE(message.find("verification.k"), std::string::npos) << message;
  EXPECT_NE(message.find("*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED"), std::string::npos) << message;
  EXPECT_NE(message.find(field), std::string::npos) << message;
  EXPECT_NE(message.find(words), std::string::npos) << message;
}

TEST(JointStiffness, BadInputIsAnErrorAtTheField) {
  {
    Spec s;  // body A deformable
    std::string deck = deck_of(s);
    const std::string ground = "*MAT_RIGID\n1,7850.0,2.1e11,0.3\n1.0,7,7\n";
    deck.replace(deck.find(ground), ground.size(), "*MAT_ELASTIC\n1,7850.0,2.1e11,0.3\n");
    expect_error(simulation_error_of(deck), "PIDA", "is not rigid");
  }
  {
    Spec s;
    s.cid = "";
    expect_error(error_of(s), "CIDA", "coordinate system 1 is not defined");
  }
  {
    Spec s;
    s.card2 = "0,0,9,0,0,0";
    expect_error(error_of(s), "LCIDPS", "load curve 9 is not defined");
  }
  {
    Spec s;  // a stop without its stiffness would be ignored
    s.card4 = "0.0,0.0,0.0,0.0,0.0,30.0";
    expect_error(error_of(s), "ESPS", "stop angle PSAPS");
  }
  {
    Spec s;  // friction without its stiffness
    s.card3 = "0.0,5.0,0.0,0.0,0.0,0.0";
    expect_error(error_of(s), "ESPH", "FMPH");
  }
  {
    Spec s;  // friction curve (negative FMPH)
    s.card3 = "100.0,-5.0,0.0,0.0,0.0,0.0";
    expect_error(error_of(s), "FMPH", "not supported");
  }
  {
    Spec s;
    s.jid = 3;
    expect_error(error_of(s), "JID", "joint 3 is not defined");
  }
  {
    Spec s;  // both on the same body
    std::string deck = deck_of(s);
    const std::string card1 = "10,1,2,1,0,0\n";
    deck.replace(deck.find(card1), card1.size(), "10,2,2,1,0,0\n");
    expect_error(simulation_error_of(deck), "PIDB", "same rigid body");
  }
  {
    Spec s;
    s.card4 = "0.0,0.0,0.0,95.0,0.0,0.0";
    s.card3 = "0.0,0.0,10.0,0.0,0.0,0.0";
    expect_error(error_of(s), "PSAT", "90");
  }
  // The other variants are refused by name.
  for (const char* variant : {"FLEXION-TORSION", "TRANSLATIONAL", "CYLINDRICAL", "SPHERICAL"}) {
    std::string deck = deck_of(Spec{});
    const std::string name = "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED";
    deck.replace(deck.find(name), name.size(),
                 std::string("*CONSTRAINED_JOINT_STIFFNESS_") + variant);
    std::string message;
    try {
      read(deck);
    } catch (const std::exception& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("joint stiffness variant that is not supported"), std::string::npos)
        << variant << ": " << message;
  }
}

}  // namespace
}  // namespace rf::test
