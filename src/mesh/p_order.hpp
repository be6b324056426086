// p-elevation of 8-node hexahedra to (p+1)^3-node Lagrange hexahedra on GLL points (the elements
// of element/lagrange_hex.hpp; *CHANGE_P-ORDER). New nodes are placed at the GLL points of each
// element's trilinear map, so the geometry is unchanged until a caller moves nodes (e.g. onto a
// curved surface, see parents()).
//
// Conformity. A node created on an edge or a face is shared by every element that has that edge
// or face, whatever the element's orientation there: edges are keyed by their sorted corner pair
// and faces by their sorted corner quadruple, and each element maps its own GLL indices on the
// entity to a canonical parametrisation of it (see p_order.cpp). One HexElevator can take several
// blocks (add_block / elevate per element), so parts that share corner nodes stay conforming.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace rf::mesh {

class HexElevator {
 public:
  // `x` holds the coordinates of the existing nodes (dense index); new nodes are appended to it,
  // so it must outlive the elevator and only the elevator may grow it meanwhile. Orders 1..8
  // (order 1 creates no nodes); throws std::invalid_argument otherwise.
  HexElevator(int order, std::vector<std::array<double, 3>>& x);

  // Nodes of the elevated element in tensor order i + (p+1)(j + (p+1)k), xi along n1->n2, eta
  // along n1->n4, zeta along n1->n5 (i = 0 at n1). `corners` in LS-DYNA order n1..n8, dense
  // indices of nodes that existed when the elevator was made. Throws std::invalid_argument,
  // creating nothing, for repeated corners (degenerate hexahedra: wedges, pyramids and tetrahedra
  // cannot be elevated), corners out of range, or a face whose four corners another element uses
  // with a different cyclic order (not a conforming mesh).
  std::vector<std::int32_t> elevate(const std::array<std::int32_t, 8>& corners);

  // Elevates a block of hexahedra: (p+1)^3 node indices per element, element-major, in the order
  // of elevate(). On error throws std::invalid_argument naming the element by element_ids[e]
  // when given (same size as hexes), else by its position in the block.
  std::vector<std::int32_t> add_block(const std::vector<std::array<std::int32_t, 8>>& hexes,
                                      const std::vector<std::int64_t>& element_ids = {});

  // For each node created so far (index - first_new_node()): the corner nodes of the edge (2,
  // sorted), face (4, cyclic, smallest first) or element (8, LS-DYNA order) it was created on. A
  // caller may move a node whose parent corners all lie on a curved surface onto that surface.
  const std::vector<std::vector<std::int32_t>>& parents() const { return parents_; }
  std::int32_t first_new_node() const { return first_new_; }
  std::int32_t node_count() const { return static_cast<std::int32_t>(x_.size()); }
  int order() const { return order_; }

 private:
  struct Face {
    std::array<std::int32_t, 4> cycle;  // canonical cyclic corner order
    std::int32_t first;                 // first of its (p-1)^2 nodes
  };
  struct FaceKeyHash {
    std::size_t operator()(const std::array<std::int32_t, 4>& k) const;
  };

  std::int32_t add_node(const std::array<double, 3>& x, std::vector<std::int32_t> parents);

  int order_;
  std::vector<std::array<double, 3>>& x_;
  std::int32_t first_new_;
  std::vector<double> points_;  // GLL points of the order
  // Edge (sorted corner pair, packed) -> first of its p-1 nodes, numbered from the smaller corner.
  std::unordered_map<std::uint64_t, std::int32_t> edges_;
  std::unordered_map<std::array<std::int32_t, 4>, Face, FaceKeyHash> faces_;
  std::vector<std::vector<std::int32_t>> parents_;
};

}  // namespace rf::mesh
