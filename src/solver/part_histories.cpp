#include "solver/part_histories.hpp"

#include <algorithm>
#include <map>

#include "rigid/rigid_body.hpp"
#include "solver/step_rotation.hpp"

namespace rf::solver {

PartHistories::PartHistories(const State& state, const RigidSystem& rigid) {
  std::map<model::Id, int> index;
  for (const element::HexBlock& block : state.hex_blocks) index[block.part_id] = 0;
  for (const element::ShellBlock& block : state.shell_blocks) index[block.part_id] = 0;
  for (const element::BeamBlock& block : state.beam_blocks) index[block.part_id] = 0;
  for (const RigidBody& body : rigid.bodies) {
    if (!body.weld) index[body.id] = 0;  // a spot weld is no part: its nodes count with theirs
  }
  for (auto& [pid, k] : index) {
    k = static_cast<int>(parts_.size());
    parts_.push_back(pid);
  }
  // Blocks in the solver's order (hexahedra, shells, beams), which is also the order of the
  // block slots add_hourglass takes.
  owner_of_node_.assign(state.nodes.size(), -1);
  auto add_block = [&](const auto& block) {
    const int part = index.at(block.part_id);
    part_of_block_.push_back(part);
    for (const std::int32_t node : block.conn) {
      if (node >= 0 && owner_of_node_[node] < 0) owner_of_node_[node] = part;
    }
  };
  for (const element::HexBlock& block : state.hex_blocks) add_block(block);
  for (const element::ShellBlock& block : state.shell_blocks) add_block(block);
  for (const element::BeamBlock& block : state.beam_blocks) add_block(block);
  internal_work_.assign(parts_.size(), 0.0);
  hourglass_.assign(parts_.size(), 0.0);
  bulk_viscosity_.assign(parts_.size(), 0.0);
}

void PartHistories::add_step_work(const State& state, const RigidSystem& rigid, const Vec3Array& vp,
                                  double dt_avg) {
  const NodalState& nodes = state.nodes;
  const std::int64_t n = static_cast<std::int64_t>(nodes.size());
  displacement_.resize(nodes.size());
  const std::int32_t* body_of = rigid.empty() ? nullptr : rigid.body_of_node.data();
  const double* modal_velocity =
      rigid.modal_work_velocity.empty() ? nullptr : rigid.modal_work_velocity.data();
  // The displacement of the step, exactly as the global energy balance takes it
  // (Simulation::update_velocities): the mean of the half-step velocities times dt_avg, and for
  // rigid-body nodes the body's motion at the node (plus the modes' share on flexible bodies).
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    double dx = 0.5 * dt_avg * (vp.x[i] + nodes.v.x[i]);
    double dy = 0.5 * dt_avg * (vp.y[i] + nodes.v.y[i]);
    double dz = 0.5 * dt_avg * (vp.z[i] + nodes.v.z[i]);
    if (body_of && body_of[i] >= 0) {
      const RigidBody& body = rigid.bodies[body_of[i]];
      const Eigen::Vector3d arm(nodes.x.x[i] - body.state.previous_centre.x(),
                                nodes.x.y[i] - body.state.previous_centre.y(),
                                nodes.x.z[i] - body.state.previous_centre.z());
      const Eigen::Vector3d d = dt_avg * (body.mid_velocity + body.mid_angular_velocity.cross(arm));
      dx = d.x();
      dy = d.y();
      dz = d.z();
      if (modal_velocity) {
        dx += dt_avg * modal_velocity[3 * i];
        dy += dt_avg * modal_velocity[3 * i + 1];
        dz += dt_avg * modal_velocity[3 * i + 2];
      }
    }
    displacement_.x[i] = dx;
    displacement_.y[i] = dy;
    displacement_.z[i] = dz;
  }
  // The rotation of the step of every node with rotations, as the global balance takes it.
  const RotationalState& rot = state.rotations;
  if (!rot.empty()) {
    rotation_increment_.resize(rot.size());
    const double* modal_work = rigid.modal_rotation_work_velocity.empty()
                                   ? nullptr
                                   : rigid.modal_rotation_work_velocity.data();
    const std::int64_t count = static_cast<std::int64_t>(rot.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t r = 0; r < count; ++r) {
      const auto [dx, dy, dz] = step_rotation(rot, rigid, body_of, modal_work, r, dt_avg);
      rotation_increment_.x[r] = dx;
      rotation_increment_.y[r] = dy;
      rotation_increment_.z[r] = dz;
    }
  }
  // Element forces (and moments) times the step's displacements (and rotations), per block.
  // `per_node`: 3 (forces) or 6 (forces, then moments) entries per node in the force slot.
  std::size_t slot = 0;
  auto add_block_work = [&](const auto& block, int nodes_per_element, int per_node,
                            const std::vector<std::int32_t>* rotation_conn) {
    const std::size_t b = slot++;
    if (block.rigid || block.force.empty()) return;
    const std::size_t npe = static_cast<std::size_t>(nodes_per_element);
    const std::size_t stride = npe * static_cast<std::size_t>(per_node);
    const bool rotations = rotation_conn && !rotation_conn->empty() && per_node == 6;
    double work = 0.0;
    for (std::size_t e = 0; e < block.size(); ++e) {
      const double* f = &block.force[stride * e];
      const std::int32_t* c = &block.conn[npe * e];
      for (std::size_t a = 0; a < npe; ++a) {
        const std::int32_t i = c[a];
        if (i < 0) continue;
        const double* fa = f + static_cast<std::size_t>(per_node) * a;
        work +=
            fa[0] * displacement_.x[i] + fa[1] * displacement_.y[i] + fa[2] * displacement_.z[i];
        if (!rotations) continue;
        const std::int32_t r = (*rotation_conn)[npe * e + a];
        if (r < 0) continue;
        work += fa[3] * rotation_increment_.x[r] + fa[4] * rotation_increment_.y[r] +
                fa[5] * rotation_increment_.z[r];
      }
    }
    internal_work_[part_of_block_[b]] += work;
  };
  for (const element::HexBlock& block : state.hex_blocks)
    add_block_work(block, block.nodes_per_element(), 3, nullptr);
  for (const element::ShellBlock& block : state.shell_blocks)
    add_block_work(block, 4, element::kShellSlot / 4, &block.rotation_conn);
  for (const element::BeamBlock& block : state.beam_blocks)
    add_block_work(block, 2, element::kBeamSlot / 2, &block.rotation_conn);
}

