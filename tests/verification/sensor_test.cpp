// Sensors, switches and controls through the whole deck path, against references that do not
// come from the solver: free flight under gravity (closed-form motion), a prescribed velocity
// ramp, the analytic crossing time of a threshold, closed-form functions of time, uniaxial
// stress sigma = E eps in a slowly stretched bar, the exact Hencky strain and neo-Hookean stress
// of homogeneous deformations, and the switch sequence the manual's SWITn/NREP rules prescribe.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "deck_builder.hpp"
#include "element/kernels.hpp"
#include "model/error.hpp"
#include "sensor/sensor.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

constexpr double kPi = std::numbers::pi;

// One hexahedron [x0, x0 + a]^3 with nodes first_node.. (LS-DYNA order) and element eid.
std::string cube(int first_node, int eid, double x0, double y0, double z0, double a) {
  std::string s = "*NODE\n";
  const int order[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                           {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int k = 0; k < 8; ++k) {
    s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", first_node + k, x0 + a * order[k][0],
                     y0 + a * order[k][1], z0 + a * order[k][2]);
  }
  s += fmt::format("*ELEMENT_SOLID\n{},1", eid);
  for (int k = 0; k < 8; ++k) s += fmt::format(",{}", first_node + k);
  return s + "\n";
}

std::string initial_velocity(int first_node, double vx, double vy, double vz) {
  std::string s = "*INITIAL_VELOCITY_NODE\n";
  for (int k = 0; k < 8; ++k) s += fmt::format("{},{},{},{}\n", first_node + k, vx, vy, vz);
  return s;
}

struct Sample {
  double time = 0.0;
  std::vector<double> values;  // per requested sensor
  std::vector<bool> switches;  // per requested switch
  std::vector<sensor::Def2RigEvent> events;
};

// Runs to the end, recording after construction (t = 0) and after every cycle.
std::vector<Sample> run_and_record(const model::Model& m, const std::vector<model::Id>& sensors,
                                   const std::vector<model::Id>& switches = {}) {
  solver::Simulation sim(m, {});
  std::vector<Sample> samples;
  auto record = [&] {
    const sensor::SensorSystem& s = sim.sensors();
    Sample sample;
    sample.time = s.time;
    for (const auto id : sensors) sample.values.push_back(sensor::sensor_value(s, id));
    for (const auto id : switches) sample.switches.push_back(sensor::switch_status(s, id));
    const auto events = sensor::def2rig_events(s);
    sample.events.assign(events.begin(), events.end());
    samples.push_back(std::move(sample));
  };
  record();
  while (true) {
    sim.cycle();
    if (sim.finished()) break;
    record();
  }
  return samples;
}

// ---------------------------------------------------------------------------------------
// Free flight under gravity: two unit cubes with different initial velocities. Rigid
// translation leaves the elements unstrained, so every node moves as
//   x(t) = x0 + v0 t + a t^2 / 2,  a = (0, 0, -g),
// which the central-difference scheme reproduces to round-off.

constexpr double kG = 9.81;

std::string free_flight_deck(const std::string& extra) {
  return "*KEYWORD\n*CONTROL_TERMINATION\n2.0\n*CONTROL_TIMESTEP\n0.0,0.5\n" +
         cube(1, 1, 0.0, 0.0, 10.0, 1.0) + cube(11, 2, 5.0, 0.0, 10.0, 1.0) +
         "*PART\ncubes\n1,1,1\n*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,1.0,400.0,0.3\n" +
         initial_velocity(1, 1.0, 0.5, 2.0) + initial_velocity(11, -0.5, 0.25, 2.0) +
         fmt::format("*LOAD_BODY_Z\n100,1.0\n*DEFINE_CURVE\n100\n0,{}\n100,{}\n", kG, kG) +
         "*DEFINE_VECTOR\n1,0,0,0,0,0,1\n2,0,0,0,1,0,0\n" + extra;
}

