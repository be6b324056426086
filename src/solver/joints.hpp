// Penalty joints (*CONSTRAINED_JOINT_SPHERICAL / _REVOLUTE / _CYLINDRICAL / _TRANSLATIONAL /
// _UNIVERSAL / _LOCKING) resolved to dense node indices. docs/theory.md "Joints".
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <vector>

#include "model/model.hpp"
#include "solver/build_state.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"

namespace rf::solver {

struct SolverJoint {
  model::Joint::Type type = model::Joint::Type::Spherical;
  model::Id id = 0;
  std::array<std::int32_t, 6> node{-1, -1, -1, -1, -1, -1};
  int pairs = 1;  // node pairs (N1,N2), (N3,N4), (N5,N6) in use
  // Universal joint: besides the pair (N1,N2), a penalty link keeps the distance between N3
  // (body A) and N4 (body B) at its initial value `link_length`. With N1 = N2 the joint centre
  // and the arms N1->N3, N2->N4 of fixed length (rigid bodies), |x4 - x3|^2 = |a|^2 + |b|^2 -
  // 2 a.b, so a constant distance is a constant angle between the arms: perpendicular arms stay
  // perpendicular, which is the Hooke (cross) joint constraint.
  bool link = false;
  double link_length = 0.0;
  // Pairs constrained only across the axis N1 -> N3 of body A (cylindrical, translational).
  bool axial_free = false;
  double rps = 1.0, damp = 1.0;
  double stiffness = 0.0;  // k of each pair's penalty spring (set by prepare_joint_stiffness)
  double damping = 0.0;    // c of each pair's dashpot
  // Total force the joint exerts on its body-A nodes (N1, N3, N5) in the last evaluation; the
  // body-B nodes get the opposite.
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  // Moment of the pair forces on the body-A nodes about N1 in the last evaluation (a revolute or
  // translational joint carries one; a spherical joint's single pair none).
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double gap = 0.0;  // largest constrained separation of a pair in the last evaluation
};

struct JointSystem {
  std::vector<SolverJoint> joints;
  bool prepared = false;
  bool empty() const { return joints.empty(); }
};

// Resolves the joints of the model. Throws InputError naming the card when a node does not
// exist, when a pair's nodes do not coincide (within 1e-6 of the larger of the model's size and
// the pair's distance from the origin), when N1 and N3 coincide where they define the axis,
// when N5 lies on the axis N1 -> N3 (translational, locking), or when the arms N1 -> N3 and
// N2 -> N4 of a universal joint are not perpendicular (within 0.01 of the cosine).
JointSystem build_joints(const model::Model& model, const NodeIndex& node_index,
                         const State& state);

// Penalty stiffness k = RPS 0.1 m* / dt0^2 per pair, with m* the effective mass of the two sides
// at the pair (a rigid body's point mass 1 / (1/M + r^2 / J_min) with the lever arm r from its
// centre of mass; a deformable node's lumped mass), combined in series: the spring's frequency
// is w dt0 = 0.32 sqrt(RPS), well inside the stability limit w dt < 2 of central differences.
// The dashpot has 10 % of critical damping times DAMP (0 for 0 < DAMP <= 0.01). Uses only
// quantities that do not change during the run (masses, reference lever arms, the first step),
// so a restart computes the same values.
void prepare_joint_stiffness(JointSystem& joints, const RigidSystem& rigid, const State& state,
                             double dt0);

// Adds the joint forces at x^{n+1} (and v^{n+1/2} for the dashpots) to f_int: a pair's force
// F = k g + c w (g = x_B - x_A, w = v_B - v_A, across the axis only where the axis is free) pulls
// the body-A node towards the body-B node and the body-B node back, so the work of the joints
// is internal work (the springs' energy and the dashpots' losses are in internal_energy). A
// universal joint's link adds F = (k (|d| - L0) + c w.e) e along e = d / |d|, d = x4 - x3.
void add_joint_forces(JointSystem& joints, State& state);

}  // namespace rf::solver
