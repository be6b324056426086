#include "switching/part_switching.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "element/switch_state.hpp"
#include "model/error.hpp"

namespace rf::switching {

namespace {

using model::Id;
using solver::RigidBody;
using solver::RigidSystem;
using solver::State;

Eigen::Vector3d node_position(const State& s, std::int32_t i) {
  return {s.nodes.x.x[i], s.nodes.x.y[i], s.nodes.x.z[i]};
}
Eigen::Vector3d node_velocity(const State& s, std::int32_t i) {
  return {s.nodes.v.x[i], s.nodes.v.y[i], s.nodes.v.z[i]};
}

// Linear momentum, angular momentum about the origin and kinetic energy of a collection of
// free nodes and bodies, at the levels x^n, v^{n-1/2} (bodies: x_c^n, v_c^{n-1/2}, L^{n-1/2}).
// A node with rotations (shells, beams) adds its spin I w to the angular momentum and
// I |w|^2 / 2 to the kinetic energy (isotropic lumped rotary inertia I).
struct Momenta {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  double kinetic = 0.0;
  void add_node(const State& s, std::int32_t i) {
    const double m = s.nodes.mass[i];
    const Eigen::Vector3d v = node_velocity(s, i);
    p += m * v;
    h += node_position(s, i).cross(m * v);
    kinetic += 0.5 * m * v.squaredNorm();
    const std::int32_t r = s.rotations.index(i);
    if (r >= 0) {
      const double inertia = s.rotations.inertia[r];
      const Eigen::Vector3d w(s.rotations.w.x[r], s.rotations.w.y[r], s.rotations.w.z[r]);
      h += inertia * w;
      kinetic += 0.5 * inertia * w.squaredNorm();
    }
  }
  // A body's kinetic energy at its present attitude R^n: M v^2 / 2 + L . J(R^n)^-1 L / 2, the
  // energy of the rigid field its nodes get on release (and of the motion a merge takes over).
  // rigid::kinetic_energy's L . w^{n+1/2} / 2 uses the step's angular velocity, which differs
  // by O(w dt) when the body precesses (a spinning shell or beam part at DTMAX); booking that
  // difference as switch energy would keep the rigid phase's measuring error for good.
  void add_body(const rigid::RigidBodyState& b) {
    const Eigen::Vector3d pb = b.mass * b.velocity;
    p += pb;
    h += b.centre.cross(pb) + b.angular_momentum;
    kinetic +=
        0.5 * b.mass * b.velocity.squaredNorm() +
        0.5 * b.angular_momentum.dot(rigid::global_inertia(b).ldlt().solve(b.angular_momentum));
  }
};

rigid::MassProperties body_properties(const rigid::RigidBodyState& b) {
  return {b.mass, b.centre, rigid::global_inertia(b)};
}

rigid::MassProperties card_properties(const model::SwitchInertia& in) {
  rigid::MassProperties p;
  p.mass = in.tm;
  p.centre = {in.xc[0], in.xc[1], in.xc[2]};
  const auto& c = in.inertia;
  p.inertia << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  return p;
}

// Nodes on one line without rotary inertia (a straight chain of trusses) have no moment of
// inertia about it, and J^-1 would not exist. As for spot welds (solver/rigid_bodies.cpp), the
// body gets a moment of 1e-6 of the largest about that line only (the other principal moments
// stay exact): the nodes' angular momentum has no component along it, so no motion changes.
void regularise(rigid::MassProperties& props) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(props.inertia);
  const double largest = eigen.eigenvalues().maxCoeff();
  if (!(largest > 0.0)) return;
  for (int k = 0; k < 3; ++k) {
    if (eigen.eigenvalues()[k] < 1e-6 * largest) {
      const Eigen::Vector3d axis = eigen.eigenvectors().col(k);
      props.inertia += 1e-6 * largest * axis * axis.transpose();
    }
  }
}

// Nodes with rotations take the angular velocity w (a rigid body's nodes turn with it).
void set_node_spins(const std::vector<std::int32_t>& nodes, const Eigen::Vector3d& w,
                    State& state) {
  auto& rot = state.rotations;
  if (rot.empty()) return;
  for (const auto i : nodes) {
    const std::int32_t r = rot.index(i);
    if (r < 0) continue;
    rot.w.x[r] = w.x();
    rot.w.y[r] = w.y();
    rot.w.z[r] = w.z();
  }
}

// Removes the bodies whose index is in `gone` and renumbers every reference to bodies.
void remove_bodies(RigidSystem& rigid, const std::set<int>& gone,
                   const std::map<int, int>& moved_to) {
  solver::remove_rigid_bodies(rigid, gone, moved_to);
}

std::vector<std::uint8_t> deformable_nodes(const State& state) {
  std::vector<std::uint8_t> flag(state.nodes.size(), 0);
  auto mark = [&](const auto& blocks) {  // every element family
    for (const auto& block : blocks) {
      if (block.rigid) continue;
      for (const std::int32_t i : block.conn) flag[i] = 1;
    }
  };
  mark(state.hex_blocks);
  mark(state.shell_blocks);
  mark(state.beam_blocks);
  return flag;
}

// Gives a body new mass properties and the velocity that carries momenta `m` exactly; the
// physical rotation R R0^T stays continuous; nodes get the rigid velocity field.
void define_body(RigidBody& body, const rigid::MassProperties& props, const Momenta& m,
                 const Eigen::Matrix3d& physical_rotation, int update_type, State& state) {
  rigid::RigidBodyState fresh = rigid::make_rigid_body(props);
  fresh.constraints = body.state.constraints;
  const Eigen::Vector3d v = m.p / props.mass;
  const Eigen::Vector3d w = props.inertia.ldlt().solve(m.h - props.centre.cross(m.p));
  rigid::set_velocity(fresh, v, w);
  fresh.previous_centre = fresh.centre;
  fresh.previous_rotation = fresh.rotation;
  body.state = fresh;
  // Phi = R R0^T must equal physical_rotation: R0 = Phi^T R.
  body.initial_rotation = physical_rotation.transpose() * fresh.rotation;
  body.velocity_before = v;
  body.angular_velocity_before = w;
  body.mid_velocity = v;
  body.mid_angular_velocity = w;
  std::sort(body.nodes.begin(), body.nodes.end());
  body.nodes.erase(std::unique(body.nodes.begin(), body.nodes.end()), body.nodes.end());
  auto& nodes = state.nodes;
  body.body_coordinates = rigid::body_coordinates(body.state, body.nodes, nodes.x.x.data(),
                                                  nodes.x.y.data(), nodes.x.z.data());
  const auto deformable = deformable_nodes(state);
  body.shares_nodes = false;
  for (const auto i : body.nodes) {
    if (deformable[i]) body.shares_nodes = true;
  }
  body.update = (update_type != 2 && body.shares_nodes) ? solver::NodeUpdate::kLinear
                                                        : solver::NodeUpdate::kCurvilinear;
  rigid::rigid_node_velocities(v, w, body.state.centre, body.nodes, nodes.x.x.data(),
                               nodes.x.y.data(), nodes.x.z.data(), nodes.v.x.data(),
                               nodes.v.y.data(), nodes.v.z.data());
  set_node_spins(body.nodes, w, state);
}

}  // namespace

