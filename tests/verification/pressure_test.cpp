// Pressure loads (*LOAD_SEGMENT, *LOAD_SEGMENT_SET, *LOAD_SHELL_ELEMENT, *LOAD_SHELL_SET) and
// nodal moments (*LOAD_NODE DOF 5-7). References that do not come from our code:
//  - impulse-momentum: a pressure history p(t) on a flat face of area A changes the momentum by
//    -n A int p dt (the integral of the piecewise-linear curve in closed form);
//  - a follower pressure on a plate spinning at constant omega about an in-plane axis: the force
//    -p A n(t) turns with the plate, so the momentum is -p A int n(t) dt in closed form;
//  - Timoshenko & Woinowsky-Krieger, Theory of Plates and Shells (2nd ed., 1959), section 30,
//    table 8: centre deflection of a simply supported square plate under uniform load q,
//    w = 0.00406 q a^4 / D (nu = 0.3), D = E t^3 / (12 (1 - nu^2));
//  - a thin ring (a cylinder with free ends) under internal pressure: hoop stress p R / t, radial
//    expansion u = p R^2 / (E t); for a polygon of n flat facets the hoop force is p R cos(pi/n)
//    (equilibrium of a node: the facets' pressure forces against the two hoop forces);
//  - Euler-Bernoulli cantilever under a tip moment M: tip deflection M L^2 / (2 E I).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "deck_builder.hpp"
#include "model/error.hpp"
#include "shell_builder.hpp"
#include "solver/pressure_loads.hpp"

