// Modal state of one flexible rigid body (*PART_MODES) in its floating frame, independent of
// the mesh: preparation of the modes for the body frame, the inertia invariants, one explicit
// step of the modal equations (kick + exact damped-oscillator flow) and the modal energies.
// Theory, notation and choices: docs/flexible_bodies.md.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <vector>

namespace rf::modal {

// Formulation (*PART_MODES FORM): 0 keeps the frame inertia terms (centrifugal, Coriolis,
// Euler) in the modal equations, 1 drops them.
enum class ModalForm : std::uint8_t { kExact = 0, kFast = 1 };

struct FlexibleBody {
  ModalForm form = ModalForm::kExact;
  std::size_t node_count = 0;  // N, nodes in the order of the body's node list
  std::size_t mode_count = 0;  // n
  std::vector<double> omega;   // w_k (rad/s), in the kept order (ascending if re-orthonormalised)
  std::vector<double> zeta;    // fraction of critical damping per mode
  // Body-axes mode shapes, node-major: phi[(3 i + d) n + k]. Mass-orthonormal with `mass`,
  // free of rigid content (docs/flexible_bodies.md section 1).
  std::vector<double> shapes;
  std::vector<double> mass;         // lumped mass per node (the solver's)
  // Nodes with rotations (shells, beams): r of them. rotation_position[j] is the position in
  // the node list of rotation row j, rotation_of[k] the row of node position k (-1: none).
  // Rotational mode shapes psi, body axes, row-major like `shapes`: psi[(3 j + d) n + k], with
  // the solver's isotropic lumped rotational inertia J_j. Mass-orthonormality and the rigid
  // content (section 1 of docs/flexible_bodies.md) include them: Phi^T M Phi + Psi^T J Psi = I.
  std::size_t rotation_count = 0;
  std::vector<std::int32_t> rotation_position;
  std::vector<std::int32_t> rotation_of;
  std::vector<double> rotation_shapes;
  std::vector<double> rotational_inertia;
  std::vector<double> body_coords;  // X_i, 3 per node, body axes
  // Inertia invariants (FORM 0): A_k (9 per mode, row-major), B_kl (9 per pair, index k n + l),
  // s_lk (3 per pair, index l n + k).
  std::vector<double> inv_a;
  std::vector<double> trace_a;
  std::vector<double> inv_b;
  std::vector<double> inv_s;
  // FORM 0 with a mesh: the cubic strain-energy invariants G_mkl (index (m n + k) n + l,
  // symmetric in k, l) that give geometric (stress) stiffening, U3 = 1/2 G_mkl q_m q_k q_l.
  std::vector<double> inv_g;

  // State: q^n and s (the modal velocity after the last flow, i.e. before the next kick).
  std::vector<double> q;
  std::vector<double> s;
  std::vector<double> q_previous;  // q before the last step (output at t^n)
  std::vector<double> s_mid;       // mean of s before and after the last kick (work)
  std::vector<double> force;       // scratch: modal forces g_k of the current step
  std::vector<double> inertia;     // scratch: inertia terms h_k of the current step
  std::vector<double> stiffening;  // scratch: geometric-stiffening forces of the current step
  double damping_loss = 0.0;       // energy removed by modal damping in the last step
  double inertia_work = 0.0;       // work of the inertia terms in the last step (FORM 0)
  double stiffening_work = 0.0;    // work of the geometric-stiffening forces in the last step

  // Link to the solver (filled by solver::attach_flexible_bodies).
  int body = -1;                           // index of the rigid body
  std::int64_t part = 0;                   // lead part ID
  std::vector<int> file_modes;             // 1-based mode numbers in the database, per kept mode
  std::vector<std::int32_t> active;        // positions in the body's node list updated every cycle
  std::vector<std::int32_t> active_nodes;  // their dense node indices
  std::vector<std::int32_t> passive;       // positions reconstructed only for output

  const double* shape_row(std::size_t node, int d) const {
    return shapes.data() + (3 * node + d) * mode_count;
  }
  const double* rotation_row(std::size_t row, int d) const {
    return rotation_shapes.data() + (3 * row + d) * mode_count;
  }
  // theta_j = sum_k psi_jk a_k (body axes) for rotation row j.
  Eigen::Vector3d rotation(std::size_t row, const std::vector<double>& a) const;
  // u_i = sum_k phi_ik a_k (body axes) for amplitudes a.
  Eigen::Vector3d displacement(std::size_t node, const std::vector<double>& a) const;
  double kinetic_energy() const;  // 1/2 sum s_k^2
  double elastic_energy() const;  // 1/2 sum w_k^2 q_k^2
};

// Input to prepare_flexible_body: the body's nodes (body axes, solver masses) and the selected
// database modes (global axes at the reference configuration, mass-normalised with the
// database's masses), with their eigenvalues.
struct ModeInput {
  std::vector<double> body_coords;    // X_i, 3 per node
  std::vector<double> mass;           // per node
  Eigen::Matrix3d initial_rotation;   // R0: body axes -> global axes
  std::vector<double> shapes_global;  // mode k node i direction d at [k 3N + 3 i + d]
  std::vector<double> eigenvalues;    // per selected mode
  std::vector<double> damping;        // per selected mode (fraction of critical)
  // Nodes with rotations (optional): positions in the node list, their lumped rotational
  // inertia, and the modes' rotational components (global axes), mode k row j axis d at
  // [k 3r + 3 j + d].
  std::vector<std::int32_t> rotation_position;
  std::vector<double> rotational_inertia;
  std::vector<double> rotation_shapes_global;
  ModalForm form = ModalForm::kExact;
  // Optional (FORM 0): the body's 8-node hexahedra as positions in its node list, and its
  // material's Lame constants, for the geometric-stiffening invariants. Empty: none.
  std::vector<std::int32_t> hexahedra;
  double lame_lambda = 0.0;
  double lame_mu = 0.0;
};

// Rotates the modes to body axes, removes their rigid content with the given masses,
// re-orthonormalises them (n x n eigenproblem with the database stiffness diag(lambda)) and
// computes the invariants. Throws std::invalid_argument when a mode is (nearly) rigid.
FlexibleBody prepare_flexible_body(const ModeInput& input);

// One step of the modal equations (docs/flexible_bodies.md section 3): uses body.force (g, set
// by the caller from the nodal forces at t^n), adds the inertia terms for FORM 0 with the body
// angular velocity `omega_body` and acceleration `alpha_body` at t^n (body axes), kicks s by
// dt_avg, then advances (q, s) over dt with the exact damped-oscillator flow.
void advance_modes(FlexibleBody& body, const Eigen::Vector3d& omega_body,
                   const Eigen::Vector3d& alpha_body, double dt_avg, double dt);

// The exact flow of q'' + 2 zeta w q' + w^2 q = 0 over h (under-, critically and over-damped).
void oscillator_flow(double omega, double zeta, double h, double& q, double& s);

}  // namespace rf::modal