TEST(Sensors, NodeSensorsFollowFreeFlightExactly) {
  const std::string sensors =
      "*SENSOR_DEFINE_NODE\n"
      "1,7,0,1,,COORD\n"   // z of node 7
      "2,7,0,1,,VEL\n"     // vz of node 7
      "3,7,0,1,,ACC\n"     // az of node 7
      "4,7,0,0,,COORD\n"   // |x| of node 7
      "5,1,0,2,,VEL\n"     // vx of node 1
      "6,1,11,0,,COORD\n"  // distance node 1 - node 11
      "7,1,11,2,,VEL\n"    // relative vx
      "8,1,11,0,,ACC\n"    // |relative acceleration|
      "9,7,0,0\n";         // CTYPE blank: ACC, magnitude
  const model::Model m = read(free_flight_deck(sensors));
  const auto samples = run_and_record(m, {1, 2, 3, 4, 5, 6, 7, 8, 9});
  ASSERT_GT(samples.size(), 40u);
  EXPECT_NEAR(samples.back().time, 2.0, 1e-12);
  double worst = 0.0;
  for (const auto& s : samples) {
    const double t = s.time;
    const Eigen::Vector3d x7(1.0 + 1.0 * t, 1.0 + 0.5 * t, 11.0 + 2.0 * t - 0.5 * kG * t * t);
    const Eigen::Vector3d d(-5.0 + 1.5 * t, 0.25 * t, 0.0);  // x1 - x11
    const double expected[] = {x7.z(), 2.0 - kG * t, -kG, x7.norm(), 1.0, d.norm(), 1.5, 0.0, kG};
    for (std::size_t k = 0; k < 9; ++k) {
      const double error = std::abs(s.values[k] - expected[k]);
      worst = std::max(worst, error);
      EXPECT_LT(error, 1e-9 * (1.0 + std::abs(expected[k])))
          << "sensor " << k + 1 << " at t = " << t << ": " << s.values[k] << " vs " << expected[k];
    }
  }
  RecordProperty("worst_error", fmt::format("{:.3g}", worst));
}

// A prescribed velocity ramp v = A t (VAD 0): the solver samples it at mid-steps, so x = x0 +
// A t^2 / 2 exactly; the sensors must report the motion the constraint imposes (A), not the
// unconstrained force balance (zero here).
TEST(Sensors, NodeSensorsReportPrescribedMotion) {
  constexpr double kA = 3.0;
  const std::string deck =
      "*KEYWORD\n*CONTROL_TERMINATION\n1.0\n*CONTROL_TIMESTEP\n0.0,0.5\n" +
      cube(1, 1, 0.0, 0.0, 0.0, 1.0) +
      "*PART\ncube\n1,1,1\n*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,1.0,100.0,0.3\n" +
      node_set(1, {1, 2, 3, 4, 5, 6, 7, 8}) + "*BOUNDARY_PRESCRIBED_MOTION_SET\n1,1,0,200,1.0\n" +
      fmt::format("*DEFINE_CURVE\n200\n0,0\n10,{}\n", 10 * kA) +
      "*DEFINE_VECTOR\n2,0,0,0,1,0,0\n"
      "*SENSOR_DEFINE_NODE\n1,7,0,2,,COORD\n2,7,0,2,,VEL\n3,7,0,2,,ACC\n";
  const auto samples = run_and_record(read(deck), {1, 2, 3});
  ASSERT_GT(samples.size(), 10u);
  for (std::size_t n = 0; n < samples.size(); ++n) {
    const double t = samples[n].time;
    EXPECT_NEAR(samples[n].values[0], 1.0 + 0.5 * kA * t * t, 1e-12) << "t = " << t;
    EXPECT_NEAR(samples[n].values[1], kA * t, 1e-12) << "t = " << t;
    // At t = 0 nothing has been imposed yet: the unconstrained (f_ext - f_int) / m = 0.
    EXPECT_NEAR(samples[n].values[2], n == 0 ? 0.0 : kA, 1e-9) << "t = " << t;
  }
}

