// The element formulations behind one call per block: the solver asks a block for its forces,
// step and mass, and the block's order (and ELFORM) selects the kernel. Dispatch happens once
// per block per cycle, never per element.
#pragma once

#include "element/hex_block.hpp"
#include "element/lagrange_hex.hpp"
#include "element/tet10_block.hpp"

namespace rf::element {

inline void initialize_block(HexBlock& block, const NodalView& nodes) {
  if (block.quadratic_tetrahedra())
    initialize_tet10_block(block, nodes);
  else if (block.order > 1)
    initialize_lagrange_hex_block(block, nodes);
  else
    initialize_hex_block(block, nodes);
}

inline KernelResult compute_block_forces(HexBlock& block, const NodalView& nodes, double dt) {
  if (block.quadratic_tetrahedra()) return compute_tet10_forces(block, nodes, dt);
  return block.order > 1 ? compute_lagrange_hex_forces(block, nodes, dt)
                         : compute_hex_forces(block, nodes, dt);
}

inline KernelResult block_critical_timestep(const HexBlock& block, const NodalView& nodes) {
  if (block.quadratic_tetrahedra()) return tet10_critical_timestep(block, nodes);
  return block.order > 1 ? lagrange_hex_critical_timestep(block, nodes)
                         : hex_critical_timestep(block, nodes);
}

inline void add_block_lumped_mass(const HexBlock& block, std::vector<double>& nodal_mass) {
  if (block.quadratic_tetrahedra())
    add_tet10_lumped_mass(block, nodal_mass);
  else if (block.order > 1)
    add_lagrange_hex_lumped_mass(block, nodal_mass);
  else
    add_hex_lumped_mass(block, nodal_mass);
}

}  // namespace rf::element