Eigen::Matrix3d body_rotation(const RigidBody& body) {
  return body.state.rotation * body.initial_rotation.transpose();
}

PartSwitcher::PartSwitcher(const model::Model& model, const State& state) : model_(model) {
  using Family = PartBlock::Family;
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    block_of_part_[state.hex_blocks[b].part_id] = {Family::kHex, static_cast<int>(b)};
  }
  for (std::size_t b = 0; b < state.shell_blocks.size(); ++b) {
    block_of_part_[state.shell_blocks[b].part_id] = {Family::kShell, static_cast<int>(b)};
  }
  for (std::size_t b = 0; b < state.beam_blocks.size(); ++b) {
    block_of_part_[state.beam_blocks[b].part_id] = {Family::kBeam, static_cast<int>(b)};
  }
}

std::vector<Id> PartSwitcher::expand(const std::vector<model::PartSwitch>& cards) const {
  std::vector<Id> parts;
  for (const auto& c : cards) {
    if (c.part_set) {
      const auto& set = model_.part_sets.at(c.pid);  // checked by the reader
      parts.insert(parts.end(), set.parts.begin(), set.parts.end());
    } else {
      parts.push_back(c.pid);
    }
  }
  return parts;
}

void PartSwitcher::enable_flexible_bodies(const solver::ModeLoader& loader, const State& state) {
  auto flexible = std::make_unique<FlexibleSwitching>(model_, state, loader);
  if (!flexible->empty()) flexible_ = std::move(flexible);
}

