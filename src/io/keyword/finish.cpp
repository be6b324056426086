// After every file is read: resolve what needed the whole deck, then check that every
// reference points at something defined. Errors name the referring definition.
#include <fmt/format.h>

#include <map>
#include <set>

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "io/keyword/context.hpp"
#include "io/keyword/geometry.hpp"
#include "io/keyword/handlers.hpp"

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

// *LOAD_SEGMENT*, *LOAD_SHELL*: curves, sets, shells and nodes exist (the solver checks the
// segments' node repetitions again, solver/pressure_loads.cpp).
void check_pressure_loads(const model::Model& m, const std::unordered_set<Id>& nodes) {
  std::unordered_set<Id> shells;
  if (!m.pressure_loads.empty()) {
    for (const auto& e : m.shells) shells.insert(e.id);
  }
  for (const auto& l : m.pressure_loads) {
    check_curve(m, l.lcid, l.where, "LCID");
    switch (l.target) {
      case model::PressureTarget::Segment: {
        static const char* const kNode[] = {"N1", "N2", "N3", "N4"};
        for (std::size_t k = 0; k < 4; ++k) {
          if (!nodes.count(l.nodes[k])) {
            throw located_error(l.where, kNode[k],
                                fmt::format("node {} is not defined", l.nodes[k]));
          }
        }
        break;
      }
      case model::PressureTarget::SegmentSet:
        if (!m.segment_sets.count(l.id)) {
          throw located_error(l.where, "SSID",
                              fmt::format("segment set {} is not defined (*SET_SEGMENT)", l.id));
        }
        break;
      case model::PressureTarget::Shell:
        if (!shells.count(l.id)) {
          throw located_error(
              l.where, "EID",
              fmt::format("shell element {} is not defined (*ELEMENT_SHELL)", l.id));
        }
        break;
      case model::PressureTarget::ShellSet: {
        const auto set = m.shell_sets.find(l.id);
        if (set == m.shell_sets.end()) {
          throw located_error(l.where, "ESID",
                              fmt::format("shell set {} is not defined (*SET_SHELL)", l.id));
        }
        for (const Id e : set->second.elements) {
          if (!shells.count(e)) {
            throw located_error(l.where, "ESID",
                                fmt::format("shell set {} lists element {}, which is not a shell "
                                            "(*ELEMENT_SHELL)",
                                            l.id, e));
          }
        }
        break;
      }
    }
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
    case model::Target::Geometry:
      if (!m.geometry_seeds.count(id)) {
        throw located_error(where, "ID", fmt::format("geometry {} is not defined", id));
      }
      break;
  }
}

void check_function(const model::Model& m, Id function, const model::SourceLocation& where) {
  if (function != 0 && !m.functions.count(function)) {
    throw located_error(where, "FUNCTION",
                        fmt::format("function {} is not defined (*FUNCTION)", function));
  }
}

const model::CoordinateSystem& coordinate_system(const model::Model& m, Id cid,
                                                 const model::SourceLocation& where,
                                                 const char* field) {
  const auto it = m.coordinate_systems.find(cid);
  if (it == m.coordinate_systems.end()) {
    throw located_error(
        where, field,
        fmt::format("coordinate system {} is not defined (*DEFINE_COORDINATE_...)", cid));
  }
  return it->second;
}

// A part that must be a rigid body: defined and made of *MAT_RIGID.
void check_rigid_part(const model::Model& m, Id pid, const model::SourceLocation& where,
                      const char* field, const char* what) {
  const auto it = m.parts.find(pid);
  if (it == m.parts.end()) {
    throw located_error(where, field, fmt::format("part {} is not defined", pid));
  }
  const auto& material = m.materials.at(it->second.mid);  // checked with the parts
  if (material.kind != model::MaterialKind::Rigid) {
    throw located_error(where, field,
                        fmt::format("part {} is not rigid (material {} is {}); {} needs a "
                                    "*MAT_RIGID part",
                                    pid, material.id, material.keyword, what));
  }
}

// Rigid bodies that motions and loads may address: rigid parts and nodal rigid bodies.
void check_rigid_body(const model::Model& m, Id pid, const model::SourceLocation& where,
                      const char* what) {
  if (m.nodal_rigid_bodies.count(pid)) return;
  if (!m.parts.count(pid)) {
    throw located_error(where, "PID",
                        fmt::format("part {} is not defined (neither a *PART nor a "
                                    "*CONSTRAINED_NODAL_RIGID_BODY)",
                                    pid));
  }
  check_rigid_part(m, pid, where, "PID", what);
}

