// Torque-free rotation of an asymmetric body near its unstable (intermediate) axis, checked
// against an independent high-accuracy integration of Euler's equations in body axes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "rigid/rigid_body.hpp"
#include "rigid/so3.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using rf::rigid::RigidBodyState;

const Vector3d kInertia(1.0, 2.0, 3.0);
const Vector3d kOmega0(0.01, 1.0, 0.01);  // near the intermediate axis: flips every ~30 s

// Euler's equations J W' = (J W) x W in body axes, classical RK4 (the reference).
Vector3d euler_rate(const Vector3d& w) {
  return (kInertia.cwiseProduct(w)).cross(w).cwiseQuotient(kInertia);
}
Vector3d rk4_step(const Vector3d& w, double h) {
  const Vector3d k1 = euler_rate(w);
  const Vector3d k2 = euler_rate(w + 0.5 * h * k1);
  const Vector3d k3 = euler_rate(w + 0.5 * h * k2);
  const Vector3d k4 = euler_rate(w + h * k3);
  return w + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

RigidBodyState make_spinning_body() {
  RigidBodyState body;
  body.mass = 1.0;
  body.principal_inertia = kInertia;
  body.rotation = Matrix3d::Identity();
  rf::rigid::set_velocity(body, Vector3d::Zero(), kOmega0);
  return body;
}

Vector3d body_angular_velocity(const RigidBodyState& b) {
  return (b.rotation.transpose() * b.angular_momentum).cwiseQuotient(b.principal_inertia);
}

double rotational_energy(const RigidBodyState& b) {
  const Vector3d pi = b.rotation.transpose() * b.angular_momentum;
  return 0.5 * pi.dot(pi.cwiseQuotient(b.principal_inertia));
}

// Max over the samples t = k * sample_dt of |W - W_ref| with the scheme at step dt.
double max_error_against_reference(double dt, double end_time) {
  constexpr double kSample = 0.5;
  constexpr int kReferenceSubsteps = 5000;  // h = 1e-4: RK4 error ~1e-13, far below ours
  const int samples = static_cast<int>(std::lround(end_time / kSample));
  const int steps_per_sample = static_cast<int>(std::lround(kSample / dt));
  RigidBodyState body = make_spinning_body();
  Vector3d reference = kOmega0;
  double max_error = 0.0;
  for (int s = 0; s < samples; ++s) {
    for (int k = 0; k < steps_per_sample; ++k) {
      rf::rigid::advance_rigid_body(body, Vector3d::Zero(), Vector3d::Zero(), dt, dt);
    }
    for (int k = 0; k < kReferenceSubsteps; ++k) {
      reference = rk4_step(reference, kSample / kReferenceSubsteps);
    }
    max_error = std::max(max_error, (body_angular_velocity(body) - reference).norm());
  }
  return max_error;
}

TEST(RigidFreeRotation, ReferenceIsConverged) {
  // The reference itself: halving its step changes it by far less than the errors we test.
  Vector3d a = kOmega0, b = kOmega0;
  for (int k = 0; k < 200000; ++k) a = rk4_step(a, 5e-4);
  for (int k = 0; k < 400000; ++k) b = rk4_step(b, 2.5e-4);
  EXPECT_LT((a - b).norm(), 1e-10);
  // And it does flip: W_2 changes sign within 100 s.
  Vector3d w = kOmega0;
  double min_w2 = 1.0;
  for (int k = 0; k < 100000; ++k) {
    w = rk4_step(w, 1e-3);
    min_w2 = std::min(min_w2, w.y());
  }
  EXPECT_LT(min_w2, -0.9);
}

TEST(RigidFreeRotation, MatchesEulerEquationsWithSecondOrderConvergence) {
  constexpr double kEnd = 100.0;  // about three flips of the intermediate axis
  const double e1 = max_error_against_reference(4e-3, kEnd);
  const double e2 = max_error_against_reference(2e-3, kEnd);
  const double e3 = max_error_against_reference(1e-3, kEnd);
  std::printf(
      "[ measured ] max |W - W_ref| over 100 s: dt=4e-3 %.3e, 2e-3 %.3e, 1e-3 %.3e;"
      " ratios %.3f %.3f\n",
      e1, e2, e3, e1 / e2, e2 / e3);
  EXPECT_LT(e3, 1e-4);
  EXPECT_NEAR(e1 / e2, 4.0, 0.4);
  EXPECT_NEAR(e2 / e3, 4.0, 0.4);
}

TEST(RigidFreeRotation, MomentumExactEnergyBoundedOverHundredThousandSteps) {
  constexpr double kDt = 0.01;
  constexpr int kSteps = 100000;  // 1000 s, about 30 flips
  RigidBodyState body = make_spinning_body();
  const Vector3d l0 = body.angular_momentum;
  const double e0 = rotational_energy(body);
  double max_drift_first_quarter = 0.0, max_drift_last_quarter = 0.0;
  double max_momentum_error = 0.0, max_orthogonality_error = 0.0;
  double max_w_gap = 0.0;
  for (int n = 0; n < kSteps; ++n) {
    const Matrix3d r_old = body.rotation;
    rf::rigid::advance_rigid_body(body, Vector3d::Zero(), Vector3d::Zero(), kDt, kDt);
    const double drift = std::abs(rotational_energy(body) - e0) / e0;
    if (n < kSteps / 4) max_drift_first_quarter = std::max(max_drift_first_quarter, drift);
    if (n >= 3 * kSteps / 4) max_drift_last_quarter = std::max(max_drift_last_quarter, drift);
    // L through the body-frame momentum: |R^T L| = |L| tests that R stays a rotation.
    const Vector3d body_momentum = body.rotation.transpose() * body.angular_momentum;
    max_momentum_error =
        std::max(max_momentum_error, std::abs(body_momentum.norm() - l0.norm()) / l0.norm());
    max_momentum_error =
        std::max(max_momentum_error, (body.angular_momentum - l0).norm() / l0.norm());
    max_orthogonality_error =
        std::max(max_orthogonality_error,
                 (body.rotation.transpose() * body.rotation - Matrix3d::Identity()).norm());
    // Stored w (mean of the step) vs R J^-1 R^T L at the geodesic midpoint: O(dt^2).
    const Matrix3d r_mid =
        rf::rigid::rotation_from_vector(0.5 * kDt * body.angular_velocity) * r_old;
    const Vector3d w_mid = rf::rigid::angular_velocity_from_momentum(r_mid, body.principal_inertia,
                                                                     body.angular_momentum);
    max_w_gap = std::max(max_w_gap, (body.angular_velocity - w_mid).norm() / w_mid.norm());
  }
  std::printf(
      "[ measured ] dt=0.01, 1e5 steps: max |dE|/E first quarter %.3e, last quarter"
      " %.3e; max rel. error |L|, L %.3e; |R^T R - I| %.3e; |w - w_mid|/|w| %.3e\n",
      max_drift_first_quarter, max_drift_last_quarter, max_momentum_error, max_orthogonality_error,
      max_w_gap);
  EXPECT_LT(max_momentum_error, 1e-12);
  EXPECT_LT(max_orthogonality_error, 1e-13);
  // Bounded, O(dt^2) energy error; no secular growth between the first and last quarters.
  EXPECT_LT(max_drift_first_quarter, 1e-3);
  EXPECT_LT(max_drift_last_quarter, 1.5 * max_drift_first_quarter);
  EXPECT_LT(max_w_gap, 1e-3);
}

TEST(RigidFreeRotation, SteadySpinAboutPrincipalAxisIsExact) {
  RigidBodyState body = make_spinning_body();
  rf::rigid::set_velocity(body, Vector3d::Zero(), Vector3d(0.0, 0.0, 2.0));
  constexpr double kDt = 0.01;
  for (int n = 0; n < 1000; ++n) {
    rf::rigid::advance_rigid_body(body, Vector3d::Zero(), Vector3d::Zero(), kDt, kDt);
  }
  const Matrix3d expected = rf::rigid::rotation_from_vector(Vector3d(0.0, 0.0, 2.0 * 10.0));
  EXPECT_LT((body.rotation - expected).norm(), 1e-12);
  EXPECT_LT((body.angular_velocity - Vector3d(0.0, 0.0, 2.0)).norm(), 1e-12);
}

TEST(RigidSo3, ExpLogRoundTrip) {
  for (const Vector3d& theta : {Vector3d(1e-9, -2e-9, 3e-9), Vector3d(1e-5, 0.0, -2e-5),
                                Vector3d(0.3, -0.2, 0.1), Vector3d(1.0, 2.0, -0.5)}) {
    const Matrix3d r = rf::rigid::rotation_from_vector(theta);
    EXPECT_LT((r.transpose() * r - Matrix3d::Identity()).norm(), 1e-15);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-15);
    EXPECT_LT((rf::rigid::rotation_vector(r) - theta).norm(), 1e-15 + 1e-14 * theta.norm());
    // Against Eigen's own angle-axis.
    const Matrix3d eigen_r = Eigen::AngleAxisd(theta.norm(), theta.normalized()).toRotationMatrix();
    EXPECT_LT((r - eigen_r).norm(), 1e-15);
  }
}

}  // namespace
