// *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED (docs/theory.md "Joint stiffness").
#include "solver/joint_stiffness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::solver {

using model::context_of;

double JointCurve::value(double q) const {
  const std::size_t n = x.size();
  if (n == 0) return 0.0;
  if (n == 1) return y[0];
  std::size_t k = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), q) - x.begin());
  k = std::clamp<std::size_t>(k, 1, n - 1);  // segment [k-1, k], the end ones extended
  return y[k - 1] + (y[k] - y[k - 1]) / (x[k] - x[k - 1]) * (q - x[k - 1]);
}

double JointCurve::integral(double q) const {
  if (x.empty()) return 0.0;
  // Trapezoids between the breakpoints between 0 and q (exact: the curve is linear between).
  const double lo = std::min(0.0, q), hi = std::max(0.0, q);
  double a = lo, sum = 0.0;
  for (const double xk : x) {
    if (xk <= a) continue;
    if (xk >= hi) break;
    sum += 0.5 * (value(a) + value(xk)) * (xk - a);
    a = xk;
  }
  sum += 0.5 * (value(a) + value(hi)) * (hi - a);
  return q >= 0.0 ? sum : -sum;
}

double JointCurve::largest_slope() const {
  double k = 0.0;
  for (std::size_t i = 1; i < x.size(); ++i) {
    k = std::max(k, std::abs((y[i] - y[i - 1]) / (x[i] - x[i - 1])));
  }
  return k;
}

namespace {

constexpr const char* kCurveField[3] = {"LCIDPH", "LCIDT", "LCIDPS"};
constexpr const char* kDampingField[3] = {"DLCIDPH", "DLCIDT", "DLCIDPS"};
constexpr const char* kStiffnessField[3] = {"ESPH", "EST", "ESPS"};
constexpr const char* kFrictionField[3] = {"FMPH", "FMT", "FMPS"};
constexpr const char* kNegativeField[3] = {"NSAPH", "NSAT", "NSAPS"};
constexpr const char* kPositiveField[3] = {"PSAPH", "PSAT", "PSAPS"};

// The rigid body made of part `pid` (-1: none).
int body_of_part(const RigidSystem& rigid, model::Id pid) {
  for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
    const RigidBody& body = rigid.bodies[b];
    if (body.nodal) continue;
    if (std::find(body.parts.begin(), body.parts.end(), pid) != body.parts.end()) {
      return static_cast<int>(b);
    }
  }
  return -1;
}

int rigid_body_of(const model::Model& model, const RigidSystem& rigid, model::Id pid,
                  const model::SourceLocation& where, const char* field) {
  const auto part = model.parts.find(pid);
  if (pid <= 0 || part == model.parts.end()) {
    throw InputError(context_of(where, field), fmt::format("part {} is not defined", pid));
  }
  const auto& material = model.materials.at(part->second.mid);
  if (material.kind != model::MaterialKind::Rigid) {
    throw InputError(context_of(where, field),
                     fmt::format("part {} is not rigid (material {} is {}); a joint stiffness "
                                 "acts between rigid bodies (*MAT_RIGID parts)",
                                 pid, material.id, material.keyword));
  }
  const int body = body_of_part(rigid, pid);
  if (body < 0) {
    throw InputError(context_of(where, field),
                     fmt::format("part {} has no rigid body (no nodes)", pid));
  }
  return body;
}

Eigen::Matrix3d axes_of(const model::Model& model, model::Id cid,
                        const model::SourceLocation& where, const char* field) {
  const auto it = model.coordinate_systems.find(cid);
  if (cid <= 0 || it == model.coordinate_systems.end()) {
    throw InputError(context_of(where, field),
                     fmt::format("coordinate system {} is not defined (*DEFINE_COORDINATE_...); "
                                 "the joint stiffness needs a local system on each body",
                                 cid));
  }
  Eigen::Matrix3d axes;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) axes(c, r) = it->second.axes[r][c];  // rows -> columns
  return axes;
}