// ---------------------------------------------------------------------------------------
// Switches: node 7 falls below z = 5 at the root t* of 11 + 2 t - g t^2 / 2 = 5.

double crossing_time() {
  const double a = 0.5 * kG, b = -2.0, c = 5.0 - 11.0;
  return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

// Evaluation time at which `column` first reads true, and the evaluation before it.
std::pair<double, double> first_true(const std::vector<Sample>& samples, std::size_t column) {
  for (std::size_t n = 0; n < samples.size(); ++n) {
    if (samples[n].switches[column]) {
      return {samples[n].time, n > 0 ? samples[n - 1].time : -1.0};
    }
  }
  ADD_FAILURE() << "switch column " << column << " never turned on";
  return {0.0, 0.0};
}

TEST(Sensors, SwitchesFireAtTheAnalyticCrossingTime) {
  const std::string cards =
      "*SENSOR_DEFINE_NODE\n1,7,0,1,,COORD\n"
      "*SENSOR_SWITCH\n"
      "601,SENSOR,1,LT,5.0\n"
      "602,SENSOR,1,LT,5.0,,0.1\n"  // TIMWIN 0.1
      "603,,1,LT,5.0,,,0.2\n"       // TDELAY 0.2 (TYPE blank: SENSOR)
      "605,TIME,,GT,1.5\n"
      "606,TIME,,GT,0.5\n"
      "607,SENSOR,1,GT,10.5\n"  // z > 10.5 from the start until the top of the arc
      "*SENSOR_SWITCH_CALC-LOGIC\n"
      "610,601,605\n"    // AND
      "611,-601,-606\n"  // OR
      "*SENSOR_CONTROL\n"
      "701,DEF2RIG,42\nOFF,601\n"
      "702,DEF2RIG,43\n,602\n";  // INITSTT blank: ON
  const model::Model m = read(free_flight_deck(cards));
  const auto samples = run_and_record(m, {1}, {601, 602, 603, 605, 606, 607, 610, 611});
  const double t_star = crossing_time();
  ASSERT_GT(t_star, 1.0);
  ASSERT_LT(t_star, 1.9);

  const auto [t601, before601] = first_true(samples, 0);
  EXPECT_GE(t601, t_star);
  EXPECT_LT(before601, t_star);
  const double dt = t601 - before601;
  // TIMWIN: the condition must have held over the window, measured from t601.
  const auto [t602, before602] = first_true(samples, 1);
  EXPECT_GE(t602, t601 + 0.1 - 1e-12);
  EXPECT_LT(before602, t601 + 0.1 - 1e-12);
  EXPECT_LT(t602 - (t_star + 0.1), 2.0 * dt + 1e-12);
  // TDELAY: the rising edge takes effect 0.2 later.
  const auto [t603, before603] = first_true(samples, 2);
  EXPECT_GE(t603, t601 + 0.2 - 1e-12);
  EXPECT_LT(before603, t601 + 0.2 - 1e-12);
  // CALC-LOGIC: AND waits for the later input, OR takes the earlier.
  const auto [t605, before605] = first_true(samples, 3);
  const double t606 = first_true(samples, 4).first;
  EXPECT_GT(t605, 1.5);
  EXPECT_LE(before605, 1.5);
  EXPECT_EQ(first_true(samples, 6).first, std::max(t601, t605));
  EXPECT_EQ(first_true(samples, 7).first, std::min(t601, t606));
  // A switch follows its condition: z > 10.5 holds from t = 0 until z falls back below 10.5,
  // the later root of 11 + 2 t - g t^2 / 2 = 10.5.
  const double t_down = (2.0 + std::sqrt(4.0 + 2.0 * kG * 0.5)) / kG;
  for (const auto& s : samples) {
    if (s.time < t_down - 1e-9) EXPECT_TRUE(s.switches[5]) << "t = " << s.time;
    if (s.time > t_down + 1e-9) EXPECT_FALSE(s.switches[5]) << "t = " << s.time;
  }

  // DEF2RIG events: 701 (initially OFF) turns ON once, at t601; 702 (initially ON) is reported
  // ON at t = 0 and turns OFF at t602. Nothing else happens.
  std::vector<std::pair<double, sensor::Def2RigEvent>> events;
  for (const auto& s : samples) {
    for (const auto& e : s.events) events.push_back({s.time, e});
  }
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].first, 0.0);
  EXPECT_EQ(events[0].second.swset, 43);
  EXPECT_TRUE(events[0].second.status_on);
  EXPECT_EQ(events[1].first, t601);
  EXPECT_EQ(events[1].second.swset, 42);
  EXPECT_TRUE(events[1].second.status_on);
  EXPECT_EQ(events[2].first, t602);
  EXPECT_EQ(events[2].second.swset, 43);
  EXPECT_FALSE(events[2].second.status_on);
  RecordProperty("crossing",
                 fmt::format("t* = {:.6f}, fired at {:.6f} (dt {:.4f})", t_star, t601, dt));
}

