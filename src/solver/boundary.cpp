#include "solver/boundary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "element/tet10_block.hpp"
#include "mesh/surface.hpp"
#include "model/curve.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"
#include "model/function.hpp"
#include "solver/mass_damping.hpp"

namespace rf::solver {

namespace {

using model::context_of;

ScaledCurve make_curve(const model::Model& model, model::Id lcid, double sf, double shift,
                       const model::SourceLocation& where) {
  return make_time_function(model, lcid, 0, sf, shift, where);
}

int translation_axis(int dof, const model::SourceLocation& where) {
  const int a = std::abs(dof);
  if (a < 1 || a > 3) {
    throw InputError(
        context_of(where, "DOF"),
        fmt::format("DOF={} is not supported here (supported: 1, 2, 3 for x, y, z)", dof));
  }
  return a - 1;
}

}  // namespace

ScaledCurve make_time_function(const model::Model& model, model::Id lcid, model::Id function,
                               double sf, double shift, const model::SourceLocation& where) {
  ScaledCurve c;
  c.scale = sf;
  c.shift = shift;
  if (lcid != 0) {
    const auto it = model.curves.find(lcid);
    if (it == model.curves.end()) {
      throw InputError(context_of(where, "LCID"),
                       fmt::format("load curve {} is not defined", lcid));
    }
    c.curve = &it->second;
  } else if (function != 0) {
    const auto it = model.functions.find(function);
    if (it == model.functions.end()) {
      throw InputError(context_of(where, "FUNCTION"),
                       fmt::format("function {} is not defined (*FUNCTION)", function));
    }
    c.function = it->second.evaluator.get();
  }
  return c;
}

std::vector<std::int32_t> select_geometry(const State& state, const model::GeometrySeed& seed) {
  std::vector<mesh::HexView> hexes;
  for (const auto& block : state.hex_blocks) {
    // The surface search walks hexahedral faces; 10-node tetrahedra (ELFORM 16) have none, so a
    // seed that could reach them is refused rather than answered without them.
    if (block.quadratic_tetrahedra()) {
      if (seed.pid == 0 || seed.pid == block.part_id) {
        throw InputError(context_of(seed.where, seed.pid == 0 ? "" : "pid"),
                         fmt::format("the surface of geometry seed {} would be searched over "
                                     "part {}, whose 10-node tetrahedra (ELFORM 16) the search "
                                     "does not cover: restrict the seed to another part (pid) or "
                                     "use a node set",
                                     seed.id, block.part_id));
      }
      continue;
    }
    const auto npe = static_cast<std::size_t>(block.nodes_per_element());
    for (std::size_t e = 0; e < block.size(); ++e) {
      hexes.push_back({block.order, &block.conn[npe * e], block.part_id});
    }
  }
  const auto& x0 = state.nodes.x0;
  return mesh::select_surface_by_seed(hexes, {x0.x.data(), x0.y.data(), x0.z.data()}, seed.point,
                                      seed.feature_angle_deg, seed.pid);
}

namespace {
bool relaxation_running = false;
}

bool dynamic_relaxation_running() {
  return relaxation_running;
}
DynamicRelaxationPhase::DynamicRelaxationPhase() {
  relaxation_running = true;
}
DynamicRelaxationPhase::~DynamicRelaxationPhase() {
  relaxation_running = false;
}

double load_curve_value(const model::Curve& curve, double t) {
  // SIDR 0: transient only; 1: dynamic relaxation only; 2: both (LS-DYNA *DEFINE_CURVE).
  if (relaxation_running ? curve.sidr == 0 : curve.sidr == 1) return 0.0;
  return model::evaluate(curve, t);
}

double ScaledCurve::operator()(double t) const {
  if (curve) return scale * load_curve_value(*curve, t - shift);
  if (function) return scale * (*function)(t - shift);
  return scale;
}

namespace {

// The mid-side nodes that *ELEMENT_SOLID_TET4TOTET10 created (the deck does not know them, so no
// node set lists them) belong to a node set when both ends of their edge do: a constraint or load
// on the corner nodes of a face reaches the whole quadratic face, as the set's author meant.
void add_created_midside_nodes(const State& state, const NodeIndex& node_index,
                               std::vector<std::int32_t>& nodes) {
  const std::size_t deck_nodes = node_index.size();
  if (state.nodes.size() <= deck_nodes || nodes.empty()) return;
  std::vector<std::uint8_t> in_set(state.nodes.size(), 0);
  for (const std::int32_t i : nodes) in_set[static_cast<std::size_t>(i)] = 1;
  for (const auto& block : state.hex_blocks) {
    if (!block.quadratic_tetrahedra()) continue;
    for (std::size_t e = 0; e < block.size(); ++e) {
      const std::int32_t* c = &block.conn[element::kTet10Nodes * e];
      for (int m = 0; m < 6; ++m) {
        const auto mid = static_cast<std::size_t>(c[4 + m]);
        if (mid < deck_nodes || in_set[mid]) continue;
        if (in_set[static_cast<std::size_t>(c[element::kTet10Edge[m][0]])] &&
            in_set[static_cast<std::size_t>(c[element::kTet10Edge[m][1]])]) {
          in_set[mid] = 1;
          nodes.push_back(static_cast<std::int32_t>(mid));
        }
      }
    }
  }
}

}  // namespace

std::vector<std::int32_t> resolve_nodes(const model::Model& model, const NodeIndex& node_index,
                                        const State& state, model::Target target, model::Id id,
                                        const model::SourceLocation& where, const char* field) {
  std::vector<std::int32_t> out;
  auto add_part = [&](model::Id pid) {
    bool found = false;
    auto take = [&](const auto& blocks) {  // every element family
      for (const auto& block : blocks) {
        if (block.part_id != pid) continue;
        found = true;
        out.insert(out.end(), block.conn.begin(), block.conn.end());
      }
    };
    take(state.hex_blocks);
    take(state.shell_blocks);
    take(state.beam_blocks);
    if (!found && model.parts.count(pid) == 0) {
      throw InputError(context_of(where, field), fmt::format("part {} is not defined", pid));
    }
  };
  switch (target) {
    case model::Target::Node:
      out.push_back(node_index.at(id, where, field));
      break;
    case model::Target::NodeSet: {
      const auto it = model.node_sets.find(id);
      if (it == model.node_sets.end()) {
        throw InputError(context_of(where, field), fmt::format("node set {} is not defined", id));
      }
      for (const model::Id nid : it->second.nodes) out.push_back(node_index.at(nid, where, field));
      add_created_midside_nodes(state, node_index, out);
      break;
    }
    case model::Target::Part:
      add_part(id);
      break;
    case model::Target::PartSet: {
      const auto it = model.part_sets.find(id);
      if (it == model.part_sets.end()) {
        throw InputError(context_of(where, field), fmt::format("part set {} is not defined", id));
      }
      for (const model::Id pid : it->second.parts) add_part(pid);
      break;
    }
    case model::Target::All:
      out.resize(state.nodes.size());
      for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::int32_t>(i);
      break;
    case model::Target::Geometry: {
      const auto it = model.geometry_seeds.find(id);
      if (it == model.geometry_seeds.end()) {
        throw InputError(context_of(where, field), fmt::format("geometry {} is not defined", id));
      }
      out = select_geometry(state, it->second);
      if (out.empty()) {
        throw InputError(context_of(it->second.where, "pid"),
                         fmt::format("geometry {} selects no surface (no boundary face{})", id,
                                     it->second.pid ? " of that part" : ""));
      }
      break;
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

// Nodal prescribed motion (any DOF) on a node that moves with a rigid body is an error: the
// body's motion is prescribed with *BOUNDARY_PRESCRIBED_MOTION_RIGID.
void refuse_rigid_nodes(const std::vector<std::int32_t>& nodes,
                        const std::vector<std::int32_t>& body_of_node,
                        const model::PrescribedMotion& pm, const State& state) {
  if (body_of_node.empty()) return;
  for (const auto i : nodes) {
    if (body_of_node[static_cast<std::size_t>(i)] < 0) continue;
    throw InputError(context_of(pm.where, pm.target == model::Target::Node ? "NID" : "NSID"),
                     fmt::format("node {} moves with a rigid body (rigid part, extra node or "
                                 "nodal rigid body); prescribe the motion of the body with "
                                 "*BOUNDARY_PRESCRIBED_MOTION_RIGID",
                                 state.nodes.id[i]));
  }
}

// *BOUNDARY_PRESCRIBED_MOTION DOF 4 (along VID) and 5-8 (rotation about x, y, z, VID) on nodes.
void add_prescribed_direction(const model::Model& model, const NodeIndex& node_index,
                              const State& state, const std::vector<std::int32_t>& body_of_node,
                              const model::PrescribedMotion& pm, Boundary& b) {
  const bool rotation = pm.dof >= 5;
  std::array<double, 3> n{};
  if (pm.dof == 4 || pm.dof == 8) {
    const auto it = model.vectors.find(pm.vid);
    if (pm.vid == 0 || it == model.vectors.end()) {
      throw InputError(context_of(pm.where, "VID"),
                       fmt::format("DOF {} acts along a vector, but VID {} is not a "
                                   "*DEFINE_VECTOR",
                                   pm.dof, pm.vid));
    }
    const auto& d = it->second.direction;
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 0.0)) {
      throw InputError(context_of(pm.where, "VID"),
                       fmt::format("vector {} has zero length", pm.vid));
    }
    for (int k = 0; k < 3; ++k) n[k] = d[k] / len;
  } else {
    n[pm.dof - 5] = 1.0;
  }
  const char* field = pm.target == model::Target::Node ? "NID" : "NSID";
  const auto nodes = resolve_nodes(model, node_index, state, pm.target, pm.id, pm.where, field);
  const ScaledCurve value =
      make_time_function(model, pm.lcid, pm.function, pm.sf, pm.birth, pm.where);
  const double death = pm.death <= 0.0 ? 1e28 : pm.death;
  refuse_rigid_nodes(nodes, body_of_node, pm, state);
  for (const auto i : nodes) {
    PrescribedDirection p{i, -1, n, pm.vad, value, pm.birth, death};
    if (rotation) {
      p.rotation = state.rotations.index(i);
      if (p.rotation < 0) {
        throw InputError(context_of(pm.where, field),
                         fmt::format("DOF {} is a rotation, but node {} has no rotational degrees "
                                     "of freedom (only nodes of shells and beams have them)",
                                     pm.dof, state.nodes.id[i]));
      }
      if (b.rotation_fixed[static_cast<std::size_t>(p.rotation)] != 0) {
        throw InputError(context_of(pm.where, "DOF"),
                         fmt::format("node {} has a prescribed rotation (DOF {}) but a rotation "
                                     "of it is also fixed by an SPC or *NODE RC",
                                     state.nodes.id[i], pm.dof));
      }
    } else if (b.fixed[i] != 0) {
      throw InputError(context_of(pm.where, "DOF"),
                       fmt::format("node {} moves along a vector (DOF 4) but a translation of it "
                                   "is also fixed by an SPC or *NODE TC",
                                   state.nodes.id[i]));
    }
    b.prescribed_directions.push_back(p);
  }
}

}  // namespace

Boundary resolve_boundary(const model::Model& model, const NodeIndex& node_index,
                          const State& state, const std::vector<std::int32_t>& body_of_node,
                          std::vector<model::Warning>& warnings) {
  Boundary b;
  const std::size_t n = state.nodes.size();
  auto rigid = [&](std::int32_t i) { return !body_of_node.empty() && body_of_node[i] >= 0; };
  b.fixed.assign(n, 0);
  // *NODE TC: 1 x, 2 y, 3 z, 4 xy, 5 yz, 6 zx, 7 xyz.
  static constexpr std::uint8_t kTcMask[8] = {0, 1, 2, 4, 3, 6, 5, 7};
  std::int64_t ignored_tc = 0;
  // Generated nodes (*CHANGE_P-ORDER) follow the model's nodes and carry no TC of their own.
  for (std::size_t i = 0; i < std::min(n, model.nodes.size()); ++i) {
    const int tc = model.nodes[i].tc;
    if (tc <= 0 || tc > 7) continue;
    if (rigid(static_cast<std::int32_t>(i))) {
      ++ignored_tc;
      continue;
    }
    b.fixed[i] |= kTcMask[tc];
  }
  if (ignored_tc > 0) {
    warnings.push_back({{},
                        fmt::format("*NODE: TC on {} node(s) of rigid bodies is ignored; "
                                    "constrain a rigid body with CMO/CON1/CON2 on "
                                    "*MAT_RIGID",
                                    ignored_tc)});
  }
  // *NODE RC on nodes with rotations: 1 x, 2 y, 3 z, 4 x+y, 5 y+z, 6 z+x, 7 all.
  b.rotation_fixed.assign(state.rotations.size(), 0);
  for (std::size_t i = 0; i < std::min(n, model.nodes.size()); ++i) {
    const int rc = model.nodes[i].rc;
    const std::int32_t r = state.rotations.index(static_cast<std::int32_t>(i));
    if (rc <= 0 || rc > 7 || r < 0 || rigid(static_cast<std::int32_t>(i))) continue;
    b.rotation_fixed[static_cast<std::size_t>(r)] |= kTcMask[rc];  // same codes
  }
  for (const auto& spc : model.spcs) {
    const auto nodes = resolve_nodes(model, node_index, state, spc.target, spc.id, spc.where,
                                     spc.target == model::Target::Node ? "NID" : "NSID");
    const std::uint8_t mask = static_cast<std::uint8_t>(
        (spc.fix[0] ? 1 : 0) | (spc.fix[1] ? 2 : 0) | (spc.fix[2] ? 4 : 0));
    std::int64_t ignored = 0;
    const std::uint8_t rotation_mask = static_cast<std::uint8_t>(
        (spc.fix_rot[0] ? 1 : 0) | (spc.fix_rot[1] ? 2 : 0) | (spc.fix_rot[2] ? 4 : 0));
    for (const auto i : nodes) {
      if (rigid(i)) {
        ++ignored;
      } else {
        b.fixed[i] |= mask;
        // Rotational DOFs act on nodes that have them (shells, beams); solids have none.
        if (const std::int32_t r = state.rotations.index(i); r >= 0) {
          b.rotation_fixed[static_cast<std::size_t>(r)] |= rotation_mask;
        }
      }
    }
    if (ignored > 0) {
      warnings.push_back(
          {spc.where, fmt::format("{} node(s) belong to rigid bodies; the SPC is ignored on them "
                                  "(constrain a rigid body with CMO/CON1/CON2 on *MAT_RIGID)",
                                  ignored)});
    }
  }
  for (const auto& pm : model.prescribed_motions) {
    if (pm.dof >= 4 && pm.dof <= 8) {
      add_prescribed_direction(model, node_index, state, body_of_node, pm, b);
      continue;
    }
    const bool rotation = pm.dof >= 9 && pm.dof <= 11;
    const int axis = rotation ? pm.dof - 9 : translation_axis(pm.dof, pm.where);
    if (rotation && pm.vad == 1) {
      throw InputError(context_of(pm.where, "VAD"),
                       "VAD=1 (angular acceleration) is not supported with DOF 9, 10, 11; use "
                       "0 (angular velocity) or 2 (angle)");
    }
    if (pm.vad < 0 || pm.vad > 2) {
      throw InputError(context_of(pm.where, "VAD"),
                       fmt::format("VAD={} is not supported (0 velocity, 1 acceleration, "
                                   "2 displacement)",
                                   pm.vad));
    }
    const auto nodes = resolve_nodes(model, node_index, state, pm.target, pm.id, pm.where,
                                     pm.target == model::Target::Node ? "NID" : "NSID");
    const ScaledCurve value =
        make_time_function(model, pm.lcid, pm.function, pm.sf, pm.birth, pm.where);
    refuse_rigid_nodes(nodes, body_of_node, pm, state);
    for (const auto i : nodes) {
      const double death = pm.death <= 0.0 ? 1e28 : pm.death;
      if (rotation) {
        // The two translations normal to the rotation axis follow the circle; the one along
        // the axis stays free (LS-DYNA: radial motion is not permitted for DOF 9..11 > 0).
        for (const int k : {(axis + 1) % 3, (axis + 2) % 3}) {
          if (b.fixed[i] & (1u << k)) {
            throw InputError(context_of(pm.where, "DOF"),
                             fmt::format("node {} turns about an axis (DOF {}) but its "
                                         "translation {} is fixed by an SPC",
                                         state.nodes.id[i], pm.dof, "xyz"[k]));
          }
          PrescribedDof p{i, k, pm.vad, axis, {pm.offset1, pm.offset2}, value, pm.birth, death};
          b.prescribed.push_back(p);
        }
        continue;
      }
      if (b.fixed[i] & (1u << axis)) {
        throw InputError(context_of(pm.where, "DOF"),
                         fmt::format("node {} has a prescribed motion in a DOF that is also "
                                     "fixed by an SPC",
                                     state.nodes.id[i]));
      }
      b.prescribed.push_back(PrescribedDof{i, axis, pm.vad, -1, {}, value, pm.birth, death});
    }
  }
  for (const auto& load : model.nodal_loads) {
    const char* field = load.target == model::Target::Node ? "NID" : "NSID";
    const bool moment = load.dof >= 5 && load.dof <= 7;
    const int axis = moment ? load.dof - 5 : translation_axis(load.dof, load.where);
    auto nodes = resolve_nodes(model, node_index, state, load.target, load.id, load.where, field);
    // A nodal force acts on each listed node: the mid-side nodes a set gains from
    // *ELEMENT_SOLID_TET4TOTET10 (add_created_midside_nodes) would add to the total load.
    if (load.target == model::Target::NodeSet) {
      std::erase_if(
          nodes, [&](std::int32_t i) { return static_cast<std::size_t>(i) >= node_index.size(); });
    }
    const ScaledCurve value = make_curve(model, load.lcid, load.sf, 0.0, load.where);
    if (!moment) {
      for (const auto i : nodes) b.nodal_forces.push_back(NodalForce{i, axis, value});
      continue;
    }
    // Moments act on nodes with rotational DOFs (shell and beam nodes); a solid node has none.
    for (const auto i : nodes) {
      const std::int32_t r = state.rotations.index(i);
      if (r < 0) {
        throw InputError(context_of(load.where, field),
                         fmt::format("DOF {} is a moment, but node {} has no rotational degrees "
                                     "of freedom (only nodes of shells and beams have them)",
                                     load.dof, state.nodes.id[i]));
      }
      b.nodal_moments.push_back(NodalMoment{r, axis, value});
    }
  }
  b.pressure = resolve_pressure_loads(model, node_index);
  for (const auto& body : model.body_loads) {
    b.body_accelerations.push_back(
        BodyAcceleration{body.direction, make_curve(model, body.lcid, body.sf, 0.0, body.where)});
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (b.fixed[i]) b.constrained_nodes.push_back(static_cast<std::int32_t>(i));
  }
  set_body_force_masses(b, state.nodes, body_of_node);
  b.damping = resolve_mass_damping(model, state);
  for (const auto& p : b.prescribed) b.constrained_nodes.push_back(p.node);
  for (const auto& p : b.prescribed_directions)
    if (p.rotation < 0) b.constrained_nodes.push_back(p.node);
  std::sort(b.constrained_nodes.begin(), b.constrained_nodes.end());
  b.constrained_nodes.erase(std::unique(b.constrained_nodes.begin(), b.constrained_nodes.end()),
                            b.constrained_nodes.end());
  return b;
}

void apply_initial_velocities(const model::Model& model, const NodeIndex& node_index,
                              State& state) {
  NodalState& nodes = state.nodes;
  for (const auto& iv : model.initial_velocities) {
    const char* field = iv.target == model::Target::Node      ? "NID"
                        : iv.target == model::Target::NodeSet ? "NSID"
                                                              : "ID";
    auto targets = resolve_nodes(model, node_index, state, iv.target, iv.id, iv.where, field);
    if (!iv.exempt_nodes.empty()) {
      std::vector<std::int32_t> exempt;
      for (const auto nid : iv.exempt_nodes)
        exempt.push_back(node_index.at(nid, iv.where, "NSIDEX"));
      std::sort(exempt.begin(), exempt.end());
      std::erase_if(targets, [&](std::int32_t i) {
        return std::binary_search(exempt.begin(), exempt.end(), i);
      });
    }
    double ax = iv.axis[0], ay = iv.axis[1], az = iv.axis[2];
    const double len = std::sqrt(ax * ax + ay * ay + az * az);
    if (iv.omega != 0.0) {
      if (len == 0.0) {
        throw InputError(context_of(iv.where, "NX"), "rotation axis has zero length");
      }
      ax /= len;
      ay /= len;
      az /= len;
    }
    for (const auto i : targets) {
      // v = v_t + omega * (axis x (x - point)): rigid rotation about the axis.
      const double rx = nodes.x0.x[i] - iv.point[0];
      const double ry = nodes.x0.y[i] - iv.point[1];
      const double rz = nodes.x0.z[i] - iv.point[2];
      nodes.v.x[i] = iv.v[0] + iv.omega * (ay * rz - az * ry);
      nodes.v.y[i] = iv.v[1] + iv.omega * (az * rx - ax * rz);
      nodes.v.z[i] = iv.v[2] + iv.omega * (ax * ry - ay * rx);
      // Nodes with rotations turn with the field: omega * axis (a rigid rotation).
      if (const std::int32_t r = state.rotations.index(i); r >= 0) {
        state.rotations.w.x[r] = iv.omega * ax + iv.w[0];
        state.rotations.w.y[r] = iv.omega * ay + iv.w[1];
        state.rotations.w.z[r] = iv.omega * az + iv.w[2];
      }
    }
  }
}

void set_body_force_masses(Boundary& boundary, const NodalState& nodes,
                           const std::vector<std::int32_t>& body_of_node,
                           const std::vector<double>* physical_mass) {
  boundary.body_force_mass = physical_mass ? *physical_mass : nodes.mass;
  if (body_of_node.empty()) return;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (body_of_node[i] >= 0) boundary.body_force_mass[i] = 0.0;
  }
}