namespace rf::test {
namespace {

// A block of 2 x 2 x 2 hexahedra on [0, 1]^3 with pressure on its top face z = 1 (segment
// nodes counterclockwise seen from +z: normal +z, so positive pressure pushes toward -z). The
// pulse is a triangle 0 -> P -> 0 over [AT, AT + 2 T1] (curve points at 0, T1, 2 T1).
struct PulseBlock {
  BoxMesh mesh{2, 2, 2};
  double p = 1.0e5, t1 = 0.01, at = 0.005;
  std::string segments() const {
    std::string s = "*SET_SEGMENT\n7\n";
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        s += fmt::format("{},{},{},{}\n", mesh.node_id(i, j, 2), mesh.node_id(i + 1, j, 2),
                         mesh.node_id(i + 1, j + 1, 2), mesh.node_id(i, j + 1, 2));
      }
    return s + fmt::format(
                   "*LOAD_SEGMENT_SET\n7,3,{:.17g},{:.17g}\n*DEFINE_CURVE\n3\n0,0\n{:.17g},"
                   "1\n{:.17g},0\n1,0\n",
                   p, at, t1, 2 * t1);
  }
  double impulse() const { return p * 1.0 * t1; }  // area 1, triangle area P T1
};

// A rigid block: its top face stays flat, the step is DTINIT, and the curve's corners fall on
// step times, so the impulse is exact to round-off (the velocity update sums dt p(t_n): the
// trapezoidal rule, exact for a piecewise-linear p with corners at the samples).
TEST(Pressure, RigidBlockMomentumEqualsPressureImpulse) {
  const PulseBlock b;
  std::string deck = "*KEYWORD\n" + b.mesh.keyword_text(1);
  deck += "*PART\nrigid\n1,1,1\n*SECTION_SOLID\n1,1\n*MAT_RIGID\n1,7800,2e11,0.3\n";
  deck += b.segments();
  deck += "*CONTROL_TIMESTEP\n1e-4\n*CONTROL_TERMINATION\n0.03\n*END\n";
  solver::Simulation sim(read(deck), {});
  double before_arrival = 0.0;
  sim.run([&](const solver::Simulation& s) {
    if (s.state().time <= b.at)
      before_arrival = std::max(before_arrival, std::abs(s.energy().momentum[2]));
  });
  EXPECT_EQ(before_arrival, 0.0);  // nothing before AT
  const auto& e = sim.energy();
  RecordProperty("momentum_error", fmt::format("{:.3g}", e.momentum[2] / -b.impulse() - 1.0));
  RecordProperty("energy_error", fmt::format("{:.3g}", e.kinetic / e.external_work - 1.0));
  EXPECT_NEAR(e.momentum[2] / -b.impulse(), 1.0, 1e-12) << e.momentum[2];
  EXPECT_NEAR(e.momentum[0], 0.0, 1e-9 * b.impulse());
  EXPECT_NEAR(e.momentum[1], 0.0, 1e-9 * b.impulse());
  // The pressure's work is external work: kinetic energy = external work.
  EXPECT_GT(e.kinetic, 0.0);
  EXPECT_NEAR(e.kinetic / e.external_work, 1.0, 1e-10);
}

// A deformable block: the face deforms a little (strain ~1e-6), the step is the element's.
TEST(Pressure, DeformableBlockMomentumAndEnergyBalance) {
  const PulseBlock b;
  std::string deck = "*KEYWORD\n" + b.mesh.keyword_text(1) + elastic(1, 7800, 2e11, 0.3);
  deck += b.segments();
  deck += "*CONTROL_TERMINATION\n0.03\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  const auto& e = sim.energy();
  RecordProperty("momentum_error", fmt::format("{:.3g}", e.momentum[2] / -b.impulse() - 1.0));
  RecordProperty("energy_ratio", fmt::format("{:.8f}", e.ratio()));
  EXPECT_NEAR(e.momentum[2] / -b.impulse(), 1.0, 1e-4) << e.momentum[2];
  EXPECT_GT(e.external_work, 0.0);
  EXPECT_NEAR(e.ratio(), 1.0, 1e-3);
}

// A rigid square shell plate (a x a in its local u-v plane) spinning about its in-plane axis
// u at omega, with a constant pressure from t = 0: the force -p A n(t) follows the plate.
// n(0) = +z, n(t) = (0, -sin wt, cos wt) for a rotation about +x; the momentum is
// -p A (0, (cos wt - 1) / w, sin wt / w). A fixed-direction load would give -p A t z instead.
TEST(Pressure, FollowerPressureTurnsWithASpinningPlate) {
  ShellPlate plate;
  plate.nx = plate.ny = 2;
  plate.lx = plate.ly = 1.0;
  plate.place = [](double u, double v) { return Eigen::Vector3d(u - 0.5, v - 0.5, 0.0); };
  const double p = 100.0, omega = 10.0, end = 0.3;
  std::string deck = "*KEYWORD\n" + plate.text();
  deck +=
      "*PART\nplate\n1,1,1\n*SECTION_SHELL\n1,2,0.8333,2\n0.01,0.01,0.01,0.01\n"
      "*MAT_RIGID\n1,7800,2e11,0.3\n";
  deck += "*SET_SHELL\n5\n1,2,3,4\n*LOAD_SHELL_SET\n5,1," + fmt::format("{:.17g}", p) + "\n";
  deck += "*DEFINE_CURVE\n1\n0,1\n10,1\n";
  deck += fmt::format("*INITIAL_VELOCITY_GENERATION\n1,2,{:.17g}\n0,0,0,1,0,0\n", omega);
  deck += fmt::format("*CONTROL_TIMESTEP\n1e-5\n*CONTROL_TERMINATION\n{:.17g},\n*END\n", end);
  solver::Simulation sim(read(deck), {});
  sim.run();
  const double t = sim.state().time;
  const double pa = p * 1.0;
  const auto& e = sim.energy();
  // The momentum after the last cycle is of v^{n+1/2}, t^n = t: the load integrated to
  // t + dt / 2 (midpoint samples, the first half step dt / 2), so the error is O((omega dt)^2).
  const double th = omega * (t + 0.5 * sim.state().dt);
  const double scale = pa / omega;
  RecordProperty(
      "momentum_y_error",
      fmt::format("{:.3g}", (e.momentum[1] + pa * (std::cos(th) - 1.0) / omega) / scale));
  RecordProperty("momentum_z_error",
                 fmt::format("{:.3g}", (e.momentum[2] + pa * std::sin(th) / omega) / scale));
  EXPECT_NEAR(e.momentum[0], 0.0, 1e-9 * scale);
  EXPECT_NEAR(e.momentum[1], -pa * (std::cos(th) - 1.0) / omega, 1e-8 * scale) << e.momentum[1];
  EXPECT_NEAR(e.momentum[2], -pa * std::sin(th) / omega, 1e-8 * scale) << e.momentum[2];
  // A load that kept its initial direction would have pushed -p A t along z only.
  EXPECT_GT(std::abs(e.momentum[2] + pa * t), 0.5 * pa * t);
}

// Simply supported square plate (edges: w = 0 and in-plane fixed), uniform pressure ramped
// and held, damped to rest: centre deflection against Timoshenko's 0.00406 q a^4 / D.
TEST(Pressure, SimplySupportedPlateMatchesTimoshenko) {
  ShellPlate plate;
  plate.nx = plate.ny = 10;
  const double e = 2.0e11, nu = 0.3, t = 0.01, a = 1.0;
  const double d = e * t * t * t / (12.0 * (1.0 - nu * nu));
  const double q = 900.0;  // w / t ~ 0.02: linear
  const double expected = 0.00406 * q * std::pow(a, 4) / d;
  std::string deck = "*KEYWORD\n" + plate.text() + shell_part(1, t, 7800.0, e, nu);
  std::vector<int> edge;
  for (int j = 0; j <= plate.ny; ++j)
    for (int i = 0; i <= plate.nx; ++i)
      if (i == 0 || j == 0 || i == plate.nx || j == plate.ny) edge.push_back(plate.node_id(i, j));
  deck += node_set(1, edge) + "*BOUNDARY_SPC_SET\n1,0,1,1,1,0,0,0\n";
  deck += "*SET_SHELL\n2\n";
  for (int k = 1; k <= plate.element_count(); ++k) {
    deck += fmt::format("{}{}", k, k % 8 == 0 || k == plate.element_count() ? "\n" : ",");
  }
  // Pressure on the +z side pushes toward -z (normal of the element node order is +z).
  deck += fmt::format("*LOAD_SHELL_SET\n2,1,{:.17g}\n", q);
  // First mode omega_11 = 2 pi^2 / a^2 sqrt(D / (rho t)) ~ 302 rad/s: ramp over 0.03 s, damping
  // near critical (2 omega).
  deck += "*DEFINE_CURVE\n1\n0,0\n0.03,1\n10,1\n*DAMPING_GLOBAL\n0,600.0\n";
  deck += "*CONTROL_TERMINATION\n0.15\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  const auto centre = static_cast<std::size_t>(plate.node_id(plate.nx / 2, plate.ny / 2) - 1);
  const double w = -sim.state().nodes.x.z[centre];
  RecordProperty("centre_deflection_ratio", std::to_string(w / expected));
  EXPECT_NEAR(w / expected, 1.0, 0.02) << "w " << w << " Timoshenko " << expected;
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 2e-3);
}

