#include "solver/build_state.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "element/kernels.hpp"
#include "material/hyperelastic_setup.hpp"
#include "material/johnson_cook_setup.hpp"
#include "material/plastic_setup.hpp"
#include "material/registry.hpp"
#include "mesh/p_order.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"
#include "solver/mass_damping.hpp"

namespace rf::solver {

namespace {

using model::context_of;

// Interpolation order of each part from *CHANGE_P-ORDER cards (later cards win).
int part_order(const model::Model& model, model::Id pid) {
  int order = 1;
  for (const auto& change : model.p_order_changes) {
    bool applies = change.target == model::Target::All ||
                   (change.target == model::Target::Part && change.id == pid);
    if (change.target == model::Target::PartSet) {
      const auto it = model.part_sets.find(change.id);
      if (it == model.part_sets.end()) {
        throw InputError(context_of(change.where, "enid"),
                         fmt::format("part set {} is not defined", change.id));
      }
      for (const model::Id p : it->second.parts) applies |= p == pid;
    }
    if (applies) order = change.order;
  }
  return order;
}

// Moves nodes created on the mantle of a generated cylinder onto the exact surface, where the
// part asks for surface smoothing (IMPETUS *PART alpha_max) wider than the angle between the
// flat facets. A node qualifies when every corner of the edge or face it was created on lies
// on the mantle.
void project_onto_cylinders(const model::Model& model, const mesh::HexElevator& elevator,
                            const std::vector<std::int64_t>& part_of_new_node,
                            std::vector<std::array<double, 3>>& x) {
  for (const auto& cyl : model.cylinder_surfaces) {
    const auto part = model.parts.find(cyl.pid);
    if (part == model.parts.end() || !(part->second.smoothing_angle > cyl.facet_angle_deg)) {
      continue;
    }
    std::array<double, 3> axis{cyl.p2[0] - cyl.p1[0], cyl.p2[1] - cyl.p1[1], cyl.p2[2] - cyl.p1[2]};
    const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (double& a : axis) a /= length;
    const double tol = 1e-9 * std::max(cyl.radius, length);
    // Radial offset of a point from the axis, and its axial coordinate.
    auto split = [&](const std::array<double, 3>& p, std::array<double, 3>& radial) {
      const std::array<double, 3> d{p[0] - cyl.p1[0], p[1] - cyl.p1[1], p[2] - cyl.p1[2]};
      const double s = d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2];
      for (int k = 0; k < 3; ++k) radial[k] = d[k] - s * axis[k];
      return s;
    };
    auto on_mantle = [&](std::int32_t node) {
      std::array<double, 3> r{};
      const double s = split(x[static_cast<std::size_t>(node)], r);
      const double radius = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
      return std::abs(radius - cyl.radius) < tol && s > -tol && s < length + tol;
    };
    const auto& parents = elevator.parents();
    for (std::size_t i = 0; i < parents.size(); ++i) {
      if (parents[i].size() == 8 || part_of_new_node[i] != cyl.pid) continue;
      bool all = true;
      for (const std::int32_t corner : parents[i]) all = all && on_mantle(corner);
      if (!all) continue;
      auto& p = x[static_cast<std::size_t>(elevator.first_new_node()) + i];
      std::array<double, 3> r{};
      const double s = split(p, r);
      const double radius = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
      for (int k = 0; k < 3; ++k) {
        p[k] = cyl.p1[k] + s * axis[k] + r[k] * (cyl.radius / radius);
      }
    }
  }
}

// Raises the blocks whose parts have order > 1 (*CHANGE_P-ORDER) and appends the new nodes to
// the nodal arrays with IDs above every user node ID.
void elevate_blocks(const model::Model& model, State& state) {
  bool any = false;
  for (const auto& block : state.hex_blocks) any |= block.order > 1;
  if (!any) return;
  NodalState& nodes = state.nodes;
  // Parts of different order must not share nodes: the mesh would not be conforming.
  std::vector<int> order_of_node(nodes.size(), 0);
  std::vector<model::Id> part_of_node(nodes.size(), 0);
  for (const auto& block : state.hex_blocks) {
    for (const std::int32_t node : block.conn) {
      int& o = order_of_node[static_cast<std::size_t>(node)];
      if (o != 0 && o != block.order) {
        throw InputError(
            context_of(model.parts.at(block.part_id).where, "order"),
            fmt::format("part {} (order {}) shares node {} with part {} (order {}): parts "
                        "joined by nodes must have the same order (*CHANGE_P-ORDER)",
                        block.part_id, block.order, nodes.id[static_cast<std::size_t>(node)],
                        part_of_node[static_cast<std::size_t>(node)], o));
      }
      o = block.order;
      part_of_node[static_cast<std::size_t>(node)] = block.part_id;
    }
  }
  std::vector<std::array<double, 3>> x(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    x[i] = {nodes.x0.x[i], nodes.x0.y[i], nodes.x0.z[i]};
  }
  std::map<int, std::unique_ptr<mesh::HexElevator>> elevators;
  std::vector<std::int64_t> part_of_new_node;
  for (auto& block : state.hex_blocks) {
    if (block.order == 1) continue;
    auto& elevator = elevators[block.order];
    if (!elevator) elevator = std::make_unique<mesh::HexElevator>(block.order, x);
    std::vector<std::int32_t> conn;
    conn.reserve(block.size() * static_cast<std::size_t>(block.nodes_per_element()));
    for (std::size_t e = 0; e < block.size(); ++e) {
      std::array<std::int32_t, 8> corners{};
      std::copy_n(&block.conn[8 * e], 8, corners.begin());
      try {
        const auto elevated = elevator->elevate(corners);
        conn.insert(conn.end(), elevated.begin(), elevated.end());
      } catch (const std::invalid_argument& error) {
        throw InputError(context_of(model.parts.at(block.part_id).where, "order"),
                         fmt::format("element {} of part {}: {}", block.element_id[e],
                                     block.part_id, error.what()));
      }
    }
    block.conn = std::move(conn);
    part_of_new_node.resize(x.size() - nodes.size(), block.part_id);
  }
  // One elevator per order, so new nodes of different orders interleave only by block; the
  // projection needs each elevator's own parent list.
  for (const auto& [order, elevator] : elevators) {
    std::vector<std::int64_t> part_of(elevator->parents().size(), 0);
    const std::size_t offset = static_cast<std::size_t>(elevator->first_new_node()) - nodes.size();
    for (std::size_t i = 0; i < part_of.size() && offset + i < part_of_new_node.size(); ++i) {
      part_of[i] = part_of_new_node[offset + i];
    }
    project_onto_cylinders(model, *elevator, part_of, x);
  }
  model::Id next_id = 0;
  for (const model::Id id : nodes.id) next_id = std::max(next_id, id);
  const std::size_t old_count = nodes.size();
  nodes.id.resize(x.size());
  for (std::size_t i = old_count; i < x.size(); ++i) nodes.id[i] = ++next_id;
  nodes.x0.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    nodes.x0.x[i] = x[i][0];
    nodes.x0.y[i] = x[i][1];
    nodes.x0.z[i] = x[i][2];
  }
  state.generated_node_count = static_cast<std::int64_t>(x.size() - old_count);
}

