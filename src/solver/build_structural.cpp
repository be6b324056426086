// Shell and beam blocks in the solver state: one block per part, the rotational degrees of
// freedom of their nodes, lumped masses and inertias, and the structural incidence that gathers
// their forces and moments (docs/architecture.md, "Element families").
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "material/element_family.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"
#include "solver/build_state.hpp"

namespace rf::solver {

namespace {

using model::context_of;

const model::Part& part_of(const model::Model& model, model::Id pid, model::Id eid,
                           const model::SourceLocation& where) {
  const auto it = model.parts.find(pid);
  if (it == model.parts.end()) {
    throw InputError(context_of(where, "PID"),
                     fmt::format("element {} refers to part {}, which is not defined", eid, pid));
  }
  return it->second;
}

// The elements of one part of a family with the part's section and material resolved.
template <class Section>
struct PartGroup {
  model::Id pid = 0;
  const model::Part* part = nullptr;
  const Section* section = nullptr;
  ResolvedMaterial material;
  std::vector<std::size_t> elements;  // indices into the model's element list, input order
};

// Groups a family's elements by part (parts in ID order, elements in input order) and resolves
// each part's section (which must be of the family) and material.
template <class Elements, class Sections>
std::vector<PartGroup<typename Sections::mapped_type>> group_by_part(
    const model::Model& model, const Elements& elements, const Sections& sections,
    unsigned family, const char* family_name, const char* section_keyword) {
  std::map<model::Id, std::vector<std::size_t>> elements_of_part;
  for (std::size_t e = 0; e < elements.size(); ++e) elements_of_part[elements[e].pid].push_back(e);
  std::vector<PartGroup<typename Sections::mapped_type>> groups;
  for (auto& [pid, indices] : elements_of_part) {
    const auto& first = elements[indices.front()];
    const model::Part& part = part_of(model, pid, first.id, first.where);
    const auto sec = sections.find(part.secid);
    if (sec == sections.end()) {
      throw InputError(context_of(part.where, "SECID"),
                       fmt::format("part {} has {} but section {} is not a {}", pid, family_name,
                                   part.secid, section_keyword));
    }
    groups.push_back({pid, &part, &sec->second,
                      resolve_material(model, part, family, family_name), std::move(indices)});
  }
  return groups;
}

// Shell parts: sections resolved, elements in input order within a part, parts in ID order.
void build_shell_blocks(const model::Model& model, const NodeIndex& node_index, State& state) {
  // The contacts keep the shells' initial thickness offset (LS-DYNA's THKCHG 0): a deck that
  // asks them to follow a thickness update is refused rather than run otherwise.
  if (model.shell_control.istupd != 0 && model.contact_control.thkchg != 0 &&
      !model.shells.empty()) {
    throw InputError(context_of(model.contact_control.where, "THKCHG"),
                     fmt::format("THKCHG {} (contact thickness following the shell thickness "
                                 "update of *CONTROL_SHELL ISTUPD {}) is not supported: the "
                                 "contacts keep the initial shell thickness (THKCHG 0)",
                                 model.contact_control.thkchg, model.shell_control.istupd));
  }
  for (const auto& group : group_by_part(model, model.shells, model.shell_sections,
                                         material::kShell, "shell elements", "*SECTION_SHELL")) {
    const model::Id pid = group.pid;
    const model::Part& part = *group.part;
    const model::SectionShell& section = *group.section;
    const ResolvedMaterial& material = group.material;
    const std::vector<std::size_t>& indices = group.elements;
    element::ShellBlock block;
    block.part_id = pid;
    block.part_index = static_cast<int>(state.parts.size());
    block.elform = section.elform != 0 ? section.elform : model.shell_control.theory;
    block.rigid = material.rigid;
    block.has_force_slots = !material.rigid;
    block.material = material.elastic;
    block.material_index = std::max(material.index, 0);
    block.plastic = material.plastic;
    block.barlat = material.barlat;
    if (!block.rigid) {
      block.hourglass = resolve_hourglass(model, part);
      if (block.hourglass.ihq > 5) {
        throw InputError(context_of(part.where, "HGID"),
                         fmt::format("hourglass type IHQ {} is not defined for shells of part "
                                     "{} (1-5)",
                                     block.hourglass.ihq, pid));
      }
      // TYPE -1 and -2 differ in LS-DYNA only in whether the shells' viscous dissipation enters
      // the energy balance (-2) or not (-1); RigidFlex always accounts it (glstat's bulk
      // viscosity energy), so both act the same.
      if (model.bulk_viscosity.type < 0) block.bulk_viscosity = resolve_bulk_viscosity(model, part);
    }
    block.shear_factor = section.shrf;
    block.nip = section.nip;
    // *CONTROL_SHELL INTGRD 1 asks for Lobatto with 3..10 points (LS-DYNA keeps Gauss below).
    block.rule = model.shell_control.intgrd == 1 && section.nip >= 3
                     ? element::ThroughThicknessRule::kLobatto
                     : element::ThroughThicknessRule::kGauss;
    block.warping_correction = model.shell_control.bwc == 1;
    // *CONTROL_SHELL ISTUPD 1/4 (shell_block.cpp, section 12). A rigid part runs no kernel, so
    // its thickness stays as it is until it is switched deformable again.
    block.thickness_update = model.shell_control.istupd;
    block.element_id.reserve(indices.size());
    for (const std::size_t e : indices) {
      const auto& shell = model.shells[e];
      block.element_id.push_back(shell.id);
      for (int k = 0; k < 4; ++k) {
        block.conn.push_back(node_index.at(shell.nodes[k], shell.where, "N"));
        // *ELEMENT_SHELL_THICKNESS overrides the section's T1..T4 where given.
        const double t = shell.thickness[k] > 0.0 ? shell.thickness[k] : section.t[k];
        block.thickness.push_back(t);
      }
      block.triangle.push_back(shell.nodes[2] == shell.nodes[3] ? 1 : 0);
    }
    state.parts.push_back(PartInfo{pid, part.title, block.elform,
                                   static_cast<std::int64_t>(block.size())});
    state.shell_blocks.push_back(std::move(block));
  }
}

// A default s axis for a beam without third node or vector: the global axis least aligned with
// the beam, made perpendicular to it (documented in docs/elements.md).
std::array<double, 3> default_orientation(const std::array<double, 3>& axis) {
  int least = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(axis[k]) < std::abs(axis[least])) least = k;
  }
  std::array<double, 3> s{};
  s[least] = 1.0;
  return s;
}