// The cycle check walks lead links; each constrained part has at most one lead.
void check_merges(const model::Model& m) {
  std::map<Id, const model::RigidBodyMerge*> lead_of;
  for (const auto& merge : m.rigid_body_merges) {
    check_rigid_part(m, merge.lead, merge.where, "PIDL", "*CONSTRAINED_RIGID_BODIES");
    check_rigid_part(m, merge.constrained, merge.where, "PIDC", "*CONSTRAINED_RIGID_BODIES");
    const auto [it, inserted] = lead_of.try_emplace(merge.constrained, &merge);
    if (!inserted && it->second->lead != merge.lead) {
      const auto& w = it->second->where;
      throw located_error(
          merge.where, "PIDC",
          fmt::format("part {} is merged into part {} here and into part {} at "
                      "{}:{}; a part can be merged into one lead part only",
                      merge.constrained, merge.lead, it->second->lead, w.file, w.line));
    }
  }
  std::unordered_set<Id> done;
  for (const auto& [start, first] : lead_of) {
    std::vector<Id> path;
    Id current = start;
    while (!done.count(current)) {
      const auto in_path = std::find(path.begin(), path.end(), current);
      if (in_path != path.end()) {
        std::string parts;
        for (auto p = in_path; p != path.end(); ++p) parts += fmt::format("{} -> ", *p);
        parts += fmt::format("{}", current);
        throw located_error(lead_of.at(current)->where, "PIDC",
                            fmt::format("rigid body merges form a cycle: part {} (each part "
                                        "merged into the next)",
                                        parts));
      }
      path.push_back(current);
      const auto next = lead_of.find(current);
      if (next == lead_of.end()) break;
      current = next->second->lead;
    }
    done.insert(path.begin(), path.end());
  }
}

void finish_inertia(const model::Model& m, const std::unordered_set<Id>& nodes,
                    const std::unordered_map<Id, Vec3>& coordinates, model::RigidInertia& in) {
  if (in.nodeid != 0) {
    if (!nodes.count(in.nodeid)) {
      throw located_error(in.where, "NODEID", fmt::format("node {} is not defined", in.nodeid));
    }
    in.xc = coordinates.at(in.nodeid);  // the manual: XC YC ZC are then ignored
  }
  if (in.ircs == 1 && in.cid != 0) {
    in.principal_axes = coordinate_system(m, in.cid, in.where, "CID").axes;
  }
}

// Rigid-body definitions: resolve what needs node coordinates or coordinate systems, then
// check every reference. Runs after the general checks, so parts have known materials.
void finish_rigid(model::Model& m, const std::unordered_set<Id>& nodes) {
  std::unordered_map<Id, Vec3> coordinates;
  const bool need_coordinates = [&] {
    for (const auto& [id, cs] : m.coordinate_systems) {
      if (cs.kind == model::CoordinateKind::Nodes) return true;
    }
    for (const auto& [id, p] : m.parts) {
      if (p.inertia && p.inertia->nodeid != 0) return true;
    }
    for (const auto& [id, b] : m.nodal_rigid_bodies) {
      if (b.inertia && b.inertia->nodeid != 0) return true;
    }
    return false;
  }();
  if (need_coordinates) {
    coordinates.reserve(m.nodes.size());
    for (const auto& n : m.nodes) coordinates.emplace(n.id, n.x);
  }

  static const char* const kNodeFields[] = {"N1", "N2", "N3"};
  for (auto& [id, cs] : m.coordinate_systems) {
    if (cs.kind != model::CoordinateKind::Nodes) continue;
    std::array<Vec3, 3> x{};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto it = coordinates.find(cs.nodes[k]);
      if (it == coordinates.end()) {
        throw located_error(cs.where, kNodeFields[k],
                            fmt::format("node {} is not defined", cs.nodes[k]));
      }
      x[k] = it->second;
    }
    const int axis = cs.dir - 'X';
    const auto axes = axes_from(sub(x[1], x[0]), sub(x[2], x[0]), axis);
    if (!axes) {
      throw located_error(cs.where, "N3",
                          fmt::format("nodes {}, {} and {} lie on one line (or coincide); they "
                                      "do not define coordinate system {}",
                                      cs.nodes[0], cs.nodes[1], cs.nodes[2], id));
    }
    cs.origin = x[0];
    cs.axes = *axes;
  }
  for (auto& [id, v] : m.vectors) {
    if (v.cid == 0) continue;
    const auto& cs = coordinate_system(m, v.cid, v.where, "CID");
    v.direction = *unit(to_global(cs.axes, sub(v.head, v.tail)));
  }
  for (const auto& [id, mat] : m.materials) {
    if (mat.kind != model::MaterialKind::Rigid) continue;
    if (mat.cmo == -1.0) coordinate_system(m, mat.cmo_cid, mat.where, "CON1");
    if (mat.lco != 0) coordinate_system(m, mat.lco, mat.where, "LCO");
  }
  for (auto& [id, p] : m.parts) {
    if (!p.inertia) continue;
    const auto& material = m.materials.at(p.mid);
    if (material.kind != model::MaterialKind::Rigid) {
      throw located_error(p.where, "MID",
                          fmt::format("part {} has *PART_INERTIA but material {} is {}; inertia "
                                      "properties need a *MAT_RIGID part",
                                      id, p.mid, material.keyword));
    }
    finish_inertia(m, nodes, coordinates, *p.inertia);
  }
  check_merges(m);
  for (const auto& e : m.extra_nodes) {
    check_rigid_part(m, e.pid, e.where, "PID", "*CONSTRAINED_EXTRA_NODES");
    check_target(m, nodes, e.target, e.id, e.where);
  }
  for (auto& [id, b] : m.nodal_rigid_bodies) {
    if (const auto it = m.parts.find(id); it != m.parts.end()) {
      throw located_error(b.where, "PID",
                          fmt::format("nodal rigid body {} has the ID of the *PART defined at "
                                      "{}:{}; give it an ID of its own",
                                      id, it->second.where.file, it->second.where.line));
    }
    if (!m.node_sets.count(b.nsid)) {
      throw located_error(b.where, "NSID",
                          fmt::format("node set {} is not defined{}", b.nsid,
                                      b.nsid == id ? " (NSID blank or 0 means NSID = PID)" : ""));
    }
    if (b.pnode != 0 && !nodes.count(std::abs(b.pnode))) {
      throw located_error(b.where, "PNODE",
                          fmt::format("node {} is not defined", std::abs(b.pnode)));
    }
    if (b.cid != 0) coordinate_system(m, b.cid, b.where, "CID");
    if (b.cmo == -1.0) coordinate_system(m, b.cmo_cid, b.where, "CON1");
    if (b.inertia) finish_inertia(m, nodes, coordinates, *b.inertia);
  }
  for (const auto& p : m.rigid_prescribed_motions) {
    check_rigid_body(m, p.pid, p.where, "*BOUNDARY_PRESCRIBED_MOTION_RIGID");
    if (p.function != 0)
      check_function(m, p.function, p.where);
    else if (p.lcid != 0 || p.where.keyword.starts_with("*BOUNDARY"))
      check_curve(m, p.lcid, p.where, "LCID");
    if (p.vid != 0 && !m.vectors.count(p.vid)) {
      throw located_error(p.where, "VID",
                          fmt::format("vector {} is not defined (*DEFINE_VECTOR)", p.vid));
    }
  }
  for (const auto& l : m.rigid_loads) {
    check_rigid_body(m, l.pid, l.where, "*LOAD_RIGID_BODY");
    check_curve(m, l.lcid, l.where, "LCID");
  }
}

}  // namespace

