// Planar rigid walls (*RIGIDWALL_PLANAR, _FINITE, _MOVING) enforced as kinematic constraints,
// the LS-DYNA "stonewall" constraint method (LS-DYNA Theory Manual, rigid walls): after the
// velocity update, a tracked node whose step x^{n+1} = x^n + dt v^{n+1/2} would end behind the
// wall loses the normal velocity that carries it past the wall, friction acts on its
// tangential velocity, and the wall force is the momentum it removed per step,
// f = m dv / dt_avg. The force is added to f_ext, so the energy balance counts the wall's work
// like any other reaction (external work). Nodes of rigid bodies are not changed one by one:
// their body receives the impulses that make its nodes land on the wall (solved together for
// all nodes of the body in contact, projected Gauss-Seidel with Coulomb friction), as nodal
// forces that advance_rigid_bodies then gathers. A moving wall is a mass on a straight guide
// along its normal; the impulses it gives the nodes change its momentum by the opposite amount.
// Theory, choices and limits: docs/theory.md section 6.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "solver/boundary.hpp"
#include "solver/build_state.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"

namespace rf::contact {

// A node the wall pushed in the last cycle and the force it applied (impulse / dt_avg, global).
struct WallContact {
  std::int32_t node = 0;
  std::int32_t body = -1;  // rigid body index when the node moves with a body, else -1
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

// The surface a wall keeps nodes away from: a plane (*RIGIDWALL_PLANAR, *RIGIDWALL_GEOMETRIC_FLAT,
// with the rectangle of _FINITE/FLAT), or the closed shapes of *RIGIDWALL_GEOMETRIC_PRISM
// (box), _CYLINDER (lateral surface only, axis along `normal`) and _SPHERE.
enum class WallShape { Plane, Prism, Cylinder, Sphere };

struct RigidWall {
  int number = 0;     // 1-based position in the deck (what *DEFORMABLE_TO_RIGID_AUTOMATIC uses)
  model::Id id = 0;   // the _ID card's ID, else equal to `number`
  std::string title;  // _ID card title
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   // XT YT ZT at t = 0
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, towards the tracked side
  // _FINITE: the wall is the rectangle origin + a l + b m, 0 <= a <= length_l, 0 <= b <=
  // length_m (a length of 0: unbounded in that direction). l, m, normal are orthonormal.
  bool finite = false;
  Eigen::Vector3d edge_l = Eigen::Vector3d::UnitX();
  Eigen::Vector3d edge_m = Eigen::Vector3d::UnitY();
  double length_l = 0.0;
  double length_m = 0.0;
  double friction = 0.0;    // Coulomb coefficient (FRIC in (0, 1))
  bool no_sliding = false;  // FRIC = 1: tangential motion stopped while in contact
  double birth = 0.0;
  double death = 1e20;
  bool active = true;  // switched by set_wall_active (the RWF flag of part switching)

  WallShape shape = WallShape::Plane;
  bool geometric = false;  // *RIGIDWALL_GEOMETRIC_*
  double depth = 0.0;      // prism: LENP, extent behind the face (along -normal)
  double radius = 0.0;     // cylinder, sphere
  double length = 0.0;     // cylinder: LENCYL from the tail along the axis (0: infinite)

  // The wall is at origin + displacement * motion_direction (rigid translation). _MOVING: a
  // mass moved by the nodes along its normal (motion_direction = normal). _MOTION of a
  // geometric wall: prescribed by `motion`, a velocity (OPT 0) or a displacement (OPT 1)
  // along motion_direction, as a function of t - BIRTH.
  Eigen::Vector3d motion_direction = Eigen::Vector3d::UnitZ();
  bool prescribed = false;
  bool prescribed_displacement = false;
  solver::ScaledCurve motion;
  bool moving = false;
  double mass = 0.0;
  double displacement = 0.0;     // s^n
  double velocity = 0.0;         // V^{n+1/2} (initially V0)
  double velocity_before = 0.0;  // V^{n-1/2}

  // Tracked nodes (dense indices, ascending) and, parallel to them, the translations that a
  // fixed or prescribed DOF holds (bit k: axis k; 7 = fully held, never moved by the wall)
  // and whether the node is in front of the wall (or reached it from the front): nodes that
  // are behind the plane, or came there beside a finite wall, are left alone.
  std::vector<std::int32_t> nodes;
  std::vector<std::uint8_t> locked_axes;
  std::vector<std::uint8_t> in_front;
  // Per tracked node: the side of a closed surface it is kept on (1: inside; a cylinder with
  // _INTERIOR, a sphere the node started inside). Empty for planes and prisms.
  std::vector<std::uint8_t> kept_inside;
  // *RIGIDWALL_PLANAR_FORCES SSID: per node (dense index), 1 on a node of the segment set;
  // segment_force is the wall force on those nodes in the last cycle. Empty without SSID.
  std::vector<std::uint8_t> segment_nodes;
  Eigen::Vector3d segment_force = Eigen::Vector3d::Zero();