void build_beam_blocks(const model::Model& model, const NodeIndex& node_index, State& state) {
  const NodalState& nodes = state.nodes;
  for (const auto& group : group_by_part(model, model.beams, model.beam_sections, material::kBeam,
                                         "beam elements", "*SECTION_BEAM")) {
    const model::Id pid = group.pid;
    const model::Part& part = *group.part;
    const model::SectionBeam& section = *group.section;
    const ResolvedMaterial& material = group.material;
    const std::vector<std::size_t>& indices = group.elements;
    element::BeamBlock block;
    block.part_id = pid;
    block.part_index = static_cast<int>(state.parts.size());
    block.elform = section.elform;
    block.rigid = material.rigid;
    block.has_force_slots = !material.rigid;
    block.material = material.elastic;
    block.material_index = std::max(material.index, 0);
    block.plastic = material.plastic;
    block.area = section.a;
    block.iss = section.iss;
    block.itt = section.itt;
    block.torsion = section.j;
    block.shear_area = section.sa;
    block.shear_factor = section.shrf;
    block.cross_section = section.cst == 1 ? element::BeamCrossSection::kTubular
                                           : element::BeamCrossSection::kRectangular;
    block.ts1 = section.ts1;
    block.ts2 = section.ts2;
    block.tt1 = section.tt1;
    block.tt2 = section.tt2;
    for (const std::size_t e : indices) {
      const auto& beam = model.beams[e];
      block.element_id.push_back(beam.id);
      const std::int32_t a = node_index.at(beam.nodes[0], beam.where, "N1");
      const std::int32_t b = node_index.at(beam.nodes[1], beam.where, "N2");
      block.conn.push_back(a);
      block.conn.push_back(b);
      const std::array<double, 3> axis{nodes.x0.x[b] - nodes.x0.x[a], nodes.x0.y[b] - nodes.x0.y[a],
                                       nodes.x0.z[b] - nodes.x0.z[a]};
      std::array<double, 3> s{};
      if (beam.orientation) {
        s = *beam.orientation;
      } else if (beam.nodes[2] != 0) {
        const std::int32_t c = node_index.at(beam.nodes[2], beam.where, "N3");
        s = {nodes.x0.x[c] - nodes.x0.x[a], nodes.x0.y[c] - nodes.x0.y[a],
             nodes.x0.z[c] - nodes.x0.z[a]};
      } else {
        s = default_orientation(axis);
      }
      // The orientation must not be parallel to the axis (it fixes the section's s axis).
      const double cx = axis[1] * s[2] - axis[2] * s[1];
      const double cy = axis[2] * s[0] - axis[0] * s[2];
      const double cz = axis[0] * s[1] - axis[1] * s[0];
      const double la = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
      const double ls = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
      if (!(la > 0.0)) {
        throw InputError(context_of(beam.where, "N2"),
                         fmt::format("beam {} has zero length (nodes {} and {} coincide)",
                                     beam.id, beam.nodes[0], beam.nodes[1]));
      }
      if (block.elform != 3 && !(std::sqrt(cx * cx + cy * cy + cz * cz) > 1e-6 * la * ls)) {
        throw InputError(context_of(beam.where, beam.orientation ? "VX" : "N3"),
                         fmt::format("beam {}: the orientation {} is parallel to the beam axis",
                                     beam.id, beam.orientation ? "vector" : "node"));
      }
      block.orientation.insert(block.orientation.end(), s.begin(), s.end());
    }
    state.parts.push_back(PartInfo{pid, part.title, block.elform,
                                   static_cast<std::int64_t>(block.size())});
    state.beam_blocks.push_back(std::move(block));
  }
}