// Mid-side nodes created for *ELEMENT_SOLID_TET4TOTET10 elements: one per edge (a pair of
// dense corner indices), shared by every element on that edge, numbered in the order they are
// first needed (parts in ID order, elements in input order, edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4)
// with user IDs above every node ID of the deck, so that they cannot clash with one.
struct MidsideNodes {
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> of_edge;
  model::Id next_id = 0;
  std::size_t node_count = 0;
};

// Appends the 10 dense node indices of a 10-node tetrahedron (LS-DYNA order) to conn, creating
// its mid-side nodes if it came from *ELEMENT_SOLID_TET4TOTET10 (midside all 0), and checks its
// shape (element/tet10_block.hpp, tet10_geometry_problem) with the element's file and line.
void append_quadratic_tetrahedron(const model::SolidElement& solid, model::Id pid,
                                  const NodeIndex& node_index, MidsideNodes& generated,
                                  NodalState& nodes, std::vector<std::int32_t>& conn) {
  static const char* const kNodeFields[] = {"N1", "N2", "N3", "N4", "N5",
                                            "N6", "N7", "N8", "N9", "N10"};
  std::int32_t dense[10];
  for (int k = 0; k < 4; ++k) dense[k] = node_index.at(solid.nodes[k], solid.where, kNodeFields[k]);
  const bool convert = solid.midside[0] == 0;
  for (int m = 0; m < 6; ++m) {
    if (!convert) {
      dense[4 + m] = node_index.at(solid.midside[m], solid.where, kNodeFields[4 + m]);
      continue;
    }
    const std::int32_t a = dense[element::kTet10Edge[m][0]], b = dense[element::kTet10Edge[m][1]];
    const auto key = std::minmax(a, b);
    const auto [it, inserted] = generated.of_edge.try_emplace({key.first, key.second}, 0);
    if (inserted) {
      if (generated.next_id == 0)
        for (const model::Id id : nodes.id) generated.next_id = std::max(generated.next_id, id);
      const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
      const double mid[3] = {0.5 * (nodes.x0.x[ua] + nodes.x0.x[ub]),
                             0.5 * (nodes.x0.y[ua] + nodes.x0.y[ub]),
                             0.5 * (nodes.x0.z[ua] + nodes.x0.z[ub])};
      it->second = static_cast<std::int32_t>(nodes.id.size());
      nodes.id.push_back(++generated.next_id);
      nodes.x0.x.push_back(mid[0]);
      nodes.x0.y.push_back(mid[1]);
      nodes.x0.z.push_back(mid[2]);
      ++generated.node_count;
    }
    dense[4 + m] = it->second;
  }
  double x[10][3];
  for (int k = 0; k < 10; ++k) {
    const auto i = static_cast<std::size_t>(dense[k]);
    x[k][0] = nodes.x0.x[i];
    x[k][1] = nodes.x0.y[i];
    x[k][2] = nodes.x0.z[i];
  }
  const std::string problem = element::tet10_geometry_problem(x);
  if (!problem.empty()) {
    throw InputError(context_of(solid.where, "N1"),
                     fmt::format("element {} of part {} (ELFORM 16, 10-node tetrahedron): {}",
                                 solid.id, pid, problem));
  }
  conn.insert(conn.end(), dense, dense + 10);
}

}  // namespace

