// Added masses and mass-proportional damping (docs/keywords.md, docs/theory.md §"Damping").
#include "solver/mass_damping.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "element/kernels.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::solver {

using model::context_of;

namespace {

// Parts named by a part ID or part set ID of a card; errors name the card's field.
std::vector<model::Id> parts_of(const model::Model& model, model::Id id, bool part_set,
                                const model::SourceLocation& where, const char* field) {
  if (!part_set) {
    if (!model.parts.count(id)) {
      throw InputError(context_of(where, field), fmt::format("part {} is not defined", id));
    }
    return {id};
  }
  const auto it = model.part_sets.find(id);
  if (it == model.part_sets.end()) {
    throw InputError(context_of(where, field), fmt::format("part set {} is not defined", id));
  }
  return it->second.parts;
}

}  // namespace

double add_mass_elements(const model::Model& model, const NodeIndex& node_index, State& state) {
  std::vector<double>& nodal_mass = state.nodes.mass;
  double added = 0.0;
  for (const auto& point : model.point_masses) {
    nodal_mass[node_index.at(point.node, point.where, "NID")] += point.mass;
    added += point.mass;
  }
  if (model.part_mass_additions.empty()) return added;
  // Each addition is computed from the element masses alone (LS-DYNA: the part's mass is that
  // of its elements), so several cards on shared nodes do not depend on their order.
  std::vector<double> own(nodal_mass.size());
  std::vector<double> increment(nodal_mass.size(), 0.0);
  for (const auto& addition : model.part_mass_additions) {
    const char* field = addition.part_set ? "PSID" : "PID";
    const std::vector<model::Id> parts =
        parts_of(model, addition.id, addition.part_set, addition.where, field);
    std::fill(own.begin(), own.end(), 0.0);
    for (const auto& block : state.hex_blocks) {
      if (std::find(parts.begin(), parts.end(), block.part_id) == parts.end()) continue;
      element::add_block_lumped_mass(block, own);
    }
    // Shells and beams: translational mass only (the added mass is a translational mass).
    std::vector<double> inertia_scratch(state.rotations.size());
    for (const auto& block : state.shell_blocks) {
      if (std::find(parts.begin(), parts.end(), block.part_id) == parts.end()) continue;
      element::add_shell_lumped_mass(block, own, inertia_scratch);
    }
    for (const auto& block : state.beam_blocks) {
      if (std::find(parts.begin(), parts.end(), block.part_id) == parts.end()) continue;
      element::add_beam_lumped_mass(block, own, inertia_scratch);
    }
    double part_mass = 0.0;
    for (const double m : own) part_mass += m;
    if (!(part_mass > 0.0)) {
      throw InputError(context_of(addition.where, field),
                       fmt::format("{} {} has no element mass to distribute the added mass over",
                                   addition.part_set ? "part set" : "part", addition.id));
    }
    double extra = addition.addmass;
    if (addition.finmass > 0.0) {
      extra = addition.finmass - part_mass;
      if (extra < 0.0) {
        throw InputError(context_of(addition.where, "FINMASS"),
                         fmt::format("FINMASS {:.6g} is below the mass {:.6g} that {} {} already "
                                     "has: mass can only be added",
                                     addition.finmass, part_mass,
                                     addition.part_set ? "part set" : "part", addition.id));
      }
    }
    const double scale = extra / part_mass;
    for (std::size_t i = 0; i < own.size(); ++i) increment[i] += scale * own[i];
    added += extra;
  }
  for (std::size_t i = 0; i < nodal_mass.size(); ++i) nodal_mass[i] += increment[i];
  return added;
}

