// Turns a Model (user IDs, as read) into the solver's dense State.
#pragma once

#include <cstdint>
#include <unordered_map>

#include "model/model.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// Dense index of every user node ID; errors name the definition that used an unknown ID.
class NodeIndex {
 public:
  explicit NodeIndex(const model::Model& model);
  // Throws rf::InputError at `where` (field `field`) when the node does not exist.
  std::int32_t at(model::Id id, const model::SourceLocation& where, const char* field) const;
  bool contains(model::Id id) const { return index_.count(id) != 0; }
  std::size_t size() const { return index_.size(); }

 private:
  std::unordered_map<model::Id, std::int32_t> index_;
};

// Builds nodes, element blocks (one per part), lumped masses and the node->element-slot
// incidence. Throws rf::InputError for inconsistent input and rf::SolverError for inverted
// elements in the reference configuration.
State build_state(const model::Model& model, const NodeIndex& node_index);

// Sums each node's element-force slots into nodes.f_int (fixed order: deterministic).
void assemble_internal_forces(State& state);

}  // namespace rf::solver