JointCurve curve_of(const model::Model& model, model::Id lcid, const model::SourceLocation& where,
                    const char* field) {
  JointCurve out;
  if (lcid == 0) return out;
  const auto it = model.curves.find(lcid);
  if (lcid < 0 || it == model.curves.end()) {
    throw InputError(context_of(where, field), fmt::format("load curve {} is not defined", lcid));
  }
  const model::Curve& c = it->second;
  if (c.function) {
    throw InputError(context_of(where, field),
                     fmt::format("curve {} is a *DEFINE_CURVE_FUNCTION (a function of time); a "
                                 "joint stiffness needs points (*DEFINE_CURVE)",
                                 lcid));
  }
  if (c.abscissa.empty()) {
    throw InputError(context_of(where, field), fmt::format("curve {} has no points", lcid));
  }
  // value(q) = SFO f(q / SFA - OFFA) + OFFO at q = SFA (x_i + OFFA).
  for (std::size_t i = 0; i < c.abscissa.size(); ++i) {
    out.x.push_back(c.sfa * (c.abscissa[i] + c.offa));
    out.y.push_back(c.sfo * c.ordinate[i] + c.offo);
  }
  if (c.sfa < 0.0) {
    std::reverse(out.x.begin(), out.x.end());
    std::reverse(out.y.begin(), out.y.end());
  }
  for (std::size_t i = 1; i < out.x.size(); ++i) {
    if (!(out.x[i] > out.x[i - 1])) {
      throw InputError(context_of(where, field),
                       fmt::format("curve {} must have strictly increasing abscissae (angles or "
                                   "rates); points {} and {} do not",
                                   lcid, i, i + 1));
    }
  }
  return out;
}

double wrap(double a) {  // into (-pi, pi]
  constexpr double two_pi = 2.0 * std::numbers::pi;
  a = std::remainder(a, two_pi);
  return a;
}

Eigen::Matrix3d frame_of(const RigidBody& body, const Eigen::Matrix3d& axes0) {
  return body.state.rotation * body.initial_rotation.transpose() * axes0;
}

}  // namespace

Eigen::Vector3d joint_angles(const Eigen::Matrix3d& frame_a, const Eigen::Matrix3d& frame_b) {
  const Eigen::Matrix3d q = frame_a.transpose() * frame_b;
  const double theta = std::asin(std::clamp(q(0, 2), -1.0, 1.0));
  const double phi = std::atan2(-q(1, 2), q(2, 2));
  const double psi = std::atan2(-q(0, 1), q(0, 0));
  return {phi, theta, psi};
}

