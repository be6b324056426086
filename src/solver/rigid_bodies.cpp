#include "solver/rigid_bodies.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "model/error.hpp"
#include "model/error_context.hpp"
#include "solver/flexible_bodies.hpp"

namespace rf::solver {

namespace {

using model::context_of;
using model::Id;

Eigen::Vector3d vec(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

rigid::MassProperties card_properties(const model::RigidInertia& in) {
  rigid::MassProperties p;
  p.mass = in.tm;
  p.centre = vec(in.xc);
  const auto& c = in.inertia;  // IXX IXY IXZ IYY IYZ IZZ
  if (in.ircs == 0) {
    // Tensor components as the manual defines them (products of inertia are tensor entries).
    p.inertia << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  } else {
    // Principal moments IXX, IYY, IZZ about the resolved principal directions (rows).
    const double moments[3] = {c[0], c[3], c[5]};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d axis = vec(in.principal_axes[k]);
      p.inertia += moments[k] * axis * axis.transpose();
    }
  }
  return p;
}

// Decodes *NODE-style constraint codes 0..7 (1 x, 2 y, 3 z, 4 xy, 5 yz, 6 zx, 7 xyz).
std::array<bool, 3> decode_code(double code) {
  static constexpr std::array<std::array<bool, 3>, 8> kAxes = {{{false, false, false},
                                                                {true, false, false},
                                                                {false, true, false},
                                                                {false, false, true},
                                                                {true, true, false},
                                                                {false, true, true},
                                                                {true, false, true},
                                                                {true, true, true}}};
  const int c = static_cast<int>(std::lround(code));
  return (c >= 0 && c <= 7) ? kAxes[c] : kAxes[0];
}

// CMO 1: global codes; CMO -1: flags in the axes of a coordinate system.
void add_cmo_constraints(const model::Model& model, double cmo, double con1, double con2,
                         Id cmo_cid, const std::array<bool, 6>& local_fix,
                         rigid::VelocityConstraints& constraints) {
  if (cmo == 1.0) {
    constraints.fix_global_translation(decode_code(con1));
    constraints.fix_global_rotation(decode_code(con2));
  } else if (cmo == -1.0) {
    const auto& axes = model.coordinate_systems.at(cmo_cid).axes;
    for (int k = 0; k < 3; ++k) {
      if (local_fix[k]) constraints.add_translation(vec(axes[k]), 0.0);
      if (local_fix[3 + k]) constraints.add_rotation(vec(axes[k]), 0.0);
    }
  }
}

// Builds the body's state from mass properties; line-like bodies (all mass on one axis, e.g.
// a two-node nodal rigid body) get a small isotropic inertia so that J^-1 exists: no force on
// the axis has a moment about it, so the regularisation changes no motion of the nodes.
rigid::RigidBodyState make_body(rigid::MassProperties props, const RigidBody& body,
                                const model::SourceLocation& where, const char* field,
                                std::vector<model::Warning>& warnings) {
  const std::string name = fmt::format(
      "{} {}", body.weld ? "spot weld" : (body.nodal ? "nodal rigid body" : "rigid body"), body.id);
  if (!(props.mass > 0.0)) {
    throw InputError(context_of(where, field),
                     fmt::format("{} has no mass (mass {:g}): its nodes carry no element mass; "
                                 "give it *PART_INERTIA or connect it to elements",
                                 name, props.mass));
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 *
                                                       (props.inertia + props.inertia.transpose()));
  const Eigen::Vector3d moments = eigen.eigenvalues();
  if (!body.inertia_from_card) {
    const double largest = moments.maxCoeff();
    if (!(largest > 0.0)) {
      throw InputError(context_of(where, field),
                       fmt::format("{} has all its mass at one point, so its inertia is zero; "
                                   "give it *PART_INERTIA (or _INERTIA)",
                                   name));
    }
    if (!body.weld && moments.minCoeff() < 1e-6 * largest) {  // welds: spot_weld_properties
      props.inertia += 1e-6 * largest * Eigen::Matrix3d::Identity();
      warnings.push_back({where, fmt::format("{}: its nodes lie on a line; a principal moment "
                                             "of {:.3g} was added about every axis",
                                             name, 1e-6 * largest)});
    }
  } else if (!(moments.minCoeff() > 0.0)) {
    throw InputError(context_of(where, "IXX"),
                     fmt::format("{}: the inertia tensor is not positive definite (principal "
                                 "moments {:.4g}, {:.4g}, {:.4g})",
                                 name, moments[0], moments[1], moments[2]));
  }
  try {
    return rigid::make_rigid_body(props);
  } catch (const std::invalid_argument& e) {
    throw InputError(context_of(where, field), fmt::format("{}: {}", name, e.what()));
  }
}

}  // namespace

RigidSystem build_rigid_system(const model::Model& model, const NodeIndex& node_index,
                               const State& state) {
  RigidSystem rigid;
  const std::size_t n = state.nodes.size();
  const NodalState& nodes = state.nodes;

  // Lead part of every rigid part (merges were checked for cycles by the reader).
  std::map<Id, const model::RigidBodyMerge*> merge_of;
  for (const auto& merge : model.rigid_body_merges) merge_of[merge.constrained] = &merge;
  auto lead_of = [&](Id pid) {
    for (auto it = merge_of.find(pid); it != merge_of.end(); it = merge_of.find(pid)) {
      pid = it->second->lead;
    }
    return pid;
  };

  // Bodies from rigid parts, in ascending lead-part ID.
  std::map<Id, std::vector<Id>> parts_of_lead;
  for (const auto& [pid, part] : model.parts) {
    const auto mat = model.materials.find(part.mid);
    if (mat == model.materials.end() || mat->second.kind != model::MaterialKind::Rigid) continue;
    parts_of_lead[lead_of(pid)].push_back(pid);
  }
  // Connectivity of each part, whatever its element family.
  std::map<Id, const std::vector<std::int32_t>*> block_of_part;
  std::vector<std::uint8_t> deformable_node(n, 0);
  auto collect = [&](const auto& blocks) {
    for (const auto& block : blocks) {
      block_of_part[block.part_id] = &block.conn;
      if (!block.rigid) {
        for (const std::int32_t i : block.conn) deformable_node[i] = 1;
      }
    }
  };
  collect(state.hex_blocks);
  collect(state.shell_blocks);
  collect(state.beam_blocks);

  rigid.body_of_node.assign(n, -1);
  auto kind_name = [](const RigidBody& b) {
    return b.weld ? "spot weld" : (b.nodal ? "nodal rigid body" : "rigid body");
  };
  // Where each body was defined (errors and warnings).
  std::vector<model::SourceLocation> where_of;
  auto claim = [&](std::int32_t node, int body, const model::SourceLocation& where,
                   const char* field) {
    int& owner = rigid.body_of_node[node];
    if (owner == body) return;
    if (owner >= 0) {
      const RigidBody& other = rigid.bodies[owner];
      const RigidBody& self = rigid.bodies[body];
      throw InputError(
          context_of(where, field),
          fmt::format("node {} belongs to {} {} and to {} {}; a node can move with one rigid "
                      "body only (merge the bodies with *CONSTRAINED_RIGID_BODIES)",
                      nodes.id[node], kind_name(other), other.id, kind_name(self), self.id));
    }
    owner = body;
  };

  // Per body: which mass contributions to include.
  struct MassPlan {
    std::vector<rigid::MassProperties> cards;
    std::vector<std::int32_t> lumped_nodes;
  };
  std::vector<MassPlan> plans;

  for (const auto& [lead, parts] : parts_of_lead) {
    RigidBody body;
    body.id = lead;
    body.parts.push_back(lead);
    for (const Id p : parts) {
      if (p != lead) body.parts.push_back(p);
    }
    const int index = static_cast<int>(rigid.bodies.size());
    const model::Part& lead_part = model.parts.at(lead);
    rigid.bodies.push_back(std::move(body));
    where_of.push_back(lead_part.where);
    plans.emplace_back();
    RigidBody& b = rigid.bodies.back();
    MassPlan& plan = plans.back();
    const bool lead_card = lead_part.inertia.has_value();
    std::set<std::int32_t> card_nodes;  // nodes whose mass a card accounts for
    for (const Id p : b.parts) {
      const model::Part& part = model.parts.at(p);
      const auto blk = block_of_part.find(p);
      std::vector<std::int32_t> part_nodes;
      if (blk != block_of_part.end()) part_nodes = *blk->second;
      std::sort(part_nodes.begin(), part_nodes.end());
      part_nodes.erase(std::unique(part_nodes.begin(), part_nodes.end()), part_nodes.end());
      for (const auto i : part_nodes) claim(i, index, part.where, "PID");
      const bool merged_with_update = p != lead && merge_of.at(p)->iflag == 1;
      const bool counted = p == lead || !lead_card || merged_with_update;
      if (part.inertia) {
        b.inertia_from_card = true;
        if (counted) plan.cards.push_back(card_properties(*part.inertia));
        card_nodes.insert(part_nodes.begin(), part_nodes.end());
      } else if (counted) {
        plan.lumped_nodes.insert(plan.lumped_nodes.end(), part_nodes.begin(), part_nodes.end());
      }
    }
    for (const auto& extra : model.extra_nodes) {
      if (lead_of(extra.pid) != lead) continue;
      const auto extra_nodes =
          resolve_nodes(model, node_index, state, extra.target, extra.id, extra.where,
                        extra.target == model::Target::Node ? "NID" : "NSID");
      for (const auto i : extra_nodes) claim(i, index, extra.where, "NID");
      if (!lead_card || extra.iflag == 1) {
        plan.lumped_nodes.insert(plan.lumped_nodes.end(), extra_nodes.begin(), extra_nodes.end());
      }
    }
    std::sort(plan.lumped_nodes.begin(), plan.lumped_nodes.end());
    plan.lumped_nodes.erase(std::unique(plan.lumped_nodes.begin(), plan.lumped_nodes.end()),
                            plan.lumped_nodes.end());
    std::erase_if(plan.lumped_nodes, [&](std::int32_t i) { return card_nodes.count(i) != 0; });
  }

  for (const auto& [pid, nrb] : model.nodal_rigid_bodies) {
    RigidBody body;
    body.id = pid;
    body.nodal = true;
    const int index = static_cast<int>(rigid.bodies.size());
    rigid.bodies.push_back(std::move(body));
    where_of.push_back(nrb.where);
    plans.emplace_back();
    auto members = resolve_nodes(model, node_index, state, model::Target::NodeSet, nrb.nsid,
                                 nrb.where, "NSID");
    if (nrb.pnode != 0) {
      members.push_back(node_index.at(std::abs(nrb.pnode), nrb.where, "PNODE"));
    }
    for (const auto i : members) claim(i, index, nrb.where, "NSID");
    RigidBody& b = rigid.bodies.back();
    if (nrb.inertia) {
      b.inertia_from_card = true;
      plans.back().cards.push_back(card_properties(*nrb.inertia));
    } else {
      plans.back().lumped_nodes = members;
    }
  }

  // Spot welds: two-node nodal rigid bodies (docs/theory.md "Spot welds"). The body carries the
  // lumped masses of its two nodes and, for nodes with rotations, their rotary inertia.
  for (const auto& weld : model.spot_welds) {
    RigidBody body;
    body.id = weld.id;
    body.nodal = true;
    body.weld = true;
    const int index = static_cast<int>(rigid.bodies.size());
    const std::int32_t a = node_index.at(weld.n1, weld.where, "N1");
    const std::int32_t c = node_index.at(weld.n2, weld.where, "N2");
    const Eigen::Vector3d xa(nodes.x.x[a], nodes.x.y[a], nodes.x.z[a]);
    const Eigen::Vector3d xc(nodes.x.x[c], nodes.x.y[c], nodes.x.z[c]);
    const double scale = std::max({xa.norm(), xc.norm(), 1e-300});
    if (!((xa - xc).norm() > 1e-9 * scale)) {
      throw InputError(context_of(weld.where, "N2"),
                       fmt::format("spot weld {}: nodes {} and {} coincide; a spot weld joins two "
                                   "non-coincident nodes (its normal is the line between "
                                   "them); merge coincident nodes or use *CONSTRAINED_NODE_SET",
                                   weld.id, weld.n1, weld.n2));
    }
    for (const auto& [i, field] : {std::pair{a, "N1"}, std::pair{c, "N2"}}) {
      if (!(nodes.mass[i] > 0.0)) {
        throw InputError(context_of(weld.where, field),
                         fmt::format("spot weld {}: node {} has no mass (it belongs to no "
                                     "element); a spot weld joins nodes of elements",
                                     weld.id, nodes.id[i]));
      }
    }
    rigid.bodies.push_back(std::move(body));
    where_of.push_back(weld.where);
    plans.emplace_back();
    claim(a, index, weld.where, "N1");
    claim(c, index, weld.where, "N2");
    plans.back().cards.push_back(spot_weld_properties(a, c, state));
  }

  // Node lists, mass properties, constraints, update mode.
  for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
    RigidBody& body = rigid.bodies[b];
    for (std::size_t i = 0; i < n; ++i) {
      if (rigid.body_of_node[i] == static_cast<int>(b)) {
        body.nodes.push_back(static_cast<std::int32_t>(i));
        if (deformable_node[i]) body.shares_nodes = true;
      }
    }
    auto parts = plans[b].cards;
    if (!plans[b].lumped_nodes.empty()) {
      double lumped_mass = 0.0;
      for (const auto i : plans[b].lumped_nodes) lumped_mass += nodes.mass[i];
      if (lumped_mass > 0.0) {
        parts.push_back(rigid::mass_properties(plans[b].lumped_nodes, nodes.mass.data(),
                                               nodes.x.x.data(), nodes.x.y.data(),
                                               nodes.x.z.data()));
      }
    }

    body.state = make_body(rigid::combine(parts), body, where_of[b], body.nodal ? "NSID" : "PID",
                           rigid.warnings);
    body.initial_rotation = body.state.rotation;
    body.body_coordinates = rigid::body_coordinates(body.state, body.nodes, nodes.x.x.data(),
                                                    nodes.x.y.data(), nodes.x.z.data());
    // Type 0 also goes linear for bodies in contact with deformable parts (contact issue).
    const int type = model.rigid_body_update;
    body.update = (type != 2 && body.shares_nodes) ? NodeUpdate::kLinear : NodeUpdate::kCurvilinear;
    // A spot weld's nodes stay exactly on its line (x_c + R X_i), so that no nodal force has a
    // moment about the line, whose moment of inertia is only the regularisation: the linear
    // update lets them drift off it by O((w dt)^2) and that moment would spin the weld up.
    if (body.weld) body.update = NodeUpdate::kCurvilinear;
    auto axes_of_system = [&](Id cid) {
      const auto& rows = model.coordinate_systems.at(cid).axes;
      Eigen::Matrix3d a;
      for (int k = 0; k < 3; ++k) a.col(k) = vec(rows[k]);
      return a;
    };
    if (body.weld) {
      // No constraints, global output axes.
    } else if (body.nodal) {
      const auto& nrb = model.nodal_rigid_bodies.at(body.id);
      if (nrb.cid != 0) body.output_axes = axes_of_system(nrb.cid);
      add_cmo_constraints(model, nrb.cmo, nrb.con1, nrb.con2, nrb.cmo_cid, nrb.cmo_local_fix,
                          body.state.constraints);
    } else {
      const auto& mat = model.materials.at(model.parts.at(body.id).mid);
      if (mat.lco != 0) {
        body.output_axes = axes_of_system(mat.lco);
      } else if (mat.has_output_vectors) {
        // Local x along a, local z normal to a and v, local y completing the triad.
        const Eigen::Vector3d a = vec(mat.output_a), v = vec(mat.output_v);
        const Eigen::Vector3d z = a.cross(v);
        if (a.norm() > 0.0 && z.norm() > 1e-12 * a.norm() * v.norm()) {
          body.output_axes.col(0) = a.normalized();
          body.output_axes.col(2) = z.normalized();
          body.output_axes.col(1) = body.output_axes.col(2).cross(body.output_axes.col(0));
        }
      }
      add_cmo_constraints(model, mat.cmo, mat.con1, mat.con2, mat.cmo_cid, mat.cmo_local_fix,
                          body.state.constraints);
    }
  }