// Parts named by switching cards exist; what they name can switch that way (the manual:
// *MAT_RIGID parts are permanently rigid); pairs point at each other.
void finish_switching(const model::Model& m) {
  const auto& sw = m.switching;
  std::set<Id> switched_rigid;  // parts some D2R card names (LRB targets may be among them)
  auto parts_of = [&](const model::PartSwitch& s) {
    std::vector<Id> parts;
    if (s.part_set) {
      const auto it = m.part_sets.find(s.pid);
      if (it == m.part_sets.end()) {
        throw located_error(s.where, "PID",
                            fmt::format("part set {} (PTYPE PSET) is not defined", s.pid));
      }
      parts = it->second.parts;
    } else {
      parts.push_back(s.pid);
    }
    for (const Id p : parts) {
      if (!m.parts.count(p)) {
        throw located_error(s.where, "PID", fmt::format("part {} is not defined", p));
      }
    }
    return parts;
  };
  auto is_mat_rigid = [&](Id pid) {
    const auto& part = m.parts.at(pid);
    const auto mat = m.materials.find(part.mid);
    return mat != m.materials.end() && mat->second.kind == model::MaterialKind::Rigid;
  };
  auto check_to_rigid = [&](const model::PartSwitch& s) {
    const std::vector<Id> parts = parts_of(s);
    for (const Id p : parts) {
      // A deformable part with *PART_MODES becomes a flexible body of its own nodes when
      // switched (docs/flexible_bodies.md section 6); a *MAT_RIGID one is rigid already.
      if (m.part_modes.count(p) && (s.lrb != 0 || is_mat_rigid(p))) {
        throw located_error(s.where, s.lrb != 0 ? "LRB" : "PID",
                            fmt::format("part {} is a flexible body (*PART_MODES): it cannot "
                                        "be merged into another rigid body by switching",
                                        p));
      }
      if (m.part_modes.count(p) && parts.size() > 1) {
        throw located_error(s.where, "PID",
                            fmt::format("part set {} holds part {}, which has *PART_MODES, and "
                                        "other parts: switched together they would form one "
                                        "body, but the modes describe part {} alone; give the "
                                        "flexible part its own card",
                                        s.pid, p, p));
      }
      if (s.lrb == 0 && is_mat_rigid(p)) {
        throw located_error(s.where, "PID",
                            fmt::format("part {} is *MAT_RIGID, rigid already; give LRB to "
                                        "merge it into another rigid body",
                                        p));
      }
      switched_rigid.insert(p);
    }
  };
  for (const auto& s : sw.at_start) check_to_rigid(s);
  for (const auto& [pid, card] : sw.inertia) {
    if (m.part_modes.count(pid)) {
      throw located_error(card.where, "PID",
                          fmt::format("part {} has *PART_MODES: a flexible body takes its mass "
                                      "and inertia from the nodal masses its modes are "
                                      "normalised with; remove *DEFORMABLE_TO_RIGID_INERTIA",
                                      pid));
    }
  }
  for (const auto& set : sw.automatic) {
    for (const auto& s : set.to_rigid) check_to_rigid(s);
    for (const auto& s : set.to_deformable) {
      for (const Id p : parts_of(s)) {
        if (is_mat_rigid(p)) {
          throw located_error(s.where, "PID",
                              fmt::format("part {} is *MAT_RIGID: parts defined rigid in the "
                                          "input are permanently rigid and cannot become "
                                          "deformable",
                                          p));
        }
      }
    }
  }
  auto check_lead = [&](const model::PartSwitch& s) {
    if (s.lrb == 0) return;
    if (m.part_modes.count(s.lrb)) {
      throw located_error(s.where, "LRB",
                          fmt::format("part {} is a flexible body (*PART_MODES): its modes "
                                      "describe its own nodes only, so no part can be merged "
                                      "into it by switching",
                                      s.lrb));
    }
    if (!m.parts.count(s.lrb)) {
      throw located_error(s.where, "LRB", fmt::format("part {} is not defined", s.lrb));
    }
    if (!is_mat_rigid(s.lrb) && !switched_rigid.count(s.lrb)) {
      throw located_error(s.where, "LRB",
                          fmt::format("part {} is neither *MAT_RIGID nor switched to rigid by "
                                      "any card, so it cannot lead a rigid body",
                                      s.lrb));
    }
  };
  for (const auto& s : sw.at_start) check_lead(s);
  for (const auto& set : sw.automatic) {
    for (const auto& s : set.to_rigid) check_lead(s);
    if (set.paired == 0) continue;
    const model::AutomaticSwitchSet* related = nullptr;
    for (const auto& other : sw.automatic) {
      if (other.swset == set.relsw) related = &other;
    }
    if (!related) {
      throw located_error(set.where, "RELSW",
                          fmt::format("related switch set {} is not defined", set.relsw));
    }
    if (related->relsw != set.swset || related->paired != -set.paired) {
      throw located_error(set.where, "RELSW",
                          fmt::format("switch set {} (PAIRED {}) names {} as related, but set "
                                      "{} has RELSW {} and PAIRED {}: a pair names each other, "
                                      "one with PAIRED 1 and one with -1",
                                      set.swset, set.paired, set.relsw, related->swset,
                                      related->relsw, related->paired));
    }
    if ((set.code == 1 || set.code == 3) != (related->code == 1 || related->code == 3) ||
        (set.code == 2 || set.code == 4) != (related->code == 2 || related->code == 4) ||
        (set.code == 0) != (related->code == 0) || (set.code == 5) != (related->code == 5)) {
      throw located_error(set.where, "CODE",
                          fmt::format("paired sets {} and {} have CODE {} and {}: a pair uses "
                                      "consistent codes (1 with 3, 2 with 4, 0 with 0, 5 "
                                      "with 5)",
                                      set.swset, related->swset, set.code, related->code));
    }
  }
  for (const auto& [pid, in] : sw.inertia) {
    if (!m.parts.count(pid)) {
      throw located_error(in.where, "PID", fmt::format("part {} is not defined", pid));
    }
    if (is_mat_rigid(pid)) {
      throw located_error(in.where, "PID",
                          fmt::format("part {} is *MAT_RIGID; give its inertia with "
                                      "*PART_INERTIA instead",
                                      pid));
    }
  }
  for (const auto& set : sw.automatic) {
    if ((set.code == 1 || set.code == 3) && set.entno > static_cast<Id>(m.rigid_walls.size())) {
      throw located_error(set.where, "ENTNO",
                          fmt::format("CODE {} tests rigid wall {}, and this deck defines {} "
                                      "*RIGIDWALL_PLANAR (numbered 1, 2, ... in deck order)",
                                      set.code, set.entno, m.rigid_walls.size()));
    }
    if (set.code == 2 || set.code == 4) {
      // Manual, remark "Rigid Wall Numbering": the contact surface ID is the one of the
      // *CONTACT_..._ID card; only surface-to-surface and node-to-surface contacts qualify.
      const auto contact = std::find_if(m.contacts.begin(), m.contacts.end(),
                                        [&](const auto& c) { return c.id == set.entno; });
      if (contact == m.contacts.end()) {
        std::string ids;
        for (const auto& c : m.contacts) ids += (ids.empty() ? "" : ", ") + std::to_string(c.id);
        throw located_error(
            set.where, "ENTNO",
            fmt::format("CODE {} tests contact {}, and this deck defines {} "
                        "(contact IDs: {})",
                        set.code, set.entno, m.contacts.empty() ? "no contact" : "no such contact",
                        ids.empty() ? "none" : ids));
      }
      if (contact->kind == model::ContactKind::SingleSurface) {
        throw located_error(set.where, "ENTNO",
                            fmt::format("contact {} is a single-surface contact; part switching "
                                        "can test only surface-to-surface and nodes-to-surface "
                                        "contacts (*DEFORMABLE_TO_RIGID_AUTOMATIC, remarks)",
                                        set.entno));
      }
    }
    const bool has_control =
        std::any_of(m.sensor_controls.begin(), m.sensor_controls.end(), [&](const auto& entry) {
          return entry.second.type == "DEF2RIG" && entry.second.type_id == set.swset;
        });
    if (set.code == 5 && !has_control) {
      throw located_error(set.where, "CODE",
                          fmt::format("CODE 5: switch set {} is controlled by *SENSOR_CONTROL "
                                      "TYPE = DEF2RIG, TYPEID = {}, and this deck defines none",
                                      set.swset, set.swset));
    }
  }
  // A part switched to rigid that shares a node with a flexible body would be merged into it
  // (docs/flexible_bodies.md section 6): certain for a *MAT_RIGID flexible part, and for a
  // deformable one switched by the same keyword or set. Other cases depend on the switching
  // history and are checked when the switch happens.
  if (!m.part_modes.empty()) {
    std::map<Id, std::set<Id>> nodes_of;  // parts with *PART_MODES -> their node IDs
    for (const auto& e : m.solids) {
      if (m.part_modes.count(e.pid)) nodes_of[e.pid].insert(e.nodes.begin(), e.nodes.end());
    }
    auto shared_node = [&](Id part, Id flexible) -> Id {
      const auto& theirs = nodes_of[flexible];
      for (const auto& e : m.solids) {
        if (e.pid != part) continue;
        for (const Id n : e.nodes) {
          if (theirs.count(n)) return n;
        }
      }
      return 0;
    };
    auto check_group = [&](const std::vector<model::PartSwitch>& cards) {
      std::set<Id> together;
      for (const auto& c : cards) {
        for (const Id p : parts_of(c)) together.insert(p);
      }
      for (const auto& c : cards) {
        for (const Id p : parts_of(c)) {
          if (m.part_modes.count(p)) continue;
          for (const auto& [flexible, modes] : m.part_modes) {
            if (!is_mat_rigid(flexible) && !together.count(flexible)) continue;
            if (const Id n = shared_node(p, flexible); n != 0) {
              throw located_error(
                  c.where, "PID",
                  fmt::format("part {} shares node {} with part {}, a flexible body "
                              "(*PART_MODES at {}:{}): switched to rigid it would be merged into "
                              "it, but the modes describe part {} alone",
                              p, n, flexible, modes.where.file, modes.where.line, flexible));
            }
          }
        }
      }
    };
    check_group(sw.at_start);
    for (const auto& set : sw.automatic) check_group(set.to_rigid);
  }
}

