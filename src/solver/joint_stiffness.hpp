// *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED: moments between two rigid bodies from the relative
// rotation angles of two local coordinate systems, one fixed in each body (docs/theory.md
// "Joint stiffness").
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "model/model.hpp"
#include "solver/rigid_bodies.hpp"

namespace rf::solver {

// A *DEFINE_CURVE with its SFA/SFO/OFFA/OFFO applied to the points, extrapolated linearly beyond
// its ends as *MAT_S04's force curve (docs/keywords.md). Empty: the value is 0.
struct JointCurve {
  std::vector<double> x, y;
  bool empty() const { return x.empty(); }
  double value(double q) const;
  double integral(double q) const;  // from 0 to q, exact for the piecewise linear curve
  double largest_slope() const;
};

struct SolverJointStiffness {
  model::Id id = 0;   // JSID
  model::Id jid = 0;  // joint whose jntforc.csv row also reports this one (0: none)
  model::Id pida = 0, pidb = 0;
  int body_a = -1, body_b = -1;  // rigid-body indices (looked up again after part switching)
  // Columns: the axes of CIDA (CIDB) in global axes at t = 0; they turn with body A (B):
  // A(t) = R_A R_A0^T A0.
  Eigen::Matrix3d axes_a0 = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d axes_b0 = Eigen::Matrix3d::Identity();
  std::array<JointCurve, 3> moment_curve;   // LCIDPH LCIDT LCIDPS
  std::array<JointCurve, 3> damping_curve;  // DLCIDPH DLCIDT DLCIDPS
  std::array<double, 3> stop_stiffness{};   // ESPH EST ESPS
  std::array<double, 3> friction{};         // FMPH FMT FMPS
  std::array<double, 3> negative_stop{};    // radians, <= 0; 0: none
  std::array<double, 3> positive_stop{};    // radians, >= 0; 0: none
  // Stability limit of central differences for the joint (docs/theory.md "Joint stiffness"):
  // per angle, w^2 = (largest curve slope + 2 ES) / I and zeta from the largest damping slope,
  // dt < 2 (sqrt(1 + zeta^2) - zeta) / w, I the relative inertia (1/I = 1/I_A + 1/I_B over the
  // smallest principal moments; a body held in all six directions adds nothing).
  double critical_step = 0.0;

  // History (restart dump): the angles of the last evaluation (phi, psi unwrapped across +-pi),
  // the slip angles of the friction springs, the generalized moments then applied (the joint's
  // resistance f_k, conjugate to the angles), the torque then applied to body B (A gets the
  // opposite), the work the joint has absorbed sum (f^n + f^{n+1}) / 2 . (q^{n+1} - q^n), and
  // the elastic
  // energy at t = 0.
  std::array<double, 3> angle{};
  std::array<double, 3> slip{};
  std::array<double, 3> moment{};
  Eigen::Vector3d torque_b = Eigen::Vector3d::Zero();
  double absorbed = 0.0;
  double initial_elastic = 0.0;
  bool started = false;  // angles of a first evaluation exist

  // Output of the last evaluation.
  double elastic = 0.0;  // curve integrals, stop springs and friction springs
  double dissipated() const { return absorbed - (elastic - initial_elastic); }
};

struct JointStiffnessSystem {
  std::vector<SolverJointStiffness> joints;
  bool empty() const { return joints.empty(); }
};

// Resolves the cards. Throws InputError (file, line, keyword, field) when a part is missing or
// not rigid, PIDA and PIDB are the same body, a coordinate system or curve does not exist, a
// curve is a *DEFINE_CURVE_FUNCTION or has decreasing abscissae, stops or friction are given
// with a zero stiffness ESPH/EST/ESPS, a value is negative where it must not be, the JID names no
// joint, or two cards name the same JSID.
JointStiffnessSystem build_joint_stiffnesses(const model::Model& model, const RigidSystem& rigid);

// Relative angles of frame B (columns) in frame A (columns), docs/theory.md "Joint stiffness":
// Q = A^T B = R_x(phi) R_y(theta) R_z(psi), so theta = asin Q_13, phi = atan2(-Q_23, Q_33),
// psi = atan2(-Q_12, Q_11).
Eigen::Vector3d joint_angles(const Eigen::Matrix3d& frame_a, const Eigen::Matrix3d& frame_b);

// Evaluates every joint stiffness at the bodies' current orientation (t^n) and angular
// velocities (those of the step that led there), updates its history and sets the bodies'
// joint_torque for the next advance. Throws SolverError when theta reaches +-90 degrees (the angles
// are undefined there) or when the step just taken, dt, exceeds a joint's critical_step (the run
// would blow up).
void evaluate_joint_stiffnesses(JointStiffnessSystem& system, RigidSystem& rigid, double dt);

// Sets the bodies' joint_torque from the stored torque_b of each joint (after a restart; the
// bodies are looked up by part again).
void apply_joint_stiffness_torques(JointStiffnessSystem& system, RigidSystem& rigid);

}  // namespace rf::solver
