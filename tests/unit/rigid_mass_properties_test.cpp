// Creation of rigid bodies from point masses and from a given inertia tensor, and gathering
// of nodal forces into a resultant force and torque.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rigid/rigid_body.hpp"
#include "rigid/so3.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// A 3 x 4 x 5 grid of equal point masses with spacings 0.3, 0.5, 0.7, turned by `rotation`
// and moved to `offset`. In box axes the second moment about the centre along axis a is
// S_a = m N h_a^2 (n_a^2 - 1) / 12 (sum of squares of a centred arithmetic sequence).
struct Grid {
  std::array<int, 3> count = {3, 4, 5};
  Vector3d spacing = Vector3d(0.3, 0.5, 0.7);
  double point_mass = 0.25;
  std::vector<double> masses;
  std::vector<Vector3d> positions;
};

Grid make_grid(const Matrix3d& rotation, const Vector3d& offset) {
  Grid g;
  for (int i = 0; i < g.count[0]; ++i) {
    for (int j = 0; j < g.count[1]; ++j) {
      for (int k = 0; k < g.count[2]; ++k) {
        const Vector3d local((i - 0.5 * (g.count[0] - 1)) * g.spacing[0],
                             (j - 0.5 * (g.count[1] - 1)) * g.spacing[1],
                             (k - 0.5 * (g.count[2] - 1)) * g.spacing[2]);
        g.masses.push_back(g.point_mass);
        g.positions.push_back(offset + rotation * local);
      }
    }
  }
  return g;
}

TEST(RigidMassProperties, RotatedGridOfPointMassesMatchesAnalyticInertia) {
  const Matrix3d rotation = rf::rigid::rotation_from_vector(Vector3d(0.3, -0.7, 1.1));
  const Vector3d offset(1000.0, -2000.0, 500.0);  // far from the origin on purpose
  const Grid g = make_grid(rotation, offset);
  const double n_total = static_cast<double>(g.masses.size());
  Vector3d second_moment;
  for (int a = 0; a < 3; ++a) {
    const double n = g.count[a];
    second_moment[a] = g.point_mass * n_total * g.spacing[a] * g.spacing[a] * (n * n - 1) / 12;
  }
  const Vector3d box_inertia(second_moment[1] + second_moment[2],
                             second_moment[0] + second_moment[2],
                             second_moment[0] + second_moment[1]);
  const Matrix3d expected_inertia = rotation * box_inertia.asDiagonal() * rotation.transpose();

  const auto body = rf::rigid::make_rigid_body(g.masses, g.positions);
  EXPECT_NEAR(body.mass, g.point_mass * n_total, 1e-13);
  EXPECT_LT((body.centre - offset).norm(), 1e-10);
  EXPECT_LT((rf::rigid::global_inertia(body) - expected_inertia).norm(),
            1e-10 * expected_inertia.norm());

  // Principal axes: ascending moments, each a (signed) box axis, a proper rotation.
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return box_inertia[a] < box_inertia[b]; });
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(body.principal_inertia[k], box_inertia[order[k]], 1e-10 * box_inertia.norm());
    EXPECT_NEAR(std::abs(body.rotation.col(k).dot(rotation.col(order[k]))), 1.0, 1e-12);
  }
  EXPECT_NEAR(body.rotation.determinant(), 1.0, 1e-14);
  EXPECT_LT((body.rotation.transpose() * body.rotation - Matrix3d::Identity()).norm(), 1e-14);
}

TEST(RigidMassProperties, UnequalMassesMatchParallelAxisTheorem) {
  // Independent route: inertia about the origin, shifted to the centre by parallel axes.
  std::vector<double> m = {1.0, 2.5, 0.3, 4.0, 1.7};
  std::vector<Vector3d> x = {Vector3d(0.1, 0.2, 0.3), Vector3d(-1.0, 0.5, 2.0),
                             Vector3d(0.7, -0.4, 0.0), Vector3d(1.5, 1.5, -1.0),
                             Vector3d(-0.3, -2.0, 0.9)};
  double mass = 0.0;
  Vector3d moment = Vector3d::Zero();
  Matrix3d inertia_origin = Matrix3d::Zero();
  for (std::size_t i = 0; i < m.size(); ++i) {
    mass += m[i];
    moment += m[i] * x[i];
    inertia_origin += m[i] * (x[i].squaredNorm() * Matrix3d::Identity() - x[i] * x[i].transpose());
  }
  const Vector3d c = moment / mass;
  const Matrix3d expected =
      inertia_origin - mass * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose());
  const auto p = rf::rigid::mass_properties(m, x);
  EXPECT_NEAR(p.mass, mass, 1e-14);
  EXPECT_LT((p.centre - c).norm(), 1e-14);
  EXPECT_LT((p.inertia - expected).norm(), 1e-13);

  // The struct-of-arrays overload on an index subset gives the same.
  std::vector<double> sx, sy, sz, sm;
  std::vector<std::int32_t> nodes;
  sm.push_back(99.0), sx.push_back(9.0), sy.push_back(9.0), sz.push_back(9.0);  // not listed
  for (std::size_t i = 0; i < m.size(); ++i) {
    nodes.push_back(static_cast<std::int32_t>(sm.size()));
    sm.push_back(m[i]), sx.push_back(x[i].x()), sy.push_back(x[i].y()), sz.push_back(x[i].z());
  }
  const auto q = rf::rigid::mass_properties(nodes, sm.data(), sx.data(), sy.data(), sz.data());
  EXPECT_LT((q.inertia - expected).norm(), 1e-13);
  EXPECT_LT((q.centre - c).norm(), 1e-14);
}

