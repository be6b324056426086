// After every file is read: resolve what needed the whole deck, then check that every
// reference points at something defined. Errors name the referring definition.
#include <fmt/format.h>

#include <unordered_set>

#include "io/keyword/context.hpp"

namespace rf::io {

std::string ReaderContext::origin_text(const std::pair<int, int>& origin) const {
  const auto index = static_cast<std::size_t>(origin.first);
  const std::string& file = index < model.files.size() ? model.files[index] : std::string();
  return fmt::format("{}:{}", file, origin.second);
}

void warn_unread_lines(const Block& block, CardCursor& cursor, ReaderContext& context) {
  cursor.skip_blank_lines();
  if (cursor.at_end()) return;
  const DataLine* line = cursor.peek();
  context.warn({block.file, line->number, block.keyword},
               fmt::format("{} data line(s) after the last card of {} ignored", cursor.remaining(),
                           block.keyword));
}

namespace {

using model::Id;

void check_curve(const model::Model& m, Id lcid, const model::SourceLocation& where,
                 const char* field) {
  if (!m.curves.count(lcid)) {
    throw located_error(where, field, fmt::format("load curve {} is not defined", lcid));
  }
}

void check_target(const model::Model& m, const std::unordered_set<Id>& nodes, model::Target target,
                  Id id, const model::SourceLocation& where) {
  switch (target) {
    case model::Target::Node:
      if (!nodes.count(id))
        throw located_error(where, "NID", fmt::format("node {} is not defined", id));
      break;
    case model::Target::NodeSet:
      if (!m.node_sets.count(id)) {
        throw located_error(where, "NSID", fmt::format("node set {} is not defined", id));
      }
      break;
    case model::Target::Part:
      if (!m.parts.count(id))
        throw located_error(where, "ID", fmt::format("part {} is not defined", id));
      break;
    case model::Target::PartSet:
      if (!m.part_sets.count(id)) {
        throw located_error(where, "ID", fmt::format("part set {} is not defined", id));
      }
      break;
    case model::Target::All:
      break;
  }
}

}  // namespace

void finish_model(ReaderContext& context) {
  model::Model& m = context.model;
  std::unordered_set<Id> nodes;
  nodes.reserve(m.nodes.size());
  for (const auto& n : m.nodes) nodes.insert(n.id);

  // Deferred resolution.
  if (context.d3plot_npltc > 0 && m.termination.endtim > 0.0) {
    m.output.d3plot_dt = m.termination.endtim / context.d3plot_npltc;
  }
  for (const auto& h : context.history_node_sets) {
    const auto it = m.node_sets.find(h.nsid);
    if (it == m.node_sets.end()) {
      throw located_error(h.where, "NSID", fmt::format("node set {} is not defined", h.nsid));
    }
    m.output.history_nodes.insert(m.output.history_nodes.end(), it->second.nodes.begin(),
                                  it->second.nodes.end());
  }
  for (const auto& e : context.exemptions) {
    const auto it = m.node_sets.find(e.nsidex);
    if (it == m.node_sets.end()) {
      throw located_error(e.where, "NSIDEX", fmt::format("node set {} is not defined", e.nsidex));
    }
    m.initial_velocities[e.velocity_index].exempt_nodes = it->second.nodes;
  }

  // Cross references.
  static const char* const kNodeFields[] = {"N1", "N2", "N3", "N4", "N5", "N6", "N7", "N8"};
  for (const auto& e : m.solids) {
    if (!m.parts.count(e.pid)) {
      throw located_error(
          e.where, "PID",
          fmt::format("element {} refers to part {}, which is not defined", e.id, e.pid));
    }
    for (std::size_t k = 0; k < 8; ++k) {
      if (!nodes.count(e.nodes[k])) {
        throw located_error(
            e.where, kNodeFields[k],
            fmt::format("element {} refers to node {}, which is not defined", e.id, e.nodes[k]));
      }
    }
  }
  const bool skipped_materials = [&] {
    for (const auto& [keyword, count] : m.unknown_keywords) {
      if (keyword.starts_with("*MAT")) return true;
    }
    return false;
  }();
  for (const auto& [id, p] : m.parts) {
    if (!m.solid_sections.count(p.secid)) {
      throw located_error(p.where, "SECID",
                          fmt::format("part {} refers to section {}, which is not defined by a "
                                      "*SECTION_SOLID",
                                      id, p.secid));
    }
    if (!m.materials.count(p.mid)) {
      throw located_error(
          p.where, "MID",
          fmt::format("part {} refers to material {}, which is not defined{}", id, p.mid,
                      skipped_materials ? " (unsupported *MAT keywords were skipped; see the "
                                          "warnings)"
                                        : ""));
    }
    if (p.hgid != 0 && !m.hourglass.count(p.hgid)) {
      throw located_error(
          p.where, "HGID",
          fmt::format("part {} refers to *HOURGLASS {}, which is not defined", id, p.hgid));
    }
  }
  for (const auto& [id, set] : m.node_sets) {
    for (Id n : set.nodes) {
      if (!nodes.count(n)) {
        throw located_error(set.where, "NID",
                            fmt::format("node set {} lists node {}, which is not defined", id, n));
      }
    }
  }
  for (const auto& [id, set] : m.part_sets) {
    for (Id p : set.parts) {
      if (!m.parts.count(p)) {
        throw located_error(set.where, "PID",
                            fmt::format("part set {} lists part {}, which is not defined", id, p));
      }
    }
  }
  for (const auto& [id, set] : m.segment_sets) {
    for (const auto& segment : set.segments) {
      for (Id n : segment) {
        if (!nodes.count(n)) {
          throw located_error(
              set.where, "N1",
              fmt::format("segment set {} uses node {}, which is not defined", id, n));
        }
      }
    }
  }
  for (const auto& s : m.spcs) check_target(m, nodes, s.target, s.id, s.where);
  for (const auto& p : m.prescribed_motions) {
    check_target(m, nodes, p.target, p.id, p.where);
    check_curve(m, p.lcid, p.where, "LCID");
  }
  for (const auto& v : m.initial_velocities) check_target(m, nodes, v.target, v.id, v.where);
  for (const auto& l : m.nodal_loads) {
    check_target(m, nodes, l.target, l.id, l.where);
    check_curve(m, l.lcid, l.where, "LCID");
  }
  for (const auto& b : m.body_loads) check_curve(m, b.lcid, b.where, "LCID");
  if (m.timestep.lctm != 0) check_curve(m, m.timestep.lctm, context.lctm_where, "LCTM");
  for (const auto& h : context.history_nodes) {
    if (!nodes.count(h.nsid)) {
      throw located_error(h.where, "NID", fmt::format("node {} is not defined", h.nsid));
    }
  }
}

}  // namespace rf::io
