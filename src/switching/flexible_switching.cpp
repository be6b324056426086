#include "switching/flexible_switching.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <unordered_map>

#include "element/kernels.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::switching {

namespace {

using model::context_of;
using model::Id;

// Geometric stiffening (FORM 0) costs n^3 per step: the same limit as for bodies that are rigid
// in the input (solver/flexible_bodies.cpp).
constexpr int kMaxStiffeningModes = 40;

Eigen::Vector3d position(const solver::NodalState& n, std::int32_t i) {
  return {n.x.x[i], n.x.y[i], n.x.z[i]};
}

// Best-fit rotation Q (reference -> current) of a node cloud with masses: the rotation of the
// polar decomposition of sum m (x - c)(x0 - c0)^T (Kabsch; Horn, J. Opt. Soc. Am. A 4 (1987)
// 629). Exact for a rigidly moved shape; for a deformed one it is the mean rotation.
Eigen::Matrix3d best_fit_rotation(const std::vector<std::int32_t>& nodes,
                                  const solver::NodalState& n) {
  double mass = 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), c0 = Eigen::Vector3d::Zero();
  for (const auto i : nodes) {
    mass += n.mass[i];
    c += n.mass[i] * position(n, i);
    c0 += n.mass[i] * Eigen::Vector3d(n.x0.x[i], n.x0.y[i], n.x0.z[i]);
  }
  c /= mass;
  c0 /= mass;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  for (const auto i : nodes) {
    const Eigen::Vector3d x0(n.x0.x[i], n.x0.y[i], n.x0.z[i]);
    a += n.mass[i] * (position(n, i) - c) * (x0 - c0).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) d(2, 2) = -1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

// Element-node internal forces of one block at the given positions with its current stresses
// (dt = 0: no increment, zero velocity: no viscous hourglass force), in conn order.
std::vector<double> block_forces(element::HexBlock& block, const std::vector<double>& x,
                                 const std::vector<double>& y, const std::vector<double>& z,
                                 const std::vector<double>& zero) {
  const element::NodalView view{x.data(),    y.data(),    z.data(),
                                zero.data(), zero.data(), zero.data()};
  element::compute_block_forces(block, view, 0.0);
  return block.force;
}

}  // namespace

FlexibleSwitching::FlexibleSwitching(const model::Model& model, const solver::State& state,
                                     const solver::ModeLoader& loader) {
  const solver::NodalState& nodes = state.nodes;
  for (const auto& [pid, card] : model.part_modes) {
    const auto& part = model.parts.at(pid);
    const auto& material = model.materials.at(part.mid);
    if (material.kind == model::MaterialKind::Rigid) continue;  // solver/flexible_bodies.cpp
    const element::HexBlock* block = nullptr;
    for (const auto& b : state.hex_blocks) {
      if (b.part_id == pid) block = &b;
    }
    if (!block) {
      throw InputError(context_of(card.where, "PID"),
                       fmt::format("part {} has no elements to make a flexible body of", pid));
    }
    PartModes pm;
    pm.card = &card;
    pm.nodes.assign(block->conn.begin(), block->conn.end());
    std::sort(pm.nodes.begin(), pm.nodes.end());
    pm.nodes.erase(std::unique(pm.nodes.begin(), pm.nodes.end()), pm.nodes.end());
    for (const auto i : pm.nodes) pm.mass.push_back(nodes.mass[i]);

    solver::SelectedModes selected =
        solver::select_part_modes(card, fmt::format("part {}", pid), pm.nodes, nodes, loader);
    pm.file_modes = std::move(selected.file_modes);
    pm.shapes = std::move(selected.shapes);
    pm.eigenvalues = std::move(selected.eigenvalues);
    pm.damping = std::move(selected.damping);
    const std::size_t bn = pm.nodes.size();
    if (card.form != 1 && static_cast<int>(pm.file_modes.size()) <= kMaxStiffeningModes &&
        block->order == 1 && !block->quadratic_tetrahedra()) {
      std::unordered_map<std::int32_t, std::int32_t> at;
      for (std::size_t k = 0; k < bn; ++k) at.emplace(pm.nodes[k], static_cast<std::int32_t>(k));
      for (const std::int32_t i : block->conn) pm.hexahedra.push_back(at.at(i));
      pm.lame_mu = material.e / (2.0 * (1.0 + material.pr));
      pm.lame_lambda = material.e * material.pr / ((1.0 + material.pr) * (1.0 - 2.0 * material.pr));
    }
    parts_.emplace(pid, std::move(pm));
  }
}