JointStiffnessSystem build_joint_stiffnesses(const model::Model& model, const RigidSystem& rigid) {
  JointStiffnessSystem system;
  for (const model::JointStiffness& card : model.joint_stiffnesses) {
    SolverJointStiffness j;
    j.id = card.id;
    j.pida = card.pida;
    j.pidb = card.pidb;
    const model::SourceLocation& c1 = card.card[0];
    for (const auto& other : system.joints) {
      if (other.id == card.id) {
        throw InputError(context_of(c1, "JSID"),
                         fmt::format("joint stiffness ID {} is used twice", card.id));
      }
    }
    j.body_a = rigid_body_of(model, rigid, card.pida, c1, "PIDA");
    j.body_b = rigid_body_of(model, rigid, card.pidb, c1, "PIDB");
    if (j.body_a == j.body_b) {
      throw InputError(context_of(c1, "PIDB"),
                       fmt::format("parts {} and {} are the same rigid body (merged); the joint "
                                   "stiffness would act on one body against itself",
                                   card.pida, card.pidb));
    }
    j.axes_a0 = axes_of(model, card.cida, c1, "CIDA");
    j.axes_b0 = card.cidb == 0 ? j.axes_a0 : axes_of(model, card.cidb, c1, "CIDB");
    if (card.jid != 0) {
      const bool found =
          std::any_of(model.joints.begin(), model.joints.end(),
                      [&](const model::Joint& joint) { return joint.id == card.jid; });
      if (!found) {
        throw InputError(context_of(c1, "JID"),
                         fmt::format("joint {} is not defined (*CONSTRAINED_JOINT_..._ID JID); "
                                     "JID names the joint whose jntforc.csv row reports this "
                                     "stiffness",
                                     card.jid));
      }
      for (const auto& other : system.joints) {
        if (other.jid == card.jid) {
          throw InputError(context_of(c1, "JID"),
                           fmt::format("joint {} already reports joint stiffness {}; one "
                                       "stiffness per joint",
                                       card.jid, other.id));
        }
      }
    }
    j.jid = card.jid;
    for (int k = 0; k < 3; ++k) {
      j.moment_curve[k] = curve_of(model, card.lcid[k], card.card[1], kCurveField[k]);
      j.damping_curve[k] = curve_of(model, card.dlcid[k], card.card[1], kDampingField[k]);
      const double es = card.stiffness[k], fm = card.friction[k];
      if (!std::isfinite(es) || es < 0.0) {
        throw InputError(context_of(card.card[2], kStiffnessField[k]),
                         fmt::format("value {} must be a finite number >= 0", es));
      }
      if (!std::isfinite(fm) || fm < 0.0) {
        throw InputError(
            context_of(card.card[2], kFrictionField[k]),
            fmt::format("value {} is not supported: a friction moment >= 0 (a negative value, a "
                        "curve of friction vs angle, is not supported)",
                        fm));
      }
      if (fm > 0.0 && es == 0.0) {
        throw InputError(
            context_of(card.card[2], kStiffnessField[k]),
            fmt::format("{} = {} needs the elastic stiffness {} > 0 (with {} = 0 "
                        "LS-DYNA switches friction off)",
                        kFrictionField[k], fm, kStiffnessField[k], kStiffnessField[k]));
      }
      const double ns = card.negative_stop[k], ps = card.positive_stop[k];
      for (const auto& [value, field] :
           {std::pair{ns, kNegativeField[k]}, {ps, kPositiveField[k]}}) {
        if (!std::isfinite(value) || std::abs(value) >= 180.0) {
          throw InputError(context_of(card.card[3], field),
                           fmt::format("stop angle {} degrees must be finite and below 180 in "
                                       "magnitude",
                                       value));
        }
        if (value != 0.0 && es == 0.0) {
          throw InputError(context_of(card.card[2], kStiffnessField[k]),
                           fmt::format("the stop angle {} = {} needs the elastic stiffness {} > "
                                       "0 (with {} = 0 the stop would be ignored)",
                                       field, value, kStiffnessField[k], kStiffnessField[k]));
        }
      }
      if (k == 1 && (std::abs(ns) >= 90.0 || std::abs(ps) >= 90.0)) {
        throw InputError(context_of(card.card[3], std::abs(ns) >= 90.0 ? "NSAT" : "PSAT"),
                         "theta lies within -90..90 degrees; a stop at 90 or beyond is never "
                         "reached");
      }
      constexpr double degree = std::numbers::pi / 180.0;
      // NSAPH names the stop of the negative rotation: -|NSAPH| (either sign is read so).
      j.negative_stop[k] = -std::abs(ns) * degree;
      j.positive_stop[k] = std::abs(ps) * degree;
      j.stop_stiffness[k] = es;
      j.friction[k] = fm;
    }
    // Relative inertia for the stability limit.
    double inverse_inertia = 0.0;
    for (const int index : {j.body_a, j.body_b}) {
      const RigidBody& body = rigid.bodies[index];
      const rigid::VelocityConstraints& held = body.state.constraints;
      if (held.translation_count == 3 && held.rotation_count == 3) continue;
      inverse_inertia += 1.0 / body.state.principal_inertia.minCoeff();
    }
    j.critical_step = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const double stiffness =
          (j.moment_curve[k].largest_slope() + 2.0 * j.stop_stiffness[k]) * inverse_inertia;
      const double damping = j.damping_curve[k].largest_slope() * inverse_inertia;  // 2 zeta w
      double step = std::numeric_limits<double>::infinity();
      if (stiffness > 0.0) {
        const double w = std::sqrt(stiffness), zeta = 0.5 * damping / w;
        step = 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta) / w;
      } else if (damping > 0.0) {
        step = 2.0 / damping;
      }
      j.critical_step = std::min(j.critical_step, step);
    }
    system.joints.push_back(std::move(j));
  }
  return system;
}

