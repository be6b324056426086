#include "mesh/component.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

namespace rf::mesh {

namespace {

using Point2 = std::array<double, 2>;

// Cell key of a point on a grid of spacing h (for merging coincident points).
struct CellKey {
  std::int64_t i, j, k;
  bool operator==(const CellKey&) const = default;
};
struct CellHash {
  std::size_t operator()(const CellKey& c) const {
    // Unsigned: the products wrap instead of overflowing.
    return static_cast<std::size_t>(static_cast<std::uint64_t>(c.i) * 73856093ULL ^
                                    static_cast<std::uint64_t>(c.j) * 19349663ULL ^
                                    static_cast<std::uint64_t>(c.k) * 83492791ULL);
  }
};
// Callers choose h so that |x / h| stays far below 2^63 (see nearest_within).
CellKey cell_of(const std::array<double, 3>& x, double h) {
  return {static_cast<std::int64_t>(std::floor(x[0] / h)),
          static_cast<std::int64_t>(std::floor(x[1] / h)),
          static_cast<std::int64_t>(std::floor(x[2] / h))};
}

// Generated coordinates overflow when the input is near the range of double.
void check_finite(const GeneratedMesh& mesh) {
  for (const auto& x : mesh.nodes) {
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) {
      throw std::invalid_argument(
          "the generated node coordinates overflow (the dimensions are too large)");
    }
  }
}

// Collects 2D points, merging those closer than tol (block boundaries are generated twice).
class PointPool {
 public:
  explicit PointPool(double tol) : tol_(tol) {}
  std::int32_t add(const Point2& p) {
    const std::array<double, 3> x{p[0], p[1], 0.0};
    const CellKey c = cell_of(x, tol_ * 4.0);
    for (std::int64_t di = -1; di <= 1; ++di) {
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        const auto it = cells_.find({c.i + di, c.j + dj, 0});
        if (it == cells_.end()) continue;
        for (std::int32_t index : it->second) {
          if (std::hypot(points_[index][0] - p[0], points_[index][1] - p[1]) < tol_) return index;
        }
      }
    }
    const auto index = static_cast<std::int32_t>(points_.size());
    points_.push_back(p);
    cells_[c].push_back(index);
    return index;
  }
  const std::vector<Point2>& points() const { return points_; }

 private:
  double tol_;
  std::vector<Point2> points_;
  std::unordered_map<CellKey, std::vector<std::int32_t>, CellHash> cells_;
};

}  // namespace

GeneratedMesh generate_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi, int nx,
                           int ny, int nz) {
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("element counts must be >= 1");
  // Node indices are 32-bit.
  if (static_cast<double>(nx + 1) * (ny + 1) * (nz + 1) > 2.0e9) {
    throw std::invalid_argument("too many elements");
  }
  GeneratedMesh mesh;
  const std::array<double, 3> a{std::min(lo[0], hi[0]), std::min(lo[1], hi[1]),
                                std::min(lo[2], hi[2])};
  const std::array<double, 3> b{std::max(lo[0], hi[0]), std::max(lo[1], hi[1]),
                                std::max(lo[2], hi[2])};
  auto id = [&](int i, int j, int k) {
    return static_cast<std::int32_t>(i + (nx + 1) * (j + (ny + 1) * k));
  };
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        mesh.nodes.push_back({a[0] + (b[0] - a[0]) * i / nx, a[1] + (b[1] - a[1]) * j / ny,
                              a[2] + (b[2] - a[2]) * k / nz});
      }
    }
  }
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        mesh.hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                              id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                              id(i, j + 1, k + 1)});
      }
    }
  }
  check_finite(mesh);
  return mesh;
}

