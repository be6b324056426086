// *BOUNDARY_PRESCRIBED_MOTION_NODE / _SET with DOF 4 (translation along a vector) and DOF 5-8
// (rotation about x, y, z or a vector) on nodes (solver/boundary.cpp, constrain_rotations;
// docs/keywords.md).
//
// References: a steel beam spun up about z at its pinned root by a prescribed root rotation,
// slowly against its first bending period, turns rigidly: its tip follows the prescribed angle,
// its kinetic energy is (1/2) (m L^2 / 3) Omega^2 and its angular momentum (m L^2 / 3) Omega (a
// rod about its end), and the work of the root's reaction moment is all of it. A free
// hexahedron whose nodes are driven along n = (1, 1, 0)/sqrt 2 keeps the velocity it has
// normal to n: it moves as d(t) n + v_perp t.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "deck_builder.hpp"

namespace rf::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLength = 1.0, kSide = 0.02, kRho = 7850.0, kE = 2.1e11;
constexpr int kBeams = 8;
constexpr double kOmega = 10.0;  // rad/s after the spin-up
constexpr double kRamp = 0.3;    // s, about 5 first bending periods (16.7 Hz)
constexpr double kEnd = 0.45;

// Angular velocity (1 - cos(pi t / T)) / 2 Omega during the ramp, then Omega; its angle and its
// angular acceleration.
double omega_at(double t) {
  return t < kRamp ? 0.5 * kOmega * (1.0 - std::cos(kPi * t / kRamp)) : kOmega;
}
double angle_at(double t) {
  return t < kRamp ? 0.5 * kOmega * (t - kRamp / kPi * std::sin(kPi * t / kRamp))
                   : 0.5 * kOmega * kRamp + kOmega * (t - kRamp);
}
double acceleration_at(double t) {
  return t < kRamp ? 0.5 * kOmega * kPi / kRamp * std::sin(kPi * t / kRamp) : 0.0;
}

// Sampled to twice the end time: the final state's angular velocity is that of the half step
// after ENDTIM, and a curve held constant beyond its end is a held angle (VAD 2).
std::string curve(double (*f)(double)) {
  std::string s = "*DEFINE_CURVE\n1\n";
  const int n = 1200;
  for (int k = 0; k <= n; ++k) {
    const double t = 2.0 * kEnd * k / n;
    s += fmt::format("{:.17g},{:.17g}\n", t, f(t));
  }
  return s;
}

// Belytschko-Schwer beams (ELFORM 2) along x, square 20 mm steel, root node 1 pinned; the root
// turns by `motion` (the prescribed-motion card(s) and curve).
std::string rotor_deck(const std::string& motion) {
  std::string s = "*KEYWORD\n*NODE\n";
  for (int i = 0; i <= kBeams; ++i)
    s += fmt::format("{},{:.17g},0,0\n", i + 1, kLength * i / kBeams);
  s += "*ELEMENT_BEAM\n";
  for (int i = 0; i < kBeams; ++i) s += fmt::format("{},1,{},{}\n", i + 1, i + 1, i + 2);
  const double area = kSide * kSide, inertia = kSide * kSide * kSide * kSide / 12.0;
  s += fmt::format(
      "*PART\nrotor\n1,1,1\n*SECTION_BEAM\n1,2,0.8333\n{:.17g},{:.17g},{:.17g},{:.17g}\n"
      "*MAT_ELASTIC\n1,{},{},0.3\n",
      area, inertia, inertia, 1.687 * inertia, kRho, kE);
  s += "*BOUNDARY_SPC_NODE\n1,0,1,1,1,0,0,0\n";
  s += motion;
  s += fmt::format("*CONTROL_TERMINATION\n{:.17g},\n*END\n", kEnd);
  return s;
}

struct RotorEnd {
  double root_omega_z = 0.0, root_omega_x = 0.0, root_omega_y = 0.0;
  double tip_angle = 0.0;
  double kinetic = 0.0, internal = 0.0, external = 0.0, angular_momentum_z = 0.0;
  std::vector<double> x;  // final coordinates, all nodes
};

RotorEnd run_rotor(const std::string& motion) {
  solver::Simulation sim(read(rotor_deck(motion)), {});
  while (!sim.finished()) sim.cycle();
  const solver::State& s = sim.state();
  RotorEnd out;
  const std::int32_t r = s.rotations.index(0);  // node 1 is the first node
  out.root_omega_x = s.rotations.w.x[r];
  out.root_omega_y = s.rotations.w.y[r];
  out.root_omega_z = s.rotations.w.z[r];
  out.tip_angle = std::atan2(s.nodes.x.y[kBeams], s.nodes.x.x[kBeams]);
  out.kinetic = sim.energy().kinetic;
  out.internal = sim.energy().internal() + sim.energy().hourglass;
  out.external = sim.energy().external_work;
  out.angular_momentum_z = sim.energy().angular_momentum[2];
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    out.x.push_back(s.nodes.x.x[i]);
    out.x.push_back(s.nodes.x.y[i]);
  }
  return out;
}