// A ring of 32 x 1 shells (radius R, free ends) under internal pressure, damped to rest: the
// radius grows by p R^2 / (E t) (for the polygon: times cos(pi / n)).
TEST(Pressure, InflatedRingExpandsAsTheMembraneFormula) {
  ShellPlate ring;
  ring.nx = 32;
  ring.ny = 1;
  const double r = 1.0, len = 0.2, t = 0.01, e = 2.0e11, p = 1.0e6;
  ring.lx = 2.0 * std::numbers::pi * r;
  ring.ly = len;
  // u runs around the axis z; node order (u, then v = z) gives the normal u x z = outward,
  // so the inside pressure is a negative pressure on these segments.
  ring.place = [&](double u, double v) {
    return Eigen::Vector3d(r * std::cos(u / r), r * std::sin(u / r), v);
  };
  std::string deck = "*KEYWORD\n" + ring.nodes_text();
  // Close the ring: the last column of elements uses the first column's nodes.
  deck += "*ELEMENT_SHELL\n";
  for (int i = 0; i < ring.nx; ++i) {
    const int i1 = (i + 1) % ring.nx;
    deck += fmt::format("{},1,{},{},{},{}\n", i + 1, ring.node_id(i, 0), ring.node_id(i1, 0),
                        ring.node_id(i1, 1), ring.node_id(i, 1));
  }
  deck += shell_part(1, t, 7800.0, e, 0.3);
  for (int i = 0; i < ring.nx; ++i) {
    const int i1 = (i + 1) % ring.nx;
    deck += fmt::format("*LOAD_SEGMENT\n1,{:.17g},0,{},{},{},{}\n", -p, ring.node_id(i, 0),
                        ring.node_id(i1, 0), ring.node_id(i1, 1), ring.node_id(i, 1));
  }
  // Breathing mode omega = sqrt(E / rho) / R ~ 5060 rad/s: ramp 1 ms, damping ~ 2 omega.
  deck += "*DEFINE_CURVE\n1\n0,0\n0.001,1\n10,1\n*DAMPING_GLOBAL\n0,10000.0\n";
  deck += "*CONTROL_TERMINATION\n0.006\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  const auto& x = sim.state().nodes.x;
  double mean = 0.0;
  int count = 0;
  for (int j = 0; j <= ring.ny; ++j)
    for (int i = 0; i < ring.nx; ++i) {  // column nx coincides with column 0 and is unused
      const auto k = static_cast<std::size_t>(ring.node_id(i, j) - 1);
      mean += std::hypot(x.x[k], x.y[k]);
      ++count;
    }
  mean /= count;
  // For the polygon the hoop force is p times the inradius R cos(pi / n): u = p R^2 cos(pi / n)
  // / (E t) (0.5 % below the circle's p R^2 / (E t) at n = 32).
  const double expected = p * r * r * std::cos(std::numbers::pi / ring.nx) / (e * t);
  RecordProperty("radial_expansion_ratio", std::to_string((mean - r) / expected));
  EXPECT_NEAR((mean - r) / expected, 1.0, 2e-3) << "u " << mean - r << " expected " << expected;
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 2e-3);
}