GeneratedMesh generate_cylinder(const std::array<double, 3>& p1, const std::array<double, 3>& p2,
                                double radius, const CylinderDivisions& d) {
  if (d.axial < 1 || d.square < 1 || d.radial < 1) {
    throw std::invalid_argument("element counts must be >= 1");
  }
  if (!(radius > 0.0)) throw std::invalid_argument("the radius must be positive");
  // Node indices are 32-bit.
  const double per_layer_estimate =
      (d.square + 1.0) * (d.square + 1.0) + 4.0 * (d.square + 1.0) * (d.radial + 1.0);
  if (per_layer_estimate * (d.axial + 1.0) > 2.0e9)
    throw std::invalid_argument("too many elements");
  std::array<double, 3> axis{p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]};
  const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(length > 0.0)) throw std::invalid_argument("the two end points coincide");
  for (double& c : axis) c /= length;
  // e1, e2 complete the axis to a right-handed frame; e1 is the global axis least aligned with
  // the cylinder, projected, so a z-aligned cylinder gets e1 = x, e2 = y.
  std::array<double, 3> seed{1.0, 0.0, 0.0};
  if (std::abs(axis[0]) > std::abs(axis[1]) && std::abs(axis[0]) > std::abs(axis[2])) {
    seed = {0.0, 1.0, 0.0};
  }
  const double along = seed[0] * axis[0] + seed[1] * axis[1] + seed[2] * axis[2];
  std::array<double, 3> e1{seed[0] - along * axis[0], seed[1] - along * axis[1],
                           seed[2] - along * axis[2]};
  const double n1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (double& c : e1) c /= n1;
  const std::array<double, 3> e2{axis[1] * e1[2] - axis[2] * e1[1],
                                 axis[2] * e1[0] - axis[0] * e1[2],
                                 axis[0] * e1[1] - axis[1] * e1[0]};

  // Cross-section in the unit-radius plane. Half-width of the central square: 0.5 keeps the
  // corner elements of the outer blocks (radial extent 1 - 0.5 sqrt 2 = 0.29) and the
  // mid-side ones (0.5) within a factor 1.7 of each other.
  const int n = d.square;
  const int m = d.radial;
  const double a = 0.5;
  PointPool pool(1e-9);
  std::vector<std::array<std::int32_t, 4>> quads;
  auto add_quad = [&](const Point2& q0, const Point2& q1, const Point2& q2, const Point2& q3) {
    std::array<Point2, 4> q{q0, q1, q2, q3};
    double area2 = 0.0;
    for (int i = 0; i < 4; ++i) {
      const Point2& u = q[i];
      const Point2& v = q[(i + 1) % 4];
      area2 += u[0] * v[1] - v[0] * u[1];
    }
    if (area2 < 0.0) std::swap(q[1], q[3]);  // counter-clockwise about the axis
    quads.push_back({pool.add(q[0]), pool.add(q[1]), pool.add(q[2]), pool.add(q[3])});
  };
  auto square_point = [&](int i, int j) {
    return Point2{a * (-1.0 + 2.0 * i / n), a * (-1.0 + 2.0 * j / n)};
  };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      add_quad(square_point(i, j), square_point(i + 1, j), square_point(i + 1, j + 1),
               square_point(i, j + 1));
    }
  }
  // Outer block on the +x side, rotated by quarter turns (exact: swaps and sign changes).
  auto outer_point = [&](int i, int j, int quarter) {
    const double u = -1.0 + 2.0 * i / n;
    const double v = static_cast<double>(j) / m;
    const double theta = u * std::numbers::pi / 4.0;
    const Point2 inner{a, a * u};
    const Point2 outer{std::cos(theta), std::sin(theta)};
    Point2 p{(1.0 - v) * inner[0] + v * outer[0], (1.0 - v) * inner[1] + v * outer[1]};
    if (j == m) p = outer;  // exactly on the circle
    for (int r = 0; r < quarter; ++r) p = Point2{-p[1], p[0]};
    return p;
  };
  for (int quarter = 0; quarter < 4; ++quarter) {
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < n; ++i) {
        add_quad(outer_point(i, j, quarter), outer_point(i + 1, j, quarter),
                 outer_point(i + 1, j + 1, quarter), outer_point(i, j + 1, quarter));
      }
    }
  }

  GeneratedMesh mesh;
  const auto& section = pool.points();
  const auto per_layer = static_cast<std::int32_t>(section.size());
  for (int k = 0; k <= d.axial; ++k) {
    const double s = length * k / d.axial;
    for (const Point2& p : section) {
      const double x = radius * p[0];
      const double y = radius * p[1];
      mesh.nodes.push_back({p1[0] + x * e1[0] + y * e2[0] + s * axis[0],
                            p1[1] + x * e1[1] + y * e2[1] + s * axis[1],
                            p1[2] + x * e1[2] + y * e2[2] + s * axis[2]});
    }
    if (k == d.axial) {
      // The far end exactly at p2 along the axis (no accumulated rounding in s).
      for (std::int32_t i = 0; i < per_layer; ++i) {
        const Point2& p = section[static_cast<std::size_t>(i)];
        auto& x = mesh.nodes[static_cast<std::size_t>(k * per_layer + i)];
        x = {p2[0] + radius * (p[0] * e1[0] + p[1] * e2[0]),
             p2[1] + radius * (p[0] * e1[1] + p[1] * e2[1]),
             p2[2] + radius * (p[0] * e1[2] + p[1] * e2[2])};
      }
    }
  }
  for (int k = 0; k < d.axial; ++k) {
    for (const auto& q : quads) {
      const std::int32_t b = k * per_layer;
      const std::int32_t t = (k + 1) * per_layer;
      mesh.hexes.push_back(
          {b + q[0], b + q[1], b + q[2], b + q[3], t + q[0], t + q[1], t + q[2], t + q[3]});
    }
  }
  check_finite(mesh);
  return mesh;
}

std::vector<std::int64_t> nearest_within(const std::vector<std::array<double, 3>>& candidates,
                                         const std::vector<std::array<double, 3>>& points,
                                         double tolerance) {
  std::vector<std::int64_t> out(points.size(), -1);
  if (candidates.empty() || !(tolerance > 0.0)) return out;
  // Cells of the tolerance's size, but not so small against the coordinates that the cell
  // indices overflow (a larger cell only costs time; the distance test below decides).
  double extent = 0.0;
  for (const auto* list : {&candidates, &points}) {
    for (const auto& x : *list) {
      for (const double c : x) {
        if (!std::isfinite(c)) throw std::invalid_argument("a node coordinate is not finite");
        extent = std::max(extent, std::abs(c));
      }
    }
  }
  const double h = std::max(tolerance, 1e-12 * extent);
  std::unordered_map<CellKey, std::vector<std::int64_t>, CellHash> cells;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    cells[cell_of(candidates[i], h)].push_back(static_cast<std::int64_t>(i));
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    const CellKey c = cell_of(points[p], h);
    double best = tolerance;
    for (std::int64_t di = -1; di <= 1; ++di) {
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        for (std::int64_t dk = -1; dk <= 1; ++dk) {
          const auto it = cells.find({c.i + di, c.j + dj, c.k + dk});
          if (it == cells.end()) continue;
          for (std::int64_t index : it->second) {
            const auto& q = candidates[static_cast<std::size_t>(index)];
            const double dist = std::sqrt((q[0] - points[p][0]) * (q[0] - points[p][0]) +
                                          (q[1] - points[p][1]) * (q[1] - points[p][1]) +
                                          (q[2] - points[p][2]) * (q[2] - points[p][2]));
            if (dist < best || (dist == best && dist < tolerance && out[p] > index)) {
              best = dist;
              out[p] = index;
            }
          }
        }
      }
    }
  }
  return out;
}

}  // namespace rf::mesh
