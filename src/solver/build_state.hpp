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

// Hourglass settings of a part (its HGID, else *CONTROL_HOURGLASS); IHQ outside 1-6 is an error.
element::HourglassSettings resolve_hourglass(const model::Model& model, const model::Part& part);
// The bulk viscosity coefficients of a part's solids (*CONTROL_BULK_VISCOSITY, the part's
// *HOURGLASS Q1/Q2); shells take them only with TYPE -1/-2 (build_structural.cpp).
element::BulkViscositySettings resolve_bulk_viscosity(const model::Model& model,
                                                      const model::Part& part);

// A part's material as the kernels use it; errors when the material is undefined, not
// simulated, or does not run on the element family (`family`: a material::ElementFamily bit).
struct ResolvedMaterial {
  bool rigid = false;
  int index = -1;  // in material::SolidMaterials; -1 for *MAT_RIGID
  material::ElasticConstants elastic;
  material::PlasticParameters plastic;
  material::BarlatParameters barlat;  // *MAT_036
};
ResolvedMaterial resolve_material(const model::Model& model, const model::Part& part,
                                  unsigned family, const char* family_name);

// Shell and beam blocks (one per part), their rotational degrees of freedom, lumped masses and
// inertias, and the structural incidence (solver/build_structural.cpp). Called by build_state.
void build_structural_blocks(const model::Model& model, const NodeIndex& node_index,
                             State& state);

// Throws rf::InputError when a model with shells or beams uses a subsystem that does not
// handle them yet (contact, part switching, flexible bodies).
void check_structural_support(const model::Model& model, const State& state);

// Adds the shell and beam force slots to nodes.f_int and sets rotations.m_int (fixed order).
void assemble_structural_forces(State& state);

// Discrete element blocks (springs, dampers), one per part (solver/build_discrete.cpp).
void build_discrete_blocks(const model::Model& model, const NodeIndex& node_index, State& state);
// The inverse masses each discrete element's step is based on; rigid-body nodes count with
// their body's mass. Call once the rigid bodies exist (and after a part switch).
struct RigidSystem;
void prepare_discrete_time_steps(State& state, const RigidSystem& rigid);
// Adds the discrete elements' forces to nodes.f_int (serial, fixed order).
void assemble_discrete_forces(State& state);
// Adds the work of the discrete elements' forces over the step, with the nodal displacements
// dt_avg (v^{n-1/2} + v^{n+1/2}) / 2 of the energy sums, to their blocks' spring and damper
// energies.
void add_discrete_work(State& state, const Vec3Array& v_previous, double dt_avg);

// Builds nodes, element blocks (one per part), lumped masses and the node->element-slot
// incidence. Throws rf::InputError for inconsistent input and rf::SolverError for inverted
// elements in the reference configuration.
State build_state(const model::Model& model, const NodeIndex& node_index);

// Sums each node's element-force slots into nodes.f_int (fixed order: deterministic).
void assemble_internal_forces(State& state);

}  // namespace rf::solver
