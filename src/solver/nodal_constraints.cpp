#include "solver/nodal_constraints.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "model/error.hpp"
#include "model/error_context.hpp"
#include "solver/boundary.hpp"

namespace rf::solver {

namespace {

Eigen::Vector3d position(const NodalState& nodes, std::int32_t i) {
  return {nodes.x.x[i], nodes.x.y[i], nodes.x.z[i]};
}

// Index of the body of weld `w` while it acts (-1 when its nodes move with no body of its own).
int body_of_weld(const SpotWeldState& w, const RigidSystem& rigid) {
  if (rigid.body_of_node.empty()) return -1;
  const int b = rigid.body_of_node[w.n1];
  if (b < 0) return -1;
  const RigidBody& body = rigid.bodies[b];
  return body.weld && body.id == w.id ? b : -1;
}

}  // namespace

NodalConstraints build_nodal_constraints(const model::Model& model, const NodeIndex& node_index,
                                         const State& state, const RigidSystem& rigid) {
  NodalConstraints out;
  for (const auto& weld : model.spot_welds) {
    SpotWeldState w;
    w.id = weld.id;
    w.n1 = node_index.at(weld.n1, weld.where, "N1");
    w.n2 = node_index.at(weld.n2, weld.where, "N2");
    w.sn = weld.sn;
    w.ss = weld.ss;
    w.n = weld.n;
    w.m = weld.m;
    w.tf = weld.tf;
    out.welds.push_back(w);
  }
  static constexpr std::array<std::array<bool, 3>, 8> kAxes = {{{false, false, false},
                                                                {true, false, false},
                                                                {false, true, false},
                                                                {false, false, true},
                                                                {true, true, false},
                                                                {false, true, true},
                                                                {true, false, true},
                                                                {true, true, true}}};
  for (const auto& c : model.node_set_constraints) {
    NodeSetTie tie;
    tie.id = c.id;
    tie.axes = kAxes[c.dof];
    tie.tf = c.tf;
    tie.nodes =
        resolve_nodes(model, node_index, state, model::Target::NodeSet, c.nsid, c.where, "NSID");
    std::sort(tie.nodes.begin(), tie.nodes.end());
    tie.nodes.erase(std::unique(tie.nodes.begin(), tie.nodes.end()), tie.nodes.end());
    if (tie.nodes.size() < 2) {
      throw InputError(model::context_of(c.where, "NSID"),
                       fmt::format("constrained node set {}: node set {} has {} node; the "
                                   "constraint needs at least two",
                                   c.id, c.nsid, tie.nodes.size()));
    }
    for (const auto i : tie.nodes) {
      if (rigid.is_rigid(i)) {
        const RigidBody& body = rigid.bodies[rigid.body_of_node[i]];
        throw InputError(
            model::context_of(c.where, "NSID"),
            fmt::format("constrained node set {}: node {} moves with {} {}; a "
                        "constrained node set ties deformable nodes only",
                        c.id, state.nodes.id[i],
                        body.weld ? "spot weld" : (body.nodal ? "nodal rigid body" : "rigid body"),
                        body.id));
      }
      if (!(state.nodes.mass[i] > 0.0)) {
        throw InputError(model::context_of(c.where, "NSID"),
                         fmt::format("constrained node set {}: node {} has no mass (it belongs "
                                     "to no element)",
                                     c.id, state.nodes.id[i]));
      }
    }
    out.ties.push_back(std::move(tie));
  }
  return out;
}

void apply_node_set_ties(NodalConstraints& constraints, const RigidSystem& rigid, State& state,
                         double t) {
  NodalState& nodes = state.nodes;
  double* v[3] = {nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
  for (NodeSetTie& tie : constraints.ties) {
    if (tie.status != ConstraintStatus::kActive) continue;
    if (t >= tie.tf) {
      tie.status = ConstraintStatus::kFailed;
      tie.failure_time = t;
      constraints.notices.push_back(
          fmt::format("t = {:.6g}: constrained node set {} failed (TF = {:g})", t, tie.id, tie.tf));
      continue;
    }
    // Nodes switched into a rigid body move with it; the tie does not act on them.
    double mass = 0.0;
    double p[3] = {0.0, 0.0, 0.0};
    for (const auto i : tie.nodes) {
      if (rigid.is_rigid(i)) continue;
      mass += nodes.mass[i];
      for (int k = 0; k < 3; ++k) p[k] += nodes.mass[i] * v[k][i];
    }
    if (!(mass > 0.0)) continue;
    for (int k = 0; k < 3; ++k) {
      if (!tie.axes[k]) continue;
      const double common = p[k] / mass;
      for (const auto i : tie.nodes) {
        if (!rigid.is_rigid(i)) v[k][i] = common;
      }
    }
  }
}

int check_spot_welds(NodalConstraints& constraints, RigidSystem& rigid, const State& state,
                     const Vec3Array& v_previous, double dt_avg, double t) {
  const NodalState& nodes = state.nodes;
  std::set<int> gone;
  for (SpotWeldState& w : constraints.welds) {
    if (w.status != ConstraintStatus::kActive) continue;
    const int b = body_of_weld(w, rigid);
    if (b < 0) {  // merged into a body made by part switching (docs/switching.md)
      w.status = ConstraintStatus::kMerged;
      w.normal_force = w.shear_force = 0.0;
      constraints.notices.push_back(fmt::format(
          "t = {:.6g}: spot weld {} now moves inside rigid body {} (part switching)", t, w.id,
          rigid.body_of_node.empty() || rigid.body_of_node[w.n1] < 0
              ? model::Id{0}
              : rigid.bodies[rigid.body_of_node[w.n1]].id));
      continue;
    }
    // The force the weld exerts on each node: what moved the node beyond its nodal forces.
    auto constraint_force = [&](std::int32_t i) {
      const double m = nodes.mass[i];
      return Eigen::Vector3d(
          m * (nodes.v.x[i] - v_previous.x[i]) / dt_avg - (nodes.f_ext.x[i] - nodes.f_int.x[i]),
          m * (nodes.v.y[i] - v_previous.y[i]) / dt_avg - (nodes.f_ext.y[i] - nodes.f_int.y[i]),
          m * (nodes.v.z[i] - v_previous.z[i]) / dt_avg - (nodes.f_ext.z[i] - nodes.f_int.z[i]));
    };
    if (dt_avg > 0.0) {
      // Pull on N1 towards N2 (and its opposite on N2), averaged over the two ends.
      const Eigen::Vector3d f = 0.5 * (constraint_force(w.n1) - constraint_force(w.n2));
      const Eigen::Vector3d axis = position(nodes, w.n2) - position(nodes, w.n1);
      const double length = axis.norm();
      const Eigen::Vector3d e = length > 0.0 ? Eigen::Vector3d(axis / length) : axis;
      w.normal_force = f.dot(e);
      w.shear_force = (f - w.normal_force * e).norm();
    }
    // Only tension loads the weld in the normal direction (a pressed weld holds).
    double criterion = 0.0;
    if (w.sn > 0.0) criterion += std::pow(std::max(w.normal_force, 0.0) / w.sn, w.n);
    if (w.ss > 0.0) criterion += std::pow(w.shear_force / w.ss, w.m);
    const bool by_force = criterion >= 1.0;
    if (!by_force && !(t >= w.tf)) continue;
    w.status = ConstraintStatus::kFailed;
    w.failure_time = t;
    constraints.notices.push_back(
        by_force
            ? fmt::format("t = {:.6g}: spot weld {} failed: normal force {:.6g}, shear "
                          "force {:.6g}, criterion {:.6g} >= 1",
                          t, w.id, w.normal_force, w.shear_force, criterion)
            : fmt::format("t = {:.6g}: spot weld {} failed at its time TF = {:g}", t, w.id, w.tf));
    for (const auto i : rigid.bodies[b].nodes) rigid.body_of_node[i] = -1;
    gone.insert(b);
  }
  remove_rigid_bodies(rigid, gone);
  return static_cast<int>(gone.size());
}

void delete_nodal_constraints(NodalConstraints& constraints, RigidSystem& rigid, double t) {
  std::set<int> gone;
  for (SpotWeldState& w : constraints.welds) {
    if (w.status != ConstraintStatus::kActive) continue;
    const int b = body_of_weld(w, rigid);
    if (b < 0) continue;  // merged: check_spot_welds marks it
    // The nodes keep the velocities the weld gave them: no kinetic energy changes.
    for (const auto i : rigid.bodies[b].nodes) rigid.body_of_node[i] = -1;
    gone.insert(b);
    w.status = ConstraintStatus::kDeleted;
    w.normal_force = w.shear_force = 0.0;
    constraints.notices.push_back(
        fmt::format("t = {:.6g}: spot weld {} deleted (NCSF = 1)", t, w.id));
  }
  remove_rigid_bodies(rigid, gone);
  for (NodeSetTie& tie : constraints.ties) {
    if (tie.status != ConstraintStatus::kActive) continue;
    tie.status = ConstraintStatus::kDeleted;
    constraints.notices.push_back(
        fmt::format("t = {:.6g}: constrained node set {} deleted (NCSF = 1)", t, tie.id));
  }
}

double activate_nodal_constraints(NodalConstraints& constraints, RigidSystem& rigid, State& state,
                                  double t) {
  NodalState& nodes = state.nodes;
  double change = 0.0;
  for (SpotWeldState& w : constraints.welds) {
    if (w.status != ConstraintStatus::kDeleted && w.status != ConstraintStatus::kMerged) continue;
    if (rigid.is_rigid(w.n1) || rigid.is_rigid(w.n2)) {
      if (w.status == ConstraintStatus::kDeleted) {
        constraints.notices.push_back(fmt::format(
            "t = {:.6g}: spot weld {} not activated (NCSF = 2): a node of it moves with a rigid "
            "body",
            t, w.id));
      }
      continue;
    }
    // The weld starts from the current configuration: a rigid body of its two nodes as they
    // are now, carrying their momenta exactly (the relative motion's kinetic energy is lost).
    const rigid::MassProperties props = spot_weld_properties(w.n1, w.n2, state);
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), h = Eigen::Vector3d::Zero();
    double kinetic = 0.0;
    for (const std::int32_t i : {w.n1, w.n2}) {
      const Eigen::Vector3d v(nodes.v.x[i], nodes.v.y[i], nodes.v.z[i]);
      p += nodes.mass[i] * v;
      h += position(nodes, i).cross(nodes.mass[i] * v);
      kinetic += 0.5 * nodes.mass[i] * v.squaredNorm();
    }
    RigidBody body;
    body.id = w.id;
    body.nodal = true;
    body.weld = true;
    body.nodes = {std::min(w.n1, w.n2), std::max(w.n1, w.n2)};
    body.state = rigid::make_rigid_body(props);
    const Eigen::Vector3d vc = p / props.mass;
    const Eigen::Vector3d omega = props.inertia.ldlt().solve(h - props.centre.cross(p));
    rigid::set_velocity(body.state, vc, omega);
    body.state.previous_centre = body.state.centre;
    body.state.previous_rotation = body.state.rotation;
    body.initial_rotation = body.state.rotation;
    body.velocity_before = body.mid_velocity = vc;
    body.angular_velocity_before = body.mid_angular_velocity = omega;
    body.body_coordinates = rigid::body_coordinates(body.state, body.nodes, nodes.x.x.data(),
                                                    nodes.x.y.data(), nodes.x.z.data());
    body.shares_nodes = true;                // a weld joins nodes of elements
    body.update = NodeUpdate::kCurvilinear;  // as build_rigid_system does for welds
    rigid::rigid_node_velocities(vc, omega, body.state.centre, body.nodes, nodes.x.x.data(),
                                 nodes.x.y.data(), nodes.x.z.data(), nodes.v.x.data(),
                                 nodes.v.y.data(), nodes.v.z.data());
    if (rigid.body_of_node.empty()) rigid.body_of_node.assign(nodes.size(), -1);
    const int index = static_cast<int>(rigid.bodies.size());
    rigid.bodies.push_back(std::move(body));
    rigid.body_of_node[w.n1] = rigid.body_of_node[w.n2] = index;
    change += rigid::kinetic_energy(rigid.bodies.back().state) - kinetic;
    w.status = ConstraintStatus::kActive;
    constraints.notices.push_back(
        fmt::format("t = {:.6g}: spot weld {} activated (NCSF = 2)", t, w.id));
  }
  for (NodeSetTie& tie : constraints.ties) {
    if (tie.status != ConstraintStatus::kDeleted) continue;
    // The common velocity is the tied nodes' mass-weighted mean: momentum exact.
    double mass = 0.0, before = 0.0, after = 0.0;
    double p[3] = {0.0, 0.0, 0.0};
    double* v[3] = {nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
    for (const auto i : tie.nodes) {
      if (rigid.is_rigid(i)) continue;
      mass += nodes.mass[i];
      for (int k = 0; k < 3; ++k) {
        p[k] += nodes.mass[i] * v[k][i];
        before += 0.5 * nodes.mass[i] * v[k][i] * v[k][i];
      }
    }
    for (const auto i : tie.nodes) {
      if (rigid.is_rigid(i)) continue;
      for (int k = 0; k < 3; ++k) {
        if (tie.axes[k] && mass > 0.0) v[k][i] = p[k] / mass;
        after += 0.5 * nodes.mass[i] * v[k][i] * v[k][i];
      }
    }
    change += after - before;
    tie.status = ConstraintStatus::kActive;
    constraints.notices.push_back(
        fmt::format("t = {:.6g}: constrained node set {} activated (NCSF = 2)", t, tie.id));
  }
  return change;
}

}  // namespace rf::solver