// *PART_MODES: the part must be a rigid body's lead part, ANSID a node set, and the
// damping ranges may not overlap.
void finish_part_modes(const model::Model& m) {
  for (const auto& entry : m.part_modes) {
    // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
    const Id pid = entry.first;
    const auto& modes = entry.second;
    if (!m.parts.count(pid)) {
      throw located_error(modes.where, "PID", fmt::format("part {} is not defined", pid));
    }
    // A deformable part may carry *PART_MODES when a card switches it to rigid (it is then a
    // flexible body while rigid, docs/flexible_bodies.md section 6).
    const auto& material = m.materials.at(m.parts.at(pid).mid);
    if (material.kind != model::MaterialKind::Rigid) {
      bool switched = false;
      auto names = [&](const model::PartSwitch& s) {
        if (!s.part_set) return s.pid == pid;
        const auto set = m.part_sets.find(s.pid);
        return set != m.part_sets.end() &&
               std::find(set->second.parts.begin(), set->second.parts.end(), pid) !=
                   set->second.parts.end();
      };
      for (const auto& s : m.switching.at_start) switched |= names(s);
      for (const auto& set : m.switching.automatic) {
        for (const auto& s : set.to_rigid) switched |= names(s);
        for (const auto& s : set.to_deformable) switched |= names(s) && set.code == 5;
      }
      if (!switched) {
        throw located_error(modes.where, "PID",
                            fmt::format("part {} is not rigid (material {} is {}) and no "
                                        "*DEFORMABLE_TO_RIGID or *DEFORMABLE_TO_RIGID_AUTOMATIC "
                                        "card switches it to rigid; *PART_MODES needs a "
                                        "*MAT_RIGID part or a part switched to rigid",
                                        pid, material.id, material.keyword));
      }
    }
    for (const auto& merge : m.rigid_body_merges) {
      if (merge.constrained == pid) {
        throw located_error(modes.where, "PID",
                            fmt::format("part {} is merged into part {} by "
                                        "*CONSTRAINED_RIGID_BODIES: give *PART_MODES for the "
                                        "lead part {} (the merged parts form one flexible body)",
                                        pid, merge.lead, merge.lead));
      }
    }
    if (m.parts.at(pid).inertia) {
      throw located_error(modes.where, "PID",
                          fmt::format("part {} has *PART_INERTIA: a flexible body takes its mass "
                                      "and inertia from the nodal masses its modes are "
                                      "normalised with; remove the _INERTIA card",
                                      pid));
    }
    if (modes.ansid != 0 && !m.node_sets.count(modes.ansid)) {
      throw located_error(modes.where, "ANSID",
                          fmt::format("node set {} is not defined", modes.ansid));
    }
    for (std::size_t a = 0; a < modes.damping.size(); ++a) {
      for (std::size_t b = 0; b < a; ++b) {
        const auto& x = modes.damping[a];
        const auto& y = modes.damping[b];
        if (x.mstart <= y.mstop && y.mstart <= x.mstop) {
          throw located_error(
              x.where, "MSTART",
              fmt::format("modes {}..{} already have damping from the card at "
                          "line {}",
                          std::max(x.mstart, y.mstart), std::min(x.mstop, y.mstop), y.where.line));
        }
      }
    }
  }
}

