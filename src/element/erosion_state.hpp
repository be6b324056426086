// Element erosion (issue 17): which elements of a block have failed and left the model, and the
// work their forces did before they left (the eroded internal energy of glstat).
//
// An eroded element keeps its place in the block (indices, IDs, output order and restart
// layout never change); it leaves the block's ElementOwnership (element_ownership.hpp), so the
// kernels, the time-step minimum and the assembly no longer see it, and its force slots hold
// zeros. Contact (contact/contact.hpp) drops its segments and exposes the faces of solids it
// uncovered; nodes whose every element has eroded are removed (NodalState::removed).
// docs/materials.md, "Failure and erosion".
#pragma once

#include <cstdint>
#include <vector>

namespace rf::element {

struct ErosionState {
  // The block has a criterion that deletes elements (FS, FAIL, TDEL, Johnson-Cook damage,
  // *MAT_ADD_EROSION). False: every array below is empty and the block never erodes.
  bool enabled = false;
  // Per element: the time it eroded, -1 while it is in the model (a double so that the restart
  // dump carries it like every other element array).
  std::vector<double> time;
  // Per element: work of its nodal forces (and moments) since t = 0, with the displacement of
  // the step that glstat's balance uses; frozen at erosion (its eroded internal energy).
  std::vector<double> work;
  std::int64_t count = 0;  // eroded elements of the block

  bool is_eroded(std::size_t e) const { return enabled && time[e] >= 0.0; }
  void allocate(std::size_t n) {
    time.assign(n, -1.0);
    work.assign(n, 0.0);
    count = 0;
  }
};

}  // namespace rf::element
