#include "rigid/rigid_body.hpp"

#include <cmath>
#include <stdexcept>

#include "rigid/so3.hpp"

namespace rf::rigid {

namespace {

// Constraint matrices with at most six rows/columns (three from the body, three per step):
// fixed maximum sizes keep the time loop free of heap allocation.
using ConstraintAxes = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6>;
using ConstraintValues = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
using ConstraintSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

// Accumulates mass, first and second moments about a reference point (the first node), so
// that the centred second moment does not lose digits when the body sits far from the origin.
class MomentAccumulator {
 public:
  void add(double m, const Eigen::Vector3d& x) {
    if (count_++ == 0) origin_ = x;
    const Eigen::Vector3d d = x - origin_;
    mass_ += m;
    first_ += m * d;
    second_ += m * d * d.transpose();
  }
  MassProperties result() const {
    MassProperties p;
    p.mass = mass_;
    if (!(mass_ > 0.0)) throw std::invalid_argument("rigid body: total mass must be positive");
    const Eigen::Vector3d offset = first_ / mass_;
    p.centre = origin_ + offset;
    // Second moment about the centre (parallel axes), then I = tr(S) 1 - S.
    const Eigen::Matrix3d s = second_ - mass_ * offset * offset.transpose();
    p.inertia = s.trace() * Eigen::Matrix3d::Identity() - s;
    p.inertia = 0.5 * (p.inertia + p.inertia.transpose()).eval();
    return p;
  }

 private:
  std::size_t count_ = 0;
  double mass_ = 0.0;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d first_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second_ = Eigen::Matrix3d::Zero();
};

// The exact flow of H_k = Pi_k^2 / (2 J_k) over time h: the body turns about its own axis k
// at the constant rate Pi_k / J_k. R <- R Q_k(theta) (column operations) and the body-frame
// momentum Pi <- Q_k(theta)^T Pi, so that L = R Pi is unchanged.
void principal_axis_flow(int k, double h, const Eigen::Vector3d& principal_inertia,
                         Eigen::Matrix3d& rotation, Eigen::Vector3d& body_momentum) {
  const int j = (k + 1) % 3;
  const int l = (k + 2) % 3;
  const double theta = h * body_momentum[k] / principal_inertia[k];
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  const Eigen::Vector3d column_j = rotation.col(j);
  const Eigen::Vector3d column_l = rotation.col(l);
  rotation.col(j) = c * column_j + s * column_l;
  rotation.col(l) = c * column_l - s * column_j;
  const double pj = body_momentum[j];
  const double pl = body_momentum[l];
  body_momentum[j] = c * pj + s * pl;
  body_momentum[l] = c * pl - s * pj;
}

// Constraints along a global axis hold exactly (not only to round-off of the solve), so that a
// fixed DOF stays bit-exactly at rest however long the run.
void snap_axis_constraints(const ConstraintAxes& axes, const ConstraintValues& values,
                           Eigen::Vector3d& velocity) {
  for (Eigen::Index k = 0; k < axes.cols(); ++k) {
    for (int a = 0; a < 3; ++a) {
      const double c = axes(a, k);
      if ((c == 1.0 || c == -1.0) && axes((a + 1) % 3, k) == 0.0 && axes((a + 2) % 3, k) == 0.0) {
        velocity[a] = c * values[k];
      }
    }
  }
}

// Rotation with constrained components n_k . w = c_k. The constrained angular velocity is the
// one closest to the free motion in the kinetic-energy metric: w = I^-1 (L + N lambda) with
// N^T w = c (Lagrange multipliers lambda, the reaction angular impulse N lambda). I is taken at
// the midpoint rotation (two fixed-point passes). L is then reset to I w. For one free global
// axis a (a hinge) I_aa does not change as the body turns about a, so this is exact; otherwise
// it is second order.
void advance_constrained_rotation(RigidBodyState& body, const ConstraintAxes& axes,
                                  const ConstraintValues& values, double dt) {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_mid = global_inertia(body);
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::Matrix3d rotation_mid = rotation_from_vector(0.5 * dt * w) * body.rotation;
    inertia_mid = rotation_mid * body.principal_inertia.asDiagonal() * rotation_mid.transpose();
    const Eigen::LLT<Eigen::Matrix3d> inertia_llt(inertia_mid);
    const ConstraintAxes inv_i_n = inertia_llt.solve(axes);
    const Eigen::Vector3d w_free = inertia_llt.solve(body.angular_momentum);
    const ConstraintSquare schur = axes.transpose() * inv_i_n;
    const ConstraintValues lambda =
        schur.completeOrthogonalDecomposition().solve(values - axes.transpose() * w_free);
    w = w_free + inv_i_n * lambda;
    snap_axis_constraints(axes, values, w);
  }
  const Eigen::Vector3d constrained_momentum = inertia_mid * w;
  body.reaction_angular_impulse = constrained_momentum - body.angular_momentum;
  body.angular_momentum = constrained_momentum;
  body.angular_velocity = w;
  body.rotation = orthonormalise(rotation_from_vector(dt * w) * body.rotation);
}

// Columns: the constraint axes of both sets; values alongside.
void stack(const std::array<Eigen::Vector3d, 3>& axis_a, const std::array<double, 3>& value_a,
           int count_a, const std::array<Eigen::Vector3d, 3>* axis_b,
           const std::array<double, 3>* value_b, int count_b, ConstraintAxes& axes,
           ConstraintValues& values) {
  axes.resize(3, count_a + count_b);
  values.resize(count_a + count_b);
  for (int k = 0; k < count_a; ++k) {
    axes.col(k) = axis_a[k];
    values[k] = value_a[k];
  }
  for (int k = 0; k < count_b; ++k) {
    axes.col(count_a + k) = (*axis_b)[k];
    values[count_a + k] = (*value_b)[k];
  }
}

bool columns_independent(const ConstraintAxes& axes) {
  if (axes.cols() == 0) return true;
  if (axes.cols() > 3) return false;
  Eigen::FullPivLU<ConstraintAxes> lu(axes);
  lu.setThreshold(1e-8);
  return lu.rank() == axes.cols();
}

}  // namespace