  auto body_index = [&](Id pid) {
    const Id lead = model.nodal_rigid_bodies.count(pid) ? pid : lead_of(pid);
    for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
      if (rigid.bodies[b].id == lead && !rigid.bodies[b].weld &&
          rigid.bodies[b].nodal == (model.nodal_rigid_bodies.count(pid) != 0)) {
        return static_cast<int>(b);
      }
    }
    return -1;
  };

  // Prescribed motions, grouped by body; their axes together with the body's permanent
  // constraints must be independent (else the body is over-constrained).
  std::vector<std::vector<RigidMotion>> motions_of(rigid.bodies.size());
  for (const auto& pm : model.rigid_prescribed_motions) {
    RigidMotion m;
    m.body = body_index(pm.pid);
    if (m.body < 0) {
      throw InputError(context_of(pm.where, "PID"),
                       fmt::format("part {} is not a rigid body", pm.pid));
    }
    m.rotation = pm.dof >= 5;
    if (pm.dof == 4 || pm.dof == 8) {
      m.axis = vec(model.vectors.at(pm.vid).direction);
    } else {
      m.axis = Eigen::Vector3d::Unit((pm.dof - 1) % 4);
    }
    if (pm.local) {
      // Components in the body's output axes; as a global direction at t = 0.
      m.body_fixed = true;
      m.axis = (rigid.bodies[m.body].output_axes * m.axis).normalized();
    }
    m.vad = pm.vad;
    m.value = make_time_function(model, pm.lcid, pm.function, pm.sf, pm.birth, pm.where);
    m.birth = pm.birth;
    m.death = pm.death <= 0.0 ? 1e28 : pm.death;
    m.reference =
        (m.rotation || m.body_fixed) ? 0.0 : m.axis.dot(rigid.bodies[m.body].state.centre);
    m.where = pm.where;
    motions_of[m.body].push_back(m);
  }
  for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
    rigid::VelocityConstraints all;
    for (const auto& m : motions_of[b]) {
      const bool added =
          m.rotation ? all.add_rotation(m.axis, 0.0) : all.add_translation(m.axis, 0.0);
      if (!added || !rigid::constraints_independent(rigid.bodies[b].state.constraints, all)) {
        throw InputError(
            context_of(m.where, "DOF"),
            fmt::format("rigid body {} is over-constrained: this prescribed {} repeats a "
                        "direction already prescribed or held by CMO/CON1/CON2",
                        rigid.bodies[b].id, m.rotation ? "rotation" : "translation"));
      }
    }
    rigid.motions.insert(rigid.motions.end(), motions_of[b].begin(), motions_of[b].end());
  }

  for (const auto& load : model.rigid_loads) {
    RigidLoadTerm term;
    term.body = body_index(load.pid);
    term.moment = load.dof >= 5;
    term.axis = (load.dof - 1) % 4;
    term.value = make_time_function(model, load.lcid, 0, load.sf, 0.0, load.where);
    rigid.loads.push_back(term);
  }
  if (rigid.bodies.empty()) rigid.body_of_node.clear();
  return rigid;
}

