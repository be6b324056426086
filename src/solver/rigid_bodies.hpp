// Rigid bodies in the explicit cycle: which nodes move with which body (rigid parts, merged
// parts, extra nodes, nodal rigid bodies), the bodies' mass properties and constraints, and
// the coupling phases that turn nodal forces into body motion and body motion into nodal
// velocities and positions. The body dynamics themselves live in rigid/rigid_body.hpp.
// Theory and choices: docs/rigid_bodies.md.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "modal/flexible_body.hpp"
#include "model/model.hpp"
#include "rigid/rigid_body.hpp"
#include "solver/boundary.hpp"
#include "solver/build_state.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// How the nodes of a body follow it (*RIGID_BODY_UPDATE, docs/rigid_bodies.md):
// linear: x_i += dt (v_c + w x (x_i - x_c)), the increment deformable neighbours see;
// curvilinear: x_i = x_c + R X_i, exactly rigid.
enum class NodeUpdate : std::uint8_t { kLinear, kCurvilinear };

// A *BOUNDARY_PRESCRIBED_MOTION_RIGID resolved to one body and one global axis.
struct RigidMotion {
  int body = 0;
  bool rotation = false;                            // DOF 5-8
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit, global, fixed in time
  int vad = 0;                                      // 0 velocity, 1 acceleration, 2 displacement
  ScaledCurve value;
  double birth = 0.0;
  double death = 1e28;
  // _LOCAL: `axis` is fixed in the body; the global axis is R R0^T axis at each step.
  bool body_fixed = false;
  double reference = 0.0;  // VAD 2 global translation: axis . x_c at t = 0
  double travelled = 0.0;  // VAD 2 rotation or body-fixed translation: so far
  model::SourceLocation where;
};

// A *LOAD_RIGID_BODY resolved: force (or moment) along a global axis at the centre of mass.
struct RigidLoadTerm {
  int body = 0;
  bool moment = false;
  int axis = 0;
  ScaledCurve value;
};

struct RigidBody {
  model::Id id = 0;                 // lead part ID, or the nodal rigid body's PID
  bool nodal = false;               // *CONSTRAINED_NODAL_RIGID_BODY (or a spot weld)
  bool weld = false;                // *CONSTRAINED_SPOTWELD: id is the weld ID (nodal is set)
  std::vector<model::Id> parts;     // merged parts, lead first
  std::vector<std::int32_t> nodes;  // dense node indices, ascending
  bool inertia_from_card = false;   // *PART_INERTIA / _INERTIA (else from lumped masses)
  bool shares_nodes = false;        // a node also belongs to a deformable element
  NodeUpdate update = NodeUpdate::kCurvilinear;
  rigid::RigidBodyState state;
  rigid::BodyCoordinates body_coordinates;  // X_i = R0^T (x_i - x_c0), parallel to nodes
  Eigen::Matrix3d initial_rotation = Eigen::Matrix3d::Identity();
  // Columns: the body's output axes at t = 0 in global axes (*MAT_RIGID LCO or A/V vectors,
  // the nodal rigid body's CID; else the global axes). rbdout reports R R0^T output_axes.
  Eigen::Matrix3d output_axes = Eigen::Matrix3d::Identity();

  // Filled by each advance: velocities before it (v^{n-1/2}, w^{n-1/2}) for output and the
  // energy balance; force and torque that drove it (t^n).
  Eigen::Vector3d velocity_before = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_before = Eigen::Vector3d::Zero();
  Eigen::Vector3d mid_velocity = Eigen::Vector3d::Zero();          // (v^{n-1/2} + v^{n+1/2}) / 2
  Eigen::Vector3d mid_angular_velocity = Eigen::Vector3d::Zero();  // the same for w
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  // Force and torque (about x_c) of *CONSTRAINED_JOINT_STIFFNESS on the body, evaluated at t^n
  // (solver/joint_stiffness.hpp) and added to the next advance; their work is internal work.
  Eigen::Vector3d joint_force = Eigen::Vector3d::Zero();
  Eigen::Vector3d joint_torque = Eigen::Vector3d::Zero();
  rigid::VelocityConstraints step_constraints;  // scratch, reused every step
  int flexible = -1;  // index into RigidSystem::flexible (*PART_MODES), -1: rigid
};

