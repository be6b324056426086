// Small SO(3) helpers for the rigid-body integrator: exponential and logarithm maps and
// re-orthonormalisation. Rotation vectors theta: R = exp([theta]x), |theta| = angle.
#pragma once

#include <Eigen/Dense>

namespace rf::rigid {

// Skew-symmetric matrix [a]x with [a]x b = a x b.
Eigen::Matrix3d skew(const Eigen::Vector3d& a);

// Rodrigues' formula R = I + sin(t)/t [theta] + (1 - cos(t))/t^2 [theta]^2, t = |theta|,
// with Taylor series for small t so that round-off does not depend on the angle.
Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& theta);

// Inverse of rotation_from_vector for angles below pi: via the unit quaternion, which is
// accurate for small angles (unlike acos of the trace).
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& rotation);

// One Newton step towards the polar factor, R <- R (3 I - R^T R) / 2. Near-orthogonal input
// (round-off level) converges quadratically, so one step per cycle keeps R^T R = I to
// machine precision forever instead of letting products of rotations random-walk away.
Eigen::Matrix3d orthonormalise(const Eigen::Matrix3d& rotation);

}  // namespace rf::rigid