void initialize_rigid_velocities(const model::Model& model, const NodeIndex& node_index,
                                 RigidSystem& rigid, State& state) {
  if (rigid.empty()) return;
  NodalState& nodes = state.nodes;
  std::vector<std::uint8_t> override_card(rigid.bodies.size(), 0);
  for (const auto& iv : model.initial_velocities) {
    if (iv.irigid != 1) continue;
    const auto targets = resolve_nodes(model, node_index, state, iv.target, iv.id, iv.where, "ID");
    for (const auto i : targets) {
      if (rigid.body_of_node[i] >= 0) override_card[rigid.body_of_node[i]] = 1;
    }
  }
  for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
    RigidBody& body = rigid.bodies[b];
    rigid::RigidBodyState& s = body.state;
    // Mass-weighted rigid fit of the nodal velocities (unit weights if the nodes are massless).
    double mass = 0.0;
    for (const auto i : body.nodes) mass += nodes.mass[i];
    const bool unit_weights = !(mass > 0.0);
    auto weight = [&](std::int32_t i) { return unit_weights ? 1.0 : nodes.mass[i]; };
    Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();
    if (!body.nodes.empty()) {
      double total = 0.0;
      Eigen::Vector3d momentum = Eigen::Vector3d::Zero(), centre = Eigen::Vector3d::Zero();
      for (const auto i : body.nodes) {
        total += weight(i);
        momentum += weight(i) * Eigen::Vector3d(nodes.v.x[i], nodes.v.y[i], nodes.v.z[i]);
        centre += weight(i) * Eigen::Vector3d(nodes.x.x[i], nodes.x.y[i], nodes.x.z[i]);
      }
      v = momentum / total;
      centre /= total;
      Eigen::Vector3d spin = Eigen::Vector3d::Zero();
      Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
      for (const auto i : body.nodes) {
        const Eigen::Vector3d r =
            Eigen::Vector3d(nodes.x.x[i], nodes.x.y[i], nodes.x.z[i]) - centre;
        const Eigen::Vector3d u = Eigen::Vector3d(nodes.v.x[i], nodes.v.y[i], nodes.v.z[i]) - v;
        spin += weight(i) * r.cross(u);
        inertia += weight(i) * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
      }
      // Nodes with rotations (shells, beams) add their spin I w and rotary inertia I, so that
      // the body gets the angular momentum of the whole initial field (a rigid rotation of the
      // field gives back its w exactly, as without them).
      if (!unit_weights && !state.rotations.empty()) {
        for (const auto i : body.nodes) {
          const std::int32_t r = state.rotations.index(i);
          if (r < 0) continue;
          const double j = state.rotations.inertia[static_cast<std::size_t>(r)];
          spin += j * Eigen::Vector3d(state.rotations.w.x[r], state.rotations.w.y[r],
                                      state.rotations.w.z[r]);
          inertia += j * Eigen::Matrix3d::Identity();
        }
      }
      // Pseudo-inverse: a line of nodes says nothing about spin about the line.
      w = inertia.completeOrthogonalDecomposition().solve(spin);
      // The fit is about the nodes' centre; the body turns about its own centre.
      v += w.cross(s.centre - centre);
    }
    const model::RigidInertia* card = nullptr;
    if (body.weld) {
      // No inertia card.
    } else if (body.nodal) {
      const auto& nrb = model.nodal_rigid_bodies.at(body.id);
      if (nrb.inertia) card = &*nrb.inertia;
    } else if (model.parts.at(body.id).inertia) {
      card = &*model.parts.at(body.id).inertia;
    }
    if (card && !override_card[b]) {
      v = vec(card->vt);
      w = vec(card->vr);
    }
    rigid::set_velocity(s, v, w);
    body.velocity_before = v;
    body.angular_velocity_before = w;
    std::vector<double> given;  // flexible bodies: the nodes' velocities before the rigid fit
    if (body.flexible >= 0) {
      given.resize(3 * body.nodes.size());
      for (std::size_t k = 0; k < body.nodes.size(); ++k) {
        given[3 * k] = nodes.v.x[body.nodes[k]];
        given[3 * k + 1] = nodes.v.y[body.nodes[k]];
        given[3 * k + 2] = nodes.v.z[body.nodes[k]];
      }
    }
    rigid::rigid_node_velocities(v, w, s.centre, body.nodes, nodes.x.x.data(), nodes.x.y.data(),
                                 nodes.x.z.data(), nodes.v.x.data(), nodes.v.y.data(),
                                 nodes.v.z.data());
    if (body.flexible >= 0) {
      initialize_modal_velocities(body, rigid.flexible[body.flexible], given, nodes,
                                  &state.rotations);
    }
  }
}