// ---------------------------------------------------------------------------------------
// Function sensors: f(a, b) = a - 2 b + time of the z coordinate and z velocity of node 7,
// given both ways (SENS1 > 0, and SENS1 = -count), and a function of a function sensor.

TEST(Sensors, FunctionSensorsEvaluateTheirExpression) {
  const std::string cards =
      "*SENSOR_DEFINE_NODE\n1,7,0,1,,COORD\n2,7,0,1,,VEL\n"
      "*DEFINE_FUNCTION\n500,combination\nf(a, b)= a - 2*b\n + time\n"
      "*DEFINE_FUNCTION_TITLE\nsquare\n501\ng(c)=pow(c, 2)\n"
      "*SENSOR_DEFINE_FUNCTION\n30,500,1,2\n31,500,-2,1,2\n32,501,30\n";
  const auto samples = run_and_record(read(free_flight_deck(cards)), {30, 31, 32});
  for (const auto& s : samples) {
    const double t = s.time;
    const double z = 11.0 + 2.0 * t - 0.5 * kG * t * t, vz = 2.0 - kG * t;
    const double f = z - 2.0 * vz + t;
    EXPECT_NEAR(s.values[0], f, 1e-9) << "t = " << t;
    EXPECT_EQ(s.values[1], s.values[0]) << "t = " << t;
    EXPECT_NEAR(s.values[2], f * f, 1e-8 * (1.0 + f * f)) << "t = " << t;
  }
}

// ---------------------------------------------------------------------------------------
// Controls: SWIT1 changes the initial status, SWITn the status SWITn-1 set, and NREP repeats
// the list (the manual: '601, 602' with NREP 3 means '601, 602, 601, 602, 601, 602').

std::string static_cube_deck(double end_time, const std::string& extra) {
  return fmt::format("*KEYWORD\n*CONTROL_TERMINATION\n{},\n*CONTROL_TIMESTEP\n0.0,0.5\n",
                     end_time) +
         cube(1, 1, 0.0, 0.0, 0.0, 1.0) +
         "*PART\ncube\n1,1,1\n*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,1.0,1.0e4,0.3\n" + extra;
}

// Status of each control after every evaluation, and the evaluation index of each change.
struct ControlHistory {
  std::vector<double> times;
  std::vector<std::vector<bool>> status;  // [evaluation][control]
};

ControlHistory control_history(const model::Model& m, const std::vector<model::Id>& controls) {
  solver::Simulation sim(m, {});
  ControlHistory h;
  auto record = [&] {
    h.times.push_back(sim.sensors().time);
    std::vector<bool> row;
    for (const auto id : controls) row.push_back(sensor::control_status(sim.sensors(), id));
    h.status.push_back(row);
  };
  record();
  while (true) {
    sim.cycle();
    if (sim.finished()) break;
    record();
  }
  return h;
}