element::HourglassSettings resolve_hourglass(const model::Model& model, const model::Part& part) {
  element::HourglassSettings hg;
  hg.ihq = model.hourglass_control.ihq;
  hg.qm = model.hourglass_control.qh;
  if (part.hgid != 0) {
    const auto it = model.hourglass.find(part.hgid);
    if (it == model.hourglass.end()) {
      throw InputError(
          context_of(part.where, "HGID"),
          fmt::format("part {} refers to *HOURGLASS {}, which is not defined", part.id, part.hgid));
    }
    if (it->second.ihq != 0) hg.ihq = it->second.ihq;
    if (it->second.qm > 0.0) hg.qm = it->second.qm;
  }
  if (hg.ihq < 1 || hg.ihq > 6) {
    throw InputError(
        context_of(part.where, "HGID"),
        fmt::format("hourglass type IHQ={} for part {} is not supported (1-6)", hg.ihq, part.id));
  }
  return hg;
}

// LS-DYNA decks: *CONTROL_BULK_VISCOSITY (on with LS-DYNA's defaults when absent), the part's
// *HOURGLASS Q1/Q2 where given. IMPETUS decks: none (docs/impetus.md). Order > 1 (Lagrange
// hexahedra): not applied (docs/theory.md).
element::BulkViscositySettings resolve_bulk_viscosity(const model::Model& model,
                                                      const model::Part& part) {
  element::BulkViscositySettings bv;
  if (model.dialect == "impetus") return bv;
  bv.q1 = model.bulk_viscosity.q1;
  bv.q2 = model.bulk_viscosity.q2;
  if (part.hgid != 0) {
    const auto it = model.hourglass.find(part.hgid);
    if (it != model.hourglass.end()) {
      if (!std::isnan(it->second.q1)) bv.q1 = it->second.q1;
      if (!std::isnan(it->second.q2)) bv.q2 = it->second.q2;
    }
  }
  return bv;
}

