// Small vector helpers for building local coordinate systems from keyword data.
#pragma once

#include <array>
#include <cmath>
#include <optional>

namespace rf::io {

using Vec3 = std::array<double, 3>;
using Axes = std::array<Vec3, 3>;  // rows: local x, y, z in global coordinates

inline Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

inline double length(const Vec3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// Unit vector, or nullopt for a zero or non-finite vector.
inline std::optional<Vec3> unit(const Vec3& a) {
  const double l = length(a);
  if (!(l > 0.0) || !std::isfinite(l)) return std::nullopt;
  return Vec3{a[0] / l, a[1] / l, a[2] / l};
}

// The LS-DYNA construction of a local system from two directions: local axis `axis`
// (0, 1, 2 for x, y, z) along `primary`; `in_plane` lies in the plane of that axis and the
// cyclically next one (x-y for x, y-z for y, z-x for z). The third axis is
// primary x in_plane, and the second completes a right-handed set. nullopt when primary is
// zero or the two directions are (nearly) parallel.
inline std::optional<Axes> axes_from(const Vec3& primary, const Vec3& in_plane, int axis) {
  const auto a = unit(primary);
  const auto q = unit(in_plane);
  if (!a || !q) return std::nullopt;
  const Vec3 n = cross(*a, *q);
  // Relative to unit vectors, so the test does not depend on the model's length unit.
  if (!(length(n) > 1e-9)) return std::nullopt;
  Axes e{};
  e[axis] = *a;
  e[(axis + 2) % 3] = *unit(n);
  e[(axis + 1) % 3] = cross(e[(axis + 2) % 3], e[axis]);
  return e;
}

// Components given in a local system -> global components (a direction, no origin shift).
inline Vec3 to_global(const Axes& axes, const Vec3& local) {
  Vec3 g{};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) g[k] += local[i] * axes[i][k];
  }
  return g;
}

}  // namespace rf::io