void compute_external_forces(const Boundary& boundary, double t, State& state) {
  NodalState& nodes = state.nodes;
  std::fill(nodes.f_ext.x.begin(), nodes.f_ext.x.end(), 0.0);
  std::fill(nodes.f_ext.y.begin(), nodes.f_ext.y.end(), 0.0);
  std::fill(nodes.f_ext.z.begin(), nodes.f_ext.z.end(), 0.0);
  double* f[3] = {nodes.f_ext.x.data(), nodes.f_ext.y.data(), nodes.f_ext.z.data()};
  for (const auto& body : boundary.body_accelerations) {
    // LS-DYNA *LOAD_BODY prescribes a base acceleration: the body force is -m a.
    const double a = body.value(t);
    double* fa = f[body.axis];
    const std::size_t n = nodes.size();
    const double* mass = boundary.body_force_mass.data();
    for (std::size_t i = 0; i < n; ++i) fa[i] -= mass[i] * a;
  }
  for (const auto& load : boundary.nodal_forces) f[load.axis][load.node] += load.value(t);
  add_pressure_forces(boundary.pressure, t, state);
  RotationalState& rot = state.rotations;
  if (!rot.empty()) {
    std::fill(rot.m_ext.x.begin(), rot.m_ext.x.end(), 0.0);
    std::fill(rot.m_ext.y.begin(), rot.m_ext.y.end(), 0.0);
    std::fill(rot.m_ext.z.begin(), rot.m_ext.z.end(), 0.0);
    double* m[3] = {rot.m_ext.x.data(), rot.m_ext.y.data(), rot.m_ext.z.data()};
    for (const auto& load : boundary.nodal_moments) {
      m[load.axis][load.rotation] += load.value(t);
    }
  }
  add_damping_forces(boundary.damping, boundary.body_force_mass, t, state);
}