ResolvedMaterial resolve_material(const model::Model& model, const model::Part& part,
                                  unsigned family, const char* family_name) {
  const auto mat_it = model.materials.find(part.mid);
  if (mat_it == model.materials.end()) {
    throw InputError(
        context_of(part.where, "MID"),
        fmt::format("part {} refers to material {}, which is not defined", part.id, part.mid));
  }
  const model::Material& mat = mat_it->second;
  ResolvedMaterial out;
  out.rigid = mat.kind == model::MaterialKind::Rigid;
  out.elastic = material::make_elastic(mat.rho, mat.e, mat.pr);
  if (out.rigid) return out;
  if (model::is_discrete_material(mat.kind)) {
    throw InputError(context_of(part.where, "MID"),
                     fmt::format("part {} has {} but its material {} is a {}, which serves "
                                 "only *ELEMENT_DISCRETE parts",
                                 part.id, family_name, mat.id, mat.keyword));
  }
  out.index = material::material_index(mat.kind);
  if (out.index < 0) {
    throw InputError(context_of(mat.where, "MID"),
                     fmt::format("part {} uses {} (material {}), which this version does not "
                                 "simulate yet",
                                 part.id, mat.keyword, mat.id));
  }
  // The registry says which element families the material runs on (material/registry.hpp).
  if (!material::serves(out.index, static_cast<material::ElementFamily>(family))) {
    throw InputError(context_of(part.where, "MID"),
                     fmt::format("part {} uses {} (material {}) on {}, which this material does "
                                 "not run on yet",
                                 part.id, mat.keyword, mat.id, family_name));
  }
  if (mat.kind == model::MaterialKind::PlasticKinematic ||
      mat.kind == model::MaterialKind::PiecewiseLinearPlasticity)
    out.plastic = material::make_plastic_parameters(model, mat);
  if (mat.kind == model::MaterialKind::ThreeParameterBarlat)
    out.barlat = material::make_barlat_parameters(model, mat);
  return out;
}

NodeIndex::NodeIndex(const model::Model& model) {
  index_.reserve(model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    index_.emplace(model.nodes[i].id, static_cast<std::int32_t>(i));
  }
}

std::int32_t NodeIndex::at(model::Id id, const model::SourceLocation& where,
                           const char* field) const {
  const auto it = index_.find(id);
  if (it == index_.end()) {
    throw InputError(context_of(where, field), fmt::format("node {} is not defined", id));
  }
  return it->second;
}

