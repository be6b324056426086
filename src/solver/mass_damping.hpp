// Added masses (*ELEMENT_MASS, *ELEMENT_MASS_PART) and mass-proportional damping
// (*DAMPING_GLOBAL, *DAMPING_PART_MASS), resolved to dense node indices.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/model.hpp"
#include "solver/boundary.hpp"
#include "solver/build_state.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// Adds the masses of *ELEMENT_MASS and *ELEMENT_MASS_PART to the lumped nodal masses
// (state.nodes.mass must hold the element masses). A part's addition is spread over its nodes in
// proportion to the mass the part's own elements lump to each node, so the part's centre of mass
// and the shape of its mass distribution stay as they were. Returns the total mass added.
// Throws InputError naming the card for unknown nodes, parts or sets, and for a FINMASS below
// the part's own mass.
double add_mass_elements(const model::Model& model, const NodeIndex& node_index, State& state);

// MassDampingSystem (the resolved damping cards) lives in Boundary (solver/boundary.hpp).
// Resolves the damping cards to terms and a term per node. Throws InputError naming the card
// for unknown curves, parts or part sets.
MassDampingSystem resolve_mass_damping(const model::Model& model, const State& state);

// Adds the damping forces f = -d(t) ST m v to f_ext of every node that is not on a rigid body
// (`mass_of_node` = Boundary::body_force_mass: the lumped mass, 0 on rigid-body nodes), with the
// velocity v^{n+1/2} that carried the nodes to t: the forces at t^{n+1} see v^{n+1/2}, the usual
// explicit lag of velocity-dependent forces (stable for d dt < 2), and the moments
// m = -d(t) SR J w to m_ext of the nodal spins (shells, beams). Rigid bodies are damped at
// their centre of mass in advance_rigid_bodies. Also records the forces in damping.force and the
// moments in damping.moment.
void add_damping_forces(const MassDampingSystem& damping, const std::vector<double>& mass_of_node,
                        double t, State& state);

}  // namespace rf::solver