// Every part with deformable elements is switched rigid by *DEFORMABLE_TO_RIGID_AUTOMATIC sets
// without DTMAX, and neither DTINIT nor LCTM gives a step: after the switch the run keeps the
// step in force before it (solver/simulation.cpp, select_time_step). Said up front, so `check`
// shows it (issue 22).
void warn_all_rigid_without_step(ReaderContext& context) {
  const model::Model& m = context.model;
  const auto& automatic = m.switching.automatic;
  if (automatic.empty() || !m.part_modes.empty()) return;
  if (m.timestep.dtinit > 0.0 || m.timestep.lctm != 0 || m.timestep.dt_max > 0.0) return;
  std::set<Id> switched;
  for (const auto& set : automatic) {
    if (set.dtmax > 0.0 && !set.to_rigid.empty()) return;  // that set caps the step
    for (const auto& s : set.to_rigid) {
      if (!s.part_set) {
        switched.insert(s.pid);
      } else if (const auto it = m.part_sets.find(s.pid); it != m.part_sets.end()) {
        switched.insert(it->second.parts.begin(), it->second.parts.end());
      }
    }
  }
  std::set<Id> deformable;
  for (const auto& e : m.solids) {
    const auto part = m.parts.find(e.pid);
    if (part == m.parts.end()) continue;
    const auto mat = m.materials.find(part->second.mid);
    if (mat != m.materials.end() && mat->second.kind != model::MaterialKind::Rigid) {
      deformable.insert(e.pid);
    }
  }
  if (deformable.empty()) return;
  for (const Id p : deformable) {
    if (!switched.count(p)) return;
  }
  context.warn(automatic.front().where,
               "*DEFORMABLE_TO_RIGID_AUTOMATIC can make every deformable part rigid and no "
               "DTMAX (on the switch set), DTINIT or LCTM (*CONTROL_TIMESTEP) sets the step "
               "then: the run keeps the step in force before the switch");
}

