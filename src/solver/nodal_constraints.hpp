// Nodal constraints between deformable nodes: spot welds (*CONSTRAINED_SPOTWELD, two-node nodal
// rigid bodies of the rigid system, failing by force or time) and constrained node sets
// (*CONSTRAINED_NODE_SET, a common velocity in chosen DOF). Both act on the replicated nodal
// state after the ranks' force sum. Theory and choices: docs/theory.md "Spot welds and
// constrained node sets"; switching (NCSF): docs/switching.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "solver/build_state.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// What became of a spot weld or a node set: acting, failed (for good), deleted by a switch with
// NCSF = 1 (NCSF = 2 activates it again), or merged into a rigid body made by part switching.
enum class ConstraintStatus : std::uint8_t { kActive = 0, kFailed = 1, kDeleted = 2, kMerged = 3 };

struct SpotWeldState {
  model::Id id = 0;
  std::int32_t n1 = -1, n2 = -1;  // dense node indices
  double sn = 0.0, ss = 0.0, n = 1.0, m = 1.0, tf = 1e20;
  ConstraintStatus status = ConstraintStatus::kActive;
  double failure_time = -1.0;  // time of failure (-1: has not failed)
  // Constraint force of the last check: normal (tension > 0, along N1 -> N2) and shear magnitude.
  double normal_force = 0.0;
  double shear_force = 0.0;
};

struct NodeSetTie {
  model::Id id = 0;
  std::vector<std::int32_t> nodes;  // dense, ascending
  std::array<bool, 3> axes{};       // x, y, z shared
  double tf = 1e20;
  ConstraintStatus status = ConstraintStatus::kActive;
  double failure_time = -1.0;
};

struct NodalConstraints {
  std::vector<SpotWeldState> welds;  // deck order
  std::vector<NodeSetTie> ties;      // deck order
  std::vector<std::string> notices;  // failures, deletions, activations (the log shows them)
  bool empty() const { return welds.empty() && ties.empty(); }
};

// Resolves the spot welds (whose bodies build_rigid_system made) and the node sets. Throws
// InputError naming the card for a missing set, a set of fewer than two nodes, or a tied node
// that moves with a rigid body.
NodalConstraints build_nodal_constraints(const model::Model& model, const NodeIndex& node_index,
                                         const State& state, const RigidSystem& rigid);

// Shares the velocity of each active tie's nodes in its DOF: v = sum m_i v_i / sum m_i, i.e. the
// common acceleration sum f_i / sum m_i (momentum exact). A tie whose time TF has come fails
// first. Call after v^{n+1/2} = v^{n-1/2} + dt a, before the nodal constraints.
void apply_node_set_ties(NodalConstraints& constraints, const RigidSystem& rigid, State& state,
                         double t);

// After the rigid bodies advanced: the force each active weld carries, from its nodes'
// momentum change, m_i (v_i^{n+1/2} - v_i^{n-1/2}) / dt_avg - (f_ext - f_int)_i; welds whose
// criterion (max(fn,0)/SN)^N + (|fs|/SS)^M >= 1 holds or whose time TF has come fail: their
// bodies are removed and the nodes go on with the velocities they have. Welds whose body was
// merged into another by switching are marked merged. Returns how many failed.
int check_spot_welds(NodalConstraints& constraints, RigidSystem& rigid, const State& state,
                     const Vec3Array& v_previous, double dt_avg, double t);

// NCSF = 1: every active weld and tie is deleted (welds: their bodies removed, nodes keep their
// velocities). NCSF = 2: deleted and merged welds and deleted ties act again from the current
// configuration, conserving the momenta of their nodes (the returned kinetic energy change is
// <= 0); a weld whose node moves with a rigid body now stays inactive (notice).
void delete_nodal_constraints(NodalConstraints& constraints, RigidSystem& rigid, double t);
double activate_nodal_constraints(NodalConstraints& constraints, RigidSystem& rigid, State& state,
                                  double t);

}  // namespace rf::solver