modal::FlexibleBody FlexibleSwitching::prepare(Id pid, const solver::RigidBody& body,
                                               const Eigen::Matrix3d& frame, double time) const {
  const PartModes& pm = parts_.at(pid);
  if (body.nodes != pm.nodes) {
    throw SolverError(fmt::format(
        "at time {:.6g}: part {} (*PART_MODES at {}:{}) switched to rigid would share its rigid "
        "body with other nodes; its modes describe its own nodes only: keep it apart from "
        "other switched parts and rigid bodies (no shared nodes, no LRB)",
        time, pid, pm.card->where.file, pm.card->where.line));
  }
  modal::ModeInput input;
  input.form = pm.card->form == 1 ? modal::ModalForm::kFast : modal::ModalForm::kExact;
  input.initial_rotation = frame;
  const std::size_t bn = pm.nodes.size();
  input.mass = pm.mass;
  input.body_coords.resize(3 * bn);
  for (std::size_t k = 0; k < bn; ++k) {
    input.body_coords[3 * k] = body.body_coordinates.x[k];
    input.body_coords[3 * k + 1] = body.body_coordinates.y[k];
    input.body_coords[3 * k + 2] = body.body_coordinates.z[k];
  }
  input.shapes_global = pm.shapes;
  input.eigenvalues = pm.eigenvalues;
  input.damping = pm.damping;
  input.hexahedra = pm.hexahedra;
  input.lame_lambda = pm.lame_lambda;
  input.lame_mu = pm.lame_mu;
  modal::FlexibleBody f;
  try {
    f = modal::prepare_flexible_body(input);
  } catch (const std::invalid_argument& e) {
    throw SolverError(
        fmt::format("at time {:.6g}: part {} (*PART_MODES at {}:{}) switched to "
                    "rigid: {}",
                    time, pid, pm.card->where.file, pm.card->where.line, e.what()));
  }
  f.part = pid;
  f.file_modes = pm.file_modes;
  // Every node is reconstructed every cycle (switching reads all nodes).
  for (std::size_t k = 0; k < bn; ++k) {
    f.active.push_back(static_cast<std::int32_t>(k));
    f.active_nodes.push_back(pm.nodes[k]);
  }
  return f;
}

double FlexibleSwitching::attach(Id pid, int body_index, const std::vector<double>& velocities,
                                 solver::State& state, solver::RigidSystem& rigid) {
  solver::RigidBody& body = rigid.bodies[body_index];
  // The modes are global at the reference configuration; the part has turned by Q since (best
  // fit), so in body axes they are R^T Q phi: prepare_flexible_body applies R0^T with
  // R0 = Q^T R.
  const Eigen::Matrix3d frame =
      best_fit_rotation(parts_.at(pid).nodes, state.nodes).transpose() * body.state.rotation;
  modal::FlexibleBody f = prepare(pid, body, frame, state.time);
  f.body = body_index;
  // s = Phi^T M R^T (v - v_c - w x r), and v_i += R Phi_i s (the body's nodes carry the rigid
  // field now).
  solver::initialize_modal_velocities(body, f, velocities, state.nodes);
  body.update = solver::NodeUpdate::kCurvilinear;
  body.flexible = static_cast<int>(rigid.flexible.size());
  if (rigid.modal_work_velocity.size() != 3 * state.nodes.size()) {
    rigid.modal_work_velocity.assign(3 * state.nodes.size(), 0.0);
  }
  const double kinetic = f.kinetic_energy();
  rigid.flexible.push_back(std::move(f));
  frames_[pid] = frame;
  return kinetic;
}

void FlexibleSwitching::rebuild(Id pid, int body_index, const Eigen::Matrix3d& frame,
                                const solver::State& state, solver::RigidSystem& rigid) {
  solver::RigidBody& body = rigid.bodies[body_index];
  modal::FlexibleBody f = prepare(pid, body, frame, state.time);
  f.body = body_index;
  body.update = solver::NodeUpdate::kCurvilinear;
  body.flexible = static_cast<int>(rigid.flexible.size());
  if (rigid.modal_work_velocity.size() != 3 * state.nodes.size()) {
    rigid.modal_work_velocity.assign(3 * state.nodes.size(), 0.0);
  }
  rigid.flexible.push_back(std::move(f));
  frames_[pid] = frame;
}

