// Element erosion (issue 17): the failure criteria of every block (material FS / FAIL / TDEL,
// Johnson-Cook damage, *MAT_ADD_EROSION), the cycle phase that deletes failed elements, the
// removal of nodes left without elements, and the ledger of what left the model (eroded
// internal and kinetic energy, momentum). docs/materials.md, "Failure and erosion".
//
// The erosion phase runs after the element kernels of a cycle (stresses and history at
// t^{n+1}) and before the element forces are gathered: an element that fails there contributes
// no force from this cycle on. It leaves its block's ElementOwnership, so the kernels, the
// step minimum and the assembly never see it again; the block keeps its slot and its ID.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// What has left the model since t = 0.
struct ErosionLedger {
  // Work the eroded elements' forces did before they left, less their hourglass and bulk
  // viscosity work (which stays in those glstat columns).
  double internal_energy = 0.0;
  double kinetic_energy = 0.0;       // 1/2 m v^2 (+ 1/2 I w^2) of the removed nodes at removal
  std::array<double, 3> momentum{};  // m v of the removed nodes at removal
  std::array<double, 3> angular_momentum{};  // x x m v (+ I w) of the removed nodes
  std::int64_t elements = 0;
  std::int64_t nodes = 0;
};

// One deleted element, for erosion.csv and the log.
struct ErosionEvent {
  double time = 0.0;
  model::Id part = 0;
  model::Id element = 0;
  const char* family = "";  // "solid", "shell", "beam"
  std::string criterion;    // e.g. "plastic strain 0.3012 >= FAIL 0.3"
};

// An element that met its criterion, before it is deleted: what a rank found among its own
// elements, and what the ranks of a distributed run exchange so that every rank deletes the same
// elements in the same order (docs/parallel.md).
struct ElementFailure {
  std::int32_t family = 0;  // 0 hexahedra, 1 shells, 2 beams (the blocks' order in State)
  std::int32_t block = 0;
  std::int64_t element = 0;
  // Work its forces did less its hourglass and bulk viscosity work: known where it was computed.
  double internal_energy = 0.0;
  std::string criterion;

  // The order in which one process deletes: blocks of each family in turn, ascending elements.
  bool operator<(const ElementFailure& o) const {
    if (family != o.family) return family < o.family;
    if (block != o.block) return block < o.block;
    return element < o.element;
  }
};

// Failures as bytes and back (the exchange of a distributed run).
std::string pack_failures(const std::vector<ElementFailure>& failures);
void unpack_failures(const std::string& bytes, std::vector<ElementFailure>& out);

class Erosion {
 public:
  // Resolves the criteria of every block from the model (sets ErosionState::criteria, enabled,
  // allocates) and the node bookkeeping. Throws rf::InputError for criteria on a part that
  // cannot carry them (naming the card). Cheap and inert when nothing can erode.
  void setup(const model::Model& model, State& state);
  bool enabled() const { return enabled_; }

  // Per-element work of the erodible blocks for the step just taken, with the displacement the
  // global balance uses (d = dt_avg (v^{n-1/2} + v^{n+1/2}) / 2, rotations alike). Deformable
  // nodes only: erodible blocks are deformable while they compute forces.
  void add_step_work(State& state, const Vec3Array& v_previous, double dt_avg);

  // Evaluates the criteria at t^{n+1} on every computed element of the erodible blocks, deletes
  // the failed ones (force slots and stresses zeroed, ownership updated) and removes the nodes
  // left without any element (not rigid-body nodes: `body_of` per node or null). Returns the
  // number of elements deleted now; their events are in events() until the next call.
  std::int64_t erode_failed_elements(State& state, double time,
                                     const std::vector<std::int32_t>* body_of);
  // The two halves of erode_failed_elements, for a distributed run, where the ranks exchange the
  // failures in between: the elements this process computes that meet their criterion at t^{n+1}
  // (in deletion order), and the deletion of `failures` (sorted, no duplicates; every rank the
  // same list), which returns their number.
  std::vector<ElementFailure> find_failed_elements(State& state, double time);
  std::int64_t delete_elements(State& state, double time,
                               const std::vector<ElementFailure>& failures,
                               const std::vector<std::int32_t>* body_of);
  // In a distributed run a rank's blocks list its own elements (element_ownership.hpp): a
  // deletion then takes the element out of that list instead of rebuilding it from every live
  // element of the block.
  void set_distributed(bool distributed) { distributed_ = distributed; }

  // After a restart dump was read (the blocks' erosion times and the ledger): ownership, live
  // element counts and removed nodes (mass, inertia) as the interrupted run had them.
  void restore(State& state, const std::vector<std::int32_t>* body_of);

  // *CONTROL_TIMESTEP ERODE: the element step below which the elements of the named families
  // erode, TSMIN / TSSFAC with TSMIN = DTMIN times the run's first step (0: not yet known or no
  // DTMIN, nothing erodes by it).
  void set_minimum_step(double element_step) { minimum_step_ = element_step; }

  // The time of the last criteria evaluation: the Tuler-Butcher stress impulse integrates from it
  // (restart dumps carry it).
  double impulse_time() const { return impulse_time_; }
  void set_impulse_time(double t) { impulse_time_ = t; }

  const ErosionLedger& ledger() const { return ledger_; }
  ErosionLedger& ledger() { return ledger_; }
  const std::vector<ErosionEvent>& events() const { return events_; }

 private:
  void remove_orphan_nodes(State& state, const std::vector<std::int32_t>* body_of, bool book);
  bool enabled_ = false;
  bool distributed_ = false;
  ErosionLedger ledger_;
  std::vector<ErosionEvent> events_;
  // Per node: elements of any family (hexahedra, shells, beams, springs) that reference it and
  // have not eroded; a node of at least one erodible element whose count reaches zero is
  // removed.
  std::vector<std::int32_t> live_elements_;
  std::vector<std::uint8_t> erodible_node_;
  std::vector<double> scratch_steps_;  // TDEL, ERODE: element steps of one block
  double minimum_step_ = 0.0;
  double impulse_time_ = 0.0;
};

// Rebuilds a block's ownership from its erosion times: every element not eroded (one process).
template <class Block>
void own_live_elements(Block& block) {
  if (!block.erosion.enabled) return;
  block.owned.partitioned = block.erosion.count > 0;
  block.owned.elements.clear();
  block.owned.batches.clear();
  block.owned.batch_lanes = 0;
  if (!block.owned.partitioned) return;
  for (std::size_t e = 0; e < block.size(); ++e)
    if (!block.erosion.is_eroded(e)) block.owned.elements.push_back(static_cast<std::int64_t>(e));
}

// The loops of the kernels: a process's own elements less the deleted ones. One process owns
// every live element; a rank keeps its partition's elements (element/element_ownership.hpp) less
// the deleted ones.
template <class Block>
void own_remaining_elements(Block& block, bool distributed) {
  if (!distributed) {
    own_live_elements(block);
    return;
  }
  std::erase_if(block.owned.elements, [&](std::int64_t e) {
    return block.erosion.is_eroded(static_cast<std::size_t>(e));
  });
  block.owned.batches.clear();
  block.owned.batch_lanes = 0;
}

}  // namespace rf::solver