MassProperties combine(const std::vector<MassProperties>& parts) {
  MassProperties sum;
  for (const auto& p : parts) sum.mass += p.mass;
  if (!(sum.mass > 0.0)) return sum;
  for (const auto& p : parts) sum.centre += p.mass * p.centre;
  sum.centre /= sum.mass;
  for (const auto& p : parts) {
    const Eigen::Vector3d d = p.centre - sum.centre;
    sum.inertia +=
        p.inertia + p.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return sum;
}

MassProperties mass_properties(std::span<const double> masses,
                               std::span<const Eigen::Vector3d> positions) {
  if (masses.size() != positions.size()) {
    throw std::invalid_argument("rigid body: masses and positions differ in length");
  }
  MomentAccumulator acc;
  for (std::size_t i = 0; i < masses.size(); ++i) acc.add(masses[i], positions[i]);
  return acc.result();
}

MassProperties mass_properties(const std::vector<std::int32_t>& nodes, const double* mass,
                               const double* x, const double* y, const double* z) {
  MomentAccumulator acc;
  for (const std::int32_t i : nodes) acc.add(mass[i], Eigen::Vector3d(x[i], y[i], z[i]));
  return acc.result();
}

RigidBodyState make_rigid_body(double mass, const Eigen::Vector3d& centre,
                               const Eigen::Matrix3d& inertia) {
  if (!(mass > 0.0)) throw std::invalid_argument("rigid body: mass must be positive");
  const Eigen::Matrix3d symmetric = 0.5 * (inertia + inertia.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(symmetric);
  if (eigen.info() != Eigen::Success) {
    throw std::invalid_argument("rigid body: inertia tensor eigen-decomposition failed");
  }
  RigidBodyState body;
  body.mass = mass;
  body.centre = centre;
  body.previous_centre = centre;
  body.principal_inertia = eigen.eigenvalues();  // ascending
  // Line, plane or point bodies have (nearly) zero principal moments; J^-1 would blow up.
  const double largest = body.principal_inertia.maxCoeff();
  if (!(body.principal_inertia.minCoeff() > 1e-12 * largest) || !(largest > 0.0)) {
    throw std::invalid_argument("rigid body: inertia tensor is not positive definite");
  }
  // The eigenvectors are orthonormal; flipping one axis makes them a proper rotation.
  body.rotation = eigen.eigenvectors();
  if (body.rotation.determinant() < 0.0) body.rotation.col(2) *= -1.0;
  body.previous_rotation = body.rotation;
  return body;
}

RigidBodyState make_rigid_body(const MassProperties& properties) {
  return make_rigid_body(properties.mass, properties.centre, properties.inertia);
}

RigidBodyState make_rigid_body(std::span<const double> masses,
                               std::span<const Eigen::Vector3d> positions) {
  return make_rigid_body(mass_properties(masses, positions));
}

Eigen::Matrix3d global_inertia(const RigidBodyState& body) {
  return body.rotation * body.principal_inertia.asDiagonal() * body.rotation.transpose();
}

Eigen::Vector3d angular_velocity_from_momentum(const Eigen::Matrix3d& rotation,
                                               const Eigen::Vector3d& principal_inertia,
                                               const Eigen::Vector3d& angular_momentum) {
  const Eigen::Vector3d body_momentum = rotation.transpose() * angular_momentum;
  return rotation * body_momentum.cwiseQuotient(principal_inertia);
}

void set_velocity(RigidBodyState& body, const Eigen::Vector3d& velocity,
                  const Eigen::Vector3d& angular_velocity) {
  body.velocity = velocity;
  body.angular_velocity = angular_velocity;
  body.angular_momentum = global_inertia(body) * angular_velocity;
}

double kinetic_energy(const RigidBodyState& body) {
  return 0.5 * body.mass * body.velocity.squaredNorm() +
         0.5 * body.angular_momentum.dot(body.angular_velocity);
}

Eigen::Matrix3d free_rotation(const Eigen::Matrix3d& rotation,
                              const Eigen::Vector3d& principal_inertia,
                              const Eigen::Vector3d& angular_momentum, double h) {
  Eigen::Matrix3d r = rotation;
  Eigen::Vector3d body_momentum = rotation.transpose() * angular_momentum;
  // Strang splitting of H = H_1 + H_2 + H_3: symmetric, hence time-reversible and second
  // order; each factor is an exact Poisson flow, hence the composition is symplectic on
  // T*SO(3) and keeps the spatial L invariant (McLachlan 1993, PRL 71:3043; Dullweber,
  // Leimkuhler & McLachlan 1997, J. Chem. Phys. 107:5840; Touma & Wisdom 1994).
  principal_axis_flow(0, 0.5 * h, principal_inertia, r, body_momentum);
  principal_axis_flow(1, 0.5 * h, principal_inertia, r, body_momentum);
  principal_axis_flow(2, h, principal_inertia, r, body_momentum);
  principal_axis_flow(1, 0.5 * h, principal_inertia, r, body_momentum);
  principal_axis_flow(0, 0.5 * h, principal_inertia, r, body_momentum);
  return orthonormalise(r);
}

bool VelocityConstraints::add_translation(const Eigen::Vector3d& axis, double value) {
  if (translation_count == 3) return false;
  translation_axis[translation_count] = axis.normalized();
  translation_value[translation_count++] = value;
  return true;
}

bool VelocityConstraints::add_rotation(const Eigen::Vector3d& axis, double value) {
  if (rotation_count == 3) return false;
  rotation_axis[rotation_count] = axis.normalized();
  rotation_value[rotation_count++] = value;
  return true;
}

void VelocityConstraints::fix_global_translation(const std::array<bool, 3>& axes) {
  for (int a = 0; a < 3; ++a) {
    if (axes[a]) add_translation(Eigen::Vector3d::Unit(a), 0.0);
  }
}

void VelocityConstraints::fix_global_rotation(const std::array<bool, 3>& axes) {
  for (int a = 0; a < 3; ++a) {
    if (axes[a]) add_rotation(Eigen::Vector3d::Unit(a), 0.0);
  }
}

bool constraints_independent(const VelocityConstraints& a, const VelocityConstraints& b) {
  ConstraintAxes axes;
  ConstraintValues values;
  stack(a.translation_axis, a.translation_value, a.translation_count, &b.translation_axis,
        &b.translation_value, b.translation_count, axes, values);
  if (!columns_independent(axes)) return false;
  stack(a.rotation_axis, a.rotation_value, a.rotation_count, &b.rotation_axis, &b.rotation_value,
        b.rotation_count, axes, values);
  return columns_independent(axes);
}

void advance_rigid_body(RigidBodyState& body, const Eigen::Vector3d& force,
                        const Eigen::Vector3d& torque_about_centre, double dt_avg, double dt,
                        const VelocityConstraints* step_constraints) {
  const VelocityConstraints& fixed = body.constraints;
  const int step_translations = step_constraints ? step_constraints->translation_count : 0;
  const int step_rotations = step_constraints ? step_constraints->rotation_count : 0;
  body.previous_rotation = body.rotation;

  // Translation: the nodes' central-difference update applied to the centre of mass, then
  // the orthogonal (mass-weighted) projection onto n_k . v = c_k.
  const Eigen::Vector3d velocity_free = body.velocity + (dt_avg / body.mass) * force;
  body.velocity = velocity_free;
  if (fixed.translation_count + step_translations > 0) {
    ConstraintAxes axes;
    ConstraintValues values;
    stack(fixed.translation_axis, fixed.translation_value, fixed.translation_count,
          step_constraints ? &step_constraints->translation_axis : nullptr,
          step_constraints ? &step_constraints->translation_value : nullptr, step_translations,
          axes, values);
    const ConstraintSquare gram = axes.transpose() * axes;
    const ConstraintValues mu =
        gram.completeOrthogonalDecomposition().solve(values - axes.transpose() * velocity_free);
    body.velocity = velocity_free + axes * mu;
    snap_axis_constraints(axes, values, body.velocity);
  }
  body.reaction_impulse = body.mass * (body.velocity - velocity_free);

  // Rotation: the torque kick is exact momentum balance; the drift at constant L is the
  // free-body flow. Kick-drift with L at half steps is the leapfrog (Verlet) form of the
  // splitting H = T(L, R) + V(R), so the whole cycle stays second order and symplectic.
  body.angular_momentum += dt_avg * torque_about_centre;
  if (fixed.rotation_count + step_rotations > 0) {
    ConstraintAxes axes;
    ConstraintValues values;
    stack(fixed.rotation_axis, fixed.rotation_value, fixed.rotation_count,
          step_constraints ? &step_constraints->rotation_axis : nullptr,
          step_constraints ? &step_constraints->rotation_value : nullptr, step_rotations, axes,
          values);
    advance_constrained_rotation(body, axes, values, dt);
  } else {
    body.reaction_angular_impulse.setZero();
    const Eigen::Matrix3d rotation_next =
        free_rotation(body.rotation, body.principal_inertia, body.angular_momentum, dt);
    // The mean angular velocity of the step: exp(dt [w]) R^n = R^{n+1} exactly, so nodes
    // moved by w (velocities, linear update) agree with the rotation of the body. It
    // differs from R J^-1 R^T L at the mid rotation by O(dt^2) (measured in the tests).
    body.angular_velocity =
        dt > 0.0 ? Eigen::Vector3d(rotation_vector(rotation_next * body.rotation.transpose()) / dt)
                 : angular_velocity_from_momentum(body.rotation, body.principal_inertia,
                                                  body.angular_momentum);
    body.rotation = rotation_next;
  }

  body.previous_centre = body.centre;
  body.centre += dt * body.velocity;
}

BodyCoordinates body_coordinates(const RigidBodyState& body, const std::vector<std::int32_t>& nodes,
                                 const double* x, const double* y, const double* z) {
  BodyCoordinates coords;
  coords.x.resize(nodes.size());
  coords.y.resize(nodes.size());
  coords.z.resize(nodes.size());
  const Eigen::Matrix3d rt = body.rotation.transpose();
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const std::int32_t i = nodes[k];
    const Eigen::Vector3d local = rt * (Eigen::Vector3d(x[i], y[i], z[i]) - body.centre);
    coords.x[k] = local.x();
    coords.y[k] = local.y();
    coords.z[k] = local.z();
  }
  return coords;
}

void place_nodes_curvilinear(const RigidBodyState& body, const std::vector<std::int32_t>& nodes,
                             const BodyCoordinates& body_coords, double* x, double* y, double* z) {
  const Eigen::Matrix3d& r = body.rotation;
  const Eigen::Vector3d& c = body.centre;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const std::int32_t i = nodes[k];
    const Eigen::Vector3d local(body_coords.x[k], body_coords.y[k], body_coords.z[k]);
    const Eigen::Vector3d global = c + r * local;
    x[i] = global.x();
    y[i] = global.y();
    z[i] = global.z();
  }
}