// *LOAD_SHELL_ELEMENT, *LOAD_SHELL_SET and *LOAD_SEGMENT(_SET) on the same faces give the same
// forces, hence bit-identical runs.
TEST(Pressure, ShellAndSegmentKeywordsAgree) {
  ShellPlate plate;
  plate.nx = plate.ny = 2;
  const std::string base = "*KEYWORD\n" + plate.text() + shell_part(1, 0.01, 7800, 2e11, 0.3) +
                           "*DEFINE_CURVE\n1\n0,0\n0.001,1\n10,1\n"
                           "*CONTROL_TERMINATION\n0.002\n";
  auto run = [&](const std::string& loads) {
    solver::Simulation sim(read(base + loads + "*END\n"), {});
    sim.run();
    return sim.state().nodes.x;
  };
  std::string shells = "*LOAD_SHELL_ELEMENT\n", segments = "*LOAD_SEGMENT\n";
  std::string segment_set = "*SET_SEGMENT\n4\n";
  for (int j = 0, eid = 1; j < 2; ++j)
    for (int i = 0; i < 2; ++i, ++eid) {
      shells += fmt::format("{},1,{},0.0002\n", eid, 500.0 * eid);
      const std::string q = fmt::format("{},{},{},{}", plate.node_id(i, j), plate.node_id(i + 1, j),
                                        plate.node_id(i + 1, j + 1), plate.node_id(i, j + 1));
      segments += fmt::format("1,{},0.0002,{}\n", 500.0 * eid, q);
      segment_set += q + "\n";
    }
  const auto a = run(shells);
  const auto b = run(segments);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.x, b.x);
  EXPECT_NE(a.z[4], plate.position(1, 1).z());  // it moved
  // One pressure on all four: shell set and segment set.
  const auto c = run("*SET_SHELL\n3\n1,2,3,4\n*LOAD_SHELL_SET_ID\n9,all\n3,1,700\n");
  const auto d = run(segment_set + "*LOAD_SEGMENT_SET\n4,1,700\n");
  EXPECT_EQ(c.z, d.z);
  EXPECT_EQ(c.y, d.y);
}