State build_state(const model::Model& model, const NodeIndex& node_index) {
  // LS-DYNA's BTYPE 1/2 add bulk viscosity to beams, which RigidFlex does not do: accepted only
  // where it changes nothing. (TYPE -1/-2 act on shells: build_structural.cpp.)
  const model::BulkViscosityControl& bulk = model.bulk_viscosity;
  if (bulk.btype != 0 && !model.beams.empty()) {
    throw InputError(context_of(bulk.where, "BTYPE"),
                     fmt::format("bulk viscosity in beams (BTYPE {}) is not supported (the model "
                                 "has {} beam elements): use BTYPE 0",
                                 bulk.btype, model.beams.size()));
  }
  // An equation of state belongs to a *MAT_JOHNSON_COOK part (the only material that takes one).
  for (const auto& [pid, part] : model.parts) {
    if (part.eosid == 0) continue;
    const auto mat_it = model.materials.find(part.mid);
    if (mat_it != model.materials.end() && mat_it->second.kind != model::MaterialKind::JohnsonCook)
      throw InputError(context_of(part.where, "EOSID"),
                       fmt::format("part {} gives equation of state {} but its material {} is a "
                                   "{}, which takes no equation of state (only "
                                   "*MAT_JOHNSON_COOK does here; leave EOSID blank)",
                                   pid, part.eosid, part.mid, mat_it->second.keyword));
  }
  State state;
  NodalState& nodes = state.nodes;
  const std::size_t model_nodes = model.nodes.size();
  nodes.id.resize(model_nodes);
  nodes.x0.resize(model_nodes);
  for (std::size_t i = 0; i < model_nodes; ++i) {
    nodes.id[i] = model.nodes[i].id;
    nodes.x0.x[i] = model.nodes[i].x[0];
    nodes.x0.y[i] = model.nodes[i].x[1];
    nodes.x0.z[i] = model.nodes[i].x[2];
  }

  MidsideNodes generated;
  // Group elements by part in part-ID order; input order is kept within a part so that
  // results do not depend on how the deck interleaves parts.
  std::map<model::Id, std::vector<std::size_t>> elements_of_part;
  for (std::size_t e = 0; e < model.solids.size(); ++e) {
    elements_of_part[model.solids[e].pid].push_back(e);
  }

  for (const auto& [pid, element_indices] : elements_of_part) {
    const auto& first = model.solids[element_indices.front()];
    const auto part_it = model.parts.find(pid);
    if (part_it == model.parts.end()) {
      throw InputError(
          context_of(first.where, "PID"),
          fmt::format("element {} refers to part {}, which is not defined", first.id, pid));
    }
    const model::Part& part = part_it->second;
    const auto sec_it = model.solid_sections.find(part.secid);
    if (sec_it == model.solid_sections.end()) {
      throw InputError(context_of(part.where, "SECID"),
                       fmt::format("part {} refers to *SECTION_SOLID {}, which is not defined", pid,
                                   part.secid));
    }
    const auto mat_it = model.materials.find(part.mid);
    if (mat_it == model.materials.end()) {
      throw InputError(
          context_of(part.where, "MID"),
          fmt::format("part {} refers to material {}, which is not defined", pid, part.mid));
    }
    const model::Material& mat = mat_it->second;
    const int material_index = material::material_index(mat.kind);
    if (model::is_discrete_material(mat.kind)) {
      throw InputError(context_of(part.where, "MID"),
                       fmt::format("part {} has solid elements but its material {} is a {}, "
                                   "which serves only *ELEMENT_DISCRETE parts",
                                   pid, mat.id, mat.keyword));
    }
    if (material_index < 0 && mat.kind != model::MaterialKind::Rigid) {
      throw InputError(context_of(mat.where, "MID"),
                       fmt::format("part {} uses {} (material {}), which this version does not "
                                   "simulate yet",
                                   pid, mat.keyword, mat.id));
    }

    element::HexBlock block;
    block.part_id = pid;
    block.part_index = static_cast<int>(state.parts.size());
    // ELFORM 10, the one-point tetrahedron, is the ELFORM 1 kernel on LS-DYNA's degenerate
    // hexahedron n1 n2 n3 n4 n4 n4 n4 n4: hex_block.cpp evaluates it as the collapsed hexahedron
    // that reproduces the linear tetrahedron exactly, so its one-point gradient is the
    // constant-strain gradient. A tetrahedron has no hourglass modes (every velocity field of
    // four nodes is linear), so the hourglass control is switched off (QM 0): LS-DYNA's IHQ 1-3
    // base vectors are not orthogonal to linear fields on a collapsed element and would resist
    // ordinary deformation.
    // ELFORM 13, the nodal-pressure tetrahedron (element/tet13_block.hpp), keeps its number:
    // the hexahedron kernels hand its blocks to their own kernel.
    const int elform = sec_it->second.elform;
    const bool tetrahedra_only = elform == 10 || elform == 13;
    const bool quadratic = elform == 16;
    block.elform = elform == 10 ? 1 : elform;
    block.rigid = mat.kind == model::MaterialKind::Rigid;
    block.has_force_slots = !block.rigid;
    block.order = part_order(model, pid);
    if (quadratic && block.order != 1) {
      throw InputError(context_of(part.where, "SECID"),
                       fmt::format("part {} has *SECTION_SOLID {} ELFORM 16 (10-node "
                                   "tetrahedra) and *CHANGE_P-ORDER order {}: p-elevation "
                                   "serves hexahedra only",
                                   pid, part.secid, block.order));
    }
    // Rigid parts: the section and hourglass do not matter; E and PR only for contact later.
    if (!block.rigid) block.hourglass = resolve_hourglass(model, part);
    if (tetrahedra_only) block.hourglass.qm = 0.0;
    if (!block.rigid && block.order == 1)
      block.bulk_viscosity = resolve_bulk_viscosity(model, part);
    block.material = material::make_elastic(mat.rho, mat.e, mat.pr);
    if (!block.rigid) {
      // The registry says which element families the material runs on (material/registry.hpp).
      const auto family = block.order > 1 ? material::kLagrangeHex : material::kHex8;
      if (!material::serves(material_index, material::kHex8) &&
          material::serves(material_index, material::kShell)) {
        throw InputError(context_of(part.where, "MID"),
                         fmt::format("part {} uses {} (material {}) on solid elements: this "
                                     "material is a plane-stress law for shells only",
                                     pid, mat.keyword, mat.id));
      }
      if (elform == 13 && !block.rigid && !material::serves(material_index, material::kTet13)) {
        throw InputError(context_of(part.where, "MID"),
                         fmt::format("part {} uses {} (material {}) with *SECTION_SOLID {} ELFORM "
                                     "13, the nodal-pressure tetrahedron, which runs *MAT_ELASTIC, "
                                     "*MAT_PLASTIC_KINEMATIC, *MAT_PIECEWISE_LINEAR_PLASTICITY, "
                                     "*MAT_MOONEY-RIVLIN_RUBBER and *MAT_OGDEN_RUBBER only (use "
                                     "ELFORM 10 for this material)",
                                     pid, mat.keyword, mat.id, part.secid));
      }
      if (quadratic && !material::serves(material_index, material::kTet10)) {
        throw InputError(
            context_of(part.where, "MID"),
            fmt::format("part {} uses {} (material {}) with *SECTION_SOLID {} ELFORM "
                        "16, the 10-node tetrahedron, which runs *MAT_ELASTIC, "
                        "*MAT_PLASTIC_KINEMATIC, *MAT_PIECEWISE_LINEAR_PLASTICITY, "
                        "*MAT_MOONEY-RIVLIN_RUBBER and *MAT_OGDEN_RUBBER only (element "
                        "{} is the first of the part)",
                        pid, mat.keyword, mat.id, part.secid, first.id));
      }
      if (!material::serves(material_index, family)) {
        throw InputError(context_of(part.where, "MID"),
                         fmt::format("part {} uses {} (material {}) on order {} elements, which "
                                     "run elastic materials only (*MAT_ELASTIC); remove the part "
                                     "from *CHANGE_P-ORDER or use *MAT_ELASTIC",
                                     pid, mat.keyword, mat.id, block.order));
      }
      block.material_index = material_index;
      if (mat.kind == model::MaterialKind::PlasticKinematic ||
          mat.kind == model::MaterialKind::PiecewiseLinearPlasticity)
        block.plastic = material::make_plastic_parameters(model, mat);
      if (mat.kind == model::MaterialKind::MooneyRivlinRubber ||
          mat.kind == model::MaterialKind::OgdenRubber)
        block.hyperelastic = material::make_hyperelastic_parameters(mat);
      if (mat.kind == model::MaterialKind::JohnsonCook)
        block.johnson_cook =
            material::make_johnson_cook_parameters(model, part, mat, block.material);
    }
    block.element_id.reserve(element_indices.size());
    block.conn.reserve(element_indices.size() * static_cast<std::size_t>(quadratic ? 10 : 8));
    for (const std::size_t e : element_indices) {
      const auto& solid = model.solids[e];
      if (solid.ten_node != quadratic) {
        throw InputError(
            context_of(solid.where, quadratic ? "N1" : "N9"),
            quadratic
                ? fmt::format("element {} of part {} has 8 node fields (a hexahedron or 4-node "
                              "tetrahedron), but its section {} is ELFORM 16, the 10-node "
                              "tetrahedron: write N1..N10 on the second card or use "
                              "*ELEMENT_SOLID_TET4TOTET10",
                              solid.id, pid, part.secid)
                : fmt::format("element {} of part {} has 10 nodes, but its section {} is ELFORM "
                              "{}; 10-node tetrahedra need ELFORM 16",
                              solid.id, pid, part.secid, elform));
      }
      if (quadratic) {
        block.element_id.push_back(solid.id);
        append_quadratic_tetrahedron(solid, pid, node_index, generated, nodes, block.conn);
        continue;
      }
      if (tetrahedra_only) {
        std::array<model::Id, 8> sorted = solid.nodes;
        std::sort(sorted.begin(), sorted.end());
        const auto distinct = std::unique(sorted.begin(), sorted.end()) - sorted.begin();
        if (distinct != 4) {
          throw InputError(context_of(solid.where, "N1"),
                           fmt::format("element {} of part {} has {} distinct nodes, but its "
                                       "section {} is ELFORM {}, the 4-node {}tetrahedron",
                                       solid.id, pid, distinct, part.secid, elform,
                                       elform == 13 ? "nodal-pressure " : ""));
        }
      }
      block.element_id.push_back(solid.id);
      for (int k = 0; k < 8; ++k) {
        block.conn.push_back(node_index.at(solid.nodes[k], solid.where, "N"));
      }
    }
    state.parts.push_back(
        PartInfo{pid, part.title, sec_it->second.elform, static_cast<std::int64_t>(block.size())});
    state.hex_blocks.push_back(std::move(block));
  }

  // p-elevation appends nodes; the nodal arrays are sized once all nodes exist.
  elevate_blocks(model, state);
  state.generated_node_count += static_cast<std::int64_t>(generated.node_count);
  const std::size_t total = nodes.id.size();
  nodes.x = nodes.x0;
  nodes.v.resize(total);
  nodes.a.resize(total);
  nodes.f_int.resize(total);
  nodes.f_ext.resize(total);
  nodes.mass.assign(total, 0.0);
  const std::size_t n_all = nodes.size();
  const element::NodalView view{nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
  for (auto& block : state.hex_blocks) {
    element::initialize_block(block, view);
    element::add_block_lumped_mass(block, nodes.mass);
  }
  build_structural_blocks(model, node_index, state);
  build_discrete_blocks(model, node_index, state);
  state.added_mass = add_mass_elements(model, node_index, state);

  // Node -> element-slot incidence, counted then filled (CSR).
  NodeIncidence& inc = state.incidence;
  const std::size_t n = n_all;
  inc.offset.assign(n + 1, 0);
  for (const auto& block : state.hex_blocks) {
    if (!block.has_force_slots) continue;
    for (const std::int32_t node : block.conn) ++inc.offset[node + 1];
  }
  for (std::size_t i = 0; i < n; ++i) inc.offset[i + 1] += inc.offset[i];
  inc.slot.resize(inc.offset[n]);
  inc.block.resize(inc.offset[n]);
  std::vector<std::int64_t> fill(inc.offset.begin(), inc.offset.end() - 1);
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    if (!state.hex_blocks[b].has_force_slots) continue;
    const auto& conn = state.hex_blocks[b].conn;
    for (std::size_t k = 0; k < conn.size(); ++k) {
      const std::int64_t pos = fill[conn[k]]++;
      inc.slot[pos] = static_cast<std::int64_t>(k) * 3;  // (element*npe + local)*3
      inc.block[pos] = static_cast<std::int32_t>(b);
    }
  }
  return state;
}