void advance_nodes_linear(const RigidBodyState& body, const std::vector<std::int32_t>& nodes,
                          double dt, double* x, double* y, double* z) {
  const Eigen::Vector3d& v = body.velocity;
  const Eigen::Vector3d& w = body.angular_velocity;
  const Eigen::Vector3d& c = body.previous_centre;
  for (const std::int32_t i : nodes) {
    const Eigen::Vector3d arm(x[i] - c.x(), y[i] - c.y(), z[i] - c.z());
    const Eigen::Vector3d u = dt * (v + w.cross(arm));
    x[i] += u.x();
    y[i] += u.y();
    z[i] += u.z();
  }
}

void rigid_node_velocities(const Eigen::Vector3d& velocity, const Eigen::Vector3d& angular_velocity,
                           const Eigen::Vector3d& centre, const std::vector<std::int32_t>& nodes,
                           const double* x, const double* y, const double* z, double* vx,
                           double* vy, double* vz) {
  for (const std::int32_t i : nodes) {
    const Eigen::Vector3d arm(x[i] - centre.x(), y[i] - centre.y(), z[i] - centre.z());
    const Eigen::Vector3d v = velocity + angular_velocity.cross(arm);
    vx[i] = v.x();
    vy[i] = v.y();
    vz[i] = v.z();
  }
}

ForceAndTorque gather_force_and_torque(const Eigen::Vector3d& centre,
                                       const std::vector<std::int32_t>& nodes, const double* fx,
                                       const double* fy, const double* fz, const double* x,
                                       const double* y, const double* z) {
  ForceAndTorque sum;
  for (const std::int32_t i : nodes) {
    const Eigen::Vector3d f(fx[i], fy[i], fz[i]);
    const Eigen::Vector3d arm(x[i] - centre.x(), y[i] - centre.y(), z[i] - centre.z());
    sum.force += f;
    sum.torque += arm.cross(f);
  }
  return sum;
}

}  // namespace rf::rigid