// Rotational indices for every node of a shell or a non-truss beam, in dense node order.
void number_rotations(State& state) {
  const std::size_t n = state.nodes.size();
  RotationalState& rot = state.rotations;
  std::vector<std::uint8_t> needs(n, 0);
  for (const auto& block : state.shell_blocks) {
    for (const std::int32_t i : block.conn) needs[static_cast<std::size_t>(i)] = 1;
  }
  for (const auto& block : state.beam_blocks) {
    if (block.elform == 3) continue;
    for (const std::int32_t i : block.conn) needs[static_cast<std::size_t>(i)] = 1;
  }
  if (std::find(needs.begin(), needs.end(), 1) == needs.end()) return;
  rot.of_node.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (!needs[i]) continue;
    rot.of_node[i] = static_cast<std::int32_t>(rot.node.size());
    rot.node.push_back(static_cast<std::int32_t>(i));
  }
  const std::size_t r = rot.node.size();
  rot.w.resize(r);
  rot.w_previous.resize(r);
  rot.m_int.resize(r);
  rot.m_ext.resize(r);
  rot.inertia.assign(r, 0.0);
  for (auto& block : state.shell_blocks) {
    block.rotation_conn.resize(block.conn.size());
    for (std::size_t k = 0; k < block.conn.size(); ++k) {
      block.rotation_conn[k] = rot.of_node[static_cast<std::size_t>(block.conn[k])];
    }
  }
  for (auto& block : state.beam_blocks) {
    block.rotation_conn.resize(block.conn.size());
    for (std::size_t k = 0; k < block.conn.size(); ++k) {
      block.rotation_conn[k] =
          block.elform == 3 ? -1 : rot.of_node[static_cast<std::size_t>(block.conn[k])];
    }
  }
}

}  // namespace

