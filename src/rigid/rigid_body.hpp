// Rigid-body dynamics, independent of the mesh: the state of one body, its creation from
// lumped nodal masses or from user-given inertia (*PART_INERTIA), and one explicit cycle of
// its translational and rotational motion in the same staggered (leapfrog) scheme as the
// nodes. Theory, order and measured conservation: docs/rigid_bodies.md.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Dense>

namespace rf::rigid {

// Velocity constraints of a body: each row says n . v_c = value (translation) or n . w = value
// (rotation), n a unit vector in global axes. Fixed DOFs have value 0; prescribed motion sets
// the value every step. At most three of each kind (a fully held body).
struct VelocityConstraints {
  int translation_count = 0;
  int rotation_count = 0;
  std::array<Eigen::Vector3d, 3> translation_axis;
  std::array<double, 3> translation_value{};
  std::array<Eigen::Vector3d, 3> rotation_axis;
  std::array<double, 3> rotation_value{};

  // Returns false (and adds nothing) when three constraints of the kind exist already.
  bool add_translation(const Eigen::Vector3d& axis, double value);
  bool add_rotation(const Eigen::Vector3d& axis, double value);
  // Holds the global axes whose flags are set (CMO-style codes decoded by the caller).
  void fix_global_translation(const std::array<bool, 3>& axes);
  void fix_global_rotation(const std::array<bool, 3>& axes);
  bool empty() const { return translation_count == 0 && rotation_count == 0; }
  void clear() { translation_count = rotation_count = 0; }
};

// True when the constraint axes of each kind are linearly independent (the constrained
// velocity is then unique; dependent axes would over-constrain the body).
bool constraints_independent(const VelocityConstraints& a, const VelocityConstraints& b);

// Time levels follow the nodes: positions and rotation at t^n, velocities and momenta at
// t^{n+1/2} (at creation, the initial values stand for t^{-1/2}).
struct RigidBodyState {
  double mass = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();    // x_c^n, centre of mass
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // v_c^{n+1/2}
  // R^n, body (principal) axes -> global axes; a proper rotation (det +1).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  // J_b: principal moments about the centre of mass, in body axes (ascending if computed).
  Eigen::Vector3d principal_inertia = Eigen::Vector3d::Ones();
  // L^{n+1/2} about the centre of mass, global axes. The primary rotational variable: the
  // torque changes it exactly (L += dt T), the free rotation never touches it.
  Eigen::Vector3d angular_momentum = Eigen::Vector3d::Zero();
  // w^{n+1/2}, global axes: the constant angular velocity that carries R^n to R^{n+1},
  // R^{n+1} = exp(dt [w]) R^n, so nodes moved with it follow the body (see advance).
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  // x_c and R before the last advance (x_c^n, R^n once the body sits at n+1): the linear node
  // update needs the lever arms x_i^n - x_c^n, output reports the body at t^n.
  Eigen::Vector3d previous_centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d previous_rotation = Eigen::Matrix3d::Identity();