TEST(RigidMassProperties, PartInertiaVariantKeepsGivenTensor) {
  Matrix3d inertia;
  inertia << 4.0, -0.5, 0.2, -0.5, 3.0, 0.1, 0.2, 0.1, 5.0;
  const auto body = rf::rigid::make_rigid_body(12.0, Vector3d(1, 2, 3), inertia);
  EXPECT_EQ(body.mass, 12.0);
  EXPECT_LT((rf::rigid::global_inertia(body) - inertia).norm(), 1e-13);
  EXPECT_NEAR(body.rotation.determinant(), 1.0, 1e-14);
  EXPECT_LE(body.principal_inertia[0], body.principal_inertia[1]);
  EXPECT_LE(body.principal_inertia[1], body.principal_inertia[2]);
  EXPECT_THROW(rf::rigid::make_rigid_body(0.0, Vector3d::Zero(), inertia), std::invalid_argument);
  EXPECT_THROW(rf::rigid::make_rigid_body(1.0, Vector3d::Zero(), Matrix3d::Zero()),
               std::invalid_argument);
}

struct Forces {
  std::vector<double> x, y, z, fx, fy, fz;
  std::int32_t add(const Vector3d& p, const Vector3d& f) {
    x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z());
    fx.push_back(f.x()), fy.push_back(f.y()), fz.push_back(f.z());
    return static_cast<std::int32_t>(x.size() - 1);
  }
  rf::rigid::ForceAndTorque gather(const Vector3d& c, const std::vector<std::int32_t>& nodes) {
    return rf::rigid::gather_force_and_torque(c, nodes, fx.data(), fy.data(), fz.data(), x.data(),
                                              y.data(), z.data());
  }
};

TEST(RigidGather, CoupleGivesPureTorque) {
  const Vector3d c(5.0, -1.0, 2.0);
  const Vector3d a(0.3, 0.0, 0.4);
  const Vector3d f(0.0, 7.0, 0.0);
  Forces s;
  s.add(Vector3d(100, 100, 100), Vector3d(1e6, 0, 0));  // a node of another part
  const std::vector<std::int32_t> nodes = {s.add(c + a, f), s.add(c - a, -f)};
  const auto ft = s.gather(c, nodes);
  EXPECT_LT(ft.force.norm(), 1e-14);
  // 2 a x f = 2 (0.3, 0, 0.4) x (0, 7, 0) = (-5.6, 0, 4.2); independent of the centre.
  EXPECT_LT((ft.torque - Vector3d(-5.6, 0.0, 4.2)).norm(), 1e-13);
  EXPECT_LT((s.gather(Vector3d(9, 9, 9), nodes).torque - Vector3d(-5.6, 0.0, 4.2)).norm(), 1e-12);
}

TEST(RigidGather, ForceThroughCentreGivesNoTorque) {
  const Vector3d c(1.0, 2.0, 3.0);
  const Vector3d f(2.0, -1.0, 0.5);
  Forces s;
  const std::vector<std::int32_t> nodes = {s.add(c + 0.7 * f, 0.4 * f), s.add(c - 2.0 * f, 0.6 * f),
                                           s.add(c, Vector3d::Zero())};
  const auto ft = s.gather(c, nodes);
  EXPECT_LT((ft.force - f).norm(), 1e-15);
  EXPECT_LT(ft.torque.norm(), 1e-14);
  // Off the line of action by d = (0, 0, 1) x-wise: T = d x F.
  const auto shifted = s.gather(c - Vector3d(0, 0, 1), nodes);
  EXPECT_LT((shifted.torque - Vector3d(0, 0, 1).cross(f)).norm(), 1e-14);
}

TEST(RigidGather, NodeVelocitiesAreRigid) {
  std::vector<double> x = {1.0, 0.0, 2.0}, y = {0.0, 1.0, 2.0}, z = {0.0, 0.0, 2.0};
  std::vector<double> vx(3, -1.0), vy(3, -1.0), vz(3, -1.0);
  rf::rigid::rigid_node_velocities(Vector3d(1, 0, 0), Vector3d(0, 0, 2), Vector3d::Zero(), {0, 1},
                                   x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data());
  EXPECT_DOUBLE_EQ(vx[0], 1.0);
  EXPECT_DOUBLE_EQ(vy[0], 2.0);   // w x (1,0,0) = (0,2,0)
  EXPECT_DOUBLE_EQ(vx[1], -1.0);  // 1 + w x (0,1,0) = 1 - 2
  EXPECT_DOUBLE_EQ(vy[1], 0.0);
  EXPECT_DOUBLE_EQ(vx[2], -1.0);  // not listed: untouched
}

}  // namespace
