// p-elevation of 8-node hexahedra (see p_order.hpp).
//
// Orientation handling. An element sees a shared edge or face in its own local indices; the
// neighbour may see it reversed, rotated or mirrored. Every entity therefore gets one canonical
// parametrisation, fixed by its corner node numbers only:
//   edge (a, b):       from the smaller corner to the larger; local index t along the element's
//                      edge direction maps to t if the element runs from the smaller corner,
//                      else to p - t.
//   face (c0..c3):     cyclic corner order rotated to start at the smallest corner C0 and turned
//                      so that C1 is the smaller of C0's two neighbours; u runs C0 -> C1, v runs
//                      C0 -> C3. The element's in-face index pair (a, b) maps to (u, v) by
//                      projecting (a, b) - P(C0) on P(C1) - P(C0) and P(C3) - P(C0), P being the
//                      corner's position in the element's (a, b) grid: one formula covers the
//                      four rotations and both mirror images (the dihedral group of the square).
// The entity's nodes are created together, in canonical order, the first time any element meets
// it. Their coordinates come from the canonical linear (edge) or bilinear (face) interpolation of
// the corners at the GLL points; that is the restriction of every adjacent element's trilinear
// map to the entity, because the GLL points are symmetric (points[p - i] == -points[i], exactly),
// so the position of a node does not depend on which element created it.
#include "mesh/p_order.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "element/lagrange_hex.hpp"

