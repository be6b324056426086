#include "rigid/so3.hpp"

#include <cmath>

namespace rf::rigid {

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& theta) {
  const double t2 = theta.squaredNorm();
  double a = 0.0;  // sin(t) / t
  double b = 0.0;  // (1 - cos(t)) / t^2
  if (t2 < 1e-8) {
    // Taylor series; the next terms are below 1e-17 for t < 1e-4.
    a = 1.0 - t2 / 6.0;
    b = 0.5 - t2 / 24.0;
  } else {
    const double t = std::sqrt(t2);
    a = std::sin(t) / t;
    const double half_sine = std::sin(0.5 * t);
    b = 2.0 * half_sine * half_sine / t2;  // 1 - cos t = 2 sin^2(t/2), no cancellation
  }
  const Eigen::Matrix3d k = skew(theta);
  return Eigen::Matrix3d::Identity() + a * k + b * (k * k);
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& rotation) {
  Eigen::Quaterniond q(rotation);
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // the short way round
  const Eigen::Vector3d v = q.vec();
  const double s = v.norm();              // sin(angle / 2)
  if (s < 1e-12) return 2.0 * v / q.w();  // angle/2 ~ sin(angle/2); error O(s^3)
  const double angle = 2.0 * std::atan2(s, q.w());
  return v * (angle / s);
}

Eigen::Matrix3d orthonormalise(const Eigen::Matrix3d& rotation) {
  return 0.5 * rotation * (3.0 * Eigen::Matrix3d::Identity() - rotation.transpose() * rotation);
}

}  // namespace rf::rigid