std::vector<PartSummary> PartHistories::summaries(const State& state,
                                                  const RigidSystem& rigid) const {
  std::vector<PartSummary> rows(parts_.size());
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    rows[p].part = parts_[p];
    rows[p].internal_energy = internal_work_[p] - hourglass_[p] - bulk_viscosity_[p];
    rows[p].hourglass_energy = hourglass_[p];
    rows[p].bulk_viscosity_energy = bulk_viscosity_[p];
  }
  const NodalState& nodes = state.nodes;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int p = owner_of_node_[i];
    // Nodes of a spot weld count with their parts (their velocity is the weld's rigid field).
    if (p < 0 || (rigid.is_rigid(static_cast<std::int32_t>(i)) &&
                  !rigid.bodies[rigid.body_of_node[i]].weld)) {
      continue;
    }
    const double m = nodes.mass[i];
    const double v[3] = {nodes.v.x[i], nodes.v.y[i], nodes.v.z[i]};
    rows[p].kinetic_energy += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; ++k) rows[p].momentum[k] += m * v[k];
  }
  // Rotary kinetic energy of shell and beam nodes, with their node's part (body nodes: the body
  // holds it, as in glstat).
  const RotationalState& rot = state.rotations;
  for (std::size_t r = 0; r < rot.size(); ++r) {
    const std::int32_t i = rot.node[r];
    const int p = owner_of_node_[static_cast<std::size_t>(i)];
    if (p < 0 || rigid.is_rigid(i)) continue;
    const double wx = rot.w.x[r], wy = rot.w.y[r], wz = rot.w.z[r];
    rows[p].kinetic_energy += 0.5 * rot.inertia[r] * (wx * wx + wy * wy + wz * wz);
  }
  for (const RigidBody& body : rigid.bodies) {
    // Bodies can come and go with part switching: found by their lead part's ID.
    if (body.weld) continue;
    const auto it = std::lower_bound(parts_.begin(), parts_.end(), body.id);
    if (it == parts_.end() || *it != body.id) continue;
    const rigid::RigidBodyState& s = body.state;
    PartSummary& row = rows[static_cast<std::size_t>(it - parts_.begin())];
    row.kinetic_energy += rigid::kinetic_energy(s);
    for (int k = 0; k < 3; ++k) {
      row.momentum[k] += s.mass * s.velocity[k];
      row.rigid_velocity[k] = s.velocity[k];
    }
  }
  return rows;
}

std::vector<NodeReaction> constraint_reactions(const State& state, const Boundary& boundary,
                                               const RigidSystem& rigid, const Vec3Array& vp,
                                               double dt_avg) {
  std::vector<NodeReaction> out;
  if (dt_avg <= 0.0) return out;
  const NodalState& nodes = state.nodes;
  std::vector<std::uint8_t> prescribed(nodes.size(), 0);
  for (const PrescribedDof& dof : boundary.prescribed) {
    if (dof.active(state.time)) prescribed[dof.node] |= static_cast<std::uint8_t>(1 << dof.axis);
  }
  for (const std::int32_t i : boundary.constrained_nodes) {
    if (rigid.is_rigid(i)) continue;  // moves with its body; its SPC does not act
    const std::uint8_t mask =
        static_cast<std::uint8_t>((boundary.fixed.empty() ? 0 : boundary.fixed[i]) | prescribed[i]);
    if (mask == 0) continue;
    NodeReaction r;
    r.node = i;
    const double m = nodes.mass[i];
    const double dv[3] = {nodes.v.x[i] - vp.x[i], nodes.v.y[i] - vp.y[i], nodes.v.z[i] - vp.z[i]};
    const double f[3] = {nodes.f_ext.x[i] - nodes.f_int.x[i], nodes.f_ext.y[i] - nodes.f_int.y[i],
                         nodes.f_ext.z[i] - nodes.f_int.z[i]};
    for (int k = 0; k < 3; ++k) r.force[k] = (mask >> k & 1) ? m * dv[k] / dt_avg - f[k] : 0.0;
    out.push_back(r);
  }
  return out;
}

}  // namespace rf::solver
