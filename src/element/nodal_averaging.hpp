// The nodal averaging of the nodal-pressure tetrahedron (*SECTION_SOLID ELFORM 13,
// element/tet13_block.hpp): which block-local node each corner is, which elements meet at each
// block-local node (a CSR list in ascending element order, so that a node's sum has one order
// for any thread count), and the scratch arrays of one force evaluation. Built once when the
// block is initialised; the scratch is overwritten in every evaluation before it is read, so
// nothing here is state (restart dumps need none of it, docs/restart.md).
#pragma once

#include <cstdint>
#include <vector>

namespace rf::element {

struct NodalAveraging {
  // Per element, 4 values: the block-local node of each corner (corners in the order of their
  // first appearance in the element's 8 connectivity entries) and the connectivity slot (0-7)
  // of that first appearance, where the corner's force goes.
  std::vector<std::int32_t> corner;
  std::vector<std::uint8_t> corner_slot;
  // Per block-local node: its dense node index; the elements that meet there are
  // element[offset[k] .. offset[k + 1]) in ascending order.
  std::vector<std::int32_t> node;
  std::vector<std::int32_t> offset;
  std::vector<std::int32_t> element;
  // Scratch of one evaluation. Per element: the mid-step velocity gradient (9, row-major), the
  // mid-step volume and its rate dV/dt = V tr L (both 0 for an eroded element). Per block-local
  // node: the volumetric strain rate of the node's volume, sum dV/dt / sum V over its elements.
  std::vector<double> velocity_gradient;
  std::vector<double> mid_volume;
  std::vector<double> volume_rate;
  std::vector<double> node_rate;

  std::size_t node_count() const { return node.size(); }
};

}  // namespace rf::element