  // Permanent constraints (CMO, nodal rigid body _SPC), applied after each momentum update
  // together with any per-step constraints passed to advance_rigid_body. The impulses they
  // exerted in the last step are kept for reactions and reaction work.
  VelocityConstraints constraints;
  Eigen::Vector3d reaction_impulse = Eigen::Vector3d::Zero();          // on v_c (M dv)
  Eigen::Vector3d reaction_angular_impulse = Eigen::Vector3d::Zero();  // on L
};

// Mass, centre and inertia tensor about the centre of a set of point masses.
struct MassProperties {
  double mass = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // global axes, about the centre
};

// Parallel-axis sum of mass properties, each about its own centre (merged bodies).
MassProperties combine(const std::vector<MassProperties>& parts);

MassProperties mass_properties(std::span<const double> masses,
                               std::span<const Eigen::Vector3d> positions);
// The same for the nodes `nodes` of struct-of-arrays nodal data (the solver's NodalState).
MassProperties mass_properties(const std::vector<std::int32_t>& nodes, const double* mass,
                               const double* x, const double* y, const double* z);

// A body at rest whose rotation R0 holds the principal axes of `inertia` (global, about the
// centre) as columns, ordered by ascending moment and made a proper rotation. This is the
// *PART_INERTIA path; the point-mass overloads call it with their own mass properties.
RigidBodyState make_rigid_body(double mass, const Eigen::Vector3d& centre,
                               const Eigen::Matrix3d& inertia);
RigidBodyState make_rigid_body(const MassProperties& properties);
RigidBodyState make_rigid_body(std::span<const double> masses,
                               std::span<const Eigen::Vector3d> positions);

// I = R J_b R^T, the inertia tensor about the centre in global axes at the current R.
Eigen::Matrix3d global_inertia(const RigidBodyState& body);
// w = R J_b^-1 R^T L at rotation `rotation`.
Eigen::Vector3d angular_velocity_from_momentum(const Eigen::Matrix3d& rotation,
                                               const Eigen::Vector3d& principal_inertia,
                                               const Eigen::Vector3d& angular_momentum);
// Sets v_c and w and the matching L = I(R) w (initial conditions).
void set_velocity(RigidBodyState& body, const Eigen::Vector3d& velocity,
                  const Eigen::Vector3d& angular_velocity);
// 1/2 M |v_c|^2 + 1/2 L . w at the half step (the scheme's kinetic energy, see docs).
double kinetic_energy(const RigidBodyState& body);

// One cycle. dt_avg = (dt^{n-1/2} + dt^{n+1/2}) / 2 for the momenta, dt = dt^{n+1/2} for the
// positions; force and torque (about x_c^n) are evaluated at t^n:
//   v_c^{n+1/2} = v_c^{n-1/2} + dt_avg F / M          then translation constraints
//   L^{n+1/2}   = L^{n-1/2}   + dt_avg T
//   R^{n+1}     = free rotation of R^n over dt at constant L^{n+1/2} (symmetric splitting)
//   x_c^{n+1}   = x_c^n + dt v_c^{n+1/2}
// With rotation constraints the body turns with the constrained w instead (see docs).
// `step_constraints` (may be null) are added to body.constraints for this step only
// (prescribed motion).
void advance_rigid_body(RigidBodyState& body, const Eigen::Vector3d& force,
                        const Eigen::Vector3d& torque_about_centre, double dt_avg, double dt,
                        const VelocityConstraints* step_constraints = nullptr);

// R^{n+1} from R^n for the torque-free body with constant spatial L over step h:
// R <- R e1(h/2) e2(h/2) e3(h) e2(h/2) e1(h/2), the exact flows of the three principal
// parts of the kinetic energy (McLachlan 1993; Dullweber, Leimkuhler & McLachlan 1997).
Eigen::Matrix3d free_rotation(const Eigen::Matrix3d& rotation,
                              const Eigen::Vector3d& principal_inertia,
                              const Eigen::Vector3d& angular_momentum, double h);

// ---- Node kinematics on struct-of-arrays data -------------------------------------------

// Body-frame coordinates X_i = R^T (x_i - x_c), fixed at creation of the body.
struct BodyCoordinates {
  std::vector<double> x, y, z;  // parallel to the node list they were made from
};
BodyCoordinates body_coordinates(const RigidBodyState& body, const std::vector<std::int32_t>& nodes,
                                 const double* x, const double* y, const double* z);

// Curvilinear update: x_i = x_c + R X_i. Exactly rigid at any rotation.
void place_nodes_curvilinear(const RigidBodyState& body, const std::vector<std::int32_t>& nodes,
                             const BodyCoordinates& body_coords, double* x, double* y, double* z);

// Linear (incremental tangent) update: x_i += dt (v_c + w x (x_i - x_c^n)), with
// x_c^n = body.previous_centre. Matches the element strain increments v dt, but a node at
// radius r moves out by about r (w dt)^2 / 2 per step.
void advance_nodes_linear(const RigidBodyState& body, const std::vector<std::int32_t>& nodes,
                          double dt, double* x, double* y, double* z);

// v_i = v_c + w x (x_i - centre), written into vx, vy, vz for the listed nodes.
void rigid_node_velocities(const Eigen::Vector3d& velocity, const Eigen::Vector3d& angular_velocity,
                           const Eigen::Vector3d& centre, const std::vector<std::int32_t>& nodes,
                           const double* x, const double* y, const double* z, double* vx,
                           double* vy, double* vz);

struct ForceAndTorque {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // about the centre used to gather
  ForceAndTorque& operator+=(const ForceAndTorque& o) {
    force += o.force;
    torque += o.torque;
    return *this;
  }
  ForceAndTorque& operator-=(const ForceAndTorque& o) {
    force -= o.force;
    torque -= o.torque;
    return *this;
  }
};

// F = sum f_i, T = sum (x_i - centre) x f_i over the listed nodes.
ForceAndTorque gather_force_and_torque(const Eigen::Vector3d& centre,
                                       const std::vector<std::int32_t>& nodes, const double* fx,
                                       const double* fy, const double* fz, const double* x,
                                       const double* y, const double* z);

}  // namespace rf::rigid