// The consistent nodal forces of a warped quadrilateral against a numerical integral of
// -p N_a (x_xi x x_eta) with a 6 x 6 Gauss rule (exact for these polynomials, computed here).
TEST(Pressure, ConsistentNodalForcesOfAWarpedQuad) {
  const double x[4][3] = {{0, 0, 0}, {2.0, 0.1, 0.3}, {1.8, 1.5, -0.2}, {-0.1, 1.2, 0.4}};
  const double p = 3.0;
  double f[4][3];
  solver::segment_pressure_forces(x, p, f);
  const double g[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                       0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
  const double w[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                       0.4679139345726910, 0.3607615730481386, 0.1713244923791704};
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  double ref[4][3] = {};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      double dxi[3] = {}, deta[3] = {};
      for (int a = 0; a < 4; ++a)
        for (int k = 0; k < 3; ++k) {
          dxi[k] += 0.25 * sx[a] * (1 + sy[a] * g[j]) * x[a][k];
          deta[k] += 0.25 * sy[a] * (1 + sx[a] * g[i]) * x[a][k];
        }
      const double n[3] = {dxi[1] * deta[2] - dxi[2] * deta[1], dxi[2] * deta[0] - dxi[0] * deta[2],
                           dxi[0] * deta[1] - dxi[1] * deta[0]};
      for (int a = 0; a < 4; ++a) {
        const double na = 0.25 * (1 + sx[a] * g[i]) * (1 + sy[a] * g[j]);
        for (int k = 0; k < 3; ++k) ref[a][k] -= p * w[i] * w[j] * na * n[k];
      }
    }
  for (int a = 0; a < 4; ++a)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[a][k], ref[a][k], 1e-13) << a << " " << k;
  // A triangle (N3 = N4): -p A n / 3 on each corner.
  const double tri[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 1, 0}};
  solver::segment_pressure_forces(tri, p, f);
  EXPECT_NEAR(f[0][2], -p * 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(f[1][2], -p * 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(f[2][2] + f[3][2], -p * 1.0 / 3.0, 1e-14);
}

// A cantilever shell strip (L x b x t along x, clamped at x = 0) with a tip moment about y,
// damped to rest: tip deflection -M L^2 / (2 E I) (a moment about +y turns +x toward -z).
TEST(Pressure, CantileverTipMomentMatchesBeamTheory) {
  ShellPlate p;
  p.nx = 10;
  p.ny = 1;
  p.lx = 1.0;
  p.ly = 0.1;
  const double e = 2.0e11, t = 0.01, moment = 2.0;
  const double ei = e * p.ly * t * t * t / 12.0;
  const double expected = -moment * p.lx * p.lx / (2.0 * ei);
  std::string deck = "*KEYWORD\n" + p.text() + shell_part(1, t, 7800.0, e, 0.0);
  deck += node_set(1, p.column(0)) + "*BOUNDARY_SPC_SET\n1,0,1,1,1,1,1,1\n";
  deck += node_set(2, p.column(p.nx)) + fmt::format("*LOAD_NODE_SET\n2,6,1,{:.17g}\n", moment / 2);
  deck += "*DEFINE_CURVE\n1\n0,0\n0.2,1\n10,1\n*DAMPING_GLOBAL\n0,50.0\n";
  deck += "*CONTROL_TERMINATION\n0.6\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  double tip = 0.0;
  for (const int id : p.column(p.nx))
    tip += sim.state().nodes.x.z[static_cast<std::size_t>(id - 1)] / 2;
  RecordProperty("tip_deflection_ratio", std::to_string(tip / expected));
  EXPECT_NEAR(tip / expected, 1.0, 0.03) << "tip " << tip << " beam theory " << expected;
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 2e-3);
}