void constrain_accelerations(const Boundary& boundary, double t_n, State& state) {
  NodalState& nodes = state.nodes;
  double* a[3] = {nodes.a.x.data(), nodes.a.y.data(), nodes.a.z.data()};
  for (const auto i : boundary.constrained_nodes) {
    const std::uint8_t mask = boundary.fixed[i];
    for (int k = 0; k < 3; ++k) {
      if (mask & (1u << k)) a[k][i] = 0.0;
    }
  }
  for (const auto& p : boundary.prescribed) {
    if (p.vad == 1 && p.active(t_n)) a[p.axis][p.node] = p.value(t_n);
  }
  for (const auto& p : boundary.prescribed_directions) {
    if (p.rotation >= 0 || p.vad != 1 || !p.active(t_n)) continue;
    const std::int32_t i = p.node;
    const auto& n = p.direction;
    const double along = p.value(t_n) - (a[0][i] * n[0] + a[1][i] * n[1] + a[2][i] * n[2]);
    for (int k = 0; k < 3; ++k) a[k][i] += along * n[k];
  }
}

namespace {

// Coordinate `p.axis` of the point where a node turning about an axis (DOF 9..11) must be at
// t^n + dt: its reference position x0 turned about the axis by the angle theta(t^n + dt), so
// that it stays on its circle exactly (radius from x0). VAD 2 gives theta directly; VAD 0 the
// angular velocity, integrated from the node's present angle with the mid-step value (exact
// for a linear omega(t)), so that no state other than the positions is needed.
double rotated_position(const PrescribedDof& p, const double* const x[3], const double* const x0[3],
                        double t_n, double dt) {
  const int a = (p.rotation + 1) % 3, b = (p.rotation + 2) % 3;
  const std::int32_t i = p.node;
  const double qa = x0[a][i] - p.centre[0], qb = x0[b][i] - p.centre[1];
  double theta = 0.0;
  if (p.vad == 2) {
    theta = p.value(t_n + dt);
  } else {
    const double ra = x[a][i] - p.centre[0], rb = x[b][i] - p.centre[1];
    const double now = std::atan2(qa * rb - qb * ra, qa * ra + qb * rb);  // angle of x^n
    theta = now + dt * p.value(t_n + 0.5 * dt);
  }
  const double c = std::cos(theta), s = std::sin(theta);
  return p.axis == a ? p.centre[0] + c * qa - s * qb : p.centre[1] + s * qa + c * qb;
}

}  // namespace