double PartSwitcher::frozen_energy() const {
  double sum = 0.0;
  for (const auto& [pid, p] : switched_) sum += p.frozen_energy;
  return sum;
}

SwitchEvent PartSwitcher::to_rigid(const std::vector<model::PartSwitch>& cards, double time,
                                   State& state, RigidSystem& rigid) {
  SwitchEvent event;
  event.time = time;
  event.to_rigid = true;
  if (rigid.body_of_node.empty()) rigid.body_of_node.assign(state.nodes.size(), -1);

  // Groups: one per lead (LRB) and, without a lead, one per part; groups that share nodes
  // with each other or with existing bodies are united below.
  struct Group {
    Id lead_part = 0;  // LRB, 0 if none
    std::vector<Id> parts;
  };
  std::vector<Group> groups;
  for (const auto& card : cards) {
    for (const Id pid : expand({card})) {
      const bool already_rigid = switched_.count(pid) != 0;
      const auto blk = block_of_part_.find(pid);
      const bool mat_rigid =
          blk != block_of_part_.end() &&
          with_block(state, blk->second, [](const auto& b) { return b.rigid; }) && !already_rigid;
      if ((already_rigid || mat_rigid) && card.lrb == 0) {
        notices.push_back(
            fmt::format("t = {:.6g}: part {} is rigid already; nothing to switch", time, pid));
        continue;
      }
      if (blk == block_of_part_.end()) {
        notices.push_back(
            fmt::format("t = {:.6g}: part {} has no elements; nothing to switch", time, pid));
        continue;
      }
      auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
        return card.lrb != 0 && g.lead_part == card.lrb;
      });
      if (it == groups.end()) {
        groups.push_back({card.lrb, {}});
        it = groups.end() - 1;
      }
      it->parts.push_back(pid);
      event.parts.push_back(pid);
    }
  }
  if (groups.empty()) return event;

  // Body index of a part (-1 if none): bodies list their parts.
  auto body_of_part = [&](Id pid) {
    for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
      const auto& parts = rigid.bodies[b].parts;
      if (std::find(parts.begin(), parts.end(), pid) != parts.end()) return static_cast<int>(b);
    }
    return -1;
  };

  Momenta total;  // everything this switch touches
  // Bodies made or re-defined by an earlier group of this switch: a later group that shares
  // nodes with one merges it, and its momenta are in `total` already.
  std::set<int> defined;
  std::set<int> removed;
  std::map<int, int> moved_to;
  for (auto& group : groups) {
    // Nodes of the group's parts, and the bodies they touch (merged into the result).
    std::vector<std::int32_t> nodes;
    for (const Id pid : group.parts) {
      with_block(state, block_of_part_.at(pid), [&](const auto& block) {
        nodes.insert(nodes.end(), block.conn.begin(), block.conn.end());
      });
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    std::set<int> bodies;
    int lead_body = -1;
    if (group.lead_part != 0) {
      lead_body = body_of_part(group.lead_part);
      if (lead_body < 0) {
        throw SolverError(
            fmt::format("at time {:.6g}: part {} is to be merged into the rigid "
                        "body of part {} (LRB), which is not rigid now",
                        time, group.parts.front(), group.lead_part));
      }
      bodies.insert(lead_body);
    }
    for (const Id pid : group.parts) {  // parts already in a body (merged by LRB)
      const int b = body_of_part(pid);
      if (b >= 0) bodies.insert(b);
    }
    for (const auto i : nodes) {
      if (rigid.body_of_node[i] >= 0) bodies.insert(rigid.body_of_node[i]);
    }
    for (const int b : removed) bodies.erase(b);
    for (const int b : bodies) {  // docs/flexible_bodies.md: their modes cover their own nodes
      if (rigid.bodies[b].flexible >= 0) {
        throw SolverError(fmt::format(
            "at time {:.6g}: part {} switched to rigid would merge with flexible body {} "
            "(*PART_MODES), whose modes describe its own nodes only; keep the switched part "
            "apart from the flexible body (no shared nodes, no LRB)",
            time, group.parts.front(), rigid.bodies[b].id));
      }
    }

    // A part named by *PART_MODES becomes a flexible body of its own nodes only
    // (docs/flexible_bodies.md section 6).
    Id modes_part = 0;
    for (const Id pid : group.parts) {
      if (model_.part_modes.count(pid)) modes_part = pid;
    }
    if (modes_part != 0 && !flexible_) {
      throw SolverError(
          fmt::format("at time {:.6g}: part {} has *PART_MODES but no mode data "
                      "was prepared for switching it",
                      time, modes_part));
    }
    if (modes_part != 0 && (group.parts.size() > 1 || !bodies.empty())) {
      throw SolverError(fmt::format(
          "at time {:.6g}: part {} (*PART_MODES) switched to rigid would merge with {}; its "
          "modes describe its own nodes only: keep it apart from other switched parts and "
          "rigid bodies (no shared nodes, no LRB, no part set with other parts)",
          time, modes_part,
          bodies.empty()
              ? fmt::format("part {}", group.parts.front() == modes_part ? group.parts.back()
                                                                         : group.parts.front())
              : fmt::format("rigid body {}", rigid.bodies[*bodies.begin()].id)));
    }
    std::vector<double> given;  // the nodes' velocities before the switch (modal projection)
    if (modes_part != 0) {
      for (const auto i : nodes) {
        given.push_back(state.nodes.v.x[i]);
        given.push_back(state.nodes.v.y[i]);
        given.push_back(state.nodes.v.z[i]);
      }
    }

    Momenta m;
    std::vector<rigid::MassProperties> props;
    std::vector<std::int32_t> lumped;
    std::vector<std::int32_t> all_nodes;
    for (const auto i : nodes) {
      if (rigid.body_of_node[i] >= 0) continue;  // counted with its body
      m.add_node(state, i);
      lumped.push_back(i);
    }
    // The body that stays (the lead's, else the lowest-index one touched, else a new one).
    int keep = lead_body;
    // A spot weld's body never becomes the merged body (it would lend its weld ID).
    for (const int b : bodies) {
      if (keep < 0 && !rigid.bodies[b].weld) keep = b;
    }
    const bool lead_card = keep >= 0 && rigid.bodies[keep].inertia_from_card;
    Eigen::Matrix3d physical = Eigen::Matrix3d::Identity();
    if (keep >= 0) physical = body_rotation(rigid.bodies[keep]);
    for (const int b : bodies) {
      const RigidBody& body = rigid.bodies[b];
      m.add_body(body.state);
      if (defined.count(b)) {
        Momenta counted;
        counted.add_body(body.state);
        total.p -= counted.p;
        total.h -= counted.h;
        total.kinetic -= counted.kinetic;
      }
      if (!lead_card || b == keep) props.push_back(body_properties(body.state));
      all_nodes.insert(all_nodes.end(), body.nodes.begin(), body.nodes.end());
    }
    // *DEFORMABLE_TO_RIGID_INERTIA replaces the lumped masses of its part's nodes.
    std::set<std::int32_t> card_nodes;
    for (const Id pid : group.parts) {
      const auto card = model_.switching.inertia.find(pid);
      if (card == model_.switching.inertia.end()) continue;
      if (!lead_card) props.push_back(card_properties(card->second));
      with_block(state, block_of_part_.at(pid), [&](const auto& block) {
        card_nodes.insert(block.conn.begin(), block.conn.end());
      });
    }
    std::erase_if(lumped, [&](std::int32_t i) { return card_nodes.count(i) != 0; });
    if (!lead_card && !lumped.empty()) {
      props.push_back(solver::lumped_mass_properties(lumped, state));
    }
    rigid::MassProperties combined = rigid::combine(props);
    regularise(combined);
    if (!(combined.mass > 0.0)) {
      throw SolverError(fmt::format("at time {:.6g}: part {} has no mass to make a rigid body of",
                                    time, group.parts.front()));
    }

    RigidBody* body = nullptr;
    if (keep < 0) {
      rigid.bodies.emplace_back();
      keep = static_cast<int>(rigid.bodies.size()) - 1;
      body = &rigid.bodies.back();
      body->id = *std::min_element(group.parts.begin(), group.parts.end());
    } else {
      body = &rigid.bodies[keep];
    }
    for (const int b : bodies) {
      if (b == keep) continue;
      RigidBody& other = rigid.bodies[b];
      body->parts.insert(body->parts.end(), other.parts.begin(), other.parts.end());
      if (body->state.constraints.empty()) body->state.constraints = other.state.constraints;
      // Parts switched earlier into `other` keep their rotation reference.
      for (auto& [pid, sp] : switched_) {
        if (sp.body_id == other.id) {
          sp.rotation_offset = physical.transpose() * body_rotation(other) * sp.rotation_offset;
          sp.body_id = body->id;
        }
      }
      removed.insert(b);
      moved_to[b] = keep;
    }
    for (const Id pid : group.parts) {
      if (std::find(body->parts.begin(), body->parts.end(), pid) == body->parts.end()) {
        body->parts.push_back(pid);
      }
    }
    body->inertia_from_card = lead_card || !card_nodes.empty();
    all_nodes.insert(all_nodes.end(), nodes.begin(), nodes.end());
    body->nodes = all_nodes;
    for (const auto i : all_nodes) rigid.body_of_node[i] = keep;

    // Freeze the elements: no kernel, no force, stresses kept. Q = Phi Phi_switch^T later.
    for (const Id pid : group.parts) {
      with_block(state, block_of_part_.at(pid), [&](auto& block) {
        if (!switched_.count(pid) && !block.rigid) {
          switched_[pid] = {body->id, physical.transpose(), element::frozen_strain_energy(block)};
          block.rigid = true;
          std::fill(block.force.begin(), block.force.end(), 0.0);
        }
      });
    }
    define_body(*body, combined, m, physical, model_.rigid_body_update, state);
    defined.insert(keep);
    if (modes_part != 0) flexible_->attach(modes_part, keep, given, state, rigid);
    total.p += m.p;
    total.h += m.h;
    total.kinetic += m.kinetic;
  }
  remove_bodies(rigid, removed, moved_to);
  // Bodies touched: every body now containing a switched part.
  double after = 0.0;
  std::set<const RigidBody*> counted;
  for (const Id pid : event.parts) {
    for (const auto& body : rigid.bodies) {
      if (std::find(body.parts.begin(), body.parts.end(), pid) != body.parts.end() &&
          counted.insert(&body).second) {
        after += rigid::kinetic_energy(body.state);
        if (body.flexible >= 0) after += rigid.flexible[body.flexible].kinetic_energy();
      }
    }
  }
  event.kinetic_energy_before = total.kinetic;
  event.kinetic_energy_after = after;
  event.momentum = total.p;
  event.angular_momentum = total.h;
  return event;
}