RigidStepSums advance_rigid_bodies(RigidSystem& rigid, const Boundary& boundary, double t_n,
                                   double dt_avg, double dt, State& state) {
  RigidStepSums sums;
  if (rigid.empty()) return sums;
  NodalState& nodes = state.nodes;
  const double t_mid = t_n + 0.5 * dt;
  const double t_end = t_n + dt;
  const std::int64_t body_count = static_cast<std::int64_t>(rigid.bodies.size());
  std::size_t motion_begin = 0;

  for (std::int64_t b = 0; b < body_count; ++b) {
    RigidBody& body = rigid.bodies[b];
    rigid::RigidBodyState& s = body.state;
    body.velocity_before = s.velocity;
    body.angular_velocity_before = s.angular_velocity;

    // Force and torque about x_c^n: nodal forces f_ext - f_int (f_int only from deformable
    // neighbours; rigid elements have no kernel), body-level loads and body forces. A flexible
    // body's passive nodes carry no force (docs/flexible_bodies.md).
    modal::FlexibleBody* flexible = body.flexible >= 0 ? &rigid.flexible[body.flexible] : nullptr;
    const std::vector<std::int32_t>& loaded = flexible ? flexible->active_nodes : body.nodes;
    rigid::ForceAndTorque ft = rigid::gather_force_and_torque(
        s.centre, loaded, nodes.f_ext.x.data(), nodes.f_ext.y.data(), nodes.f_ext.z.data(),
        nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data());
    if (flexible) gather_modal_forces(body, *flexible, nodes, state.rotations);
    ft -= rigid::gather_force_and_torque(s.centre, loaded, nodes.f_int.x.data(),
                                         nodes.f_int.y.data(), nodes.f_int.z.data(),
                                         nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data());
    Eigen::Vector3d load_force = Eigen::Vector3d::Zero(), load_moment = Eigen::Vector3d::Zero();
    for (const auto& load : rigid.loads) {
      if (load.body != b) continue;
      (load.moment ? load_moment : load_force)[load.axis] += load.value(t_n);
    }
    for (const auto& base : boundary.body_accelerations) {
      load_force[base.axis] -= s.mass * base.value(t_n);  // *LOAD_BODY: -M a at the centre
    }
    // Mass-proportional damping at the centre of mass: -d ST M v_c and -d SR L (L = J w about
    // the centre), with the velocities of the last half step as for the nodes.
    Eigen::Vector3d damping_force = Eigen::Vector3d::Zero();
    Eigen::Vector3d damping_moment = Eigen::Vector3d::Zero();
    if (!boundary.damping.empty() && !body.nodes.empty()) {
      const int term = boundary.damping.term_of_node[body.nodes.front()];
      if (term >= 0) {
        const DampingTerm& damping = boundary.damping.terms[term];
        const double d = damping.d(t_n);
        for (int k = 0; k < 3; ++k) {
          damping_force[k] = -d * damping.st[k] * s.mass * body.velocity_before[k];
          damping_moment[k] = -d * damping.sr[k] * s.angular_momentum[k];
        }
        load_force += damping_force;
        load_moment += damping_moment;
      }
    }
    body.force = ft.force + load_force + body.joint_force;
    body.torque = ft.torque + load_moment + body.joint_torque;
    // Nodal moments on body nodes that carry rotations (shells and beams attached to the body).
    if (!state.rotations.empty()) {
      const RotationalState& rot = state.rotations;
      for (const std::int32_t i : loaded) {
        const std::int32_t r = rot.index(i);
        if (r < 0) continue;
        body.torque += Eigen::Vector3d(rot.m_ext.x[r] - rot.m_int.x[r], rot.m_ext.y[r] - rot.m_int.y[r],
                                       rot.m_ext.z[r] - rot.m_int.z[r]);
      }
    }

    // Prescribed motion this step (same time sampling as nodal prescribed motion).
    rigid::VelocityConstraints& step = body.step_constraints;
    step.clear();
    std::size_t motion_end = motion_begin;
    while (motion_end < rigid.motions.size() && rigid.motions[motion_end].body == b) ++motion_end;
    for (std::size_t k = motion_begin; k < motion_end; ++k) {
      RigidMotion& m = rigid.motions[k];
      const Eigen::Vector3d& before =
          m.rotation ? body.angular_velocity_before : body.velocity_before;
      // Body-fixed axes turn with the body: R^n R0^T carries them from t = 0 to t^n.
      const Eigen::Vector3d axis =
          m.body_fixed ? Eigen::Vector3d(s.rotation * (body.initial_rotation.transpose() * m.axis))
                       : m.axis;
      double value = 0.0;
      if (m.vad == 0) {
        if (!(t_mid >= m.birth && t_mid <= m.death)) continue;
        value = m.value(t_mid);
      } else if (m.vad == 1) {
        if (!(t_n >= m.birth && t_n <= m.death)) continue;
        value = axis.dot(before) + dt_avg * m.value(t_n);
      } else {
        if (!(t_end >= m.birth && t_end <= m.death)) continue;
        const bool integrated = m.rotation || m.body_fixed;
        const double now = integrated ? m.travelled : axis.dot(s.centre) - m.reference;
        value = (m.value(t_end) - now) / dt;
      }
      if (m.rotation) {
        step.add_rotation(axis, value);
      } else {
        step.add_translation(axis, value);
      }
    }

    const Eigen::Matrix3d rotation_before = s.rotation;
    rigid::advance_rigid_body(s, body.force, body.torque, dt_avg, dt, &step);
    for (std::size_t k = motion_begin; k < motion_end; ++k) {
      RigidMotion& m = rigid.motions[k];
      if (!(m.rotation || m.body_fixed)) continue;
      const Eigen::Vector3d axis =
          m.body_fixed
              ? Eigen::Vector3d(rotation_before * (body.initial_rotation.transpose() * m.axis))
              : m.axis;
      m.travelled += dt * axis.dot(m.rotation ? s.angular_velocity : s.velocity);
    }
    motion_begin = motion_end;

    // Nodal velocities v^{n+1/2}: the rigid field about x_c^n (linear update), or the secant
    // velocity onto x_c^{n+1} + R^{n+1} X_i (curvilinear), so that deformable neighbours see
    // exactly the displacement the node makes.
    const Eigen::Vector3d& c_old = s.previous_centre;
    if (flexible) {
      // Modes from t^n to t^{n+1} with the frame's angular velocity and acceleration at t^n
      // (body axes), then the secant velocities onto the reconstructed positions.
      const Eigen::Matrix3d rt = s.previous_rotation.transpose();
      const Eigen::Vector3d omega_body =
          rt * (0.5 * (body.angular_velocity_before + s.angular_velocity));
      const Eigen::Vector3d alpha_body =
          dt_avg > 0.0 ? Eigen::Vector3d(rt * (s.angular_velocity - body.angular_velocity_before) /
                                         dt_avg)
                       : Eigen::Vector3d::Zero();
      modal::advance_modes(*flexible, omega_body, alpha_body, dt_avg, dt);
      set_flexible_node_velocities(body, *flexible, dt, nodes, rigid.modal_work_velocity,
                                   state.rotations, rigid.modal_rotation_velocity,
                                   rigid.modal_rotation_work_velocity);
      sums.modal_damping_loss += flexible->damping_loss;
      sums.modal_inertia_work += flexible->inertia_work;
      sums.modal_stiffening_work += flexible->stiffening_work;
    } else if (body.update == NodeUpdate::kLinear || !(dt > 0.0)) {
      rigid::rigid_node_velocities(s.velocity, s.angular_velocity, c_old, body.nodes,
                                   nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                   nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data());
    } else {
      const double inv_dt = 1.0 / dt;
      for (std::size_t k = 0; k < body.nodes.size(); ++k) {
        const std::int32_t i = body.nodes[k];
        const Eigen::Vector3d local(body.body_coordinates.x[k], body.body_coordinates.y[k],
                                    body.body_coordinates.z[k]);
        const Eigen::Vector3d target = s.centre + s.rotation * local;
        nodes.v.x[i] = (target.x() - nodes.x.x[i]) * inv_dt;
        nodes.v.y[i] = (target.y() - nodes.x.y[i]) * inv_dt;
        nodes.v.z[i] = (target.z() - nodes.x.z[i]) * inv_dt;
      }
    }

    // Work of body-level loads and constraint reactions over the step (midpoint velocities).
    body.mid_velocity = 0.5 * (body.velocity_before + s.velocity);
    body.mid_angular_velocity = 0.5 * (body.angular_velocity_before + s.angular_velocity);
    const Eigen::Vector3d& v_mid = body.mid_velocity;
    const Eigen::Vector3d& w_mid = body.mid_angular_velocity;
    sums.damping_work += dt_avg * (damping_force.dot(v_mid) + damping_moment.dot(w_mid));
    sums.joint_stiffness_work +=
        dt_avg * (body.joint_force.dot(v_mid) + body.joint_torque.dot(w_mid));
    sums.external_work += dt_avg * (load_force.dot(v_mid) + load_moment.dot(w_mid)) +
                          s.reaction_impulse.dot(v_mid) + s.reaction_angular_impulse.dot(w_mid);
  }
  const RigidStepSums totals = rigid_body_sums(rigid);
  sums.kinetic = totals.kinetic;
  sums.modal_elastic = totals.modal_elastic;
  for (int k = 0; k < 3; ++k) {
    sums.momentum[k] = totals.momentum[k];
    sums.angular_momentum[k] = totals.angular_momentum[k];
  }
  return sums;
}