MassDampingSystem resolve_mass_damping(const model::Model& model, const State& state) {
  MassDampingSystem system;
  if (model.mass_damping.empty()) return system;
  if (model.mass_damping.size() >
      static_cast<std::size_t>(std::numeric_limits<std::int16_t>::max())) {
    throw InputError(context_of(model.mass_damping.back().where, "PID"),
                     "too many damping cards (at most 32767)");
  }
  system.term_of_node.assign(state.nodes.size(), -1);
  system.force.resize(state.nodes.size());
  // The global card first, then the part cards in deck order: part cards override it.
  std::vector<const model::MassDamping*> order;
  for (const auto& card : model.mass_damping)
    if (card.global) order.push_back(&card);
  for (const auto& card : model.mass_damping)
    if (!card.global) order.push_back(&card);
  for (const model::MassDamping* card : order) {
    DampingTerm term;
    if (card->global) {
      term.d = card->lcid != 0 ? make_time_function(model, card->lcid, 0, 1.0, 0.0, card->where)
                               : make_time_function(model, 0, 0, card->valdmp, 0.0, card->where);
    } else {
      term.d = make_time_function(model, card->lcid, 0, card->sf, 0.0, card->where);
    }
    term.st = card->st;
    term.sr = card->sr;
    const auto index = static_cast<std::int16_t>(system.terms.size());
    system.terms.push_back(term);
    if (card->global) {
      std::fill(system.term_of_node.begin(), system.term_of_node.end(), index);
      continue;
    }
    const char* field = card->part_set ? "PSID" : "PID";
    const std::vector<model::Id> parts =
        parts_of(model, card->id, card->part_set, card->where, field);
    auto mark = [&](const auto& blocks) {
      for (const auto& block : blocks) {
        if (std::find(parts.begin(), parts.end(), block.part_id) == parts.end()) continue;
        for (const std::int32_t node : block.conn) system.term_of_node[node] = index;
      }
    };
    mark(state.hex_blocks);
    mark(state.shell_blocks);  // their nodes' spins too (add_damping_forces)
    mark(state.beam_blocks);
  }
  system.coefficient.resize(system.terms.size());
  system.rotation_coefficient.resize(system.terms.size());
  system.moment.resize(state.rotations.size());
  return system;
}

void add_damping_forces(const MassDampingSystem& damping, const std::vector<double>& mass_of_node,
                        double t, State& state) {
  if (damping.empty()) return;
  NodalState& nodes = state.nodes;
  for (std::size_t k = 0; k < damping.terms.size(); ++k) {
    const double d = damping.terms[k].d(t);
    for (int a = 0; a < 3; ++a) {
      damping.coefficient[k][a] = d * damping.terms[k].st[a];
      damping.rotation_coefficient[k][a] = d * damping.terms[k].sr[a];
    }
  }
  const std::int64_t n = static_cast<std::int64_t>(nodes.size());
  const std::int16_t* term_of = damping.term_of_node.data();
  const double* m = mass_of_node.data();
  Vec3Array& force = damping.force;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const int k = term_of[i];
    if (k < 0 || m[i] == 0.0) {
      force.x[i] = force.y[i] = force.z[i] = 0.0;
      continue;
    }
    const std::array<double, 3>& c = damping.coefficient[k];
    force.x[i] = -c[0] * m[i] * nodes.v.x[i];
    force.y[i] = -c[1] * m[i] * nodes.v.y[i];
    force.z[i] = -c[2] * m[i] * nodes.v.z[i];
    nodes.f_ext.x[i] += force.x[i];
    nodes.f_ext.y[i] += force.y[i];
    nodes.f_ext.z[i] += force.z[i];
  }
  // The spins of shell and beam nodes: m = -d(t) SR J w with J the node's rotary inertia (the
  // mass-weighted damping of every DOF: a free body's angular momentum, spins included, then
  // decays as exp(-d t) when ST = SR). Nodes on rigid bodies (mass 0 here) turn with their body,
  // which is damped at its centre.
  RotationalState& rot = state.rotations;
  if (rot.empty()) return;
  const std::int64_t nr = static_cast<std::int64_t>(rot.size());
  Vec3Array& moment = damping.moment;
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < nr; ++r) {
    const std::int32_t i = rot.node[r];
    const int k = term_of[i];
    if (k < 0 || m[i] == 0.0) {
      moment.x[r] = moment.y[r] = moment.z[r] = 0.0;
      continue;
    }
    const std::array<double, 3>& c = damping.rotation_coefficient[k];
    const double inertia = rot.inertia[r];
    moment.x[r] = -c[0] * inertia * rot.w.x[r];
    moment.y[r] = -c[1] * inertia * rot.w.y[r];
    moment.z[r] = -c[2] * inertia * rot.w.z[r];
    rot.m_ext.x[r] += moment.x[r];
    rot.m_ext.y[r] += moment.y[r];
    rot.m_ext.z[r] += moment.z[r];
  }
}

}  // namespace rf::solver