double FlexibleSwitching::restore_modal_stresses(const solver::RigidBody& body,
                                                 const modal::FlexibleBody& f,
                                                 element::HexBlock& block,
                                                 solver::State& state) const {
  solver::NodalState& nodes = state.nodes;
  const rigid::RigidBodyState& s = body.state;
  const std::size_t count = nodes.size();
  std::vector<double> x(nodes.x.x), y(nodes.x.y), z(nodes.x.z);  // before: the rigid shape
  std::vector<double> ux(count, 0.0), uy(count, 0.0), uz(count, 0.0), zero(count, 0.0);
  for (std::size_t k = 0; k < body.nodes.size(); ++k) {
    const std::int32_t i = body.nodes[k];
    const Eigen::Vector3d local(f.body_coords[3 * k], f.body_coords[3 * k + 1],
                                f.body_coords[3 * k + 2]);
    const Eigen::Vector3d u = s.rotation * f.displacement(k, f.q);
    const Eigen::Vector3d rigid_place = s.centre + s.rotation * local;
    x[i] = rigid_place.x();
    y[i] = rigid_place.y();
    z[i] = rigid_place.z();
    ux[i] = u.x();
    uy[i] = u.y();
    uz[i] = u.z();
    nodes.x.x[i] = rigid_place.x() + u.x();
    nodes.x.y[i] = rigid_place.y() + u.y();
    nodes.x.z[i] = rigid_place.z() + u.z();
  }
  const std::vector<double> before = block_forces(block, x, y, z, zero);
  // The increment: the element's own strain-rate update with velocity du over dt = 1, on the
  // mid configuration x + du / 2 (the kernel's), objective rotation of the frozen stress
  // included, so ELFORM 1 (with its stiffness hourglass state), ELFORM 2 and p > 1 elements
  // all get the stress their kernel would have built over the same displacement.
  const element::NodalView step{nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                ux.data(),        uy.data(),        uz.data()};
  element::compute_block_forces(block, step, 1.0);
  const std::vector<double> after = block_forces(block, nodes.x.x, nodes.x.y, nodes.x.z, zero);
  // Work of the internal forces over du (trapezoid: exact for a linear response).
  double work = 0.0;
  const int per = block.nodes_per_element();
  for (std::size_t e = 0; e < block.size(); ++e) {
    for (int a = 0; a < per; ++a) {
      const std::int32_t i = block.conn[e * per + a];
      const std::size_t slot = (e * per + a) * 3;
      work += 0.5 *
              ((before[slot] + after[slot]) * ux[i] + (before[slot + 1] + after[slot + 1]) * uy[i] +
               (before[slot + 2] + after[slot + 2]) * uz[i]);
    }
  }
  return work;
}

void FlexibleSwitching::release_velocities(int body_index, double dt_prev, solver::State& state,
                                           solver::RigidSystem& rigid) {
  solver::RigidBody& body = rigid.bodies[body_index];
  const int index = body.flexible;
  const modal::FlexibleBody& f = rigid.flexible[index];
  const rigid::RigidBodyState& s = body.state;
  solver::NodalState& nodes = state.nodes;
  std::vector<double> half(f.mode_count);
  for (std::size_t m = 0; m < f.mode_count; ++m) {
    half[m] = dt_prev > 0.0 ? (f.q[m] - f.q_previous[m]) / dt_prev : f.s[m];
  }
  // The body's angular momentum about x_c, and that of the nodal field.
  const Eigen::Vector3d target = s.angular_momentum;
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < body.nodes.size(); ++k) {
    const std::int32_t i = body.nodes[k];
    const Eigen::Vector3d r = position(nodes, i) - s.centre;
    const Eigen::Vector3d v =
        s.velocity + s.angular_velocity.cross(r) + s.rotation * f.displacement(k, half);
    nodes.v.x[i] = v.x();
    nodes.v.y[i] = v.y();
    nodes.v.z[i] = v.z();
    const double m = nodes.mass[i];
    h += m * r.cross(v);
    j += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  // sum m r = 0 (the modes keep the centre), so a rotation about x_c leaves P unchanged.
  const Eigen::Vector3d dw = j.ldlt().solve(target - h);
  for (const std::int32_t i : body.nodes) {
    const Eigen::Vector3d dv = dw.cross(position(nodes, i) - s.centre);
    nodes.v.x[i] += dv.x();
    nodes.v.y[i] += dv.y();
    nodes.v.z[i] += dv.z();
    for (int d = 0; d < 3; ++d) rigid.modal_work_velocity[3 * i + d] = 0.0;
  }
  // Drop the flexible body; later ones move down by one.
  frames_.erase(f.part);
  rigid.flexible.erase(rigid.flexible.begin() + index);
  body.flexible = -1;
  for (auto& other : rigid.bodies) {
    if (other.flexible > index) --other.flexible;
  }
}

}  // namespace rf::switching
