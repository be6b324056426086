#include "solver/cross_sections.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::solver {
namespace {

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec unit(const Vec& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}
Vec reference(const State& state, std::int32_t i) {
  return {state.nodes.x0.x[i], state.nodes.x0.y[i], state.nodes.x0.z[i]};
}

// Members of set `id` of `sets`, or an error naming the card and field.
const std::vector<model::Id>& set_members(const std::map<model::Id, model::SolidSet>& sets,
                                          model::Id id, const model::CrossSection& section,
                                          const char* field, const char* family) {
  const auto it = sets.find(id);
  if (it == sets.end()) {
    throw InputError(context_of(section.where, field),
                     fmt::format("{} set {} is not defined", family, id));
  }
  return it->second.elements;
}

}  // namespace

void CrossSectionCut::build_from_sets(const model::Model& model, const NodeIndex& node_index,
                                      const State& state, const model::CrossSection& section) {
  const auto nodes_it = model.node_sets.find(section.node_set);
  if (nodes_it == model.node_sets.end()) {
    throw InputError(context_of(section.where, "NSID"),
                     fmt::format("node set {} is not defined", section.node_set));
  }
  std::vector<std::uint8_t> in_section(state.nodes.size(), 0);
  for (const model::Id id : nodes_it->second.nodes) {
    const std::int32_t n = node_index.at(id, section.where, "NSID");
    if (!in_section[n]) nodes_.push_back(n);
    in_section[n] = 1;
  }
  std::sort(nodes_.begin(), nodes_.end());
  // The elements of each set, found by user ID in the blocks of their family.
  auto add = [&](auto& blocks, Family family, model::Id set, const char* field, const char* name,
                 auto nodes_of, int node_stride) {
    if (set == 0) return;
    const std::vector<model::Id>& members =
        set_members(family == Family::kHex     ? model.solid_sets
                    : family == Family::kShell ? model.shell_sets
                                               : model.beam_sets,
                    set, section, field, name);
    const std::set<model::Id> wanted(members.begin(), members.end());
    std::size_t found = 0;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const auto& block = blocks[b];
      for (std::size_t e = 0; e < block.size(); ++e) {
        if (!wanted.count(block.element_id[e])) continue;
        ++found;
        if (!block.has_force_slots || block.rigid) continue;
        const auto [conn, count, stride] = nodes_of(block, e);
        for (int k = 0; k < count; ++k) {
          if (!in_section[conn[k]]) continue;
          slots_.push_back({family, static_cast<std::int32_t>(b),
                            static_cast<std::int64_t>(e) * stride + k * node_stride, conn[k]});
        }
      }
    }
    if (found != wanted.size()) {
      throw InputError(context_of(section.where, field),
                       fmt::format("{} set {}: {} of its {} elements are no {} elements", name, set,
                                   wanted.size() - found, wanted.size(), name));
    }
  };
  add(
      state.hex_blocks, Family::kHex, section.solid_set, "HSID", "solid",
      [](const element::HexBlock& block, std::size_t e) {
        const int npe = block.nodes_per_element();
        return std::tuple<const std::int32_t*, int, int>{&block.conn[e * npe], npe, 3 * npe};
      },
      3);
  add(
      state.shell_blocks, Family::kShell, section.shell_set, "SSID", "shell",
      [](const element::ShellBlock& block, std::size_t e) {
        return std::tuple<const std::int32_t*, int, int>{&block.conn[4 * e], 4,
                                                         element::kShellSlot};
      },
      6);
  add(
      state.beam_blocks, Family::kBeam, section.beam_set, "BSID", "beam",
      [](const element::BeamBlock& block, std::size_t e) {
        return std::tuple<const std::int32_t*, int, int>{&block.conn[2 * e], 2, element::kBeamSlot};
      },
      6);
  if (slots_.empty()) {
    throw InputError(context_of(section.where, "NSID"),
                     fmt::format("cross section {}: no deformable element of the element sets "
                                 "has a node in node set {}",
                                 section.id, section.node_set));
  }
}

