// The nodal-pressure tetrahedron (*SECTION_SOLID ELFORM 13): a HexBlock of 4-node tetrahedra
// (LS-DYNA's degenerate connectivity n1 n2 n3 n4 n4 n4 n4 n4) whose volumetric strain rate is
// averaged over the elements around each node (Bonet & Burton 1998). The equations are in
// tet13_block.cpp and docs/theory.md ("Tetrahedra (ELFORM 13)").
#pragma once

#include "element/hex_block.hpp"

namespace rf::element {

// Whether a block runs the nodal-pressure tetrahedron kernel.
inline bool is_nodal_pressure_tetrahedron(const HexBlock& block) {
  return block.order == 1 && block.elform == 13;
}

// Allocates the per-element state, computes the reference volumes and builds the nodal
// averaging (block.nodal_averaging). Throws rf::SolverError naming the element if one is not a
// tetrahedron (4 distinct nodes) or its volume is not positive.
void initialize_tet13_block(HexBlock& block, const NodalView& nodes);

// Internal forces of every owned element at x^{n+1}, with the strain rate of v^{n+1/2}: a pass
// over all elements for the mid-step volumetric rates, a pass over the block's nodes that
// averages them, a pass over the owned elements that updates the stresses with the averaged
// volumetric rate and writes the forces into block.force. OpenMP-parallel, no shared writes,
// the same result for any thread count; no allocation.
KernelResult compute_tet13_forces(HexBlock& block, const NodalView& nodes, double dt);

}  // namespace rf::element