namespace {

AssemblyPlan make_assembly_plan(const State& state, int threads) {
  AssemblyPlan plan;
  plan.threads = threads;
  const std::int64_t n = static_cast<std::int64_t>(state.nodes.size());
  const std::size_t blocks = state.hex_blocks.size();
  plan.node_begin.resize(static_cast<std::size_t>(threads) + 1);
  for (int t = 0; t <= threads; ++t) plan.node_begin[t] = n * t / threads;
  plan.element_range.assign(static_cast<std::size_t>(threads) * blocks,
                            {std::numeric_limits<std::int64_t>::max(), 0});
  std::int64_t visited = 0, total = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    if (!state.hex_blocks[b].has_force_slots) continue;  // ranges stay empty
    const auto& conn = state.hex_blocks[b].conn;
    const int npe = state.hex_blocks[b].nodes_per_element();
    const std::int64_t elements = static_cast<std::int64_t>(conn.size() / npe);
    total += elements;
    for (std::int64_t e = 0; e < elements; ++e) {
      for (int k = 0; k < npe; ++k) {
        const std::int64_t node = conn[npe * e + k];
        // Owner of `node`: the t with node_begin[t] <= node < node_begin[t + 1].
        const auto it = std::upper_bound(plan.node_begin.begin(), plan.node_begin.end(), node);
        const std::size_t t = static_cast<std::size_t>(it - plan.node_begin.begin()) - 1;
        auto& r = plan.element_range[t * blocks + b];
        r.first = std::min(r.first, e);
        r.second = std::max(r.second, e + 1);
      }
    }
  }
  for (auto& r : plan.element_range) {
    if (r.first >= r.second) r = {0, 0};
    visited += r.second - r.first;
  }
  // Each thread rereads the connectivity of its range; beyond ~1.5x the element count the CSR
  // gather (which touches each slot once) is the better choice.
  plan.use_csr = 2 * visited > 3 * total;
  return plan;
}