namespace rf::mesh {
namespace {

// LS-DYNA corner number of the corner whose (xi, eta, zeta) are at the +1 end where the bit is
// set: bit 0 xi, bit 1 eta, bit 2 zeta (n1 (-,-,-), n2 (+,-,-), n3 (+,+,-), n4 (-,+,-), ...).
constexpr int kCornerOfBits[8] = {0, 1, 3, 2, 4, 5, 7, 6};
constexpr int kCornerSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

}  // namespace

std::size_t HexElevator::FaceKeyHash::operator()(const std::array<std::int32_t, 4>& k) const {
  // 64-bit FNV-1a style mixing of the four indices; only used for bucketing.
  std::uint64_t h = 1469598103934665603ull;
  for (const std::int32_t v : k) {
    h ^= static_cast<std::uint32_t>(v);
    h *= 1099511628211ull;
    h ^= h >> 29;
  }
  return static_cast<std::size_t>(h);
}

HexElevator::HexElevator(int order, std::vector<std::array<double, 3>>& x)
    : order_(order), x_(x), first_new_(static_cast<std::int32_t>(x.size())) {
  if (order < 1 || order > 8)
    throw std::invalid_argument(
        fmt::format("interpolation order {} is not supported (1 to 8)", order));
  points_ = element::gll_rule(order).points;
}

std::int32_t HexElevator::add_node(const std::array<double, 3>& p,
                                   std::vector<std::int32_t> parents) {
  const auto index = static_cast<std::int32_t>(x_.size());
  x_.push_back(p);
  parents_.push_back(std::move(parents));
  return index;
}

std::vector<std::int32_t> HexElevator::elevate(const std::array<std::int32_t, 8>& corners) {
  for (int a = 0; a < 8; ++a) {
    if (corners[a] < 0 || corners[a] >= first_new_)
      throw std::invalid_argument(fmt::format(
          "corner n{} refers to node index {}, outside the {} nodes the mesh had before "
          "elevation",
          a + 1, corners[a], first_new_));
    for (int b = 0; b < a; ++b)
      if (corners[a] == corners[b])
        throw std::invalid_argument(fmt::format(
            "degenerate hexahedron (corners n{} and n{} are the same node): only 8-node "
            "hexahedra with distinct corners can be raised to a higher order",
            b + 1, a + 1));
  }
  const int p = order_;
  const int n = p + 1;
  // Corner coordinates copied first: appending nodes may reallocate x_.
  std::array<std::array<double, 3>, 8> xc;
  for (int c = 0; c < 8; ++c) xc[c] = x_[static_cast<std::size_t>(corners[c])];

  // Faces first: validate every face against the registry before creating any node, so that a
  // rejected element leaves the elevator unchanged.
  struct LocalFace {
    int fixed_dir, fixed_end;
    std::array<std::int32_t, 4> local;  // corners at (a, b) = (0,0), (p,0), (p,p), (0,p)
  };
  std::array<LocalFace, 6> faces;
  auto corner_at = [&](int bi, int bj, int bk) {
    return corners[kCornerOfBits[bi + 2 * bj + 4 * bk]];
  };
  for (int d = 0; d < 3; ++d)
    for (int end = 0; end < 2; ++end) {
      LocalFace& f = faces[2 * d + end];
      f.fixed_dir = d;
      f.fixed_end = end;
      const int d1 = d == 0 ? 1 : 0, d2 = d == 2 ? 1 : 2;  // free directions, d1 < d2
      const int ab[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (int s = 0; s < 4; ++s) {
        int bits[3];
        bits[d] = end;
        bits[d1] = ab[s][0];
        bits[d2] = ab[s][1];
        f.local[s] = corner_at(bits[0], bits[1], bits[2]);
      }
    }
  // Canonical cycle of a face given in local cyclic order; `start` and `step` (+1/-1) locate it.
  auto canonical = [](const std::array<std::int32_t, 4>& c, int& start, int& step) {
    start = static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin());
    step = c[(start + 1) % 4] < c[(start + 3) % 4] ? 1 : 3;
    std::array<std::int32_t, 4> cycle;
    for (int s = 0; s < 4; ++s) cycle[s] = c[(start + s * step) % 4];
    return cycle;
  };
  if (p >= 2) {
    for (const LocalFace& f : faces) {
      int start, step;
      const auto cycle = canonical(f.local, start, step);
      auto key = f.local;
      std::sort(key.begin(), key.end());
      const auto it = faces_.find(key);
      if (it != faces_.end() && it->second.cycle != cycle)
        throw std::invalid_argument(fmt::format(
            "face with corner nodes {} {} {} {} is used by another element with a different "
            "corner order ({} {} {} {}): the mesh is not conforming there",
            cycle[0], cycle[1], cycle[2], cycle[3], it->second.cycle[0], it->second.cycle[1],
            it->second.cycle[2], it->second.cycle[3]));
    }
  }

  std::vector<std::int32_t> out(static_cast<std::size_t>(n * n * n), -1);
  const double* pt = points_.data();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int idx[3] = {i, j, k};
        int on_end[3];  // 0 / 1 at an end of the direction, -1 inside
        int boundary = 0;
        for (int d = 0; d < 3; ++d) {
          on_end[d] = idx[d] == 0 ? 0 : (idx[d] == p ? 1 : -1);
          boundary += on_end[d] >= 0;
        }
        std::int32_t& node = out[static_cast<std::size_t>(i + n * (j + n * k))];
        if (boundary == 3) {
          node = corner_at(on_end[0], on_end[1], on_end[2]);
        } else if (boundary == 2) {
          const int d = on_end[0] < 0 ? 0 : (on_end[1] < 0 ? 1 : 2);  // the edge's direction
          int bits0[3] = {on_end[0], on_end[1], on_end[2]},
              bits1[3] = {on_end[0], on_end[1], on_end[2]};
          bits0[d] = 0;
          bits1[d] = 1;
          const std::int32_t a = corner_at(bits0[0], bits0[1], bits0[2]);
          const std::int32_t b = corner_at(bits1[0], bits1[1], bits1[2]);
          const std::uint64_t key = edge_key(a, b);
          auto it = edges_.find(key);
          if (it == edges_.end()) {
            const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
            // Copies: add_node may reallocate x_.
            const std::array<double, 3> xl = x_[static_cast<std::size_t>(lo)];
            const std::array<double, 3> xh = x_[static_cast<std::size_t>(hi)];
            std::int32_t first = -1;
            for (int t = 1; t < p; ++t) {
              const double s = pt[t];
              std::array<double, 3> xn;
              for (int c = 0; c < 3; ++c) xn[c] = 0.5 * (1.0 - s) * xl[c] + 0.5 * (1.0 + s) * xh[c];
              const std::int32_t id = add_node(xn, {lo, hi});
              if (t == 1) first = id;
            }
            it = edges_.emplace(key, first).first;
          }
          const int t = idx[d];
          node = it->second + (a < b ? t : p - t) - 1;
        } else if (boundary == 1) {
          const int d = on_end[0] >= 0 ? 0 : (on_end[1] >= 0 ? 1 : 2);  // fixed direction
          const LocalFace& f = faces[2 * d + on_end[d]];
          const int d1 = d == 0 ? 1 : 0, d2 = d == 2 ? 1 : 2;
          int start, step;
          const auto cycle = canonical(f.local, start, step);
          auto key = f.local;
          std::sort(key.begin(), key.end());
          auto it = faces_.find(key);
          if (it == faces_.end()) {
            Face face{cycle, -1};
            std::array<std::array<double, 3>, 4> xq;
            for (int s = 0; s < 4; ++s) xq[s] = x_[static_cast<std::size_t>(cycle[s])];
            for (int v = 1; v < p; ++v)
              for (int u = 1; u < p; ++u) {
                const double su = pt[u], sv = pt[v];
                const double w[4] = {0.25 * (1 - su) * (1 - sv), 0.25 * (1 + su) * (1 - sv),
                                     0.25 * (1 + su) * (1 + sv), 0.25 * (1 - su) * (1 + sv)};
                std::array<double, 3> xn{};
                for (int s = 0; s < 4; ++s)
                  for (int c = 0; c < 3; ++c) xn[c] += w[s] * xq[s][c];
                const std::int32_t id =
                    add_node(xn, std::vector<std::int32_t>(cycle.begin(), cycle.end()));
                if (u == 1 && v == 1) face.first = id;
              }
            it = faces_.emplace(key, face).first;
          }
          // Positions of the local corners in the element's (a, b) grid of the face.
          const int pos[4][2] = {{0, 0}, {p, 0}, {p, p}, {0, p}};
          const int* o = pos[start];
          const int* pu = pos[(start + step) % 4];
          const int* pv = pos[(start + 3 * step) % 4];
          const int da = idx[d1] - o[0], db = idx[d2] - o[1];
          const int u = (da * (pu[0] - o[0]) + db * (pu[1] - o[1])) / p;
          const int v = (da * (pv[0] - o[0]) + db * (pv[1] - o[1])) / p;
          node = it->second.first + (u - 1) + (p - 1) * (v - 1);
        } else {
          // Interior: trilinear map at the GLL point, N_c = (1 + xi xi_c)(1 + eta eta_c)
          // (1 + zeta zeta_c) / 8.
          const double s[3] = {pt[i], pt[j], pt[k]};
          std::array<double, 3> xn{};
          for (int c = 0; c < 8; ++c) {
            const double w = 0.125 * (1 + s[0] * kCornerSign[c][0]) *
                             (1 + s[1] * kCornerSign[c][1]) * (1 + s[2] * kCornerSign[c][2]);
            for (int m = 0; m < 3; ++m) xn[m] += w * xc[c][m];
          }
          node = add_node(xn, std::vector<std::int32_t>(corners.begin(), corners.end()));
        }
      }
  return out;
}

std::vector<std::int32_t> HexElevator::add_block(
    const std::vector<std::array<std::int32_t, 8>>& hexes,
    const std::vector<std::int64_t>& element_ids) {
  const std::size_t npe = static_cast<std::size_t>((order_ + 1) * (order_ + 1) * (order_ + 1));
  std::vector<std::int32_t> conn;
  conn.reserve(hexes.size() * npe);
  for (std::size_t e = 0; e < hexes.size(); ++e) {
    try {
      const auto nodes = elevate(hexes[e]);
      conn.insert(conn.end(), nodes.begin(), nodes.end());
    } catch (const std::invalid_argument& error) {
      const std::string who = e < element_ids.size()
                                  ? fmt::format("element {}", element_ids[e])
                                  : fmt::format("hexahedron {} of the block", e + 1);
      throw std::invalid_argument(fmt::format("{}: {}", who, error.what()));
    }
  }
  return conn;
}

}  // namespace rf::mesh