CrossSectionCut::CrossSectionCut(const model::Model& model, const NodeIndex& node_index,
                                 const State& state, const model::CrossSection& section)
    : id_(section.id) {
  if (section.from_sets) {
    build_from_sets(model, node_index, state, section);
    return;
  }
  // The plane: tail point and unit normal (nodes with RADIUS < 0, at their initial positions).
  Vec tail = section.tail;
  Vec head = section.head;
  if (section.radius < 0.0) {
    tail = reference(state, node_index.at(section.tail_node, section.where, "XCT"));
    head = reference(state, node_index.at(section.head_node, section.where, "XCH"));
  }
  const Vec axis = sub(head, tail);
  if (dot(axis, axis) == 0.0) {
    throw InputError(context_of(section.where, "XCH"),
                     "the head of the plane's normal coincides with its tail");
  }
  normal_ = unit(axis);
  // Bounds in the plane: a disc, or a rectangle spanned from the tail by L (towards the edge
  // vector's head, projected into the plane) and M = N x L; 0 lengths leave a side unbounded.
  const double radius = std::abs(section.radius);
  Vec edge_l{}, edge_m{};
  const bool rectangle = radius == 0.0 && (section.length_l > 0.0 || section.length_m > 0.0);
  if (rectangle) {
    Vec l = sub(section.edge_head, tail);
    const double along = dot(l, normal_);
    for (int k = 0; k < 3; ++k) l[k] -= along * normal_[k];
    if (dot(l, l) < 1e-24 * std::max(1.0, dot(axis, axis))) {
      throw InputError(context_of(section.where, "XHEV"),
                       "LENL/LENM bound the cut but the edge vector (XHEV YHEV ZHEV from XCT YCT "
                       "ZCT) is zero or parallel to the normal");
    }
    edge_l = unit(l);
    edge_m = cross(normal_, edge_l);
  }
  auto inside = [&](const Vec& x) {
    const Vec d = sub(x, tail);
    if (radius > 0.0) {
      const double h = dot(d, normal_);
      return dot(d, d) - h * h <= radius * radius;
    }
    if (!rectangle) return true;
    const double a = dot(d, edge_l), b = dot(d, edge_m);
    return (section.length_l <= 0.0 || (a >= 0.0 && a <= section.length_l)) &&
           (section.length_m <= 0.0 || (b >= 0.0 && b <= section.length_m));
  };

  // Parts of the set (PSID 0: all).
  std::set<model::Id> parts;
  const bool all_parts = section.part_set == 0;
  if (!all_parts) {
    const auto it = model.part_sets.find(section.part_set);
    if (it == model.part_sets.end()) {
      throw InputError(context_of(section.where, "PSID"),
                       fmt::format("part set {} is not defined", section.part_set));
    }
    parts.insert(it->second.parts.begin(), it->second.parts.end());
  }
  auto selected = [&](model::Id pid, bool has_force_slots) {
    return has_force_slots && (all_parts || parts.count(pid) != 0);
  };

  // Side of every selected element; nodes touched by each side.
  const std::size_t node_count = state.nodes.size();
  std::vector<std::uint8_t> touched(node_count, 0);  // bit 0: positive side, bit 1: negative
  struct Element {
    Family family;
    std::int32_t block;
    std::int64_t element;
    const std::int32_t* conn;
    int nodes;
    int slot_stride;  // values per element
    int node_stride;  // values per node in the slot
  };
  std::vector<Element> negative;
  auto classify = [&](const Element& e) {
    Vec centroid{0, 0, 0};
    for (int k = 0; k < e.nodes; ++k) {
      const Vec x = reference(state, e.conn[k]);
      for (int c = 0; c < 3; ++c) centroid[c] += x[c] / e.nodes;
    }
    const bool positive = dot(sub(centroid, tail), normal_) >= 0.0;
    for (int k = 0; k < e.nodes; ++k) touched[e.conn[k]] |= positive ? 1 : 2;
    if (!positive) negative.push_back(e);
  };
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    const element::HexBlock& block = state.hex_blocks[b];
    if (!selected(block.part_id, block.has_force_slots && !block.rigid)) continue;
    const int npe = block.nodes_per_element();
    for (std::size_t e = 0; e < block.size(); ++e) {
      classify({Family::kHex, static_cast<std::int32_t>(b), static_cast<std::int64_t>(e),
                &block.conn[e * npe], npe, 3 * npe, 3});
    }
  }
  for (std::size_t b = 0; b < state.shell_blocks.size(); ++b) {
    const element::ShellBlock& block = state.shell_blocks[b];
    if (!selected(block.part_id, block.has_force_slots && !block.rigid)) continue;
    for (std::size_t e = 0; e < block.size(); ++e) {
      classify({Family::kShell, static_cast<std::int32_t>(b), static_cast<std::int64_t>(e),
                &block.conn[4 * e], 4, element::kShellSlot, 6});
    }
  }
  for (std::size_t b = 0; b < state.beam_blocks.size(); ++b) {
    const element::BeamBlock& block = state.beam_blocks[b];
    if (!selected(block.part_id, block.has_force_slots && !block.rigid)) continue;
    for (std::size_t e = 0; e < block.size(); ++e) {
      classify({Family::kBeam, static_cast<std::int32_t>(b), static_cast<std::int64_t>(e),
                &block.conn[2 * e], 2, element::kBeamSlot, 6});
    }
  }

  std::vector<std::uint8_t> in_section(node_count, 0);
  for (std::size_t i = 0; i < node_count; ++i) {
    const auto n = static_cast<std::int32_t>(i);
    if (touched[i] == 3 && inside(reference(state, n))) {
      in_section[i] = 1;
      nodes_.push_back(n);
    }
  }
  if (nodes_.empty()) {
    throw InputError(context_of(section.where, "PSID"),
                     fmt::format("cross section {} cuts no deformable element of {}: no node is "
                                 "shared by elements on both sides of the plane{}",
                                 section.id,
                                 all_parts ? std::string("the model")
                                           : fmt::format("part set {}", section.part_set),
                                 radius > 0.0 || rectangle ? " inside its bounds" : ""));
  }
  // Slots in (family, block, element, local node) order: the sum is the same every run.
  for (const Element& e : negative) {
    for (int k = 0; k < e.nodes; ++k) {
      if (!in_section[e.conn[k]]) continue;
      slots_.push_back(
          {e.family, e.block, e.element * e.slot_stride + k * e.node_stride, e.conn[k]});
    }
  }
}

