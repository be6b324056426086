// The state each element family carries from one cycle to the next, named array by array: one
// visitor per family, next to the blocks, so that whatever moves a block's state as a whole (the
// restart dump, restart/dump.cpp; later the packing of element state between processes) walks
// the family's own list instead of knowing its members. A per-element array that starts to
// change during a run is added to its family's visitor and is dumped and restored from then on.
//
// `visit(std::string name, std::vector<double>& array)`; `Block` is the block type or its const.
// The material's history is visited generically, one array per registered field under the name
// `history_<field name>` (material/history.hpp), so a new material needs nothing here.
#pragma once

#include <string>
#include <vector>

#include "element/beam_block.hpp"
#include "element/hex_block.hpp"
#include "element/shell_block.hpp"

namespace rf::element {

template <class Block, class Visit>
void visit_history(Block& block, Visit& visit) {
  for (auto& h : block.history) visit("history_" + std::string(h.field.name), h.values);
}

// Erosion (element/erosion_state.hpp), in blocks that can erode: when each element left and the
// work it had done (the ownership and the removed nodes follow from these, solver/erosion.hpp).
template <class Block, class Visit>
void visit_erosion(Block& block, Visit& visit) {
  if (!block.erosion.enabled) return;
  visit(std::string("erosion_time"), block.erosion.time);
  visit(std::string("erosion_work"), block.erosion.work);
  visit(std::string("erosion_artificial_work"), block.erosion.artificial_work);
  if (!block.erosion.impulse.empty()) visit(std::string("erosion_impulse"), block.erosion.impulse);
}

// Hexahedra: stresses at every stress point, the stiffness forms' hourglass forces, volumes and
// reference volumes, the last element forces. Not visited: the order > 1 reference Jacobians,
// weights, steps and lengths, set up from x0 and never changed (a third of a p = 3 dump; the
// rebuilt model has them bit for bit).
template <class Block, class Visit>
void visit_hex_state(Block& block, Visit&& visit) {
  visit(std::string("stress"), block.stress);
  visit(std::string("hourglass_state"), block.hourglass_state);
  visit(std::string("volume0"), block.volume0);
  visit(std::string("volume0_cbrt"), block.volume0_cbrt);
  visit(std::string("volume"), block.volume);
  visit(std::string("force"), block.force);
  visit_history(block, visit);
  visit_erosion(block, visit);
}

// Shells: co-rotational stresses at every integration point, hourglass forces (accumulated for
// IHQ 4, 5; the last step's for the viscous forms), reference and current areas, nodal and
// current element thicknesses (the latter changes with *CONTROL_SHELL ISTUPD 1/4), the last
// element forces and moments, the integrated strain when an erosion criterion keeps one. Not
// visited: the initial element thickness element_thickness0, set up from the nodal thicknesses
// and never changed. Mass scaling's step_scale belongs to the mass scaling (its element
// factors).
template <class Block, class Visit>
void visit_shell_state(Block& block, Visit&& visit) {
  visit(std::string("stress"), block.stress);
  visit(std::string("hourglass_state"), block.hourglass_state);
  visit(std::string("area0"), block.area0);
  visit(std::string("area"), block.area);
  visit(std::string("thickness"), block.thickness);
  visit(std::string("element_thickness"), block.element_thickness);
  visit(std::string("force"), block.force);
  if (!block.strain.empty()) visit(std::string("strain"), block.strain);
  visit_history(block, visit);
  visit_erosion(block, visit);
}

// Beams and trusses: the co-rotational frames, resultants, axial stresses per point, reference
// and current lengths, the last element forces and moments.
template <class Block, class Visit>
void visit_beam_state(Block& block, Visit&& visit) {
  visit(std::string("frame"), block.frame);
  visit(std::string("resultant"), block.resultant);
  visit(std::string("stress"), block.stress);
  visit(std::string("length0"), block.length0);
  visit(std::string("length"), block.length);
  visit(std::string("force"), block.force);
  visit_history(block, visit);
  visit_erosion(block, visit);
}

}  // namespace rf::element