SwitchEvent PartSwitcher::to_deformable(const std::vector<model::PartSwitch>& cards, double time,
                                        State& state, RigidSystem& rigid) {
  SwitchEvent event;
  event.time = time;
  event.to_rigid = false;
  std::set<int> emptied;
  Momenta before, after_nodes;
  double after_bodies = 0.0;
  std::set<int> touched;
  for (const Id pid : expand(cards)) {
    const auto sp = switched_.find(pid);
    if (sp == switched_.end()) {
      notices.push_back(fmt::format(
          "t = {:.6g}: part {} is not rigid by switching; nothing to switch", time, pid));
      continue;
    }
    int b = -1;
    for (std::size_t k = 0; k < rigid.bodies.size(); ++k) {
      if (rigid.bodies[k].id == sp->second.body_id) b = static_cast<int>(k);
    }
    if (b < 0) throw SolverError(fmt::format("part {}: its rigid body is missing", pid));
    touched.insert(b);
    event.parts.push_back(pid);
    RigidBody& body = rigid.bodies[b];
    const PartBlock where = block_of_part_.at(pid);
    const Eigen::Matrix3d q = body_rotation(body) * sp->second.rotation_offset;
    with_block(state, where, [&](auto& block) { element::turn_frozen_state(block, q); });
    if (body.flexible >= 0) {  // + the modal displacement's stress (docs/flexible_bodies.md)
      // Flexible bodies are made of hexahedra only (solver::check_structural_support).
      if (where.family != PartBlock::Family::kHex) {
        throw SolverError(fmt::format("part {}: a flexible body of shells or beams", pid));
      }
      const auto& f = rigid.flexible[body.flexible];
      event.modal_elastic_released += f.elastic_energy();
      event.strain_energy_restored += flexible_->restore_modal_stresses(
          body, f, state.hex_blocks[static_cast<std::size_t>(where.index)], state);
    }
    with_block(state, where, [](auto& block) { block.rigid = false; });
    std::erase(body.parts, pid);
    switched_.erase(sp);
  }
  if (event.parts.empty()) return event;

  for (const int b : touched) {
    RigidBody& body = rigid.bodies[b];
    before.add_body(body.state);
    if (body.flexible >= 0) {
      // A flexible body is one part (to_rigid): all its nodes are released with the rigid and
      // modal velocity field, its angular momentum exact.
      before.kinetic += rigid.flexible[body.flexible].kinetic_energy();
      flexible_->release_velocities(b, state.dt_prev, state, rigid);
      for (const auto i : body.nodes) {
        rigid.body_of_node[i] = -1;
        after_nodes.add_node(state, i);
      }
      emptied.insert(b);
      continue;
    }
    // Nodes still held by a part of the body stay; the rest are released with the body's
    // velocity field (v_c + w x r at x^n, the field the nodes already carry).
    std::set<std::int32_t> keep;
    for (const Id pid : body.parts) {
      const auto blk = block_of_part_.find(pid);
      if (blk != block_of_part_.end()) {
        with_block(state, blk->second,
                   [&](const auto& block) { keep.insert(block.conn.begin(), block.conn.end()); });
      }
    }
    const rigid::RigidBodyState s = body.state;
    // The rigid field v + w x (x - c) the nodes get carries the body's momenta P and
    // H = x_c x P + L exactly at the nodes' present positions x^n (what the next steps conserve:
    // sum m x^n x v + I w): fitted to the nodes' masses and rotary inertias as at the switch to
    // rigid. The body's own w^{n+1/2} (the free rotation from R^n to R^{n+1}) differs from
    // J^-1 L by O(dt) when it precesses, and a body whose nodes move by the linear update drifts
    // from its attitude by O((w dt)^2) per step: either would change H. A body with an inertia
    // card (its mass is not its nodes') gives its own J(R^n)^-1 L about its centre.
    Eigen::Vector3d v = s.velocity, c = s.centre;
    Eigen::Vector3d w = rigid::global_inertia(s).ldlt().solve(s.angular_momentum);
    if (!body.inertia_from_card) {
      rigid::MassProperties all = solver::lumped_mass_properties(body.nodes, state);
      regularise(all);
      if (all.mass > 0.0 && std::abs(all.mass - s.mass) <= 1e-12 * s.mass) {
        const Eigen::Vector3d p = s.mass * s.velocity;
        const Eigen::Vector3d h = s.centre.cross(p) + s.angular_momentum;
        v = p / all.mass;
        c = all.centre;
        w = all.inertia.ldlt().solve(h - c.cross(p));
      }
    }
    std::vector<std::int32_t> released, kept;
    for (const auto i : body.nodes) (keep.count(i) ? kept : released).push_back(i);
    auto& nodes = state.nodes;
    rigid::rigid_node_velocities(v, w, c, released, nodes.x.x.data(), nodes.x.y.data(),
                                 nodes.x.z.data(), nodes.v.x.data(), nodes.v.y.data(),
                                 nodes.v.z.data());
    set_node_spins(released, w, state);
    for (const auto i : released) {
      rigid.body_of_node[i] = -1;
      after_nodes.add_node(state, i);
    }
    if (kept.empty()) {
      emptied.insert(b);
      continue;
    }
    // The rest of the body keeps its velocity field (and its physical rotation).
    const Eigen::Matrix3d physical = body_rotation(body);
    body.nodes = kept;
    rigid::MassProperties props;
    if (body.inertia_from_card) {
      props = body_properties(s);  // the card's properties stay with the lead
    } else {
      props = solver::lumped_mass_properties(kept, state);
      regularise(props);
    }
    Momenta field;  // the velocity field carried by the remaining mass
    field.p = props.mass * (v + w.cross(props.centre - c));
    field.h = props.centre.cross(field.p) + props.inertia * w;
    define_body(body, props, field, physical, model_.rigid_body_update, state);
    after_bodies += rigid::kinetic_energy(body.state);
  }
  remove_bodies(rigid, emptied, {});
  event.kinetic_energy_before = before.kinetic;
  event.kinetic_energy_after = after_nodes.kinetic + after_bodies;
  event.momentum = before.p;
  event.angular_momentum = before.h;
  return event;
}