double rod_inertia() {
  const double mass = kRho * kSide * kSide * kLength;
  return mass * kLength * kLength / 3.0;
}

void expect_rigid_spin(const RotorEnd& r, const char* what) {
  // The angle lags the root by the beam's residual vibration only (ramp over 5 periods).
  EXPECT_NEAR(r.tip_angle, std::remainder(angle_at(kEnd), 2.0 * kPi), 2e-3) << what;
  EXPECT_NEAR(r.kinetic, 0.5 * rod_inertia() * kOmega * kOmega,
              0.02 * 0.5 * rod_inertia() * kOmega * kOmega)
      << what << ": lumped masses and rotary inertia within 2 % of the rod";
  EXPECT_NEAR(r.angular_momentum_z, rod_inertia() * kOmega, 0.02 * rod_inertia() * kOmega) << what;
  EXPECT_NEAR(r.kinetic + r.internal, r.external, 1e-3 * r.external)
      << what << ": the root moment's work is the rotor's energy";
  EXPECT_LT(r.internal, 1e-3 * r.kinetic) << what << ": it turned rigidly";
  EXPECT_EQ(r.root_omega_x, 0.0) << what;
  EXPECT_EQ(r.root_omega_y, 0.0) << what;
}

TEST(PrescribedNodeRotation, AngleSpinsABeamUpRigidly) {
  const RotorEnd r = run_rotor(curve(angle_at) + "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,7,2,1\n");
  std::printf(
      "angle: tip %.6f vs %.6f rad, KE %.6g vs %.6g, L %.6g vs %.6g, balance %.2e, "
      "internal/KE %.2e\n",
      r.tip_angle, std::remainder(angle_at(kEnd), 2.0 * kPi), r.kinetic,
      0.5 * rod_inertia() * kOmega * kOmega, r.angular_momentum_z, rod_inertia() * kOmega,
      (r.kinetic + r.internal) / r.external - 1.0, r.internal / r.kinetic);
  // After the ramp the curve is linear between points: the root turns at exactly Omega.
  EXPECT_NEAR(r.root_omega_z, kOmega, 1e-9 * kOmega);
  expect_rigid_spin(r, "VAD 2");
}

TEST(PrescribedNodeRotation, VelocityAndAccelerationCurvesGiveTheSameSpin) {
  const RotorEnd by_velocity =
      run_rotor(curve(omega_at) + "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,7,0,1\n");
  EXPECT_NEAR(by_velocity.root_omega_z, kOmega, 1e-9 * kOmega);
  expect_rigid_spin(by_velocity, "VAD 0");
  const RotorEnd by_acceleration =
      run_rotor(curve(acceleration_at) + "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,7,1,1\n");
  // Integrated from the sampled acceleration: Omega to the curve's discretisation.
  EXPECT_NEAR(by_acceleration.root_omega_z, kOmega, 2e-3 * kOmega);
  expect_rigid_spin(by_acceleration, "VAD 1");
}

TEST(PrescribedNodeRotation, AboutAVectorEqualsAboutItsAxis) {
  const RotorEnd about_z =
      run_rotor(curve(angle_at) + "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,7,2,1\n");
  const RotorEnd about_vector = run_rotor(curve(angle_at) +
                                          "*DEFINE_VECTOR\n5,0,0,0,0,0,2.5\n"
                                          "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,8,2,1,1.0,5\n");
  EXPECT_EQ(about_z.x, about_vector.x);
  EXPECT_EQ(about_z.kinetic, about_vector.kinetic);
  // The opposite vector with the curve reversed (SF -1) turns the same way.
  const RotorEnd reversed = run_rotor(curve(angle_at) +
                                      "*DEFINE_VECTOR\n5,0,0,0,0,0,-1\n"
                                      "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,8,2,1,-1.0,5\n");
  EXPECT_NEAR(reversed.tip_angle, about_z.tip_angle, 1e-12);
}

