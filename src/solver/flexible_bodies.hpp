// Flexible rigid bodies (*PART_MODES) in the explicit cycle: building the modal state of each
// body from the mode database, the modal forces from the nodal forces, the nodes' secant
// velocities and positions reconstructed from rigid motion plus modes, and the initial modal
// velocities. The modal dynamics live in modal/flexible_body.hpp. docs/flexible_bodies.md.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "modal/mode_set.hpp"
#include "solver/boundary.hpp"
#include "solver/rigid_bodies.hpp"

namespace rf::solver {

// Reads a mode database (default: modal::read_mode_database). Tests may hand in modes made in
// code.
using ModeLoader = std::function<modal::ModeSet(const std::filesystem::path&)>;

// The modes a *PART_MODES card selects for the nodes `body_nodes` (dense, ascending): the
// database read by `loader`, its nodes matched by ID and checked against the model's reference
// coordinates, modes chosen by NMFB (the first elastic ones) or the KMFLAG list, damping from
// the card. Throws rf::InputError at the card's FILENAME/NMFB/MODE1 field; `owner` names the
// body or part in the messages.
struct SelectedModes {
  std::vector<int> file_modes;  // 1-based mode numbers in the database
  std::vector<double> shapes;   // mode-major: 3 global components per body node
  std::vector<double> eigenvalues;
  std::vector<double> damping;  // fraction of critical damping per selected mode
  // Body nodes with rotations (positions in body_nodes) and the modes' rotational components
  // there, mode-major: 3 global components per such node (zero where the database has none).
  std::vector<std::int32_t> rotation_position;
  std::vector<double> rotation_shapes;
};
// `rotations`: the model's rotational DOFs, for bodies whose nodes may carry rotations (shells,
// beams). Null: the body is taken as translations only and a database with rotational
// components is refused.
SelectedModes select_part_modes(const model::PartModes& card, const std::string& owner,
                                const std::vector<std::int32_t>& body_nodes,
                                const NodalState& nodes, const ModeLoader& loader,
                                const RotationalState* rotations = nullptr);

// Makes the bodies named on *PART_MODES flexible: matches database nodes to the body's nodes by
// node ID, selects and prepares the modes, chooses the nodes reconstructed every cycle (those
// shared with deformable elements, constrained, loaded or recorded, and `contact_nodes`, the
// nodes of every contact surface, whose positions the contact search reads). Throws
// rf::InputError (at the *PART_MODES card) for missing nodes, geometry mismatches, too few or
// rigid modes.
void attach_flexible_bodies(const model::Model& model, const NodeIndex& node_index,
                            const State& state, const Boundary& boundary,
                            const std::vector<std::int32_t>& contact_nodes, RigidSystem& rigid,
                            const ModeLoader& loader);

// g = Phi^T R^T (f_ext - f_int) + Psi^T R^T (m_ext - m_int) over the active nodes, R = the
// body's rotation at t^n.
void gather_modal_forces(const RigidBody& body, modal::FlexibleBody& flexible,
                         const NodalState& nodes, const RotationalState& rotations);

// After the body and its modes advanced: v_i^{n+1/2} = (x_c^{n+1} + R^{n+1} (X_i + Phi_i
// q^{n+1}) - x_i^n) / dt for the active nodes, and their modal work velocity R^n Phi_i s_mid.
// Active nodes with rotations: their modal angular velocity R^{n+1} Psi_j (q^{n+1} - q^n) / dt
// (added to the body's by Simulation::update_rotations) and its work velocity R^n Psi_j s_mid,
// in `rigid.modal_rotation_velocity` / `modal_rotation_work_velocity` (3 per rotational index).
void set_flexible_node_velocities(const RigidBody& body, const modal::FlexibleBody& flexible,
                                  double dt, NodalState& nodes, std::vector<double>& work_velocity,
                                  const RotationalState& rotations,
                                  std::vector<double>& rotation_velocity,
                                  std::vector<double>& rotation_work_velocity);

// x_i = x_c + R (X_i + Phi_i q) for the active nodes (after the position update).
void place_flexible_nodes(const RigidBody& body, const modal::FlexibleBody& flexible,
                          NodalState& nodes);

// Before output between the velocity and the position update: the passive nodes get x^n
// (previous centre, rotation and q) and the secant velocity to their place at t^{n+1}.
void reconstruct_passive_nodes(const RigidSystem& rigid, State& state);

// Initial modal velocities: s_k = sum_i m_i phi_ik . R^T (v_i - v_c - w x (x_i - x_c)) from the
// nodes' initial velocities (before they are overwritten), then v_i += R Phi_i s.
// `rotations` (optional): the nodes' initial angular velocities enter s through the rotational
// components of the modes.
void initialize_modal_velocities(const RigidBody& body, modal::FlexibleBody& flexible,
                                 const std::vector<double>& initial_velocities, NodalState& nodes,
                                 const RotationalState* rotations = nullptr);

}  // namespace rf::solver
