// Section forces (LS-DYNA SECFORC, docs/output.md#secforccsv): the force and moment that the
// material on the positive side of a cutting plane transmits to the material on its negative
// side, from the element nodal forces of the last force evaluation.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/model.hpp"
#include "solver/build_state.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// One row of secforc.csv.
struct SectionForce {
  model::Id section = 0;
  std::array<double, 3> force{};     // positive side on negative side, global axes
  double normal_force = 0.0;         // force . N (positive: tension); 0 for set sections
  std::array<double, 3> moment{};    // about the centroid of the section's nodes
  std::array<double, 3> centroid{};  // mean current position of the section's nodes
};

// The cut of one *DATABASE_CROSS_SECTION_PLANE, fixed when the run starts (reference
// configuration): which element force slots act on which section node.
class CrossSectionCut {
 public:
  // Every element of the part set (deformable hexahedra, shells, beams) is on the positive side
  // when its reference centroid c satisfies (c - tail) . N >= 0, else on the negative side. The
  // section's nodes are the nodes shared by elements of both sides whose reference position lies
  // inside the cut's bounds (disc, rectangle, or unbounded plane). The section force is the sum of
  // the nodal forces (and moments) of the negative-side elements at those nodes: by the
  // equilibrium of every element this equals the force the positive side exerts across the cut.
  // Throws rf::InputError when the plane cuts no deformable element.
  CrossSectionCut(const model::Model& model, const NodeIndex& node_index, const State& state,
                  const model::CrossSection& section);

  SectionForce evaluate(const State& state) const;
  model::Id id() const { return id_; }
  std::size_t node_count() const { return nodes_.size(); }

 private:
  // A force slot: at `offset` in the force array of block `block` of `family` (3 forces, then 3
  // moments for shells and beams) acting on `node`. Looked up by index at each evaluation, so
  // that the cut stays valid when the blocks are rebuilt (restart).
  enum class Family : std::uint8_t { kHex, kShell, kBeam };
  struct Slot {
    Family family;
    std::int32_t block;
    std::int64_t offset;
    std::int32_t node;
  };
  // *DATABASE_CROSS_SECTION_SET: nodes and elements from the sets; no normal (normal_force 0).
  void build_from_sets(const model::Model& model, const NodeIndex& node_index,
                       const State& state, const model::CrossSection& section);

  model::Id id_ = 0;
  std::array<double, 3> normal_{};
  std::vector<Slot> slots_;
  std::vector<std::int32_t> nodes_;  // the section's nodes (dense indices), ascending
};

std::vector<CrossSectionCut> build_cross_sections(const model::Model& model, const State& state);

}  // namespace rf::solver