SectionForce CrossSectionCut::evaluate(const State& state) const {
  SectionForce out;
  out.section = id_;
  const NodalState& nodes = state.nodes;
  for (const std::int32_t n : nodes_) {
    out.centroid[0] += nodes.x.x[n];
    out.centroid[1] += nodes.x.y[n];
    out.centroid[2] += nodes.x.z[n];
  }
  for (double& c : out.centroid) c /= static_cast<double>(nodes_.size());
  // A negative-side element's slot is its internal (resisting) force at the node: the force the
  // element exerts on the node is minus the slot, so the force the positive side exerts on the
  // negative side, by the node's equilibrium through the cut, is plus the slot.
  for (const Slot& slot : slots_) {
    const double* values = nullptr;
    bool with_moment = false;
    switch (slot.family) {
      case Family::kHex:
        values = state.hex_blocks[slot.block].force.data() + slot.offset;
        break;
      case Family::kShell:
        values = state.shell_blocks[slot.block].force.data() + slot.offset;
        with_moment = true;
        break;
      case Family::kBeam:
        values = state.beam_blocks[slot.block].force.data() + slot.offset;
        with_moment = true;
        break;
    }
    const Vec f{values[0], values[1], values[2]};
    const Vec r =
        sub({nodes.x.x[slot.node], nodes.x.y[slot.node], nodes.x.z[slot.node]}, out.centroid);
    const Vec m = cross(r, f);
    for (int k = 0; k < 3; ++k) {
      out.force[k] += f[k];
      out.moment[k] += m[k] + (with_moment ? values[3 + k] : 0.0);
    }
  }
  out.normal_force = dot(out.force, normal_);
  return out;
}

std::vector<CrossSectionCut> build_cross_sections(const model::Model& model, const State& state) {
  std::vector<CrossSectionCut> cuts;
  cuts.reserve(model.output.cross_sections.size());
  const NodeIndex node_index(model);
  for (const model::CrossSection& section : model.output.cross_sections) {
    cuts.emplace_back(model, node_index, state, section);
  }
  return cuts;
}

}  // namespace rf::solver