void place_curvilinear_nodes(const RigidSystem& rigid, State& state) {
  NodalState& nodes = state.nodes;
  for (const RigidBody& body : rigid.bodies) {
    if (body.update != NodeUpdate::kCurvilinear) continue;
    if (body.flexible >= 0) {
      place_flexible_nodes(body, rigid.flexible[body.flexible], nodes);
      continue;
    }
    rigid::place_nodes_curvilinear(body.state, body.nodes, body.body_coordinates, nodes.x.x.data(),
                                   nodes.x.y.data(), nodes.x.z.data());
  }
}

rigid::MassProperties lumped_mass_properties(const std::vector<std::int32_t>& nodes,
                                             const State& state) {
  const NodalState& n = state.nodes;
  rigid::MassProperties props =
      rigid::mass_properties(nodes, n.mass.data(), n.x.x.data(), n.x.y.data(), n.x.z.data());
  if (!state.rotations.empty()) {
    double rotary = 0.0;
    for (const std::int32_t i : nodes) {
      const std::int32_t r = state.rotations.index(i);
      if (r >= 0) rotary += state.rotations.inertia[static_cast<std::size_t>(r)];
    }
    props.inertia += rotary * Eigen::Matrix3d::Identity();
  }
  return props;
}

rigid::MassProperties spot_weld_properties(std::int32_t a, std::int32_t b, const State& state) {
  rigid::MassProperties props = lumped_mass_properties({std::min(a, b), std::max(a, b)}, state);
  // Without rotations the two points have no moment about their line; no nodal force has one
  // either, so a small moment there (1e-6 of the others) changes no motion and makes J^-1 exist.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(props.inertia);
  const double largest = eigen.eigenvalues().maxCoeff();
  if (eigen.eigenvalues().minCoeff() < 1e-6 * largest) {
    props.inertia += 1e-6 * largest * Eigen::Matrix3d::Identity();
  }
  return props;
}