// A moment on a node of a free rigid shell plate goes to the body: its angular momentum is the
// angular impulse int M dt (a triangle pulse with corners on the step times: exact).
TEST(Pressure, MomentOnARigidShellNodeGivesTheBodyTheAngularImpulse) {
  ShellPlate plate;
  plate.nx = plate.ny = 2;
  const double m0 = 3.0, t1 = 0.01;
  std::string deck = "*KEYWORD\n" + plate.text();
  deck +=
      "*PART\nplate\n1,1,1\n*SECTION_SHELL\n1,2,0.8333,2\n0.01,0.01,0.01,0.01\n"
      "*MAT_RIGID\n1,7800,2e11,0.3\n";
  deck += fmt::format("*LOAD_NODE_POINT\n{},7,1,{:.17g}\n", plate.node_id(2, 2), m0);
  deck += fmt::format("*DEFINE_CURVE\n1\n0,0\n{:.17g},1\n{:.17g},0\n1,0\n", t1, 2 * t1);
  deck += "*CONTROL_TIMESTEP\n1e-4\n*CONTROL_TERMINATION\n0.03\n*END\n";
  solver::Simulation sim(read(deck), {});
  sim.run();
  const auto& e = sim.energy();
  EXPECT_NEAR(e.angular_momentum[2] / (m0 * t1), 1.0, 1e-12) << e.angular_momentum[2];
  EXPECT_NEAR(e.momentum[0], 0.0, 1e-12);
  EXPECT_NEAR(e.kinetic / e.external_work, 1.0, 1e-10);
}

// Bad input: file, line, keyword and field in every message.
TEST(Pressure, BadInputNamesFileLineKeywordAndField) {
  ShellPlate plate;
  const std::string base = "*KEYWORD\n" + plate.text() + shell_part(1, 0.01, 7800, 2e11, 0.3) +
                           "*DEFINE_CURVE\n1\n0,1\n1,1\n*CONTROL_TERMINATION\n0.001\n";
  auto expect_error = [&](const std::string& cards, const std::string& keyword,
                          const std::string& field, const std::string& words) {
    try {
      solver::Simulation sim(read(base + cards + "*END\n"), {});
      ADD_FAILURE() << "expected an input error at " << keyword << " " << field;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
      EXPECT_NE(what.find(keyword), std::string::npos) << what;
      EXPECT_NE(what.find(field), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  };
  expect_error("*LOAD_SEGMENT_SET\n12,1\n", "*LOAD_SEGMENT_SET", "SSID", "segment set 12");
  expect_error("*LOAD_SEGMENT\n8,1,0,1,2,3,4\n", "*LOAD_SEGMENT", "LCID", "curve 8");
  expect_error("*LOAD_SEGMENT\n-2,1,0,1,2,3,4\n", "*LOAD_SEGMENT", "LCID", "DEFINE_FUNCTION");
  expect_error("*LOAD_SEGMENT\n1,1,0,1,2,1,4\n", "*LOAD_SEGMENT", "N3", "twice");
  expect_error("*LOAD_SEGMENT\n1,1,0,1,2,3,4,5\n", "*LOAD_SEGMENT", "N5", "quadratic");
  expect_error("*SET_SEGMENT\n3\n1,2,2,4\n*LOAD_SEGMENT_SET\n3,1\n", "*LOAD_SEGMENT_SET", "SSID",
               "twice");
  expect_error("*LOAD_SHELL_ELEMENT\n7,1\n", "*LOAD_SHELL_ELEMENT", "EID", "shell element 7");
  expect_error("*LOAD_SHELL_SET\n7,1\n", "*LOAD_SHELL_SET", "ESID", "shell set 7");
  expect_error("*LOAD_SEGMENT_SET\n1,1,1,0,5\n", "*LOAD_SEGMENT_SET", "field 5", "not read");
  expect_error("*LOAD_NODE_POINT\n1,8,1,1.0\n", "*LOAD_NODE_POINT", "DOF", "follower");
  expect_error("*LOAD_NODE_POINT\n1,1,1,1.0,0,2,3,4\n", "*LOAD_NODE_POINT", "M1", "follower");
  // A moment on a node without rotations (a solid's node).
  const std::string solid = "*KEYWORD\n" + BoxMesh{}.keyword_text(1) + elastic(1, 7800, 2e11, 0.3) +
                            "*DEFINE_CURVE\n1\n0,1\n1,1\n*CONTROL_TERMINATION\n0.001\n";
  try {
    solver::Simulation sim(read(solid + "*LOAD_NODE_POINT\n3,5,1,1.0\n*END\n"), {});
    ADD_FAILURE() << "expected an error for a moment on a solid node";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("*LOAD_NODE_POINT"), std::string::npos) << what;
    EXPECT_NE(what.find("NID"), std::string::npos) << what;
    EXPECT_NE(what.find("node 3 has no rotational"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace rf::test