  // Results of the last cycle (force at t^n on the model) and totals since t = 0.
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  // force . normal (>= 0: the wall only pushes); curved walls: the sum of each node's force
  // along its own contact normal.
  double normal_force = 0.0;
  double normal_impulse = 0.0;        // sum of normal_force * dt_avg since t = 0
  double work = 0.0;                  // work of the wall forces on the model since t = 0
  std::vector<WallContact> contacts;  // capacity reserved for every tracked node

  model::SourceLocation where;
};

// Per-cycle scratch of the rigid-body path (sized once; no allocation in the time loop).
struct BodyMotion {
  std::int64_t stamp = -1;  // cycle counter value when predicted; stale otherwise
  double inverse_mass = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();    // x_c^n
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // v_c^{n+1/2} predicted, with impulses
  Eigen::Vector3d angular_momentum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inverse_inertia = Eigen::Matrix3d::Zero();  // at R^n, global axes
};

struct NodeCandidate {
  std::int32_t node = 0;
  std::int32_t slot = 0;  // index into the wall's node list
  double limit = 0.0;     // v.n + d/dt: the largest wall velocity the node does not pass
  double mass = 0.0;      // along the normal (m / |P n|^2 for a node with held axes)
  double wall_speed = 0.0;  // velocity of the wall along `normal` (prescribed motion)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // contact normal, towards the node
};

struct BodyContact {
  std::int32_t node = 0;
  std::int32_t body = 0;
  Eigen::Vector3d arm = Eigen::Vector3d::Zero();       // x_i^n - x_c^n
  double gap_rate = 0.0;                               // d^n / dt
  double wall_speed = 0.0;                             // prescribed wall velocity . normal
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // contact normal, towards the node
  Eigen::Vector3d tangent_l = Eigen::Vector3d::UnitX();
  Eigen::Vector3d tangent_m = Eigen::Vector3d::UnitY();
  double normal_inverse_mass = 0.0;                    // n^T K n (+ 1 / wall mass)
  Eigen::Matrix3d response = Eigen::Matrix3d::Zero();  // K: point velocity per impulse
  double tangent_inverse_mass = 0.0;  // largest eigenvalue of T^T K T (friction step)
  double normal_impulse = 0.0;
  Eigen::Vector2d tangent_impulse = Eigen::Vector2d::Zero();
};

struct RigidWallSystem {
  std::vector<RigidWall> walls;  // deck order: walls[k].number == k + 1
  std::vector<BodyMotion> body_motion;
  std::vector<NodeCandidate> candidates;
  std::vector<BodyContact> body_contacts;
  std::int64_t cycle_stamp = 0;
  double tolerance = 0.0;  // round-off distance of the model (nodes this far behind count as on)
  bool empty() const { return walls.empty(); }
};

// The walls of the model with their tracked nodes (NSID or all nodes, minus NSIDEX, inside
// BOXID and within OFFSET of the wall at t = 0). Call after the boundary conditions are
// resolved (held DOFs). Notices (nodes starting behind a wall) go to `warnings`.
RigidWallSystem build_rigid_walls(const model::Model& model, const solver::NodeIndex& node_index,
                                  const solver::State& state, const solver::Boundary& boundary,
                                  std::vector<model::Warning>& warnings);

// The cycle phase, after the nodal velocity update and its constraints (v^{n+1/2} of
// deformable nodes known) and before advance_rigid_bodies: moves moving walls to t^n, then
// for each active wall changes the velocities of the deformable nodes it stops and adds the
// matching forces to f_ext (also to a), and adds to f_ext of rigid-body nodes the forces that
// make their bodies land on the wall. dt_avg = (dt^{n-1/2} + dt^{n+1/2}) / 2, dt = dt^{n+1/2},
// dt_previous = dt^{n-1/2} (0 in the first cycle).
void apply_rigid_walls(RigidWallSystem& system, const solver::RigidSystem& rigid,
                       const solver::Boundary& boundary, double t_n, double dt_avg, double dt,
                       double dt_previous, solver::State& state);

// After advance_rigid_bodies: the work of this cycle's wall forces over the displacements the
// energy balance uses (dt_avg (v^{n-1/2} + v^{n+1/2}) / 2, or the body's motion at a rigid
// node). Adds each wall's share to its `work` and returns the sum, which is also part of the
// external work summed from f_ext.
double rigid_wall_work(RigidWallSystem& system, const solver::RigidSystem& rigid,
                       const solver::Vec3Array& v_previous, const solver::State& state,
                       double dt_avg);

// |normal force| of the wall with deck ordinal `number` (1-based) in the last cycle; -1 if
// there is no such wall.
double wall_normal_force(const RigidWallSystem& system, int number);
// OFFSET of part switching (CODE 3): whether a node of one of the parts `parts` lies in front
// of wall `number` (1-based) within the normal distance `offset` (and over its rectangle if
// finite), at the current positions. False if there is no such wall.
bool wall_within_offset(const RigidWallSystem& system, int number, double offset,
                        const std::vector<model::Id>& parts, const solver::State& state);
// RWF flag of part switching: activate or deactivate a wall (a deactivated wall pushes no
// node; a moving one keeps coasting). A number that names no wall is ignored.
void set_wall_active(RigidWallSystem& system, int number, bool active);

}  // namespace rf::contact