void remove_rigid_bodies(RigidSystem& rigid, const std::set<int>& gone,
                         const std::map<int, int>& moved_to) {
  if (gone.empty()) return;
  std::vector<int> new_index(rigid.bodies.size(), -1);
  int next = 0;
  for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
    if (!gone.count(static_cast<int>(b))) new_index[b] = next++;
  }
  auto remap = [&](int b) {
    if (const auto it = moved_to.find(b); it != moved_to.end()) b = it->second;
    return new_index[b];
  };
  for (auto& owner : rigid.body_of_node) {
    if (owner >= 0) owner = remap(owner);
  }
  for (auto& m : rigid.motions) m.body = remap(m.body);
  for (auto& l : rigid.loads) l.body = remap(l.body);
  for (auto& f : rigid.flexible) f.body = remap(f.body);
  std::stable_sort(rigid.motions.begin(), rigid.motions.end(),
                   [](const auto& a, const auto& b) { return a.body < b.body; });
  std::vector<RigidBody> kept;
  kept.reserve(next);
  for (std::size_t b = 0; b < rigid.bodies.size(); ++b) {
    if (new_index[b] >= 0) kept.push_back(std::move(rigid.bodies[b]));
  }
  rigid.bodies = std::move(kept);
}

Eigen::Matrix3d output_rotation(const RigidBody& body) {
  return body.state.previous_rotation * body.initial_rotation.transpose() * body.output_axes;
}

RigidStepSums rigid_body_sums(const RigidSystem& rigid) {
  RigidStepSums sums;
  for (const RigidBody& body : rigid.bodies) {
    const rigid::RigidBodyState& s = body.state;
    sums.kinetic += rigid::kinetic_energy(s);
    const Eigen::Vector3d p = s.mass * s.velocity;
    // x_c^n x p^{n+1/2} (= x_c^{n+1} x p^{n+1/2}) plus the spin about the centre.
    const Eigen::Vector3d h = s.previous_centre.cross(p) + s.angular_momentum;
    for (int k = 0; k < 3; ++k) {
      sums.momentum[k] += p[k];
      sums.angular_momentum[k] += h[k];
    }
  }
  // The modes carry no momentum and no angular momentum about the centre (mean-axis
  // conditions, docs/flexible_bodies.md), only energy.
  for (const auto& f : rigid.flexible) {
    sums.kinetic += f.kinetic_energy();
    sums.modal_elastic += f.elastic_energy();
  }
  return sums;
}

}  // namespace rf::solver