void assemble_by_incidence(State& state) {
  NodalState& nodes = state.nodes;
  const NodeIncidence& inc = state.incidence;
  const std::int64_t n = static_cast<std::int64_t>(nodes.size());
  // Gather pointers once; the loop then touches only contiguous arrays.
  std::vector<const double*>& forces = state.block_force_pointers;
  forces.resize(state.hex_blocks.size());
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    forces[b] = state.hex_blocks[b].force.data();
  }
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    double fx = 0.0, fy = 0.0, fz = 0.0;
    for (std::int64_t k = inc.offset[i]; k < inc.offset[i + 1]; ++k) {
      const double* f = forces[inc.block[k]] + inc.slot[k];
      fx += f[0];
      fy += f[1];
      fz += f[2];
    }
    nodes.f_int.x[i] = fx;
    nodes.f_int.y[i] = fy;
    nodes.f_int.z[i] = fz;
  }
}

// Adds the force slots of elements [first, last) to the nodes in [lo, hi). kNodes > 0 fixes the
// element's node count at compile time (the 8-node hot path); 0 takes it from `npe`.
template <int kNodes>
void scatter_range(const std::int32_t* conn, const double* force, std::int64_t first,
                   std::int64_t last, std::int64_t lo, std::int64_t hi, double* fx, double* fy,
                   double* fz, int npe = kNodes) {
  const int nodes = kNodes > 0 ? kNodes : npe;
  for (std::int64_t e = first; e < last; ++e) {
    for (int k = 0; k < nodes; ++k) {
      const std::int64_t node = conn[nodes * e + k];
      if (node < lo || node >= hi) continue;
      const double* f = force + 3 * (nodes * e + k);
      fx[node] += f[0];
      fy[node] += f[1];
      fz[node] += f[2];
    }
  }
}