std::vector<std::size_t> changes(const ControlHistory& h, std::size_t control) {
  std::vector<std::size_t> at;
  for (std::size_t n = 1; n < h.status.size(); ++n) {
    if (h.status[n][control] != h.status[n - 1][control]) at.push_back(n);
  }
  return at;
}

TEST(Sensors, ControlTogglesThroughItsSwitchesNrepTimes) {
  const std::string cards =
      "*SENSOR_SWITCH\n801,TIME,,GT,0.1\n802,TIME,,GT,0.2\n"
      "*SENSOR_CONTROL\n"
      "901,DEF2RIG,7,,3\nOFF,801,802\n"   // three passes
      "902,DEF2RIG,8,,-1\nOFF,801,802\n"  // without end
      "903,DEF2RIG,9\nOFF,801,802\n"      // NREP blank: one pass
      "904,DEF2RIG,10,,2\nON,801\n";      // one switch, two passes: OFF then ON
  const ControlHistory h =
      control_history(read(static_cube_deck(0.4, cards)), {901, 902, 903, 904});
  std::size_t c1 = 0, c2 = 0;  // first evaluations with t > 0.1 and t > 0.2
  for (std::size_t n = 0; n < h.times.size(); ++n) {
    if (c1 == 0 && h.times[n] > 0.1) c1 = n;
    if (c2 == 0 && h.times[n] > 0.2) c2 = n;
  }
  ASSERT_GT(c1, 0u);
  ASSERT_GT(c2, c1 + 1);
  ASSERT_GT(h.times.size(), c2 + 10);
  // Once both time switches hold, the watched switch is always met: one change per cycle.
  EXPECT_EQ(changes(h, 0), (std::vector<std::size_t>{c1, c2, c2 + 1, c2 + 2, c2 + 3, c2 + 4}));
  EXPECT_FALSE(h.status.back()[0]);
  const auto endless = changes(h, 1);
  ASSERT_GE(endless.size(), 8u);
  EXPECT_EQ(endless[0], c1);
  for (std::size_t k = 1; k < endless.size(); ++k) EXPECT_EQ(endless[k], c2 + k - 1);
  EXPECT_EQ(endless.back(), h.times.size() - 1);
  EXPECT_EQ(changes(h, 2), (std::vector<std::size_t>{c1, c2}));
  EXPECT_EQ(changes(h, 3), (std::vector<std::size_t>{c1, c1 + 1}));
  EXPECT_TRUE(h.status.back()[3]);
}

// A sensor that oscillates, sin(2 pi t / T), against thresholds +-1/2: with SWIT1 (> 1/2) and
// SWIT2 (< -1/2) and NREP 2 the control turns ON after t = T/12 and T + T/12, OFF after 7T/12
// and T + 7T/12, and then stays OFF although the sensor keeps oscillating.
TEST(Sensors, ControlFollowsAnOscillatingSensor) {
  constexpr double kPeriod = 0.4;
  const std::string cards = fmt::format(
      "*DEFINE_FUNCTION\n510\nwave()= sin(6.283185307179586 * time / {})\n"
      "*SENSOR_DEFINE_FUNCTION\n20,510\n"
      "*SENSOR_SWITCH\n811,SENSOR,20,GT,0.5\n812,SENSOR,20,LT,-0.5\n"
      "*SENSOR_CONTROL_TITLE\noscillation\n911,DEF2RIG,5,0,2\nOFF,811,812\n",
      kPeriod);
  const ControlHistory h = control_history(read(static_cube_deck(1.0, cards)), {911});
  const auto at = changes(h, 0);
  ASSERT_EQ(at.size(), 4u);
  const double expected[] = {kPeriod / 12, 7 * kPeriod / 12, kPeriod + kPeriod / 12,
                             kPeriod + 7 * kPeriod / 12};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_GT(h.times[at[k]], expected[k]) << "change " << k;
    EXPECT_LE(h.times[at[k] - 1], expected[k] + 1e-12) << "change " << k;
    EXPECT_EQ(h.status[at[k]][0], k % 2 == 0) << "change " << k;
  }
  EXPECT_GT(h.times.back(), 2 * kPeriod + kPeriod / 12);  // a later crossing was ignored
}