double PartSwitcher::delete_nodal_rigid_bodies(double time, State& state, RigidSystem& rigid) {
  std::set<int> gone;
  for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
    RigidBody& body = rigid.bodies[b];
    // Nodal bodies that shared nodes with a switched part were merged into its body already
    // (the manual: "for all values of NRBF"); a nodal body holding switched parts stays.
    if (!body.nodal || body.weld || !body.parts.empty()) continue;
    auto& nodes = state.nodes;
    rigid::rigid_node_velocities(body.state.velocity, body.state.angular_velocity,
                                 body.state.centre, body.nodes, nodes.x.x.data(), nodes.x.y.data(),
                                 nodes.x.z.data(), nodes.v.x.data(), nodes.v.y.data(),
                                 nodes.v.z.data());
    for (const auto i : body.nodes) rigid.body_of_node[i] = -1;
    notices.push_back(
        fmt::format("t = {:.6g}: nodal rigid body {} deleted (NRBF = 1)", time, body.id));
    deleted_nodal_.push_back(body);
    gone.insert(static_cast<int>(b));
  }
  remove_bodies(rigid, gone, {});
  return 0.0;  // the nodes keep the field: no kinetic energy changes
}

double PartSwitcher::activate_nodal_rigid_bodies(double time, State& state, RigidSystem& rigid) {
  double change = 0.0;
  for (RigidBody& body : deleted_nodal_) {
    Momenta m;
    bool free = true;
    for (const auto i : body.nodes) free = free && rigid.body_of_node[i] < 0;
    if (!free) {
      notices.push_back(
          fmt::format("t = {:.6g}: nodal rigid body {} not activated (NRBF = 2): "
                      "a node of it belongs to another rigid body now",
                      time, body.id));
      continue;
    }
    for (const auto i : body.nodes) m.add_node(state, i);
    rigid::MassProperties props;
    if (body.inertia_from_card) {
      // The card's mass and tensor travel with the nodes' centroid (turned as the body was).
      props = body_properties(body.state);
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (const auto i : body.nodes) centroid += node_position(state, i);
      props.centre = centroid / static_cast<double>(body.nodes.size());
    } else {
      props = solver::lumped_mass_properties(body.nodes, state);
    }
    const int index = static_cast<int>(rigid.bodies.size());
    rigid.bodies.push_back(body);
    RigidBody& fresh = rigid.bodies.back();
    define_body(fresh, props, m, body_rotation(body), model_.rigid_body_update, state);
    for (const auto i : fresh.nodes) rigid.body_of_node[i] = index;
    change += rigid::kinetic_energy(fresh.state) - m.kinetic;
    notices.push_back(
        fmt::format("t = {:.6g}: nodal rigid body {} activated (NRBF = 2)", time, body.id));
  }
  std::erase_if(deleted_nodal_, [&](const RigidBody& b) {
    return std::any_of(rigid.bodies.begin(), rigid.bodies.end(),
                       [&](const RigidBody& r) { return r.nodal && !r.weld && r.id == b.id; });
  });
  return change;
}