// Element-order scatter (see AssemblyPlan): streams the element force slots and the
// connectivity once instead of chasing the incidence lists, which made the CSR gather the second
// most expensive part of a cycle after the element kernels.
void assemble_by_elements(State& state) {
  NodalState& nodes = state.nodes;
  const AssemblyPlan& plan = state.assembly_plan;
  const std::size_t blocks = state.hex_blocks.size();
  double* fx = nodes.f_int.x.data();
  double* fy = nodes.f_int.y.data();
  double* fz = nodes.f_int.z.data();
#pragma omp parallel num_threads(plan.threads)
  // Strided so that every range is done even if the runtime grants fewer threads.
  for (int t = omp_get_thread_num(); t < plan.threads; t += omp_get_num_threads()) {
    const std::int64_t lo = plan.node_begin[t], hi = plan.node_begin[t + 1];
    std::fill(fx + lo, fx + hi, 0.0);
    std::fill(fy + lo, fy + hi, 0.0);
    std::fill(fz + lo, fz + hi, 0.0);
    for (std::size_t b = 0; b < blocks; ++b) {
      const auto [first, last] = plan.element_range[static_cast<std::size_t>(t) * blocks + b];
      const std::int32_t* conn = state.hex_blocks[b].conn.data();
      const double* force = state.hex_blocks[b].force.data();
      const int npe = state.hex_blocks[b].nodes_per_element();
      if (npe == 8) {
        scatter_range<8>(conn, force, first, last, lo, hi, fx, fy, fz);
      } else {
        scatter_range<0>(conn, force, first, last, lo, hi, fx, fy, fz, npe);
      }
    }
  }
}

}  // namespace

void assemble_internal_forces(State& state) {
  const int threads = omp_get_max_threads();
  if (state.assembly_plan.threads != threads) {
    state.assembly_plan = make_assembly_plan(state, threads);
  }
  if (state.assembly_plan.use_csr)
    assemble_by_incidence(state);
  else
    assemble_by_elements(state);
}
}  // namespace rf::solver
