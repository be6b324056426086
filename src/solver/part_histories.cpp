#include "solver/part_histories.hpp"

#include <algorithm>
#include <map>

#include "rigid/rigid_body.hpp"

namespace rf::solver {

PartHistories::PartHistories(const State& state, const RigidSystem& rigid) {
  std::map<model::Id, int> index;
  for (const element::HexBlock& block : state.hex_blocks) index[block.part_id] = 0;
  for (const RigidBody& body : rigid.bodies) {
    if (!body.weld) index[body.id] = 0;  // a spot weld is no part: its nodes count with theirs
  }
  for (auto& [pid, k] : index) {
    k = static_cast<int>(parts_.size());
    parts_.push_back(pid);
  }
  owner_of_node_.assign(state.nodes.size(), -1);
  for (const element::HexBlock& block : state.hex_blocks) {
    const int part = index.at(block.part_id);
    part_of_block_.push_back(part);
    for (const std::int32_t node : block.conn) {
      if (owner_of_node_[node] < 0) owner_of_node_[node] = part;
    }
  }
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
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    const element::HexBlock& block = state.hex_blocks[b];
    if (block.rigid || block.force.empty()) continue;
    const std::size_t npe = static_cast<std::size_t>(block.nodes_per_element());
    double work = 0.0;
    for (std::size_t e = 0; e < block.size(); ++e) {
      const double* f = &block.force[3 * npe * e];
      const std::int32_t* c = &block.conn[npe * e];
      for (std::size_t a = 0; a < npe; ++a) {
        const std::int32_t i = c[a];
        work += f[3 * a] * displacement_.x[i] + f[3 * a + 1] * displacement_.y[i] +
                f[3 * a + 2] * displacement_.z[i];
      }
    }
    internal_work_[part_of_block_[b]] += work;
  }
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