// ---------------------------------------------------------------------------------------
// Element sensors.

// A bar of four hexahedra, stretched along x by a smooth ramp u(T) = U (zero velocity at both
// ends of the ramp, so that it stays close to the quasi-static solution), with symmetry planes
// y = 0 and z = 0 and free lateral faces: uniaxial stress sigma_xx = E eps_xx.
TEST(Sensors, ElementSensorsMeasureUniaxialStress) {
  constexpr double kE = 2.1e5, kNu = 0.3, kRho = 7.8e-9, kL = 40.0, kU = 0.04, kT = 2e-3;
  BoxMesh mesh;
  mesh.nx = 4;
  mesh.lx = kL;
  mesh.ly = mesh.lz = 10.0;
  std::vector<int> y0, z0;
  for (int k = 0; k <= mesh.nz; ++k)
    for (int j = 0; j <= mesh.ny; ++j)
      for (int i = 0; i <= mesh.nx; ++i) {
        if (j == 0) y0.push_back(mesh.node_id(i, j, k));
        if (k == 0) z0.push_back(mesh.node_id(i, j, k));
      }
  std::string curve = "*DEFINE_CURVE\n300\n";
  for (int p = 0; p <= 200; ++p) {
    const double t = kT * p / 200.0;
    curve +=
        fmt::format("{:.17g},{:.17g}\n", t, kU * (t / kT - std::sin(2 * kPi * t / kT) / (2 * kPi)));
  }
  const std::string deck =
      fmt::format("*KEYWORD\n*CONTROL_TERMINATION\n{},\n", kT) + mesh.keyword_text() +
      elastic_part(kRho, kE, kNu, 1, 4) + node_set(1, mesh.face_x(0)) + node_set(2, y0) +
      node_set(3, z0) + node_set(4, mesh.face_x(mesh.nx)) +
      "*BOUNDARY_SPC_SET\n1,0,1,0,0\n2,0,0,1,0\n3,0,0,0,1\n"
      "*BOUNDARY_PRESCRIBED_MOTION_SET\n4,1,2,300,1.0\n" +
      curve +
      "*SENSOR_DEFINE_ELEMENT\n"
      "40,SOLID,2,XX,STRESS\n41,SOLID,2,XX,STRAIN\n42,SOLID,2,YY,STRAIN\n"
      "43,SOLID,2,VM,STRESS\n44,SOLID,2,YY,STRESS\n45,SOLID,3\n";  // COMP XX, CTYPE STRAIN
  const auto samples = run_and_record(read(deck), {40, 41, 42, 43, 44, 45});
  const auto& end = samples.back();
  EXPECT_NEAR(end.time, kT, 1e-15);
  const double strain = std::log(1.0 + kU / kL);  // homogeneous stretch: Hencky strain
  // The ramp is slow (about 250 wave transits), so the dynamic deviation is small (measured:
  // 2e-5 of the end stress); 1e-3 leaves room and still catches a wrong strain measure or a
  // missing weight.
  EXPECT_NEAR(end.values[1], strain, 1e-3 * strain);
  EXPECT_NEAR(end.values[5], strain, 1e-3 * strain);
  EXPECT_NEAR(end.values[0], kE * strain, 1e-3 * kE * strain);
  EXPECT_NEAR(end.values[0], kE * end.values[1], 1e-3 * kE * strain);
  EXPECT_NEAR(end.values[2], -kNu * end.values[1], 1e-2 * kNu * strain);
  EXPECT_NEAR(end.values[3], std::abs(end.values[0]), 1e-3 * kE * strain);
  EXPECT_LT(std::abs(end.values[4]), 1e-3 * kE * strain);
  // Through the second half of the ramp, the stress sensor tracks E times the strain sensor.
  double worst = 0.0;
  for (const auto& s : samples) {
    if (s.time < 0.5 * kT) continue;
    worst = std::max(worst, std::abs(s.values[0] - kE * s.values[1]) / (kE * strain));
  }
  EXPECT_LT(worst, 1e-3);
  RecordProperty("end", fmt::format("eps {:.6e} (exact {:.6e}), sigma {:.6g} (E eps {:.6g}), "
                                    "worst |sigma - E eps| / sigma_end {:.3g}",
                                    end.values[1], strain, end.values[0], kE * strain, worst));
}

