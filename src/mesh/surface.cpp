#include "mesh/surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "mesh/vec3_ops.hpp"

namespace rf::mesh {

namespace {

// Distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double point_triangle_distance(const Vec& p, const Vec& a, const Vec& b, const Vec& c) {
  const Vec ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto dist = [&](const Vec& q) {
    const Vec d = sub(p, q);
    return std::sqrt(dot(d, d));
  };
  if (d1 <= 0 && d2 <= 0) return dist(a);
  const Vec bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dist(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return dist({a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]});
  }
  const Vec cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dist(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return dist({a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return dist({b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])});
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return dist(
      {a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w});
}

struct Face {
  std::size_t hex = 0;
  int side = 0;                          // 0..5: i=0, i=p, j=0, j=p, k=0, k=p
  std::array<std::int32_t, 4> corner{};  // in cyclic order around the face
};

// Tensor positions of the four corners of side s, cyclic.
std::array<std::array<int, 3>, 4> side_corners(int s, int p) {
  const int a = (s % 2 == 0) ? 0 : p;
  switch (s / 2) {
    case 0:
      return {{{a, 0, 0}, {a, p, 0}, {a, p, p}, {a, 0, p}}};
    case 1:
      return {{{0, a, 0}, {p, a, 0}, {p, a, p}, {0, a, p}}};
    default:
      return {{{0, 0, a}, {p, 0, a}, {p, p, a}, {0, p, a}}};
  }
}

}  // namespace

std::vector<std::int32_t> select_surface_by_seed(const std::vector<HexView>& hexes,
                                                 const Coordinates& xyz, const Vec& seed,
                                                 double cutoff_deg, std::int64_t part) {
  // Boundary faces: keyed by their sorted corner nodes, kept when seen exactly once.
  std::map<std::array<std::int32_t, 4>, std::pair<int, Face>> faces;
  for (std::size_t h = 0; h < hexes.size(); ++h) {
    const int p = hexes[h].order;
    for (int s = 0; s < 6; ++s) {
      Face f{h, s, {}};
      const auto c = side_corners(s, p);
      for (int q = 0; q < 4; ++q) f.corner[q] = hex_node(hexes[h], c[q][0], c[q][1], c[q][2]);
      auto key = f.corner;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.try_emplace(key, std::pair{0, f});
      ++it->second.first;
    }
  }
  std::vector<Face> boundary;
  for (const auto& [key, entry] : faces) {
    if (entry.first == 1) boundary.push_back(entry.second);
  }
  auto point = [&](std::int32_t n) { return Vec{xyz.x[n], xyz.y[n], xyz.z[n]}; };
  std::vector<Vec> normal(boundary.size());
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    const auto& c = boundary[f].corner;
    Vec n = cross(sub(point(c[2]), point(c[0])), sub(point(c[3]), point(c[1])));
    const double len = std::sqrt(dot(n, n));
    if (len > 0) n = {n[0] / len, n[1] / len, n[2] / len};
    // Outward: away from the element's centroid (the corner cycles above are not all oriented
    // the same way, and neighbouring faces must be compared with consistent normals).
    const HexView& hex = hexes[boundary[f].hex];
    const int p = hex.order;
    Vec centre{0, 0, 0}, face_centre{0, 0, 0};
    for (int i = 0; i <= p; i += p) {
      for (int j = 0; j <= p; j += p) {
        for (int k = 0; k <= p; k += p) {
          const Vec x = point(hex_node(hex, i, j, k));
          for (int d = 0; d < 3; ++d) centre[d] += x[d] / 8.0;
        }
      }
    }
    for (int q = 0; q < 4; ++q) {
      const Vec x = point(c[q]);
      for (int d = 0; d < 3; ++d) face_centre[d] += x[d] / 4.0;
    }
    if (dot(n, sub(face_centre, centre)) < 0) n = {-n[0], -n[1], -n[2]};
    normal[f] = n;
  }
  // Nearest face to the seed.
  std::size_t start = boundary.size();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    if (part != 0 && hexes[boundary[f].hex].part != part) continue;
    const auto& c = boundary[f].corner;
    const double d = std::min(point_triangle_distance(seed, point(c[0]), point(c[1]), point(c[2])),
                              point_triangle_distance(seed, point(c[0]), point(c[2]), point(c[3])));
    if (d < best) {
      best = d;
      start = f;
    }
  }
  if (start == boundary.size()) return {};
  // Flood fill across shared edges (sorted corner pairs).
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<std::size_t>> edge_faces;
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    if (part != 0 && hexes[boundary[f].hex].part != part) continue;
    const auto& c = boundary[f].corner;
    for (int q = 0; q < 4; ++q) {
      std::int32_t a = c[q], b = c[(q + 1) % 4];
      if (a == b) continue;
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  const double cos_cutoff = std::cos(cutoff_deg * std::numbers::pi / 180.0);
  std::vector<char> selected(boundary.size(), 0);
  std::vector<std::size_t> stack{start};
  selected[start] = 1;
  while (!stack.empty()) {
    const std::size_t f = stack.back();
    stack.pop_back();
    const auto& c = boundary[f].corner;
    for (int q = 0; q < 4; ++q) {
      std::int32_t a = c[q], b = c[(q + 1) % 4];
      if (a == b) continue;
      for (std::size_t g : edge_faces[{std::min(a, b), std::max(a, b)}]) {
        if (selected[g]) continue;
        if (dot(normal[f], normal[g]) <= cos_cutoff) continue;  // a feature edge
        selected[g] = 1;
        stack.push_back(g);
      }
    }
  }
  std::vector<std::int32_t> nodes;
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    if (!selected[f]) continue;
    const HexView& hex = hexes[boundary[f].hex];
    const int p = hex.order;
    const int s = boundary[f].side;
    const int a = (s % 2 == 0) ? 0 : p;
    for (int u = 0; u <= p; ++u) {
      for (int v = 0; v <= p; ++v) {
        if (s / 2 == 0) nodes.push_back(hex_node(hex, a, u, v));
        if (s / 2 == 1) nodes.push_back(hex_node(hex, u, a, v));
        if (s / 2 == 2) nodes.push_back(hex_node(hex, u, v, a));
      }
    }
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace rf::mesh