struct RigidSystem {
  std::vector<RigidBody> bodies;
  std::vector<std::int32_t> body_of_node;  // per node: body index, -1 if not rigid
  std::vector<RigidMotion> motions;        // grouped by body (ascending body index)
  std::vector<RigidLoadTerm> loads;
  std::vector<model::Warning> warnings;  // notices found while building (shown by the CLI)
  // Flexible bodies (*PART_MODES, solver/flexible_bodies.hpp) and, per node (3 each, global
  // axes), the modal velocity R^n Phi_i s_mid of the last step: its share of the displacement
  // with which the work of the nodal forces is summed (empty without flexible bodies).
  std::vector<modal::FlexibleBody> flexible;
  std::vector<double> modal_work_velocity;
  // The same for nodes with rotations (3 per rotational index; empty without rotations): the
  // modal angular velocity added to the body's, and its work velocity.
  std::vector<double> modal_rotation_velocity;
  std::vector<double> modal_rotation_work_velocity;

  bool empty() const { return bodies.empty(); }
  bool is_rigid(std::int32_t node) const {
    return !body_of_node.empty() && body_of_node[node] >= 0;
  }
};

// Finds every rigid body of the model and its nodes, mass properties, constraints, motions,
// loads and node-update mode. Needs the state (lumped masses, blocks) already built.
RigidSystem build_rigid_system(const model::Model& model, const NodeIndex& node_index,
                               const State& state);

// Initial velocities: each body takes the rigid motion that carries the momentum and angular
// momentum of the velocities *INITIAL_VELOCITY* gave its nodes (exact for rigid velocity
// fields), unless its inertia card gives velocities and no card with IRIGID = 1 addresses it.
// The body's nodes then get the rigid velocity field.
void initialize_rigid_velocities(const model::Model& model, const NodeIndex& node_index,
                                 RigidSystem& rigid, State& state);

// What the rigid bodies contribute to the energy and momentum sums at n+1/2.
struct RigidStepSums {
  double kinetic = 0.0;
  double external_work = 0.0;  // body loads, body forces and constraint reactions
  double momentum[3] = {0, 0, 0};
  double angular_momentum[3] = {0, 0, 0};  // about the global origin
  // Flexible bodies: elastic energy of the modes (their kinetic energy is in `kinetic`), the
  // energy modal damping removed this step and the work of FORM 0 inertia terms this step.
  double modal_elastic = 0.0;
  double modal_damping_loss = 0.0;
  double modal_inertia_work = 0.0;
  double modal_stiffening_work = 0.0;  // work of the geometric-stiffening forces (internal)
  double damping_work = 0.0;           // work of *DAMPING_* on the bodies (part of external_work)
  // Work of the *CONSTRAINED_JOINT_STIFFNESS loads on the bodies this step (internal: its
  // negative is the joints' stored and dissipated energy).
  double joint_stiffness_work = 0.0;
};

// One rigid step from t^n (after the nodal velocity update): force and torque from the
// nodal forces f_ext - f_int on the body's nodes plus body-level loads and body forces,
// momentum update with constraints and prescribed motion, rotation to R^{n+1}, and the nodal
// velocities v^{n+1/2} that carry the nodes to their place at t^{n+1}.
RigidStepSums advance_rigid_bodies(RigidSystem& rigid, const Boundary& boundary, double t_n,
                                   double dt_avg, double dt, State& state);

// After x^{n+1} = x^n + dt v^{n+1/2}: puts the nodes of curvilinear bodies exactly at
// x_c + R X_i (removing the round-off of the increment).
void place_curvilinear_nodes(const RigidSystem& rigid, State& state);

// Orientation for output: the rotation that maps the body's output axes to global axes at the
// body's time t^n (previous_rotation once advanced).
Eigen::Matrix3d output_rotation(const RigidBody& body);

// Mass properties of lumped nodes (dense indices) at their current places: their masses and,
// for nodes with rotations (shells, beams), their isotropic rotary inertia I, a point of inertia
// I about every axis through itself, so that a body of them carries sum m r x v + sum I w.
rigid::MassProperties lumped_mass_properties(const std::vector<std::int32_t>& nodes,
                                             const State& state);

// Mass properties of the body of a spot weld between dense nodes a and b (at their current
// places): their lumped masses, the rotary inertia of nodes with rotations, and a small moment
// about the line between them where nothing else gives one (docs/theory.md "Spot welds").
rigid::MassProperties spot_weld_properties(std::int32_t a, std::int32_t b, const State& state);

// Removes the bodies whose index is in `gone`; every reference to a body (nodes, motions,
// loads, flexible bodies) is renumbered, a removed body's references go to moved_to[b].
void remove_rigid_bodies(RigidSystem& rigid, const std::set<int>& gone,
                         const std::map<int, int>& moved_to = {});

// Kinetic energy and momenta of the bodies at their current velocities (initial values).
RigidStepSums rigid_body_sums(const RigidSystem& rigid);

}  // namespace rf::solver
