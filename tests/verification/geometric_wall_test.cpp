// Geometric rigid walls (*RIGIDWALL_GEOMETRIC_FLAT / _PRISM / _CYLINDER / _SPHERE, _MOTION),
// *RIGIDWALL_PLANAR_FORCES and *BOUNDARY_PRESCRIBED_MOTION DOF 9-11, through the deck path.
// References that do not come from the solver:
//  - a point mass hitting a constraint ("stonewall") wall keeps the velocity's part tangent to
//    the surface at the contact point and loses the normal part (LS-DYNA Theory Manual, rigid
//    walls): v' = v - (v.n) n with n the analytic surface normal where the straight path meets
//    the surface (ray-plane, ray-cylinder, ray-sphere intersections computed here); the wall's
//    impulse is m |v.n|, its work -m (v.n)^2 / 2, and the energy balance closes;
//  - an elastic bar rebounds from a flat wall with momentum 2 m v0 (d'Alembert);
//  - a node on a wall with prescribed motion follows the motion; Coulomb sliding decelerates
//    at mu g;
//  - a node turning about an axis stays on its circle at the prescribed angle.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "deck_builder.hpp"
#include "model/error.hpp"

namespace rf::test {
namespace {

using Eigen::Vector3d;

// Node 1: a point mass (*ELEMENT_MASS) with an initial velocity, in node set 1 (the walls track
// that set). Nodes 2 and 3, far away and at rest, are joined by a soft spring only because a
// model needs an element; LCTM holds the step at `dt` (run_for).
std::string point_mass(const Vector3d& x, const Vector3d& v, double m) {
  return fmt::format(
      "*NODE\n1,{:.17g},{:.17g},{:.17g}\n2,100,100,100\n3,101,100,100\n"
      "*ELEMENT_MASS\n1,1,{:.17g}\n2,2,1.0\n3,3,1.0\n*SECTION_DISCRETE\n5,0\n*PART\nspring\n9,5,"
      "11\n"
      "*MAT_S01\n11,1.0\n*ELEMENT_DISCRETE\n10,9,2,3\n*SET_NODE_LIST\n1\n1\n"
      "*INITIAL_VELOCITY_NODE\n1,{:.17g},{:.17g},{:.17g}\n",
      x.x(), x.y(), x.z(), m, v.x(), v.y(), v.z());
}

std::string run_for(double t_end, double dt) {
  return fmt::format(
      "*CONTROL_TIMESTEP\n{0:.17g},0.9,0,0,0,77\n*DEFINE_CURVE\n77\n0,{0:.17g}\n1e3,{0:.17g}\n"
      "*CONTROL_TERMINATION\n{1:.17g},\n",  // free format: 17 digits are wider than 10 columns
      dt, t_end);
}

std::filesystem::path fresh_directory(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("rigidflex_geowall_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

std::vector<std::vector<double>> read_csv(const std::filesystem::path& path, std::string& header) {
  std::ifstream in(path);
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

Vector3d node_x(const solver::State& s, std::size_t i = 0) {
  return {s.nodes.x.x[i], s.nodes.x.y[i], s.nodes.x.z[i]};
}
Vector3d node_v(const solver::State& s, std::size_t i = 0) {
  return {s.nodes.v.x[i], s.nodes.v.y[i], s.nodes.v.z[i]};
}

// A point mass thrown at a wall: the velocity after the first contact, the final one, the
// wall's total normal impulse, the rwforc force integrated over time (as a vector), the
// wall's work, the energy ratio and the worst signed distance `distance(x)` seen.
struct Throw {
  Vector3d v_after = Vector3d::Zero();      // after the second contact cycle (see below)
  Vector3d first_force = Vector3d::Zero();  // direction of the first contact force
  Vector3d v_end = Vector3d::Zero();
  double impulse = 0.0, work = 0.0, ratio = 0.0, worst = 0.0;
  Vector3d force_integral = Vector3d::Zero();
  int contacts = 0;
};

template <class Distance>
Throw throw_at(const std::string& name, const std::string& wall, const Vector3d& x0,
               const Vector3d& v0, double m, double t_end, Distance distance) {
  const auto dir = fresh_directory(name);
  const std::string deck = "*KEYWORD\n" + point_mass(x0, v0, m) + wall +
                           "*DATABASE_RWFORC\n1e-6\n" + run_for(t_end, 1e-4) + "*END\n";
  Throw out;
  out.worst = std::numeric_limits<double>::infinity();
  {
    solver::Simulation sim(read(deck), {.output_directory = dir, .write_fields = false});
    const auto& w = sim.rigid_walls().walls.at(0);
    while (!sim.finished()) {
      sim.cycle();
      if (w.normal_force > 0.0) {
        if (out.contacts == 0) out.first_force = w.force.normalized();
        if (out.contacts < 2) out.v_after = node_v(sim.state());
        ++out.contacts;
      }
      out.worst = std::min(out.worst, distance(node_x(sim.state())));
    }
    out.v_end = node_v(sim.state());
    out.impulse = w.normal_impulse;
    out.work = w.work;
    out.ratio = sim.energy().ratio();
  }
  std::string header;
  const auto rows = read_csv(dir / "rwforc.csv", header);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double before = r > 0 ? rows[r - 1][0] : rows[r][0];
    const double after = r + 1 < rows.size() ? rows[r + 1][0] : rows[r][0];
    out.force_integral += 0.5 * (after - before) * Vector3d(rows[r][3], rows[r][4], rows[r][5]);
  }
  std::filesystem::remove_all(dir);
  return out;
}

// The stonewall answer for contact normal n (unit, towards the node) and checks common to all
// shapes. `tolerance` covers the normal taken at x^n instead of the exact contact point
// (|v| dt / R, 1e-4 here). The constraint lands the node on the surface in the first contact
// cycle (normal velocity -d^n/dt) and removes what is left of its normal velocity in the
// second: the stonewall velocity is the one after the second. `full` false: only the
// direction of the first force and the balances (a node hitting a sharp edge head-on ends on
// the edge, where the normal of the next cycles is not defined).
void expect_stonewall(const Throw& t, const Vector3d& v0, const Vector3d& n, double m,
                      double tolerance, bool full = true) {
  const double vn = v0.dot(n);
  ASSERT_LT(vn, 0.0);
  const Vector3d expected = v0 - vn * n;
  std::printf(
      "  v after %.6f %.6f %.6f, expected %.6f %.6f %.6f; impulse %.6g (m|v.n| %.6g), "
      "work %.6g (-m vn^2/2 %.6g), ratio %.12f, worst distance %.3g, %d contact cycles\n",
      t.v_after.x(), t.v_after.y(), t.v_after.z(), expected.x(), expected.y(), expected.z(),
      t.impulse, -m * vn, t.work, -0.5 * m * vn * vn, t.ratio, t.worst, t.contacts);
  EXPECT_LT((t.first_force - n).norm(), tolerance);
  if (full) {
    EXPECT_LT((t.v_after - expected).norm(), tolerance * v0.norm());
    EXPECT_NEAR(t.impulse, -m * vn, tolerance * m * v0.norm());
    EXPECT_NEAR(t.work, -0.5 * m * vn * vn, tolerance * m * v0.squaredNorm());
  }
  // The wall is the only force: the momentum change is the integral of the rwforc force.
  EXPECT_LT((t.force_integral - m * (t.v_end - v0)).norm(), 1e-9 * m * v0.norm());
  // Kinetic energy + 0 = KE0 + wall work: the energy ratio stays 1 (the wall's loss is booked).
  EXPECT_NEAR(t.ratio, 1.0, 1e-9);
  EXPECT_GE(t.worst, -1e-12);
}

// Ray x0 + s v meets the sphere |x - c| = R (first hit from outside, or the exit from inside).
double ray_sphere(const Vector3d& x0, const Vector3d& v, const Vector3d& c, double r, bool inside) {
  const Vector3d d = x0 - c;
  const double a = v.squaredNorm(), b = 2.0 * d.dot(v), q = d.squaredNorm() - r * r;
  const double root = std::sqrt(b * b - 4.0 * a * q);
  return inside ? (-b + root) / (2.0 * a) : (-b - root) / (2.0 * a);
}

TEST(GeometricWall, FlatWallStopsNormalVelocityOfPointMassAndLeavesTangential) {
  // Tilted flat wall through (0.2, 0, 0), normal (0.3, 0, 1), finite 2 x 2.
  const Vector3d tail(0.2, 0, 0), n = Vector3d(0.3, 0, 1).normalized();
  const Vector3d v0(0.4, 0.3, -1.0), x0(0.5, 0.5, 0.3);
  const double m = 2.0;
  const std::string wall =
      fmt::format("*RIGIDWALL_GEOMETRIC_FLAT_ID\n3,floor\n1\n0.2,0,0,0.5,0,1.0\n2.4,0,-0.6,4,4\n");
  // The edge head (2.4, 0, -0.6): l about +x (projected on the plane), m = n x l = +y.
  std::printf("flat:\n");
  const Throw t =
      throw_at("flat", wall, x0, v0, m, 0.5, [&](const Vector3d& x) { return (x - tail).dot(n); });
  expect_stonewall(t, v0, n, m, 1e-9);
  // Beside a finite wall the node passes: the same throw 10 m away in y.
  const Throw beside = throw_at("flat_beside", wall, x0 + Vector3d(0, 10, 0), v0, m, 0.5,
                                [](const Vector3d&) { return 0.0; });
  EXPECT_EQ(beside.contacts, 0);
  EXPECT_LT((beside.v_end - v0).norm(), 1e-12);
}

TEST(GeometricWall, PrismFaceAndEdgeGiveTheirNormals) {
  // Box 0 <= x <= 1, 0 <= y <= 1, -1 <= z <= 0 (face z = 0, normal +z, l = x, m = y).
  const std::string wall = "*RIGIDWALL_GEOMETRIC_PRISM\n1\n0,0,0,0,0,1\n1,0,0,1,1,1\n";
  auto box_distance = [](const Vector3d& x) {
    const Vector3d lo(0, 0, -1), hi(1, 1, 0);
    const Vector3d q = x - x.cwiseMax(lo).cwiseMin(hi);
    if (q.norm() > 0.0) return q.norm();
    return -std::min({x.x(), 1 - x.x(), x.y(), 1 - x.y(), x.z() + 1, -x.z()});
  };
  const double m = 1.5;
  std::printf("prism side face x = 1:\n");
  const Vector3d v_side(-1.0, 0.2, 0.1);
  const Throw side =
      throw_at("prism_side", wall, Vector3d(1.3, 0.3, -0.5), v_side, m, 0.5, box_distance);
  expect_stonewall(side, v_side, Vector3d::UnitX(), m, 1e-9);
  // Aimed at the edge x = 1, z = 0 from the quadrant x > 1, z > 0: the nearest point is on the
  // edge and the normal points from it to the node, against the velocity: the node stops.
  std::printf("prism edge x = 1, z = 0:\n");
  const Vector3d v_edge(-1.0, 0.0, -0.5);
  const Vector3d hit(1.0, 0.5, 0.0);
  const Throw edge =
      throw_at("prism_edge", wall, hit - 0.30005 * v_edge, v_edge, m, 0.5, box_distance);
  expect_stonewall(edge, v_edge, -v_edge.normalized(), m, 1e-9, false);
}

TEST(GeometricWall, CylinderFromOutsideAndInside) {
  // Axis along z through (0.1, -0.2, 0), radius 1, length 2 from z = 0.
  const Vector3d c(0.1, -0.2, 0);
  const double r = 1.0, m = 0.7;
  auto radial = [&](const Vector3d& x) {
    const Vector3d d = x - c;
    return std::hypot(d.x(), d.y());
  };
  const std::string outside = "*RIGIDWALL_GEOMETRIC_CYLINDER\n1\n0.1,-0.2,0,0.1,-0.2,1\n1.0,2.0\n";
  std::printf("cylinder from outside:\n");
  const Vector3d x0(-1.9, 0.3, 0.8), v0(1.0, 0.0, 0.2);
  const Throw out = throw_at("cyl_out", outside, x0, v0, m, 2.0,
                             [&](const Vector3d& x) { return radial(x) - r; });
  // Contact where the path's xy projection meets the circle.
  const Vector3d v_xy(v0.x(), v0.y(), 0), x_xy(x0.x(), x0.y(), 0), c_xy(c.x(), c.y(), 0);
  const Vector3d p = x_xy + ray_sphere(x_xy, v_xy, c_xy, r, false) * v_xy;
  expect_stonewall(out, v0, (p - c_xy).normalized(), m, 1e-3);
  // A convex wall touches once: the node then flies on with v_after.
  EXPECT_LT((out.v_end - out.v_after).norm(), 1e-3 * v0.norm());

  std::printf("cylinder from inside (_INTERIOR):\n");
  const std::string inside =
      "*RIGIDWALL_GEOMETRIC_CYLINDER_INTERIOR\n1\n0.1,-0.2,0,0.1,-0.2,1\n1.0,0.0\n";
  const Vector3d y0(0.1, 0.1, 0.5), w0(1.0, 0.8, 0.0);
  const Throw in =
      throw_at("cyl_in", inside, y0, w0, m, 1.5, [&](const Vector3d& x) { return r - radial(x); });
  const Vector3d q = y0 + ray_sphere(y0, w0, c + Vector3d(0, 0, 0.5), r, true) * w0;
  const Vector3d n_in = (c + Vector3d(0, 0, 0.5) - q).normalized();
  // Only the first contact is the stonewall answer (then it slides along the inside); the
  // impulse and work checks cover the whole slide, so compare the first velocity alone.
  const Vector3d expected = w0 - w0.dot(n_in) * n_in;
  std::printf("  first v %.6f %.6f, expected %.6f %.6f; end speed %.6f of %.6f; worst %.3g\n",
              in.v_after.x(), in.v_after.y(), expected.x(), expected.y(), in.v_end.norm(),
              expected.norm(), in.worst);
  EXPECT_LT((in.v_after - expected).norm(), 1e-3 * w0.norm());
  // Outside by at most the step off the tangent plane, (|v| dt)^2 / (2 R), never more.
  EXPECT_GE(in.worst, -std::pow(w0.norm() * 1e-4, 2) / r);
  // Sliding round the inside loses speed at second order per step only (measured below 1 %).
  EXPECT_NEAR(in.v_end.norm(), expected.norm(), 0.01 * expected.norm());
  EXPECT_NEAR(in.ratio, 1.0, 1e-9);
}

TEST(GeometricWall, SphereFromOutsideAndInside) {
  const Vector3d c(0.3, 0.2, -0.1);
  const double r = 0.8, m = 1.1;
  const std::string sphere = "*RIGIDWALL_GEOMETRIC_SPHERE\n1\n0.3,0.2,-0.1,0.3,0.2,0.9\n0.8\n";
  std::printf("sphere from outside:\n");
  const Vector3d x0(-1.5, 0.5, 0.3), v0(1.0, 0.1, -0.1);
  const Throw out = throw_at("sph_out", sphere, x0, v0, m, 1.2,
                             [&](const Vector3d& x) { return (x - c).norm() - r; });
  const Vector3d p = x0 + ray_sphere(x0, v0, c, r, false) * v0;
  expect_stonewall(out, v0, (p - c).normalized(), m, 1e-3);
  EXPECT_LT((out.v_end - out.v_after).norm(), 1e-3 * v0.norm());

  std::printf("sphere from inside (the node starts inside and stays there):\n");
  const Vector3d y0 = c + Vector3d(0.1, 0, 0), w0(0.9, 0.5, 0.3);
  const Throw in = throw_at("sph_in", sphere, y0, w0, m, 1.0,
                            [&](const Vector3d& x) { return r - (x - c).norm(); });
  const Vector3d q = y0 + ray_sphere(y0, w0, c, r, true) * w0;
  const Vector3d n_in = (c - q).normalized();
  const Vector3d expected = w0 - w0.dot(n_in) * n_in;
  std::printf("  first v %.6f %.6f %.6f, expected %.6f %.6f %.6f, worst %.3g\n", in.v_after.x(),
              in.v_after.y(), in.v_after.z(), expected.x(), expected.y(), expected.z(), in.worst);
  EXPECT_LT((in.v_after - expected).norm(), 1e-3 * w0.norm());
  EXPECT_GE(in.worst, -std::pow(w0.norm() * 1e-4, 2) / r);
  EXPECT_NEAR(in.ratio, 1.0, 1e-9);
}

// An elastic bar (nu = 0) dropped on a flat geometric wall rebounds with 2 m v0 (d'Alembert),
// within the few per cent the constraint method's plastic node impacts take (as for
// *RIGIDWALL_PLANAR in rigid_wall_test.cpp).
TEST(GeometricWall, ElasticBarReboundsFromFlatWall) {
  constexpr double rho = 1000.0, e = 1e6, v0 = 0.1, length = 1.0, width = 0.1, gap = 1e-3;
  const double contact_time = 2.0 * length / std::sqrt(e / rho);
  Block bar;
  bar.nz = 40;
  bar.lx = bar.ly = width;
  bar.lz = length;
  bar.shift = Vector3d(0, 0, gap);
  const std::string deck =
      "*KEYWORD\n" + bar.text() + elastic(1, rho, e, 0.0) +
      "*INITIAL_VELOCITY_GENERATION\n1,2,0,0,0,-0.1\n0,0,0,0,0,0\n"
      "*CONTROL_BULK_VISCOSITY\n0.0,0.0\n"
      "*RIGIDWALL_GEOMETRIC_FLAT\n0\n0,0,0,0,0,1\n1,0,0,0,0\n" +
      fmt::format("*CONTROL_TERMINATION\n{:.17g},\n", gap / v0 + 1.5 * contact_time);
  solver::Simulation sim(read(deck), {});
  double mass = 0.0, pz0 = 0.0;
  for (std::size_t i = 0; i < sim.state().nodes.size(); ++i) {
    mass += sim.state().nodes.mass[i];
    pz0 += sim.state().nodes.mass[i] * sim.state().nodes.v.z[i];
  }
  while (!sim.finished()) sim.cycle();
  double pz = 0.0;
  for (std::size_t i = 0; i < sim.state().nodes.size(); ++i) {
    pz += sim.state().nodes.mass[i] * sim.state().nodes.v.z[i];
  }
  const auto& wall = sim.rigid_walls().walls.at(0);
  std::printf("bar on flat geometric wall: rebound %.5f, impulse %.9g vs dp %.9g, ratio %.12f\n",
              pz / (mass * v0), wall.normal_impulse, pz - pz0, sim.energy().ratio());
  EXPECT_NEAR(pz / (mass * v0), 1.0, 0.03);
  EXPECT_NEAR(wall.normal_impulse, pz - pz0, 1e-12 * mass * v0);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-9);
}

// _MOTION: a node resting on a flat wall under gravity rides on it as the wall moves up with
// a prescribed velocity (OPT 0) or displacement (OPT 1); the wall's impulse is the node's
// momentum change plus the weight's impulse.
TEST(GeometricWall, PrescribedMotionCarriesRestingNode) {
  const double m = 3.0, g = 9.81, t_end = 0.5;
  for (const int opt : {0, 1}) {
    // OPT 0: v(t) = 2 t (m/s); OPT 1: u(t) = 0.4 t (curve points), along (0, 0, 2) (unit).
    const std::string curve =
        opt == 0 ? "*DEFINE_CURVE\n5\n0,0\n1,2\n" : "*DEFINE_CURVE\n5\n0,0\n1,0.4\n";
    const std::string deck =
        "*KEYWORD\n" + point_mass(Vector3d(0.5, 0.5, 0.0), Vector3d::Zero(), m) +
        fmt::format("*LOAD_BODY_Z\n9,1.0\n*DEFINE_CURVE\n9\n0,{0}\n10,{0}\n", g) + curve +
        fmt::format("*RIGIDWALL_GEOMETRIC_FLAT_MOTION\n1\n0,0,0,0,0,1\n1,0,0,0,0\n5,{},0,0,2\n",
                    opt) +
        run_for(t_end, 1e-3) + "*END\n";
    solver::Simulation sim(read(deck), {});
    const auto& wall = sim.rigid_walls().walls.at(0);
    double worst = 0.0;
    while (!sim.finished()) {
      sim.cycle();
      const double t = sim.state().time;
      const double u = opt == 0 ? t * t : 0.4 * t;  // exact: v linear, midpoint rule
      if (!sim.finished()) worst = std::max(worst, std::abs(node_x(sim.state()).z() - u));
    }
    const double t = sim.state().time;
    const double v_end = node_v(sim.state()).z();
    // Impulse balance over [0, t]: J_wall - m g t = m v (the last wall force acts over the
    // half step before t, the weight over t: compare with the step-centred weight impulse).
    const double weight = m * g * (t + 0.5 * sim.state().dt);
    std::printf(
        "motion OPT %d: worst |z - u(t)| %.3g, v %.6f, wall impulse %.9g vs m v + m g t "
        "%.9g, displacement %.6f\n",
        opt, worst, v_end, wall.normal_impulse, m * v_end + weight, wall.displacement);
    EXPECT_LT(worst, 1e-12);
    EXPECT_NEAR(v_end, opt == 0 ? 2.0 * (t + 0.5 * sim.state().dt) : 0.4, 1e-9);
    EXPECT_NEAR(wall.normal_impulse, m * v_end + weight, 1e-6 * m * g * t);
  }
}

TEST(GeometricWall, CoulombFrictionDeceleratesSlidingBlockAtMuG) {
  constexpr double rho = 1000.0, e = 1e9, g = 9.81, mu = 0.3, v0 = 1.0;
  Block block;
  block.nx = block.ny = 2;
  block.lx = block.ly = 0.2;
  block.lz = 0.1;
  const double stop_time = v0 / (mu * g);
  const std::string deck =
      "*KEYWORD\n" + block.text() + elastic(1, rho, e, 0.0) +
      fmt::format("*LOAD_BODY_Z\n99,1.0\n*DEFINE_CURVE\n99\n0,{0}\n1e3,{0}\n", g) +
      "*INITIAL_VELOCITY_GENERATION\n1,2,0,1.0,0,0\n0,0,0,0,0,0\n" +
      fmt::format("*RIGIDWALL_GEOMETRIC_FLAT\n0\n0,0,0,0,0,1,{}\n1,0,0,0,0\n", mu) +
      fmt::format("*CONTROL_TERMINATION\n{:.17g},\n", 0.7 * stop_time);
  solver::Simulation sim(read(deck), {});
  double mass = 0.0;
  for (const double mi : sim.state().nodes.mass) mass += mi;
  double worst = 0.0;
  while (!sim.finished()) {
    sim.cycle();
    double px = 0.0;
    for (std::size_t i = 0; i < sim.state().nodes.size(); ++i) {
      px += sim.state().nodes.mass[i] * sim.state().nodes.v.x[i];
    }
    const double t = sim.finished() ? sim.state().time + 0.5 * sim.state().dt
                                    : sim.state().time - 0.5 * sim.state().dt_prev;
    worst = std::max(worst, std::abs(px / mass - (v0 - mu * g * t)));
  }
  std::printf("friction on flat geometric wall: max |v - (v0 - mu g t)| = %.3g\n", worst);
  EXPECT_LT(worst, 1e-3 * v0);
}

// *RIGIDWALL_PLANAR_FORCES SSID: the force on the segment set's nodes. A block dropped on the
// wall: with the whole bottom face in the set it is the whole wall force; with the top face,
// which never touches the wall, it is zero.
TEST(GeometricWall, PlanarForcesSegmentSetForce) {
  Block block;
  block.nx = block.ny = 2;
  block.lx = block.ly = 0.2;
  block.lz = 0.1;
  block.shift = Vector3d(0, 0, 1e-3);
  auto face = [&](int k) {
    std::string s = "*SET_SEGMENT\n7\n";
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        s += fmt::format("{},{},{},{}\n", block.node(i, j, k), block.node(i + 1, j, k),
                         block.node(i + 1, j + 1, k), block.node(i, j + 1, k));
    return s;
  };
  for (const int k : {0, 1}) {
    const std::string deck = "*KEYWORD\n" + block.text() + elastic(1, 1000.0, 1e8, 0.3) + face(k) +
                             "*INITIAL_VELOCITY_GENERATION\n1,2,0,0.3,0,-1.0\n0,0,0,0,0,0\n"
                             "*RIGIDWALL_PLANAR_FORCES\n0\n0,0,0,0,0,1\n0,7\n*CONTROL_TIMESTEP\n0,"
                             "0.5\n*CONTROL_TERMINATION\n2e-3\n";
    solver::Simulation sim(read(deck), {});
    const auto& wall = sim.rigid_walls().walls.at(0);
    double largest = 0.0, worst = 0.0;
    while (!sim.finished()) {
      sim.cycle();
      largest = std::max(largest, wall.force.norm());
      const Eigen::Vector3d expected = k == 0 ? wall.force : Eigen::Vector3d::Zero();
      worst = std::max(worst, (wall.segment_force - expected).norm());
    }
    std::printf("segment set on face k = %d: largest wall force %.6g, worst difference %.3g\n", k,
                largest, worst);
    EXPECT_GT(largest, 0.0);
    EXPECT_EQ(worst, 0.0);
  }
}

// DOF 9, 10, 11: nodes turn about axes parallel to x, y, z through (OFFSET1, OFFSET2) in the
// other two coordinates; the coordinate along the axis stays free (a velocity along it is
// kept). VAD 2: the angle from a curve; VAD 0: the angular velocity omega(t) = 4 t, angle 2 t^2.
TEST(PrescribedRotation, NodesFollowTheirCirclesAtThePrescribedAngle) {
  for (const int vad : {0, 2}) {
    for (const int dof : {9, 10, 11}) {
      const int axis = dof - 9;
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      const double offset1 = 0.3, offset2 = -0.4;
      Vector3d centre = Vector3d::Zero();
      centre[a] = offset1;
      centre[b] = offset2;
      const Vector3d x0(1.0, 0.5, -0.2), along = 0.25 * Vector3d::Unit(axis);
      const std::string curve =
          vad == 2 ? "*DEFINE_CURVE\n3\n0,0\n0.5,1.5\n1,1.0\n" : "*DEFINE_CURVE\n3\n0,0\n1,4\n";
      const std::string deck = "*KEYWORD\n" + point_mass(x0, along, 1.0) + curve +
                               fmt::format("*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,{},{},3\n{},{}\n",
                                           dof, vad, offset1, offset2) +
                               run_for(0.8, 1e-3) + "*END\n";
      solver::Simulation sim(read(deck), {});
      double worst = 0.0;
      while (!sim.finished()) {
        sim.cycle();
        const double t = sim.finished() ? sim.state().time + sim.state().dt : sim.state().time;
        const double theta = vad == 0 ? 2.0 * t * t : (t <= 0.5 ? 3.0 * t : 1.5 - (t - 0.5));
        const Eigen::AngleAxisd turn(theta, Vector3d::Unit(axis));
        const Vector3d expected = centre + turn * (x0 - centre) + t * along;
        const Vector3d x = sim.finished()
                               ? node_x(sim.state()) + sim.state().dt * node_v(sim.state())
                               : node_x(sim.state());
        worst = std::max(worst, (x - expected).norm());
      }
      std::printf("DOF %d VAD %d: worst |x - x_analytic| = %.3g\n", dof, vad, worst);
      EXPECT_LT(worst, 1e-9);
    }
  }
}

// Unsupported values stop the run with file, line, keyword and field.
TEST(GeometricWallInput, UnsupportedValuesAreInputErrors) {
  const std::string model = "*KEYWORD\n" + point_mass(Vector3d(0, 0, 1), Vector3d::Zero(), 1.0) +
                            "*DEFINE_CURVE\n5\n0,0\n1,1\n" + run_for(0.01, 1e-3);
  auto expect_error = [&](const std::string& cards, const std::string& keyword,
                          const std::string& field, const std::string& words) {
    try {
      solver::Simulation sim(read(model + cards + "*END\n"), {});
      ADD_FAILURE() << "expected an input error at " << keyword << " " << field;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("verification.k:"), std::string::npos) << what;
      EXPECT_NE(what.find(keyword), std::string::npos) << what;
      EXPECT_NE(what.find(field), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  };
  expect_error("*RIGIDWALL_GEOMETRIC_CYLINDER\n0\n0,0,0,0,0,1\n1.0,0,3\n",
               "*RIGIDWALL_GEOMETRIC_CYLINDER", "NSEGS", "not supported");
  expect_error("*RIGIDWALL_GEOMETRIC_SPHERE\n0\n0,0,0,0,0,1,2.0\n1.0\n",
               "*RIGIDWALL_GEOMETRIC_SPHERE", "FRIC", "not supported");
  expect_error("*RIGIDWALL_GEOMETRIC_PRISM\n0\n0,0,0,0,0,1\n1,0,0,1,1,0\n",
               "*RIGIDWALL_GEOMETRIC_PRISM", "LENP", "positive");
  expect_error("*RIGIDWALL_GEOMETRIC_FLAT_MOTION\n0\n0,0,0,0,0,1\n1,0,0\n5,2,0,0,1\n",
               "*RIGIDWALL_GEOMETRIC_FLAT_MOTION", "OPT", "not supported");
  expect_error("*RIGIDWALL_GEOMETRIC_FLAT_MOTION\n0\n0,0,0,0,0,1\n1,0,0\n5,0,0,0,0\n",
               "*RIGIDWALL_GEOMETRIC_FLAT_MOTION", "VX", "nonzero");
  expect_error("*RIGIDWALL_GEOMETRIC_FLAT_MOTION\n0\n0,0,0,0,0,1\n1,0,0\n6,0,0,0,1\n",
               "*RIGIDWALL_GEOMETRIC_FLAT_MOTION", "LCID", "not defined");
  expect_error("*RIGIDWALL_GEOMETRIC_CYLINDER_DEFORM\n0\n0,0,0,0,0,1\n1.0\n",
               "*RIGIDWALL_GEOMETRIC_CYLINDER_DEFORM", "", "not supported");
  expect_error("*RIGIDWALL_PLANAR_FORCES\n0\n0,0,0,0,0,1\n3,0\n", "*RIGIDWALL_PLANAR_FORCES",
               "SOFT", "not supported");
  expect_error("*RIGIDWALL_PLANAR_FORCES\n0\n0,0,0,0,0,1\n0,8\n", "*RIGIDWALL_PLANAR_FORCES",
               "SSID", "not defined");
  // The _FORCES card comes after the _FINITE card (read the other way round, "0,1" would be
  // SSID 1, which is not defined).
  expect_error("*RIGIDWALL_PLANAR_FINITE_FORCES\n0\n0,0,0,0,0,1\n0,1,0,1,1\n3,0\n",
               "*RIGIDWALL_PLANAR_FINITE_FORCES card 4 field SOFT", "SOFT", "not supported");
  expect_error("*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,-9,0,5\n0,0\n",
               "*BOUNDARY_PRESCRIBED_MOTION_NODE", "DOF", "not supported");
  expect_error("*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,10,1,5\n0,0\n",
               "*BOUNDARY_PRESCRIBED_MOTION_NODE", "VAD", "not supported");
  expect_error("*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,11,0,5\n0,0,3\n",
               "*BOUNDARY_PRESCRIBED_MOTION_NODE", "LRB", "not supported");
}

}  // namespace
}  // namespace rf::test