// Homogeneous deformations x = R F X imposed on the nodes of a 2 x 1 x 1 mesh: the strain sensor
// must give R diag(ln l1, ln l2, ln l3) R^T exactly (for 8-node and 27-node elements alike), and
// the stress sensor of the 27-node element the neo-Hookean Cauchy stress
// sigma = (mu (b - I) + lambda ln J I) / J of element/lagrange_hex.hpp, evaluated here in closed
// form.
// Returns the largest strain error and the largest stress error / E.
std::pair<double, double> check_homogeneous_deformation(int order) {
  constexpr double kE = 1000.0, kNu = 0.25;
  BoxMesh mesh;
  mesh.nx = 2;
  mesh.lx = 2.0;
  std::string deck = "*KEYWORD\n*CONTROL_TERMINATION\n1.0\n" + mesh.keyword_text() +
                     elastic_part(1.0, kE, kNu, 1, 4);
  if (order > 1) deck += fmt::format("*CHANGE_P-ORDER\nALL,0,{}\n", order);
  const char* components[] = {"XX", "YY", "ZZ", "XY", "YZ", "ZX"};
  deck += "*SENSOR_DEFINE_ELEMENT\n";
  for (int c = 0; c < 6; ++c) {
    deck += fmt::format("{},SOLID,2,{},STRAIN\n{},SOLID,2,{},STRESS\n", 10 + c, components[c],
                        20 + c, components[c]);
  }
  deck += "30,SOLID,1,VM,STRAIN\n31,SOLID,1,VM,STRESS\n";
  const model::Model m = read(deck);
  solver::NodeIndex index(m);
  solver::State state = solver::build_state(m, index);
  sensor::SensorSystem sys = sensor::build_sensor_system(m, index, state);

  const Eigen::Vector3d stretch(1.02, 0.99, 0.995);
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const Eigen::Matrix3d f = rotation * stretch.asDiagonal();
  auto& nodes = state.nodes;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3d x = f * Eigen::Vector3d(nodes.x0.x[i], nodes.x0.y[i], nodes.x0.z[i]);
    nodes.x.x[i] = x.x();
    nodes.x.y[i] = x.y();
    nodes.x.z[i] = x.z();
  }
  const element::NodalView view{nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
  for (auto& block : state.hex_blocks) element::compute_block_forces(block, view, 1e-9);
  sensor::evaluate_sensors(sys, state, 0.0);

  const Eigen::Vector3d log_stretch(std::log(stretch[0]), std::log(stretch[1]),
                                    std::log(stretch[2]));
  const Eigen::Matrix3d strain = rotation * log_stretch.asDiagonal() * rotation.transpose();
  const int rows[] = {0, 1, 2, 0, 1, 2}, cols[] = {0, 1, 2, 1, 2, 0};
  double strain_error = 0.0, stress_error = 0.0;
  for (int c = 0; c < 6; ++c) {
    EXPECT_NEAR(sensor::sensor_value(sys, 10 + c), strain(rows[c], cols[c]), 1e-13)
        << "order " << order << " strain " << components[c];
    strain_error = std::max(strain_error,
                            std::abs(sensor::sensor_value(sys, 10 + c) - strain(rows[c], cols[c])));
  }
  const double mean = log_stretch.sum() / 3.0;
  const Eigen::Vector3d deviator = log_stretch - Eigen::Vector3d::Constant(mean);
  EXPECT_NEAR(sensor::sensor_value(sys, 30), std::sqrt(2.0 / 3.0 * deviator.squaredNorm()), 1e-13);
  if (order == 1) return {strain_error, 0.0};  // rate-form element: one step is no reference
  const double mu = kE / (2 * (1 + kNu)), lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  const double j = f.determinant();
  const Eigen::Matrix3d b = f * f.transpose();
  const Eigen::Matrix3d sigma = (mu * (b - Eigen::Matrix3d::Identity()) +
                                 lambda * std::log(j) * Eigen::Matrix3d::Identity()) /
                                j;
  for (int c = 0; c < 6; ++c) {
    EXPECT_NEAR(sensor::sensor_value(sys, 20 + c), sigma(rows[c], cols[c]), 1e-9 * kE)
        << "order " << order << " stress " << components[c];
    stress_error = std::max(
        stress_error, std::abs(sensor::sensor_value(sys, 20 + c) - sigma(rows[c], cols[c])) / kE);
  }
  const double s[6] = {sigma(0, 0), sigma(1, 1), sigma(2, 2),
                       sigma(0, 1), sigma(1, 2), sigma(2, 0)};
  const double vm = std::sqrt(0.5 * ((s[0] - s[1]) * (s[0] - s[1]) + (s[1] - s[2]) * (s[1] - s[2]) +
                                     (s[2] - s[0]) * (s[2] - s[0])) +
                              3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
  EXPECT_NEAR(sensor::sensor_value(sys, 31), vm, 1e-9 * kE);
  return {strain_error, stress_error};
}

TEST(Sensors, StrainOfHomogeneousDeformationIsExactHencky) {
  std::string measured;
  for (int order = 1; order <= 3; ++order) {
    const auto [strain, stress] = check_homogeneous_deformation(order);
    measured += fmt::format("order {}: strain {:.2g}, stress/E {:.2g}; ", order, strain, stress);
  }
  RecordProperty("errors", measured);
}

// ---------------------------------------------------------------------------------------
// sensor.csv: header, rows at t = 0, at the cycle of every change and at the end.

TEST(Sensors, SensorCsvRecordsEveryStatusChange) {
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_sensor_csv_test";
  std::filesystem::remove_all(dir);
  const std::string cards =
      "*SENSOR_SWITCH\n801,TIME,,GT,0.1\n*SENSOR_CONTROL\n901,DEF2RIG,7\nOFF,801\n"
      "*SENSOR_DEFINE_FUNCTION\n20,510\n*DEFINE_FUNCTION\n510\nclock()= 2*time\n";
  double t_change = 0.0;
  {
    solver::Simulation sim(read(static_cube_deck(0.4, cards)), {dir, false});
    while (!sim.finished()) {
      sim.cycle();
      if (!sensor::def2rig_events(sim.sensors()).empty()) t_change = sim.sensors().time;
    }
    sim.run();  // flushes
  }
  ASSERT_GT(t_change, 0.1);
  std::ifstream in(dir / "sensor.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time,kind,id,value");
  bool saw_start = false, saw_change = false, saw_end = false;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string time, kind, id, value;
    std::getline(row, time, ',');
    std::getline(row, kind, ',');
    std::getline(row, id, ',');
    std::getline(row, value, ',');
    const double t = std::stod(time);
    if (kind == "sensor") EXPECT_NEAR(std::stod(value), 2 * t, 1e-12);
    if (kind == "control" && t == 0.0) saw_start = value == "0";
    if (kind == "control" && t == t_change) saw_change = value == "1";
    if (kind == "control" && std::abs(t - 0.4) < 1e-12) saw_end = value == "1";
  }
  EXPECT_TRUE(saw_start);
  EXPECT_TRUE(saw_change);
  EXPECT_TRUE(saw_end);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rf::test