// A free unit hexahedron, every node driven along n = (1, 1, 0)/sqrt 2, with an initial
// velocity normal to n that nothing resists.
std::string sliding_cube(const std::string& motion) {
  BoxMesh mesh;
  std::string s = "*KEYWORD\n" + mesh.keyword_text() + elastic_part(kRho, kE, 0.3, 1, 4);
  std::vector<int> all;
  for (int i = 1; i <= mesh.node_count(); ++i) all.push_back(i);
  s += node_set(1, all);
  s += "*INITIAL_VELOCITY\n1\n0.0,0.0,2.0\n";
  s += "*DEFINE_VECTOR\n3,0,0,0,1,1,0\n";
  s += motion;
  // A single free element needs TSSFAC <= 0.55 (the solver's own stability message).
  s += "*CONTROL_TIMESTEP\n0.0,0.5\n*CONTROL_TERMINATION\n0.01,\n*END\n";
  return s;
}

TEST(PrescribedNodeVector, NodesFollowTheVectorAndKeepTheirNormalVelocity) {
  const double c = 1.0 / std::sqrt(2.0);
  struct Case {
    const char* motion;
    double along;  // displacement along n at t = 0.01
  };
  // VAD 0: 3 m/s; VAD 2: d(t) = 3 t. (Curves run past the end time: the final state's velocity
  // is that of the half step after it.)
  const Case cases[] = {
      {"*DEFINE_CURVE\n1\n0.0,3.0\n1.0,3.0\n*BOUNDARY_PRESCRIBED_MOTION_SET\n1,4,0,1,1.0,3\n",
       0.03},
      {"*DEFINE_CURVE\n1\n0.0,0.0\n1.0,3.0\n*BOUNDARY_PRESCRIBED_MOTION_SET\n1,4,2,1,1.0,3\n",
       0.03}};
  for (const Case& k : cases) {
    solver::Simulation sim(read(sliding_cube(k.motion)), {});
    while (!sim.finished()) sim.cycle();
    const solver::NodalState& n = sim.state().nodes;
    const double t = sim.state().time;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const double dx = n.x.x[i] - n.x0.x[i], dy = n.x.y[i] - n.x0.y[i], dz = n.x.z[i] - n.x0.z[i];
      EXPECT_NEAR(c * dx + c * dy, k.along, 1e-12) << k.motion;
      EXPECT_NEAR(c * dx - c * dy, 0.0, 1e-12) << "free normal direction in the plane";
      EXPECT_NEAR(dz, 2.0 * t, 1e-12) << "free normal velocity kept";
      // Round-off floor: strain noise of 1e-16 in a steel cube is a stress of E 1e-16 = 2e-5
      // Pa, an acceleration of 3e-10 m/s^2 per node and 3e-12 m/s over the 0.01 s (measured
      // 1.5e-12 with the displacement curve; 3e-13 while the bulk viscosity's step still took
      // the round-off of e_kk for compression, element/solid_terms.hpp).
      EXPECT_NEAR(n.v.z[i], 2.0, 1e-11);
    }
    // The mass gained the kinetic energy of the velocity along n: the reactions' work.
    const double mass = kRho;  // unit cube
    EXPECT_NEAR(sim.energy().kinetic, 0.5 * mass * (9.0 + 4.0), 1e-9 * mass) << k.motion;
    EXPECT_NEAR(sim.energy().external_work, 0.5 * mass * 9.0, 1e-9 * mass) << k.motion;
  }
}

TEST(PrescribedNodeDirection, BadInputNamesTheCause) {
  const std::string solid =
      simulation_error_of(sliding_cube("*DEFINE_CURVE\n1\n0.0,1.0\n1.0,1.0\n"
                                       "*BOUNDARY_PRESCRIBED_MOTION_SET\n1,5,0,1\n"));
  EXPECT_NE(solid.find("field NSID"), std::string::npos) << solid;
  EXPECT_NE(solid.find("no rotational degrees of freedom"), std::string::npos) << solid;
  const std::string no_vector = simulation_error_of(
      rotor_deck(curve(angle_at) + "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,8,2,1\n"));
  EXPECT_NE(no_vector.find("field VID"), std::string::npos) << no_vector;
  EXPECT_NE(no_vector.find("not a *DEFINE_VECTOR"), std::string::npos) << no_vector;
  const std::string fixed_rotation = simulation_error_of(
      rotor_deck(curve(angle_at) + "*BOUNDARY_SPC_NODE\n1,0,0,0,0,0,0,1\n"
                                   "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,7,2,1\n"));
  EXPECT_NE(fixed_rotation.find("also fixed"), std::string::npos) << fixed_rotation;
  const std::string fixed_translation =
      simulation_error_of(rotor_deck(curve(angle_at) + "*DEFINE_VECTOR\n3,0,0,0,1,0,0\n"
                                                       "*BOUNDARY_PRESCRIBED_MOTION_NODE\n"
                                                       "1,4,2,1,1.0,3\n"));
  EXPECT_NE(fixed_translation.find("DOF 4"), std::string::npos) << fixed_translation;
}

}  // namespace
}  // namespace rf::test
