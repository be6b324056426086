#pragma once
// Small 3-vector helpers on std::array for geometric kernels (surface tests, contact
// projections) that work on plain coordinates rather than Eigen types.
#include <array>
#include <cmath>

namespace rf::mesh {

using Vec = std::array<double, 3>;

inline Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double norm(const Vec& a) {
  return std::sqrt(dot(a, a));
}

}  // namespace rf::mesh
