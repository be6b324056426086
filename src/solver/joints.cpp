// Penalty joints between node pairs (docs/theory.md "Joints").
#include "solver/joints.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::solver {

using model::context_of;

namespace {

const char* const kNodeField[6] = {"N1", "N2", "N3", "N4", "N5", "N6"};

Eigen::Vector3d position(const Vec3Array& x, std::int32_t i) {
  return {x.x[i], x.y[i], x.z[i]};
}

// Inverse of the smallest effective translational mass of node i for a force at it. A rigid
// body: 1/m(n) = 1/M + (r x n)^T J^-1 (r x n) for a unit direction n, largest over n = the
// largest eigenvalue of 1/M I + [r]x^T J^-1 [r]x; evaluated in the body's principal axes with
// the lever arm at t = 0 (invariant, so a restart gets the same value). A body held in all six
// directions takes any force: 0. A deformable node: 1 / its lumped mass (infinity if none).
double inverse_point_mass(const RigidSystem& rigid, const State& state, std::int32_t i) {
  if (!rigid.is_rigid(i)) {
    const double m = state.nodes.mass[i];
    return m > 0.0 ? 1.0 / m : std::numeric_limits<double>::infinity();
  }
  const RigidBody& body = rigid.bodies[rigid.body_of_node[i]];
  const rigid::VelocityConstraints& held = body.state.constraints;
  if (held.translation_count == 3 && held.rotation_count == 3) return 0.0;
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  const auto it = std::lower_bound(body.nodes.begin(), body.nodes.end(), i);
  const std::size_t k = static_cast<std::size_t>(it - body.nodes.begin());
  if (k < body.body_coordinates.x.size()) {
    r = Eigen::Vector3d(body.body_coordinates.x[k], body.body_coordinates.y[k],
                        body.body_coordinates.z[k]);
  }
  Eigen::Matrix3d cross;
  cross << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  const Eigen::Vector3d inverse_inertia = body.state.principal_inertia.cwiseInverse();
  const Eigen::Matrix3d a = Eigen::Matrix3d::Identity() / body.state.mass +
                            cross.transpose() * inverse_inertia.asDiagonal() * cross;
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(a, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

// A force f on node a and -f on node b (a = (f_ext - f_int) / m: a force f is -f in f_int).
void add_pair_force(NodalState& nodes, std::int32_t a, std::int32_t b, const Eigen::Vector3d& f) {
  nodes.f_int.x[a] -= f.x();
  nodes.f_int.y[a] -= f.y();
  nodes.f_int.z[a] -= f.z();
  nodes.f_int.x[b] += f.x();
  nodes.f_int.y[b] += f.y();
  nodes.f_int.z[b] += f.z();
}

}  // namespace

JointSystem build_joints(const model::Model& model, const NodeIndex& node_index,
                         const State& state) {
  JointSystem system;
  double size = 0.0;  // model extent, the scale of the coincidence tolerance
  {
    const Vec3Array& x0 = state.nodes.x0;
    for (std::size_t i = 0; i < x0.size(); ++i) {
      size = std::max({size, std::abs(x0.x[i]), std::abs(x0.y[i]), std::abs(x0.z[i])});
    }
  }
  for (const model::Joint& card : model.joints) {
    SolverJoint joint;
    joint.type = card.type;
    joint.id = card.id;
    joint.rps = card.rps;
    joint.damp = card.damp;
    switch (card.type) {
      case model::Joint::Type::Spherical:
        joint.pairs = 1;
        break;
      case model::Joint::Type::Revolute:
        joint.pairs = 2;
        break;
      case model::Joint::Type::Cylindrical:
        joint.pairs = 2;
        joint.axial_free = true;
        break;
      case model::Joint::Type::Translational:
        joint.pairs = 3;
        joint.axial_free = true;
        break;
      case model::Joint::Type::Universal:
        joint.pairs = 1;
        joint.link = true;
        break;
      case model::Joint::Type::Locking:
        joint.pairs = 3;
        break;
    }
    for (int k = 0; k < 2 * joint.pairs + (joint.link ? 2 : 0); ++k) {
      joint.node[k] = node_index.at(card.nodes[k], card.where, kNodeField[k]);
    }
    for (int p = 0; p < joint.pairs; ++p) {
      const Eigen::Vector3d a = position(state.nodes.x0, joint.node[2 * p]);
      const Eigen::Vector3d b = position(state.nodes.x0, joint.node[2 * p + 1]);
      if ((b - a).norm() > 1e-6 * std::max(size, 1e-300)) {
        throw InputError(
            context_of(card.where, kNodeField[2 * p + 1]),
            fmt::format("joint {}: nodes {} and {} are {:.6g} apart; the nodes of a pair must "
                        "coincide",
                        card.id, card.nodes[2 * p], card.nodes[2 * p + 1], (b - a).norm()));
      }
      if (joint.node[2 * p] == joint.node[2 * p + 1]) {
        throw InputError(context_of(card.where, kNodeField[2 * p + 1]),
                         fmt::format("joint {}: N{} and N{} are the same node {}", card.id,
                                     2 * p + 1, 2 * p + 2, card.nodes[2 * p]));
      }
    }
    const Eigen::Vector3d a1 = position(state.nodes.x0, joint.node[0]);
    if (joint.pairs >= 2 || joint.link) {
      const Eigen::Vector3d a3 = position(state.nodes.x0, joint.node[2]);
      if ((a3 - a1).norm() <= 1e-9 * std::max(size, 1e-300)) {
        throw InputError(
            context_of(card.where, "N3"),
            fmt::format("joint {}: N1 and N3 coincide, so they define no axis", card.id));
      }
    }
    if (joint.pairs == 3) {
      // Three pairs on one line hold nothing against a turn about that line.
      const Eigen::Vector3d axis = (position(state.nodes.x0, joint.node[2]) - a1).normalized();
      const Eigen::Vector3d r5 = position(state.nodes.x0, joint.node[4]) - a1;
      if ((r5 - r5.dot(axis) * axis).norm() <= 1e-6 * std::max(size, 1e-300)) {
        throw InputError(context_of(card.where, "N5"),
                         fmt::format("joint {}: N5 lies on the axis N1 -> N3; it must be off the "
                                     "axis to hold the turn about it",
                                     card.id));
      }
    }
    if (joint.link) {
      const Eigen::Vector3d arm_a = position(state.nodes.x0, joint.node[2]) - a1;
      const Eigen::Vector3d arm_b =
          position(state.nodes.x0, joint.node[3]) - position(state.nodes.x0, joint.node[1]);
      if (arm_b.norm() <= 1e-9 * std::max(size, 1e-300)) {
        throw InputError(
            context_of(card.where, "N4"),
            fmt::format("joint {}: N2 and N4 coincide, so they define no axis", card.id));
      }
      const double cosine = arm_a.dot(arm_b) / (arm_a.norm() * arm_b.norm());
      if (std::abs(cosine) > 0.01) {
        throw InputError(
            context_of(card.where, "N4"),
            fmt::format("joint {}: the arms N1 -> N3 and N2 -> N4 of a universal joint must be "
                        "perpendicular; they make {:.4g} degrees",
                        card.id,
                        std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi));
      }
      joint.link_length =
          (position(state.nodes.x0, joint.node[3]) - position(state.nodes.x0, joint.node[2]))
              .norm();
    }
    system.joints.push_back(joint);
  }
  return system;
}

void prepare_joint_stiffness(JointSystem& joints, const RigidSystem& rigid, const State& state,
                             double dt0) {
  if (joints.prepared || joints.empty() || !(dt0 > 0.0)) return;
  for (SolverJoint& joint : joints.joints) {
    double stiffness = std::numeric_limits<double>::infinity();
    double mass = 0.0;
    for (int p = 0; p < joint.pairs + (joint.link ? 1 : 0); ++p) {  // pairs, then the link
      const double inverse = inverse_point_mass(rigid, state, joint.node[2 * p]) +
                             inverse_point_mass(rigid, state, joint.node[2 * p + 1]);
      if (!std::isfinite(inverse)) {
        const bool first = !std::isfinite(inverse_point_mass(rigid, state, joint.node[2 * p]));
        throw InputError(
            {}, fmt::format("joint {}: node {} has no mass (a joint node must "
                            "belong to a rigid body or carry mass)",
                            joint.id, state.nodes.id[joint.node[first ? 2 * p : 2 * p + 1]]));
      }
      if (inverse == 0.0) continue;  // both sides held: the pair carries nothing
      const double m = 1.0 / inverse;
      const double k = joint.rps * 0.1 * m / (dt0 * dt0);
      if (k < stiffness) {
        stiffness = k;
        mass = m;
      }
    }
    if (!std::isfinite(stiffness)) stiffness = 0.0;
    joint.stiffness = stiffness;
    const double zeta = (joint.damp > 0.0 && joint.damp <= 0.01) ? 0.0 : 0.1 * joint.damp;
    joint.damping = 2.0 * zeta * std::sqrt(stiffness * mass);
  }
  joints.prepared = true;
}

void add_joint_forces(JointSystem& joints, State& state) {
  if (joints.empty() || !joints.prepared) return;
  NodalState& nodes = state.nodes;
  for (SolverJoint& joint : joints.joints) {
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    if (joint.axial_free) {
      axis = position(nodes.x, joint.node[2]) - position(nodes.x, joint.node[0]);
      axis.normalize();
    }
    joint.force.setZero();
    joint.moment.setZero();
    joint.gap = 0.0;
    const Eigen::Vector3d origin = position(nodes.x, joint.node[0]);
    for (int p = 0; p < joint.pairs; ++p) {
      const std::int32_t a = joint.node[2 * p], b = joint.node[2 * p + 1];
      Eigen::Vector3d g = position(nodes.x, b) - position(nodes.x, a);
      Eigen::Vector3d w = position(nodes.v, b) - position(nodes.v, a);
      if (joint.axial_free) {
        g -= g.dot(axis) * axis;
        w -= w.dot(axis) * axis;
      }
      joint.gap = std::max(joint.gap, g.norm());
      const Eigen::Vector3d f = joint.stiffness * g + joint.damping * w;  // on node a
      add_pair_force(nodes, a, b, f);
      joint.force += f;
      joint.moment += (position(nodes.x, a) - origin).cross(f);
    }
    if (joint.link) {
      const std::int32_t a = joint.node[2], b = joint.node[3];
      const Eigen::Vector3d d = position(nodes.x, b) - position(nodes.x, a);
      const double length = d.norm();
      const Eigen::Vector3d e = d / length;
      const double stretch = length - joint.link_length;
      const double rate = (position(nodes.v, b) - position(nodes.v, a)).dot(e);
      const Eigen::Vector3d f = (joint.stiffness * stretch + joint.damping * rate) * e;  // on a
      add_pair_force(nodes, a, b, f);
      joint.gap = std::max(joint.gap, std::abs(stretch));
      joint.force += f;
      joint.moment += (position(nodes.x, a) - origin).cross(f);
    }
  }
}

}  // namespace rf::solver
