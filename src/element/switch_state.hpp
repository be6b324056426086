// Part switching (switching/part_switching.hpp, docs/switching.md): what each element family does
// with the state its elements keep while their part is rigid by switching. One overload per
// family, so that the switcher walks its parts' blocks without knowing their members:
//
//   frozen_strain_energy(block)   strain energy held by the frozen stresses (linear elasticity,
//                                 for the frozen_energy column of glstat.csv);
//   turn_frozen_state(block, Q)   on release: whatever the block keeps in GLOBAL axes is turned
//                                 by the rotation Q the body made since the switch, so that the
//                                 part continues as if it had been rotated (objectivity).
//
// Hexahedra keep global stresses and (IHQ 4, 5) global hourglass forces: both turn (s -> Q s
// Q^T, q -> Q q, symmetric-tensor history like the stress). Shells keep stresses, history and
// hourglass forces in the element's co-rotational frame, which turned with the body: nothing
// turns. Beams keep their resultants and axial stresses in the co-rotational frame, but the frame
// itself (rows e1, s, t) is stored in global axes and carried incrementally by the nodal
// rotations, which the kernel does not see while the part is rigid: the frames turn by Q.
#pragma once

#include <Eigen/Dense>

#include "element/beam_block.hpp"
#include "element/hex_block.hpp"
#include "element/shell_block.hpp"

namespace rf::element {

double frozen_strain_energy(const HexBlock& block);
double frozen_strain_energy(const ShellBlock& block);
double frozen_strain_energy(const BeamBlock& block);

void turn_frozen_state(HexBlock& block, const Eigen::Matrix3d& q);
void turn_frozen_state(ShellBlock& block, const Eigen::Matrix3d& q);
void turn_frozen_state(BeamBlock& block, const Eigen::Matrix3d& q);

}  // namespace rf::element
