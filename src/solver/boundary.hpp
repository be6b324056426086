// Boundary conditions, loads and initial conditions resolved to dense node indices.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/model.hpp"
#include "solver/build_state.hpp"
#include "solver/pressure_loads.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// A time function: SF * curve(t - BIRTH), SF * function(t - BIRTH) for an IMPETUS *FUNCTION, or
// a constant SF when neither is given.
struct ScaledCurve {
  const model::Curve* curve = nullptr;
  const model::ExpressionFunction* function = nullptr;
  double scale = 1.0;
  double shift = 0.0;  // subtracted from t before evaluation (BIRTH for prescribed motion)
  double operator()(double t) const;
};

// Which analysis phase the time functions serve (*DEFINE_CURVE SIDR): during dynamic relaxation
// only curves flagged SIDR 1 or 2 act (SIDR 0 curves give 0); in the transient SIDR 1 curves
// give 0. Constants and *FUNCTIONs act in both. One flag per process, set between cycles by
// the dynamic relaxation phase alone (DynamicRelaxationPhase), read by every thread.
bool dynamic_relaxation_running();
class DynamicRelaxationPhase {
 public:
  DynamicRelaxationPhase();
  ~DynamicRelaxationPhase();
  DynamicRelaxationPhase(const DynamicRelaxationPhase&) = delete;
  DynamicRelaxationPhase& operator=(const DynamicRelaxationPhase&) = delete;
};

// A load curve's value at t in the current phase: 0 where SIDR says the curve does not act.
double load_curve_value(const model::Curve& curve, double t);

// The time function of a card: curve `lcid`, else *FUNCTION `function`, else the constant `sf`.
// Throws an input error naming LCID (or FUNCTION) when the ID is not defined.
ScaledCurve make_time_function(const model::Model& model, model::Id lcid, model::Id function,
                               double sf, double shift, const model::SourceLocation& where);

struct PrescribedDof {
  std::int32_t node = 0;
  int axis = 0;  // 0,1,2
  int vad = 0;   // 0 velocity, 1 acceleration, 2 displacement
  // DOF 9/10/11 of *BOUNDARY_PRESCRIBED_MOTION: -1 for a translation; else the axis (0 x, 1 y,
  // 2 z) the node turns about, through the point whose in-plane coordinates (axes rotation+1,
  // rotation+2 mod 3) are `centre`. `axis` is then one of the two in-plane axes (each node
  // has two entries) and `value` is the angle (VAD 2) or angular velocity (VAD 0).
  int rotation = -1;
  std::array<double, 2> centre{};
  ScaledCurve value;
  double birth = 0.0;
  double death = 1e28;
  bool active(double t) const { return t >= birth && t <= death; }
};

// *BOUNDARY_PRESCRIBED_MOTION DOF 4 (translation along VID) and DOF 5, 6, 7, 8 (rotation about
// x, y, z or VID, on a node with rotational degrees of freedom): the component of the node's
// velocity (angular velocity) along `direction` follows the curve, the components normal to it
// stay free. VAD 0 velocity, 1 acceleration, 2 displacement (DOF 4: of x - x0 along the
// direction; DOF 5-8: the angle's increments over each step, see constrain_rotations).
struct PrescribedDirection {
  std::int32_t node = 0;              // dense node index
  std::int32_t rotation = -1;         // rotational index (DOF 5-8), -1 for DOF 4
  std::array<double, 3> direction{};  // unit vector, global
  int vad = 0;
  ScaledCurve value;
  double birth = 0.0;
  double death = 1e28;
  bool active(double t) const { return t >= birth && t <= death; }
};

struct NodalForce {
  std::int32_t node = 0;
  int axis = 0;
  ScaledCurve value;
};

// *LOAD_NODE DOF 5-7: a moment about a global axis on a node with rotations.
struct NodalMoment {
  std::int32_t rotation = 0;  // rotational index (RotationalState)
  int axis = 0;
  ScaledCurve value;
};

struct BodyAcceleration {
  int axis = 0;
  ScaledCurve value;
};

// One *DAMPING_GLOBAL / *DAMPING_PART_MASS card resolved (solver/mass_damping.hpp).
struct DampingTerm {
  ScaledCurve d;               // d(t) = SF * curve(t), or the constant VALDMP
  std::array<double, 3> st{};  // scales of the translational forces (global x, y, z)
  std::array<double, 3> sr{};  // scales of the damping moments (rigid bodies, nodal spins)
};

struct MassDampingSystem {
  std::vector<DampingTerm> terms;
  // Per node: the term that damps it, -1 none (empty vector: no damping at all). A
  // *DAMPING_PART_MASS card overrides *DAMPING_GLOBAL on its parts' nodes; later part cards
  // override earlier ones.
  std::vector<std::int16_t> term_of_node;
  // The damping force of each node in the last f_ext (its share of the external work is
  // summed with the same displacements as the rest, see Simulation::update_velocities), and
  // d(t) ST per term at that time. Written by add_damping_forces.
  mutable Vec3Array force;
  mutable std::vector<std::array<double, 3>> coefficient;
  // The same for the nodal spins of shells and beams (per rotational index): the damping
  // moments in m_ext and d(t) SR per term.
  mutable Vec3Array moment;
  mutable std::vector<std::array<double, 3>> rotation_coefficient;
  bool empty() const { return terms.empty(); }
};