void build_structural_blocks(const model::Model& model, const NodeIndex& node_index,
                             State& state) {
  build_shell_blocks(model, node_index, state);
  build_beam_blocks(model, node_index, state);
  if (state.shell_blocks.empty() && state.beam_blocks.empty()) return;
  number_rotations(state);
  NodalState& nodes = state.nodes;
  const element::NodalView view{nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
  std::vector<double> unused_inertia;  // trusses of a model without rotations
  auto& inertia = state.rotations.empty() ? unused_inertia : state.rotations.inertia;
  for (auto& block : state.shell_blocks) {
    element::initialize_shell_block(block, view);
    element::add_shell_lumped_mass(block, nodes.mass, inertia);
  }
  for (auto& block : state.beam_blocks) {
    element::initialize_beam_block(block, view);
    element::add_beam_lumped_mass(block, nodes.mass, inertia);
  }

  // Structural incidence: node -> (block, slot) in ascending (shells, beams; block; element;
  // local node) order.
  StructuralIncidence& inc = state.structural_incidence;
  const std::size_t n = nodes.size();
  inc.offset.assign(n + 1, 0);
  inc.forces.clear();
  struct Source {
    const std::vector<std::int32_t>* conn;
    int slot_stride;  // entries per local node in the block's force array (6)
    bool active;
  };
  std::vector<Source> sources;
  for (const auto& block : state.shell_blocks) sources.push_back({&block.conn, 6, block.has_force_slots});
  for (const auto& block : state.beam_blocks) sources.push_back({&block.conn, 6, block.has_force_slots});
  for (const auto& source : sources) {
    if (!source.active) continue;
    for (const std::int32_t i : *source.conn) ++inc.offset[static_cast<std::size_t>(i) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) inc.offset[i + 1] += inc.offset[i];
  inc.slot.resize(static_cast<std::size_t>(inc.offset[n]));
  inc.block.resize(static_cast<std::size_t>(inc.offset[n]));
  std::vector<std::int64_t> fill(inc.offset.begin(), inc.offset.end() - 1);
  for (std::size_t b = 0; b < sources.size(); ++b) {
    if (!sources[b].active) continue;
    const auto& conn = *sources[b].conn;
    for (std::size_t k = 0; k < conn.size(); ++k) {
      const std::int64_t pos = fill[static_cast<std::size_t>(conn[k])]++;
      inc.slot[static_cast<std::size_t>(pos)] = static_cast<std::int64_t>(k) * sources[b].slot_stride;
      inc.block[static_cast<std::size_t>(pos)] = static_cast<std::int32_t>(b);
    }
  }
}

void assemble_structural_forces(State& state) {
  StructuralIncidence& inc = state.structural_incidence;
  if (inc.offset.empty()) return;
  inc.forces.clear();
  for (const auto& block : state.shell_blocks) inc.forces.push_back(block.force.data());
  for (const auto& block : state.beam_blocks) inc.forces.push_back(block.force.data());
  NodalState& nodes = state.nodes;
  RotationalState& rot = state.rotations;
  const std::int64_t n = static_cast<std::int64_t>(nodes.size());
  const bool rotations = !rot.empty();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t begin = inc.offset[i], end = inc.offset[i + 1];
    if (begin == end) continue;
    double f[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (std::int64_t k = begin; k < end; ++k) {
      const double* slot = inc.forces[inc.block[k]] + inc.slot[k];
      for (int c = 0; c < 6; ++c) f[c] += slot[c];
    }
    nodes.f_int.x[i] += f[0];
    nodes.f_int.y[i] += f[1];
    nodes.f_int.z[i] += f[2];
    if (rotations) {
      const std::int32_t r = rot.of_node[static_cast<std::size_t>(i)];
      if (r >= 0) {
        rot.m_int.x[r] = f[3];
        rot.m_int.y[r] = f[4];
        rot.m_int.z[r] = f[5];
      }
    }
  }
}

}  // namespace rf::solver

namespace rf::solver {

// Subsystems that do not yet know shells and beams refuse a model that would need them, rather
// than run it with part of the physics missing (docs/elements.md lists what works).
void check_structural_support(const model::Model& model, const State& state) {
  if (state.shell_blocks.empty() && state.beam_blocks.empty()) return;
  // Contacts know shell segments (docs/contact.md); beam parts on a contact side are refused
  // by contact::build_contacts, which names the part. Part switching knows every family
  // (docs/switching.md, "Shells and beams"); flexible bodies of *MAT_RIGID shell and beam parts
  // carry the modes' rotations (docs/flexible_bodies.md section 9). A deformable shell or beam
  // part with *PART_MODES (a flexible body by switching) does not: its switch would freeze
  // shell stresses and restore them with a translational modal increment only.
  for (const auto& [pid, card] : model.part_modes) {
    const auto part = model.parts.find(pid);
    if (part == model.parts.end()) continue;
    const auto material = model.materials.find(part->second.mid);
    if (material == model.materials.end() ||
        material->second.kind == model::MaterialKind::Rigid) {
      continue;
    }
    bool structural = false;
    for (const auto& block : state.shell_blocks) structural = structural || block.part_id == pid;
    for (const auto& block : state.beam_blocks) structural = structural || block.part_id == pid;
    if (structural) {
      throw InputError(model::context_of(card.where, "PID"),
                       fmt::format("part {} is a deformable shell or beam part: *PART_MODES on "
                                   "it (a flexible body made by switching) is not supported; "
                                   "flexible bodies of shells and beams must be *MAT_RIGID "
                                   "parts",
                                   pid));
    }
  }
}

}  // namespace rf::solver
