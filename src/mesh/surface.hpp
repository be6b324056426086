// Boundary surfaces of a hexahedral mesh and their selection by a seed point
// (IMPETUS *GEOMETRY_SEED_COORDINATE).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace rf::mesh {

// One hexahedron of any order. conn holds nodes_per_element indices: LS-DYNA order n1..n8 for
// order 1, tensor order i + (p+1)(j + (p+1)k) above (see element/hex_block.hpp).
struct HexView {
  int order = 1;
  const std::int32_t* conn = nullptr;
  std::int64_t part = 0;
};

struct Coordinates {
  const double* x;
  const double* y;
  const double* z;
};

// Nodes of the boundary surface patch that contains the boundary face nearest to `seed`
// (restricted to faces of part `part` unless it is 0), grown across face edges wherever the
// normals of the two faces differ by less than `cutoff_deg`. Boundary faces are those that
// belong to one element only. Every node on the selected faces is returned (face-interior and
// edge nodes of higher-order elements included), sorted and unique. Empty when the mesh has no
// boundary face (of that part).
std::vector<std::int32_t> select_surface_by_seed(const std::vector<HexView>& hexes,
                                                 const Coordinates& coordinates,
                                                 const std::array<double, 3>& seed,
                                                 double cutoff_deg, std::int64_t part);

// Node of hexahedron `hex` at tensor position (i, j, k), 0 <= i, j, k <= order.
inline std::int32_t hex_node(const HexView& hex, int i, int j, int k) {
  if (hex.order == 1) {
    static constexpr int kCorner[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};  // [i][j][k]
    return hex.conn[kCorner[i][j][k]];
  }
  const int n = hex.order + 1;
  return hex.conn[i + n * (j + n * k)];
}

}  // namespace rf::mesh
