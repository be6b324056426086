// Tetrahedral meshes for the tetrahedron tests: a structured grid of ni x nj x nk cells whose
// nodes are placed by a position function (a box, a distorted box, a cylinder sector), each
// cell split into the six Kuhn tetrahedra about its diagonal from corner (i, j, k) to
// (i+1, j+1, k+1), conforming from cell to cell, written as 4-node *ELEMENT_SOLID cards with the
// corners ordered for a positive volume.
#pragma once

#include <fmt/format.h>

#include <Eigen/Dense>
#include <array>
#include <functional>
#include <map>
#include <string>
#include <utility>

namespace rf::test {

struct TetGrid {
  int ni = 1, nj = 1, nk = 1;
  std::function<Eigen::Vector3d(int, int, int)> position;
  int first_node = 1, first_element = 1, pid = 1;

  int node(int i, int j, int k) const { return first_node + i + (ni + 1) * (j + (nj + 1) * k); }
  int node_count() const { return (ni + 1) * (nj + 1) * (nk + 1); }
  int element_count() const { return 6 * ni * nj * nk; }
  bool on_boundary(int i, int j, int k) const {
    return i == 0 || j == 0 || k == 0 || i == ni || j == nj || k == nk;
  }

  // The four grid corners (i, j, k) of each tetrahedron, positive volume, cell by cell.
  template <class F>
  void for_each_tetrahedron(F&& f) const {
    static constexpr std::array<std::array<int, 3>, 6> kOrders{
        {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    for (int k = 0; k < nk; ++k)
      for (int j = 0; j < nj; ++j)
        for (int i = 0; i < ni; ++i)
          for (const auto& order : kOrders) {
            std::array<std::array<int, 3>, 4> v{};
            v[0] = {i, j, k};
            for (int s = 1; s < 4; ++s) {
              v[s] = v[s - 1];
              v[s][static_cast<std::size_t>(order[static_cast<std::size_t>(s - 1)])] += 1;
            }
            auto at = [&](int s) { return position(v[s][0], v[s][1], v[s][2]); };
            if ((at(1) - at(0)).cross(at(2) - at(0)).dot(at(3) - at(0)) < 0.0)
              std::swap(v[1], v[2]);
            f(v);
          }
  }

  // The same mesh as 10-node tetrahedra (ELFORM 16): each tetrahedron's corners, then the
  // mid-side nodes of edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4 (LS-DYNA's order), one node per edge
  // shared by the elements on it, with IDs after the grid's. A mid-side node sits at
  // `curved(u, v, w)` for grid coordinates half-way along the edge when given (curved
  // geometry), else at the midpoint of the edge. Two-card *ELEMENT_SOLID: EID PID, N1..N10.
  std::string text10(
      const std::function<Eigen::Vector3d(double, double, double)>& curved = {}) const {
    std::map<std::pair<int, int>, int> midside;
    std::string nodes, elements;
    int next = first_node + node_count();
    int eid = first_element;
    static constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for_each_tetrahedron([&](const std::array<std::array<int, 3>, 4>& v) {
      int ids[10];
      for (int a = 0; a < 4; ++a) ids[a] = node(v[a][0], v[a][1], v[a][2]);
      for (int m = 0; m < 6; ++m) {
        const auto& p = v[kEdge[m][0]];
        const auto& q = v[kEdge[m][1]];
        const int a = ids[kEdge[m][0]], b = ids[kEdge[m][1]];
        const auto [it, inserted] = midside.try_emplace({std::min(a, b), std::max(a, b)}, next);
        if (inserted) {
          ++next;
          const Eigen::Vector3d x =
              curved ? curved(0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2]))
                     : Eigen::Vector3d(0.5 *
                                       (position(p[0], p[1], p[2]) + position(q[0], q[1], q[2])));
          nodes += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", it->second, x.x(), x.y(), x.z());
        }
        ids[4 + m] = it->second;
      }
      elements += fmt::format("{},{}\n{},{},{},{},{},{},{},{},{},{}\n", eid++, pid, ids[0], ids[1],
                              ids[2], ids[3], ids[4], ids[5], ids[6], ids[7], ids[8], ids[9]);
    });
    std::string s = "*NODE\n";
    for (int k = 0; k <= nk; ++k)
      for (int j = 0; j <= nj; ++j)
        for (int i = 0; i <= ni; ++i) {
          const Eigen::Vector3d p = position(i, j, k);
          s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", node(i, j, k), p.x(), p.y(), p.z());
        }
    return s + nodes + "*ELEMENT_SOLID\n" + elements;
  }

  std::string text() const {
    std::string s = "*NODE\n";
    for (int k = 0; k <= nk; ++k)
      for (int j = 0; j <= nj; ++j)
        for (int i = 0; i <= ni; ++i) {
          const Eigen::Vector3d p = position(i, j, k);
          s += fmt::format("{},{:.17g},{:.17g},{:.17g}\n", node(i, j, k), p.x(), p.y(), p.z());
        }
    s += "*ELEMENT_SOLID\n";
    int eid = first_element;
    for_each_tetrahedron([&](const std::array<std::array<int, 3>, 4>& v) {
      s += fmt::format("{},{},{},{},{},{}\n", eid++, pid, node(v[0][0], v[0][1], v[0][2]),
                       node(v[1][0], v[1][1], v[1][2]), node(v[2][0], v[2][1], v[2][2]),
                       node(v[3][0], v[3][1], v[3][2]));
    });
    return s;
  }
};

// A box [0, lx] x [0, ly] x [0, lz] of ni x nj x nk cells; interior nodes moved by up to
// `jitter` of a cell in each direction (a fixed pseudo-random pattern: irregular tetrahedra).
inline TetGrid tet_box(int ni, int nj, int nk, double lx, double ly, double lz,
                       double jitter = 0.0) {
  TetGrid g;
  g.ni = ni;
  g.nj = nj;
  g.nk = nk;
  g.position = [=](int i, int j, int k) {
    Eigen::Vector3d p(lx * i / ni, ly * j / nj, lz * k / nk);
    const bool interior = i > 0 && j > 0 && k > 0 && i < ni && j < nj && k < nk;
    if (interior && jitter > 0.0) {
      auto wave = [](int a, int b, int c, double s) {
        return std::sin(12.9898 * a + 78.233 * b + 37.719 * c + s);
      };
      p.x() += jitter * lx / ni * wave(i, j, k, 0.0);
      p.y() += jitter * ly / nj * wave(j, k, i, 1.0);
      p.z() += jitter * lz / nk * wave(k, i, j, 2.0);
    }
    return p;
  };
  return g;
}

}  // namespace rf::test