void evaluate_joint_stiffnesses(JointStiffnessSystem& system, RigidSystem& rigid, double dt) {
  if (system.empty()) return;
  for (RigidBody& body : rigid.bodies) {
    body.joint_force.setZero();
    body.joint_torque.setZero();
  }
  for (SolverJointStiffness& j : system.joints) {
    // Spot-weld failures renumber the bodies: look the parts up again.
    j.body_a = body_of_part(rigid, j.pida);
    j.body_b = body_of_part(rigid, j.pidb);
    if (j.body_a < 0 || j.body_b < 0) {
      throw SolverError(fmt::format("joint stiffness {}: part {} is no longer a rigid body", j.id,
                                    j.body_a < 0 ? j.pida : j.pidb));
    }
    if (dt > j.critical_step) {
      throw SolverError(fmt::format(
          "joint stiffness {}: the time step {:.6g} exceeds the joint's stability limit {:.6g} "
          "(from its largest curve slopes, stop and friction stiffnesses and the bodies' "
          "smallest moments of inertia, docs/theory.md \"Joint stiffness\"); set a smaller "
          "step (*CONTROL_TIMESTEP DTINIT, TSSFAC or DT2MS) or a softer joint",
          j.id, dt, j.critical_step));
    }
    RigidBody& a = rigid.bodies[j.body_a];
    RigidBody& b = rigid.bodies[j.body_b];
    const Eigen::Matrix3d frame_a = frame_of(a, j.axes_a0);
    const Eigen::Matrix3d frame_b = frame_of(b, j.axes_b0);
    const Eigen::Vector3d raw = joint_angles(frame_a, frame_b);
    std::array<double, 3> q{raw.x(), raw.y(), raw.z()};
    if (j.started) {  // phi and psi continue across +-pi (a body may turn many times)
      q[0] = j.angle[0] + wrap(raw.x() - j.angle[0]);
      q[2] = j.angle[2] + wrap(raw.z() - j.angle[2]);
    }
    const double phi = raw.x(), theta = raw.y();
    const double cos_theta = std::cos(theta);
    if (cos_theta < 1e-6) {
      throw SolverError(fmt::format(
          "joint stiffness {}: theta reached {:.6g} degrees; phi and psi are undefined at +-90 "
          "degrees (the z axis of CIDB along the x axis of CIDA)",
          j.id, theta * 180.0 / std::numbers::pi));
    }
    // The relative angular velocity is w_B - w_A = J qdot with the joint axes J = [x_A, e_theta,
    // z_B], e_theta = A (0, cos phi, sin phi) the y axis after the phi turn.
    Eigen::Matrix3d jac;
    jac.col(0) = frame_a.col(0);
    jac.col(1) = frame_a * Eigen::Vector3d(0.0, std::cos(phi), std::sin(phi));
    jac.col(2) = frame_b.col(2);
    const Eigen::PartialPivLU<Eigen::Matrix3d> lu(jac);
    const Eigen::Vector3d rate = lu.solve(b.state.angular_velocity - a.state.angular_velocity);

    std::array<double, 3> f{};
    double elastic = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double es = j.stop_stiffness[k];
      double m = j.moment_curve[k].value(q[k]) + j.damping_curve[k].value(rate[k]);
      elastic += j.moment_curve[k].integral(q[k]);
      if (j.friction[k] > 0.0) {  // elastic-perfectly plastic spring: ES up to FM, then slip
        double trial = es * (q[k] - j.slip[k]);
        if (std::abs(trial) > j.friction[k]) {
          const double sign = trial > 0.0 ? 1.0 : -1.0;
          j.slip[k] = q[k] - sign * j.friction[k] / es;
          trial = sign * j.friction[k];
        }
        m += trial;
        elastic += 0.5 * trial * trial / es;
      }
      double beyond = 0.0;  // past a stop: a linear spring ES
      if (j.positive_stop[k] > 0.0 && q[k] > j.positive_stop[k]) beyond = q[k] - j.positive_stop[k];
      if (j.negative_stop[k] < 0.0 && q[k] < j.negative_stop[k]) beyond = q[k] - j.negative_stop[k];
      m += es * beyond;
      elastic += 0.5 * es * beyond * beyond;
      f[k] = m;
    }
    if (j.started) {
      // Trapezoidal: sum (f^n + f^{n+1}) / 2 . (q^{n+1} - q^n) equals sum f^n . (q^{n+1} -
      // q^{n-1}) / 2, the centred work central differences book; exact for a linear spring.
      for (int k = 0; k < 3; ++k) j.absorbed += 0.5 * (j.moment[k] + f[k]) * (q[k] - j.angle[k]);
    } else {
      j.initial_elastic = elastic;
      j.started = true;
    }
    j.angle = q;
    j.moment = f;
    j.elastic = elastic;
    // Power: T_B . (w_B - w_A) = T_B . J qdot must be -f . qdot, so J^T T_B = -f.
    j.torque_b = -jac.transpose().partialPivLu().solve(Eigen::Vector3d(f[0], f[1], f[2]));
  }
  apply_joint_stiffness_torques(system, rigid);
}

void apply_joint_stiffness_torques(JointStiffnessSystem& system, RigidSystem& rigid) {
  if (system.empty()) return;
  for (RigidBody& body : rigid.bodies) {
    body.joint_force.setZero();
    body.joint_torque.setZero();
  }
  for (SolverJointStiffness& j : system.joints) {
    j.body_a = body_of_part(rigid, j.pida);
    j.body_b = body_of_part(rigid, j.pidb);
    if (j.body_a < 0 || j.body_b < 0) continue;
    rigid.bodies[j.body_b].joint_torque += j.torque_b;
    rigid.bodies[j.body_a].joint_torque -= j.torque_b;
  }
}

}  // namespace rf::solver
