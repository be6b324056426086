// A rigid body under gravity hung from a pivot (a very stiff spring between a body point and
// a fixed point), driven through advance_rigid_body with the gathered force and torque; and
// the CMO-style hinge constraint.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "rigid/rigid_body.hpp"
#include "rigid/so3.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

TEST(RigidPendulum, SmallAmplitudePeriodMatchesPhysicalPendulum) {
  constexpr double kMass = 1.0, kGravity = 9.81, kArm = 0.5, kStiffness = 1e6;
  constexpr double kAmplitude = 0.01, kDt = 1e-4;
  Matrix3d inertia_centre = Matrix3d::Zero();
  inertia_centre.diagonal() << 1.0 / 12.0, 0.15, 0.02;  // swing about global x
  const Vector3d pivot = Vector3d::Zero();
  // Start tilted by the amplitude about x, at rest; spring unstretched.
  const Matrix3d tilt = rf::rigid::rotation_from_vector(Vector3d(kAmplitude, 0.0, 0.0));
  auto body = rf::rigid::make_rigid_body(kMass, Vector3d(0.0, 0.0, -kArm), inertia_centre);
  const Vector3d attachment_body = body.rotation.transpose() * (pivot - body.centre);
  body.rotation = tilt * body.rotation;
  body.centre = tilt * body.centre;
  body.previous_centre = body.centre;

  const double inertia_pivot = inertia_centre(0, 0) + kMass * kArm * kArm;
  const double expected_period =
      2.0 * std::numbers::pi * std::sqrt(inertia_pivot / (kMass * kGravity * kArm));

  std::vector<double> crossings;  // times of upward zero crossings of the swing angle
  double angle_old = kAmplitude;
  double max_off_plane = 0.0;
  const int steps = static_cast<int>(3.6 * expected_period / kDt);
  for (int n = 0; n < steps; ++n) {
    const Vector3d attachment = body.centre + body.rotation * attachment_body;
    const Vector3d spring_force = -kStiffness * (attachment - pivot);
    const Vector3d force = spring_force + Vector3d(0.0, 0.0, -kMass * kGravity);
    const Vector3d torque = (attachment - body.centre).cross(spring_force);
    rf::rigid::advance_rigid_body(body, force, torque, kDt, kDt);
    const double angle = std::atan2(body.centre.y(), -body.centre.z());
    if (angle_old < 0.0 && angle >= 0.0) {
      crossings.push_back((n + angle / (angle - angle_old)) * kDt);  // linear interpolation
    }
    angle_old = angle;
    max_off_plane = std::max(max_off_plane, std::abs(body.centre.x()));
  }
  ASSERT_GE(crossings.size(), 3u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double relative_error = std::abs(period - expected_period) / expected_period;
  std::printf(
      "[ measured ] pendulum period %.7f s, 2 pi sqrt(I_pivot/(m g d)) = %.7f s,"
      " relative error %.2e\n",
      period, expected_period, relative_error);
  // Expected deviations: amplitude theta0^2/16 = 6e-6, pivot compliance ~ (w_p/w_s)^2 ~ 1e-5.
  EXPECT_LT(relative_error, 1e-4);
  EXPECT_LT(max_off_plane, 1e-12);
}

TEST(RigidPendulum, HingeConstraintTurnsAboutFixedAxisWithExactRate) {
  // A body whose principal axes are skewed to the hinge axis z: products of inertia make the
  // held rotational DOFs carry a reaction; the free one integrates I_zz w_z' = T_z exactly.
  Matrix3d inertia;
  inertia << 2.0, 0.3, -0.4, 0.3, 3.0, 0.2, -0.4, 0.2, 4.0;
  auto body = rf::rigid::make_rigid_body(5.0, Vector3d(1, 1, 1), inertia);
  body.constraints.fix_global_translation({true, true, true});
  body.constraints.fix_global_rotation({true, true, false});
  const Matrix3d rotation0 = body.rotation;
  constexpr double kTorque = 0.8, kDt = 1e-3;
  double angle = 0.0;
  for (int n = 0; n < 5000; ++n) {
    rf::rigid::advance_rigid_body(body, Vector3d(1, 2, 3), Vector3d(0.5, -0.5, kTorque), kDt, kDt);
    const double rate = kTorque * (n + 1) * kDt / inertia(2, 2);
    ASSERT_NEAR(body.angular_velocity.z(), rate, 1e-12 * (1.0 + rate));
    angle += kDt * rate;
  }
  EXPECT_EQ(body.angular_velocity.x(), 0.0);
  EXPECT_EQ(body.angular_velocity.y(), 0.0);
  EXPECT_EQ(body.velocity.norm(), 0.0);
  EXPECT_LT((body.centre - Vector3d(1, 1, 1)).norm(), 1e-15);
  const Matrix3d expected = rf::rigid::rotation_from_vector(Vector3d(0, 0, angle)) * rotation0;
  EXPECT_LT((body.rotation - expected).norm(), 1e-10);
  // L = I w with I at the mid rotation of the step: the reaction took up the held components.
  const Matrix3d rotation_mid =
      rf::rigid::rotation_from_vector(-0.5 * kDt * body.angular_velocity) * body.rotation;
  const Matrix3d inertia_mid =
      rotation_mid * body.principal_inertia.asDiagonal() * rotation_mid.transpose();
  EXPECT_LT((body.angular_momentum - inertia_mid * body.angular_velocity).norm(), 1e-12);
  EXPECT_GT(body.reaction_angular_impulse.head<2>().norm(), 0.0);
  EXPECT_NEAR(body.reaction_angular_impulse.z(), 0.0, 1e-15);
}

}  // namespace