void finish_model(ReaderContext& context) {
  model::Model& m = context.model;
  std::unordered_set<Id> nodes;
  nodes.reserve(m.nodes.size());
  for (const auto& n : m.nodes) nodes.insert(n.id);

  // Deferred resolution. IMPETUS meshes are generated only from a deck read without errors:
  // a damaged card can leave sizes that would take gigabytes for nothing.
  if (!context.errors.empty()) {
    if (!context.components.empty() || !context.merges.empty() || !context.motions.empty()) return;
  }
  finish_impetus(context);
  for (const auto& n : m.nodes) nodes.insert(n.id);  // generated meshes
  handlers::finish_sets(context);
  handlers::finish_generalized_welds(context);
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

  // Cross references. Elements and parts are reported all at once (a deck converted from
  // another solver may have dozens of parts with unsupported sections).
  static const char* const kNodeFields[] = {"N1", "N2", "N3", "N4", "N5", "N6", "N7", "N8"};
  const std::size_t errors_before = context.errors.size() + context.dropped_errors;
  for (const auto& e : m.solids) {
    if (!m.parts.count(e.pid)) {
      context.report(kReferenceErrors,
                     located_error(e.where, "PID",
                                   fmt::format("element {} refers to part {}, which is not defined",
                                               e.id, e.pid)));
    }
    for (std::size_t k = 0; k < 8; ++k) {
      if (!nodes.count(e.nodes[k])) {
        context.report(kReferenceErrors,
                       located_error(e.where, kNodeFields[k],
                                     fmt::format("element {} refers to node {}, which is not "
                                                 "defined",
                                                 e.id, e.nodes[k])));
        break;
      }
    }
  }
  // Shells and beams: part and nodes defined, and the part's section of the element's kind.
  auto check_structural = [&](model::Id eid, model::Id pid, const model::SourceLocation& where,
                              const auto& element_nodes, const char* kind, const auto& sections) {
    const auto part = m.parts.find(pid);
    if (part == m.parts.end()) {
      context.report(kReferenceErrors,
                     located_error(where, "PID",
                                   fmt::format("element {} refers to part {}, which is not defined",
                                               eid, pid)));
    } else if (!sections.count(part->second.secid) &&
               !context.skipped_sections.count(part->second.secid) &&
               (m.solid_sections.count(part->second.secid) ||
                m.shell_sections.count(part->second.secid) ||
                m.beam_sections.count(part->second.secid) ||
                m.discrete_sections.count(part->second.secid))) {
      const std::string k(kind);
      context.report(kReferenceErrors,
                     located_error(where, "PID",
                                   fmt::format("{} element {} is in part {}, whose section {} is "
                                               "not a *SECTION_{}",
                                               kind, eid, pid, part->second.secid,
                                               k == "shell"  ? "SHELL"
                                               : k == "beam" ? "BEAM"
                                                             : "DISCRETE")));
    }
    std::size_t k = 0;
    for (const model::Id n : element_nodes) {
      if (n != 0 && !nodes.count(n)) {
        context.report(kReferenceErrors,
                       located_error(where, kNodeFields[k],
                                     fmt::format("element {} refers to node {}, which is not "
                                                 "defined",
                                                 eid, n)));
        break;
      }
      ++k;
    }
  };
  for (const auto& e : m.shells)
    check_structural(e.id, e.pid, e.where, e.nodes, "shell", m.shell_sections);
  for (const auto& e : m.beams)
    check_structural(e.id, e.pid, e.where, e.nodes, "beam", m.beam_sections);
  for (const auto& e : m.discretes)
    check_structural(e.id, e.pid, e.where, e.nodes, "discrete", m.discrete_sections);
  for (const auto& e : m.solids) {
    const auto part = m.parts.find(e.pid);
    if (part != m.parts.end() && !m.solid_sections.count(part->second.secid) &&
        (m.shell_sections.count(part->second.secid) || m.beam_sections.count(part->second.secid) ||
         m.discrete_sections.count(part->second.secid))) {
      context.report(kReferenceErrors,
                     located_error(e.where, "PID",
                                   fmt::format("solid element {} is in part {}, whose section {} "
                                               "is not a *SECTION_SOLID",
                                               e.id, e.pid, part->second.secid)));
    }
  }
  const bool skipped_materials = [&] {
    for (const auto& [keyword, count] : m.unknown_keywords) {
      if (keyword.starts_with("*MAT")) return true;
    }
    return false;
  }();
  for (const auto& [id, p] : m.parts) {
    if (!m.solid_sections.count(p.secid) && !m.shell_sections.count(p.secid) &&
        !m.beam_sections.count(p.secid) && !m.discrete_sections.count(p.secid)) {
      const auto skipped = context.skipped_sections.find(p.secid);
      if (skipped != context.skipped_sections.end()) {
        const auto& s = skipped->second;
        context.report(
            kReferenceErrors,
            located_error(p.where, "SECID",
                          fmt::format("part {} uses section {}, a {} at {}:{}: {}", id, p.secid,
                                      s.keyword, s.where.file, s.where.line, s.what)));
      } else {
        context.report(kReferenceErrors,
                       located_error(p.where, "SECID",
                                     fmt::format("part {} refers to section {}, which is not "
                                                 "defined (no *SECTION_SOLID, *SECTION_SHELL, "
                                                 "*SECTION_BEAM or *SECTION_DISCRETE has SECID "
                                                 "{})",
                                                 id, p.secid, p.secid)));
      }
    }
    if (!m.materials.count(p.mid)) {
      const auto skipped = context.skipped_materials.find(p.mid);
      if (skipped != context.skipped_materials.end()) {
        const auto& s = skipped->second;
        context.report(
            kReferenceErrors,
            located_error(p.where, "MID",
                          fmt::format("part {} uses material {}, a {} at {}:{}, which "
                                      "is not supported",
                                      id, p.mid, s.keyword, s.where.file, s.where.line)));
      } else {
        context.report(
            kReferenceErrors,
            located_error(
                p.where, "MID",
                fmt::format("part {} refers to material {}, which is not defined{}", id, p.mid,
                            skipped_materials ? " (unsupported *MAT keywords were "
                                                "skipped; see the warnings)"
                                              : "")));
      }
    }
    if (p.hgid != 0 && !m.hourglass.count(p.hgid)) {
      context.report(kReferenceErrors,
                     located_error(p.where, "HGID",
                                   fmt::format("part {} refers to *HOURGLASS {}, which is not "
                                               "defined",
                                               id, p.hgid)));
    }
  }
  // The checks below assume parts, materials and nodes are consistent.
  if (context.errors.size() + context.dropped_errors > errors_before) return;
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
    if (p.function != 0)
      check_function(m, p.function, p.where);
    else
      check_curve(m, p.lcid, p.where, "LCID");
  }
  for (const auto& v : m.initial_velocities) check_target(m, nodes, v.target, v.id, v.where);
  for (const auto& l : m.nodal_loads) {
    check_target(m, nodes, l.target, l.id, l.where);
    check_curve(m, l.lcid, l.where, "LCID");
  }
  for (const auto& b : m.body_loads) check_curve(m, b.lcid, b.where, "LCID");
  check_pressure_loads(m, nodes);
  if (m.timestep.lctm != 0) check_curve(m, m.timestep.lctm, context.lctm_where, "LCTM");
  for (const auto& h : context.history_nodes) {
    if (!nodes.count(h.nsid)) {
      throw located_error(h.where, "NID", fmt::format("node {} is not defined", h.nsid));
    }
  }
  finish_rigid(m, nodes);
  finish_part_modes(m);
  handlers::check_rigid_walls(m);
  handlers::check_contacts(m);
  finish_switching(m);
  warn_all_rigid_without_step(context);
  handlers::finish_sensors(context, nodes);
}

}  // namespace rf::io