AutomaticSwitching::AutomaticSwitching(const std::vector<model::AutomaticSwitchSet>& sets)
    : sets_(sets), state_(sets.size()), released_parts_(sets.size()) {
  for (std::size_t k = 0; k < sets.size(); ++k) {
    state_[k].armed = sets[k].paired != -1;
    for (const auto& c : sets[k].to_deformable) released_parts_[k].push_back(c.pid);
  }
}

void AutomaticSwitching::due(double t, const SwitchQueries& queries, std::vector<int>& out) const {
  out.clear();
  if (t < blocked_until_) return;
  for (std::size_t k = 0; k < sets_.size(); ++k) {
    const auto& set = sets_[k];
    const auto& st = state_[k];
    if (!st.armed) continue;
    bool fire = false;
    if (set.code == 5) {
      fire = queries.sensor_triggered && queries.sensor_triggered(set.swset);
    } else if (t >= set.time1 && t <= set.time2) {
      if (set.code == 0) {
        fire = !st.time_used;
      } else if (set.code == 1 || set.code == 3) {
        const double force = queries.wall_force ? queries.wall_force(set.entno) : -1.0;
        if (force < 0.0) {
          throw SolverError(
              fmt::format("switch set {}: rigid wall {} does not exist", set.swset, set.entno));
        }
        if (set.code == 1) {
          fire = force == 0.0;
        } else {
          fire = force > 0.0 ||
                 (set.offset > 0.0 && queries.wall_within_offset &&
                  queries.wall_within_offset(set.entno, set.offset, released_parts_[k]));
        }
      } else if (set.code == 2 || set.code == 4) {
        const double force = queries.contact_force ? queries.contact_force(set.entno) : -1.0;
        if (force < 0.0) {
          throw SolverError(
              fmt::format("switch set {}: contact {} does not exist", set.swset, set.entno));
        }
        if (set.code == 2) {
          fire = force == 0.0;
        } else {  // OFFSET: the released parts come within OFFSET of the other side
          fire = force > 0.0 ||
                 (set.offset > 0.0 && queries.contact_within_offset &&
                  queries.contact_within_offset(set.entno, set.offset, released_parts_[k]));
        }
      }
    }
    if (fire) out.push_back(static_cast<int>(k));
  }
}

void AutomaticSwitching::fired(int k, double t) {
  const auto& set = sets_[k];
  auto& st = state_[k];
  ++st.fired;
  st.time_used = true;
  st.armed = false;  // unpaired sets switch once
  if (set.paired != 0) {
    for (std::size_t j = 0; j < sets_.size(); ++j) {
      if (sets_[j].swset == set.relsw) state_[j].armed = true;
    }
  }
  blocked_until_ = std::max(blocked_until_, t + set.time3);
}

}  // namespace rf::switching