void constrain_velocities(const Boundary& boundary, double t_n, double dt, State& state) {
  NodalState& nodes = state.nodes;
  double* v[3] = {nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
  const double* x[3] = {nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data()};
  const double* x0[3] = {nodes.x0.x.data(), nodes.x0.y.data(), nodes.x0.z.data()};
  for (const auto i : boundary.constrained_nodes) {
    const std::uint8_t mask = boundary.fixed[i];
    for (int k = 0; k < 3; ++k) {
      if (mask & (1u << k)) v[k][i] = 0.0;
    }
  }
  const double t_mid = t_n + 0.5 * dt;
  const double t_end = t_n + dt;
  for (const auto& p : boundary.prescribed) {
    if (p.rotation >= 0) {
      if (p.vad == 0 ? p.active(t_mid) : p.active(t_end)) {
        v[p.axis][p.node] = (rotated_position(p, x, x0, t_n, dt) - x[p.axis][p.node]) / dt;
      }
      continue;
    }
    if (p.vad == 0 && p.active(t_mid)) {
      v[p.axis][p.node] = p.value(t_mid);
    } else if (p.vad == 2 && p.active(t_end)) {
      const double u_now = x[p.axis][p.node] - x0[p.axis][p.node];
      v[p.axis][p.node] = (p.value(t_end) - u_now) / dt;
    }
  }
  // DOF 4: the velocity component along the vector; the normal components stay free.
  for (const auto& p : boundary.prescribed_directions) {
    if (p.rotation >= 0) continue;
    const std::int32_t i = p.node;
    const auto& n = p.direction;
    double target = 0.0;
    if (p.vad == 0 && p.active(t_mid)) {
      target = p.value(t_mid);
    } else if (p.vad == 2 && p.active(t_end)) {
      double u_now = 0.0;
      for (int k = 0; k < 3; ++k) u_now += (x[k][i] - x0[k][i]) * n[k];
      target = (p.value(t_end) - u_now) / dt;
    } else {
      continue;
    }
    const double along = target - (v[0][i] * n[0] + v[1][i] * n[1] + v[2][i] * n[2]);
    for (int k = 0; k < 3; ++k) v[k][i] += along * n[k];
  }
}

double constrain_rotations(const Boundary& boundary, double t_n, double dt, double dt_avg,
                           State& state) {
  RotationalState& rot = state.rotations;
  double* w[3] = {rot.w.x.data(), rot.w.y.data(), rot.w.z.data()};
  const double* w0[3] = {rot.w_previous.x.data(), rot.w_previous.y.data(), rot.w_previous.z.data()};
  const double* m_int[3] = {rot.m_int.x.data(), rot.m_int.y.data(), rot.m_int.z.data()};
  const double* m_ext[3] = {rot.m_ext.x.data(), rot.m_ext.y.data(), rot.m_ext.z.data()};
  const double t_mid = t_n + 0.5 * dt, t_end = t_n + dt;
  double work = 0.0;
  for (const auto& p : boundary.prescribed_directions) {
    if (p.rotation < 0) continue;
    const auto r = static_cast<std::size_t>(p.rotation);
    const auto& n = p.direction;
    auto along = [&](const double* const f[3]) {
      return f[0][r] * n[0] + f[1][r] * n[1] + f[2][r] * n[2];
    };
    double target = 0.0;
    if (p.vad == 0 && p.active(t_mid)) {
      target = p.value(t_mid);
    } else if (p.vad == 1 && p.active(t_n)) {
      target = along(w0) + dt_avg * p.value(t_n);
    } else if (p.vad == 2 && p.active(t_end)) {
      target = (p.value(t_end) - (p.active(t_n) ? p.value(t_n) : 0.0)) / dt;
    } else {
      continue;
    }
    const double change = target - along(w);
    for (int k = 0; k < 3; ++k) w[k][r] += change * n[k];
    // Reaction moment along the axis: I (omega_new - omega_old) / dt_avg minus the applied
    // moments, working through the step's rotation dt_avg (omega_old + omega_new) / 2 (the
    // global balance's rotation, Simulation::update_rotations).
    if (dt_avg > 0.0) {
      const double w_new = along(w), w_old = along(w0);
      const double reaction =
          rot.inertia[r] * (w_new - w_old) / dt_avg - (along(m_ext) - along(m_int));
      work += reaction * 0.5 * dt_avg * (w_old + w_new);
    }
  }
  return work;
}

}  // namespace rf::solver
