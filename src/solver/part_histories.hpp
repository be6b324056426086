// Per-part and per-node histories that LS-DYNA writes as MATSUM and SPCFORC (docs/output.md):
// energies and momenta of every part, reaction forces of constrained nodes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/boundary.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// One row of matsum.csv.
struct PartSummary {
  model::Id part = 0;
  double internal_energy = 0.0;  // work of the part's element forces, hourglass excluded
  double kinetic_energy = 0.0;
  double hourglass_energy = 0.0;
  double bulk_viscosity_energy = 0.0;  // excluded from internal_energy
  std::array<double, 3> momentum{};
  std::array<double, 3> rigid_velocity{};  // centre-of-mass velocity of a rigid part, else 0
  double added_mass = 0.0;  // mass scaling: mass added to the part's elements (solver/mass_scaling)
};

// Energy bookkeeping per part, the parts' shares of glstat's internal, hourglass and kinetic
// energy and momentum. Internal work of a part: sum over its elements (solids, shells, beams)
// of the element nodal forces (and moments) times the nodal displacement (and rotation) of the
// step, the same the global balance uses, so the parts' values add up to glstat's to round-off.
// Kinetic energy (rotary included) and momentum of a node shared by several parts count for the
// first part (in block order: solids, shells, beams) that uses it; rigid
// bodies count for their lead part (nodal rigid bodies under their PID).
class PartHistories {
 public:
  PartHistories(const State& state, const RigidSystem& rigid);

  // After the velocity update of a step: adds each part's internal work over the step
  // (v_previous = v^{n-1/2}, state.nodes.v = v^{n+1/2}, dt_average as in the global balance).
  void add_step_work(const State& state, const RigidSystem& rigid, const Vec3Array& v_previous,
                     double dt_average);
  // Hourglass and bulk viscosity work of block `slot` in the last force evaluation; slots count
  // the hexahedron blocks, then the shell blocks, then the beam blocks.
  void add_hourglass(std::size_t slot, double work, double bulk_viscosity_work) {
    hourglass_[part_of_block_[slot]] += work;
    bulk_viscosity_[part_of_block_[slot]] += bulk_viscosity_work;
  }

  std::vector<PartSummary> summaries(const State& state, const RigidSystem& rigid) const;

  // Accumulated per-part work (restart dumps).
  std::vector<double>& internal_work() { return internal_work_; }
  std::vector<double>& hourglass() { return hourglass_; }
  std::vector<double>& bulk_viscosity() { return bulk_viscosity_; }

 private:
  std::vector<model::Id> parts_;        // ascending part IDs (then nodal rigid body PIDs)
  std::vector<int> part_of_block_;      // block slot (hexahedra, shells, beams) -> parts_ index
  std::vector<int> owner_of_node_;      // node -> index into parts_ (-1: no element)
  std::vector<double> internal_work_;   // per part, hourglass included
  std::vector<double> hourglass_;       // per part
  std::vector<double> bulk_viscosity_;  // per part
  Vec3Array displacement_;              // scratch: the step's work displacement per node
  Vec3Array rotation_increment_;        // scratch: the step's work rotation per rotational index
};

// Reaction of a constrained node (SPC, *NODE TC/RC, prescribed motion of any DOF) at the output
// time t^n: r = m (v^{n+1/2} - v^{n-1/2}) / dt_avg - (f_ext - f_int), the force the constraint
// applied in the step, projected on the constrained directions (the fixed or prescribed axes and
// the vectors of DOF 4): free directions get 0. The moment likewise from the rotations,
// I (omega^{n+1/2} - omega^{n-1/2}) / dt_avg - (m_ext - m_int), on the fixed rotational axes and
// the vectors of DOF 5-8; 0 at nodes without rotations.
struct NodeReaction {
  std::int32_t node = 0;  // dense index
  std::array<double, 3> force{};
  std::array<double, 3> moment{};
};
std::vector<NodeReaction> constraint_reactions(const State& state, const Boundary& boundary,
                                               const RigidSystem& rigid,
                                               const Vec3Array& v_previous, double dt_average);

}  // namespace rf::solver
