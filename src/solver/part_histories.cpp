#include "solver/part_histories.hpp"

#include <algorithm>
#include <cmath>
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

namespace {

// The part of r in the span of `directions` (Gram-Schmidt; directions already in the span are
// skipped), so that overlapping constraints (an SPC axis and a DOF 4 vector) are counted once.
std::array<double, 3> project(const std::array<double, 3>& r,
                              const std::vector<std::array<double, 3>>& directions) {
  std::array<std::array<double, 3>, 3> basis{};
  int size = 0;
  for (std::array<double, 3> d : directions) {
    for (int b = 0; b < size; ++b) {
      const double c = d[0] * basis[b][0] + d[1] * basis[b][1] + d[2] * basis[b][2];
      for (int k = 0; k < 3; ++k) d[k] -= c * basis[b][k];
    }
    const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (norm < 1e-9 || size == 3) continue;
    for (int k = 0; k < 3; ++k) basis[size][k] = d[k] / norm;
    ++size;
  }
  std::array<double, 3> out{};
  for (int b = 0; b < size; ++b) {
    const double c = r[0] * basis[b][0] + r[1] * basis[b][1] + r[2] * basis[b][2];
    for (int k = 0; k < 3; ++k) out[k] += c * basis[b][k];
  }
  return out;
}

void add_axes(std::uint8_t mask, std::vector<std::array<double, 3>>& directions) {
  for (int k = 0; k < 3; ++k) {
    if (!(mask >> k & 1)) continue;
    std::array<double, 3> e{};
    e[static_cast<std::size_t>(k)] = 1.0;
    directions.push_back(e);
  }
}

}  // namespace

std::vector<NodeReaction> constraint_reactions(const State& state, const Boundary& boundary,
                                               const RigidSystem& rigid, const Vec3Array& vp,
                                               double dt_avg) {
  std::vector<NodeReaction> out;
  if (dt_avg <= 0.0) return out;
  const NodalState& nodes = state.nodes;
  const RotationalState& rot = state.rotations;
  std::vector<std::uint8_t> prescribed(nodes.size(), 0);
  for (const PrescribedDof& dof : boundary.prescribed) {
    if (dof.active(state.time)) prescribed[dof.node] |= static_cast<std::uint8_t>(1 << dof.axis);
  }
  // DOF 4 and 5-8: the vectors of the active ones, by node and by rotational index.
  std::vector<std::pair<std::int32_t, std::array<double, 3>>> along, about;
  for (const PrescribedDirection& p : boundary.prescribed_directions) {
    if (!p.active(state.time)) continue;
    if (p.rotation < 0)
      along.emplace_back(p.node, p.direction);
    else
      about.emplace_back(p.rotation, p.direction);
  }
  // Every node with a constrained translation or rotation, ascending.
  std::vector<std::int32_t> listed = boundary.constrained_nodes;
  const bool rotations = !rot.empty();
  if (rotations) {
    for (std::size_t r = 0; r < rot.size(); ++r) {
      if (!boundary.rotation_fixed.empty() && boundary.rotation_fixed[r] != 0)
        listed.push_back(rot.node[r]);
    }
    for (const auto& [r, n] : about) listed.push_back(rot.node[static_cast<std::size_t>(r)]);
    std::sort(listed.begin(), listed.end());
    listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
  }
  std::vector<std::array<double, 3>> directions;
  for (const std::int32_t i : listed) {
    if (rigid.is_rigid(i)) continue;  // moves with its body; its SPC does not act
    NodeReaction reaction;
    reaction.node = i;
    directions.clear();
    add_axes(
        static_cast<std::uint8_t>((boundary.fixed.empty() ? 0 : boundary.fixed[i]) | prescribed[i]),
        directions);
    for (const auto& [node, n] : along)
      if (node == i) directions.push_back(n);
    if (!directions.empty()) {
      const double m = nodes.mass[i];
      const std::array<double, 3> r{
          m * (nodes.v.x[i] - vp.x[i]) / dt_avg - (nodes.f_ext.x[i] - nodes.f_int.x[i]),
          m * (nodes.v.y[i] - vp.y[i]) / dt_avg - (nodes.f_ext.y[i] - nodes.f_int.y[i]),
          m * (nodes.v.z[i] - vp.z[i]) / dt_avg - (nodes.f_ext.z[i] - nodes.f_int.z[i])};
      reaction.force = project(r, directions);
    }
    const std::int32_t ri = rotations ? rot.index(i) : -1;
    if (ri >= 0) {
      const std::size_t r = static_cast<std::size_t>(ri);
      directions.clear();
      add_axes(boundary.rotation_fixed.empty() ? std::uint8_t{0} : boundary.rotation_fixed[r],
               directions);
      for (const auto& [index, n] : about)
        if (index == ri) directions.push_back(n);
      if (!directions.empty()) {
        const double inertia = rot.inertia[r];
        const std::array<double, 3> mr{inertia * (rot.w.x[r] - rot.w_previous.x[r]) / dt_avg -
                                           (rot.m_ext.x[r] - rot.m_int.x[r]),
                                       inertia * (rot.w.y[r] - rot.w_previous.y[r]) / dt_avg -
                                           (rot.m_ext.y[r] - rot.m_int.y[r]),
                                       inertia * (rot.w.z[r] - rot.w_previous.z[r]) / dt_avg -
                                           (rot.m_ext.z[r] - rot.m_int.z[r])};
        reaction.moment = project(mr, directions);
      }
    }
    out.push_back(reaction);
  }
  return out;
}

}  // namespace rf::solver