struct Boundary {
  // Bit k set: translation k of the node is fixed (SPC, *NODE TC).
  std::vector<std::uint8_t> fixed;
  // Constrained rotations by rotational index (bit 0 x, 1 y, 2 z): *NODE RC, *BOUNDARY_SPC
  // DOFRX..DOFRZ on nodes that have rotations (shells, beams).
  std::vector<std::uint8_t> rotation_fixed;
  std::vector<PrescribedDof> prescribed;
  std::vector<PrescribedDirection> prescribed_directions;  // DOF 4 and 5-8 on nodes
  std::vector<NodalForce> nodal_forces;
  std::vector<NodalMoment> nodal_moments;  // *LOAD_NODE DOF 5-7 (solver/pressure_loads.hpp)
  PressureLoads pressure;                  // *LOAD_SEGMENT*, *LOAD_SHELL*
  std::vector<BodyAcceleration> body_accelerations;
  // Sorted unique nodes with a fixed or prescribed DOF: their reactions enter external work.
  std::vector<std::int32_t> constrained_nodes;
  // Mass that *LOAD_BODY acts on, per node: the lumped mass, zero on rigid-body nodes (the
  // body force of a rigid body is applied at its centre of mass, to the body's own mass).
  std::vector<double> body_force_mass;
  // Mass-proportional damping (*DAMPING_GLOBAL, *DAMPING_PART_MASS); acts on the nodes through
  // body_force_mass and on rigid bodies at their centre of mass.
  MassDampingSystem damping;
};

// `body_of_node` (empty when there are no rigid bodies) gives each node's rigid body or -1.
// Nodal constraints (*NODE TC, *BOUNDARY_SPC) on rigid-body nodes are ignored as in LS-DYNA,
// with a warning appended to `warnings`; nodal prescribed motion on them is an error.
Boundary resolve_boundary(const model::Model& model, const NodeIndex& node_index,
                          const State& state, const std::vector<std::int32_t>& body_of_node,
                          std::vector<model::Warning>& warnings);

// Sets body_force_mass from the nodes' rigid-body membership (`body_of_node`, empty: none).
// Part switching changes membership at run time and must call it again, else a body made
// by switching would take *LOAD_BODY twice (at its centre and through its nodes) and nodes
// freed from a body none.
// With mass scaling `physical_mass` is the mass without the added mass (body loads act on it
// only, LS-DYNA's EMSCL 0); nullptr: the nodes' mass.
void set_body_force_masses(Boundary& boundary, const NodalState& nodes,
                           const std::vector<std::int32_t>& body_of_node,
                           const std::vector<double>* physical_mass = nullptr);

// Nodes addressed by a target (node, node set, part, part set, all), as dense indices.
std::vector<std::int32_t> resolve_nodes(const model::Model& model, const NodeIndex& node_index,
                                        const State& state, model::Target target, model::Id id,
                                        const model::SourceLocation& where, const char* field);

// Nodes of the surface an IMPETUS *GEOMETRY_SEED_COORDINATE selects, on the solver's mesh
// (reference coordinates; higher-order face nodes included).
std::vector<std::int32_t> select_geometry(const State& state, const model::GeometrySeed& seed);

// Applies *INITIAL_VELOCITY* cards in input order (later cards override earlier ones).
void apply_initial_velocities(const model::Model& model, const NodeIndex& node_index, State& state);

// f_ext at time t: nodal loads, pressures and body forces (-m a_base, as LS-DYNA *LOAD_BODY);
// m_ext: nodal moments.
void compute_external_forces(const Boundary& boundary, double t, State& state);

// Before the velocity update: fixed DOFs get a = 0, prescribed accelerations (VAD 1) their
// value at t^n, so that v^{n+1/2} = v^{n-1/2} + dt_avg a^n honours them.
void constrain_accelerations(const Boundary& boundary, double t_n, State& state);

// After the velocity update: fixed DOFs get v = 0; prescribed velocity (VAD 0) is sampled at
// the mid-step t^n + dt/2; prescribed displacement (VAD 2) gives the velocity that lands the
// node exactly on u(t^n + dt) at the end of the step.
void constrain_velocities(const Boundary& boundary, double t_n, double dt, State& state);

// After the angular velocity update (omega^{n+1/2} = omega^{n-1/2} + dt_avg alpha^n, rotation
// SPCs applied): each prescribed rotation (DOF 5-8) sets the component of omega^{n+1/2} along its
// axis to the curve's angular velocity at t^n + dt/2 (VAD 0), to that of the previous half step
// plus dt_avg times the angular acceleration at t^n (VAD 1), or to the angle's increment
// (theta(t^n + dt) - theta(t^n)) / dt (VAD 2: the angle counts from the birth, as the node
// carries no total rotation). Returns the work of the reaction moments over the step (the
// moment each constraint applies, along its axis, times the step's rotation about it).
double constrain_rotations(const Boundary& boundary, double t_n, double dt, double dt_avg,
                           State& state);

}  // namespace rf::solver
