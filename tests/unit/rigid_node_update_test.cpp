// Curvilinear vs linear update of the nodes of a rotating rigid body (the IMPETUS
// *RIGID_BODY_UPDATE trade-off): the first is exactly rigid, the second moves each node on
// the tangent, |r + dt w x r| = r sqrt(1 + (w dt)^2), i.e. outward by ~ r (w dt)^2 / 2 a step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "rigid/rigid_body.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

struct Cloud {
  std::vector<double> x, y, z, m;
  std::vector<std::int32_t> nodes;
};

// Corners and face centres of a 2 x 1 x 0.6 box, unequal masses: an asymmetric body.
Cloud make_cloud() {
  Cloud c;
  const double hx = 1.0, hy = 0.5, hz = 0.3;
  int k = 0;
  for (int i : {-1, 1}) {
    for (int j : {-1, 1}) {
      for (int l : {-1, 1}) {
        c.x.push_back(i * hx + 0.1), c.y.push_back(j * hy - 0.2), c.z.push_back(l * hz + 0.3);
        c.m.push_back(1.0 + 0.1 * k++);
      }
    }
  }
  for (int i = 0; i < static_cast<int>(c.x.size()); ++i) c.nodes.push_back(i);
  return c;
}

double max_pairwise_distance_change(const Cloud& now, const Cloud& ref) {
  double worst = 0.0;
  for (std::size_t a = 0; a < now.x.size(); ++a) {
    for (std::size_t b = a + 1; b < now.x.size(); ++b) {
      const Vector3d d_now(now.x[a] - now.x[b], now.y[a] - now.y[b], now.z[a] - now.z[b]);
      const Vector3d d_ref(ref.x[a] - ref.x[b], ref.y[a] - ref.y[b], ref.z[a] - ref.z[b]);
      worst = std::max(worst, std::abs(d_now.norm() - d_ref.norm()) / d_ref.norm());
    }
  }
  return worst;
}

TEST(RigidNodeUpdate, CurvilinearStaysRigidLinearGrows) {
  const Cloud initial = make_cloud();
  auto body = rf::rigid::make_rigid_body(rf::rigid::mass_properties(
      initial.nodes, initial.m.data(), initial.x.data(), initial.y.data(), initial.z.data()));
  const auto coords = rf::rigid::body_coordinates(body, initial.nodes, initial.x.data(),
                                                  initial.y.data(), initial.z.data());
  // Tumbling with translation: |w| dt ~ 0.01 rad a step, 10^4 steps = ~16 turns.
  rf::rigid::set_velocity(body, Vector3d(0.3, -0.1, 0.2), Vector3d(1.0, 4.0, 2.5));
  constexpr double kDt = 2e-3;
  Cloud curvilinear = initial, linear = initial;
  for (int n = 0; n < 10000; ++n) {
    rf::rigid::advance_rigid_body(body, Vector3d::Zero(), Vector3d::Zero(), kDt, kDt);
    rf::rigid::place_nodes_curvilinear(body, curvilinear.nodes, coords, curvilinear.x.data(),
                                       curvilinear.y.data(), curvilinear.z.data());
    rf::rigid::advance_nodes_linear(body, linear.nodes, kDt, linear.x.data(), linear.y.data(),
                                    linear.z.data());
  }
  const double curvilinear_change = max_pairwise_distance_change(curvilinear, initial);
  const double linear_change = max_pairwise_distance_change(linear, initial);
  std::printf(
      "[ measured ] 1e4 tumbling steps, |w|dt = %.4f: max relative change of node"
      " distances curvilinear %.2e, linear %.2e\n",
      body.angular_velocity.norm() * kDt, curvilinear_change, linear_change);
  EXPECT_LT(curvilinear_change, 1e-12);
  EXPECT_GT(linear_change, 0.05);
  // Both follow the same centre of mass.
  const auto cm =
      rf::rigid::mass_properties(curvilinear.nodes, curvilinear.m.data(), curvilinear.x.data(),
                                 curvilinear.y.data(), curvilinear.z.data());
  EXPECT_LT((cm.centre - body.centre).norm(), 1e-12);
}

TEST(RigidNodeUpdate, LinearDriftMatchesTangentFormula) {
  // Steady spin about the major principal axis: w is exactly constant, so the drift of each
  // node's distance r from the axis is the pure tangent effect.
  const Cloud initial = make_cloud();
  auto body = rf::rigid::make_rigid_body(rf::rigid::mass_properties(
      initial.nodes, initial.m.data(), initial.x.data(), initial.y.data(), initial.z.data()));
  const Vector3d axis = body.rotation.col(2);
  constexpr double kRate = 5.0, kDt = 2e-3;  // w dt = 0.01
  constexpr int kSteps = 10000;
  rf::rigid::set_velocity(body, Vector3d::Zero(), kRate * axis);
  const Vector3d centre = body.centre;
  auto radius = [&](const Cloud& c, int i) {
    const Vector3d r = Vector3d(c.x[i], c.y[i], c.z[i]) - centre;
    return (r - r.dot(axis) * axis).norm();
  };
  Cloud linear = initial;
  double first_step_growth = 0.0;
  for (int n = 0; n < kSteps; ++n) {
    rf::rigid::advance_rigid_body(body, Vector3d::Zero(), Vector3d::Zero(), kDt, kDt);
    rf::rigid::advance_nodes_linear(body, linear.nodes, kDt, linear.x.data(), linear.y.data(),
                                    linear.z.data());
    if (n == 0) first_step_growth = radius(linear, 0) - radius(initial, 0);
  }
  const double wdt = kRate * kDt;
  const double r0 = radius(initial, 0);
  const double predicted_first = r0 * wdt * wdt / 2.0;
  // Per-step logarithmic growth, measured over all 10^4 steps, vs (w dt)^2 / 2.
  const double measured_rate = std::log(radius(linear, 0) / r0) / kSteps;
  std::printf(
      "[ measured ] steady spin w dt = %.3f, r0 = %.4f: first-step outward drift %.4e"
      " (r (w dt)^2/2 = %.4e); mean growth per step %.5e (formula %.5e); r grew x%.4f"
      " in 1e4 steps\n",
      wdt, r0, first_step_growth, predicted_first, measured_rate, wdt * wdt / 2.0,
      radius(linear, 0) / r0);
  EXPECT_NEAR(first_step_growth, predicted_first, 1e-3 * predicted_first);
  EXPECT_NEAR(measured_rate, wdt * wdt / 2.0, 1e-3 * wdt * wdt / 2.0);
  // The component along the axis does not drift.
  for (int i : initial.nodes) {
    const Vector3d r0v = Vector3d(initial.x[i], initial.y[i], initial.z[i]) - centre;
    const Vector3d r1v = Vector3d(linear.x[i], linear.y[i], linear.z[i]) - centre;
    EXPECT_NEAR(r1v.dot(axis), r0v.dot(axis), 1e-12);
  }
}

}  // namespace