namespace rf::io {

void check_runnable(ReaderContext& context) {
  const model::Model& m = context.model;
  const model::SourceLocation deck{m.files.empty() ? std::string() : m.files.front(), 1, ""};
  const bool eigen = m.implicit.eigenvalue && m.implicit.neig > 0 &&
                     (!m.implicit.general || m.implicit.imflag == 1);
  if (m.implicit.imflag == 1 && !eigen) {
    context.report(
        kModelErrors,
        InputError({context.implicit_general_where.file, context.implicit_general_where.line,
                    "*CONTROL_IMPLICIT_GENERAL", 1, "IMFLAG"},
                   "IMFLAG 1 (implicit) is supported only for an eigen analysis: add "
                   "*CONTROL_IMPLICIT_EIGENVALUE with NEIG > 0"));
  }
  if (eigen) return;  // no transient run: no end time or time step needed
  if (m.termination.endtim <= 0.0 && m.termination.endcyc <= 0) {
    const bool present = !context.termination_where.file.empty();
    context.report(kModelErrors,
                   present ? located_error(context.termination_where, "ENDTIM",
                                           "ENDTIM is not positive (and ENDCYC is 0): nothing "
                                           "says when the analysis ends")
                           : located_error(deck, "",
                                           "the deck has no *CONTROL_TERMINATION: nothing says "
                                           "when the analysis ends (add one with ENDTIM)"));
  }
  if (m.solids.empty() && m.shells.empty() && m.beams.empty() && m.discretes.empty() &&
      m.nodal_rigid_bodies.empty()) {
    std::string skipped;
    for (const auto& [keyword, count] : m.unknown_keywords) {
      if (keyword.starts_with("*ELEMENT_")) {
        skipped += fmt::format("{}{} ({} block(s))", skipped.empty() ? "" : ", ", keyword, count);
      }
    }
    context.report(
        kModelErrors,
        located_error(deck, "",
                      skipped.empty() ? std::string("the model has no elements or rigid bodies to "
                                                    "simulate")
                                      : fmt::format("the model has no elements or rigid bodies to "
                                                    "simulate; skipped element keywords: {}",
                                                    skipped)));
    return;
  }
  // Without a deformable element nothing gives a stable time step: the user must. Parts
  // switched to rigid by *DEFORMABLE_TO_RIGID are left to the solver's own check.
  if (m.timestep.dtinit > 0.0 || m.timestep.lctm != 0 || m.timestep.dt_max > 0.0 ||
      !m.switching.at_start.empty() || !m.switching.automatic.empty() || !m.part_modes.empty()) {
    return;
  }
  auto deformable_part = [&](model::Id pid) {
    const auto part = m.parts.find(pid);
    if (part == m.parts.end()) return true;  // reported above
    const auto material = m.materials.find(part->second.mid);
    if (material == m.materials.end()) return true;
    return material->second.kind != model::MaterialKind::Rigid;
  };
  for (const auto& e : m.solids) {
    if (deformable_part(e.pid)) return;
  }
  for (const auto& e : m.shells) {
    if (deformable_part(e.pid)) return;
  }
  for (const auto& e : m.beams) {
    if (deformable_part(e.pid)) return;
  }
  if (!m.discretes.empty()) return;  // springs and dampers give a step from the nodal masses
  context.report(kModelErrors,
                 located_error(deck, "",
                               "the model has no deformable elements, so nothing limits the time "
                               "step: give DTINIT (or LCTM) on *CONTROL_TIMESTEP"));
}

}  // namespace rf::io
