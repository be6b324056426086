#include "solver/build_state.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <limits>
#include <map>

#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::solver {

namespace {

using model::context_of;

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

}  // namespace

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
  State state;
  NodalState& nodes = state.nodes;
  const std::size_t n = model.nodes.size();
  nodes.id.resize(n);
  nodes.x0.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    nodes.id[i] = model.nodes[i].id;
    nodes.x0.x[i] = model.nodes[i].x[0];
    nodes.x0.y[i] = model.nodes[i].x[1];
    nodes.x0.z[i] = model.nodes[i].x[2];
  }
  nodes.x = nodes.x0;
  nodes.v.resize(n);
  nodes.a.resize(n);
  nodes.f_int.resize(n);
  nodes.f_ext.resize(n);
  nodes.mass.assign(n, 0.0);

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
    if (mat.kind != model::MaterialKind::Elastic && mat.kind != model::MaterialKind::Rigid) {
      throw InputError(context_of(mat.where, "MID"),
                       fmt::format("part {} uses {} (material {}), which this version does not "
                                   "simulate yet",
                                   pid, mat.keyword, mat.id));
    }

    element::HexBlock block;
    block.part_id = pid;
    block.part_index = static_cast<int>(state.parts.size());
    block.elform = sec_it->second.elform;
    block.rigid = mat.kind == model::MaterialKind::Rigid;
    // Rigid parts: the section and hourglass do not matter; E and PR only for contact later.
    if (!block.rigid) block.hourglass = resolve_hourglass(model, part);
    block.material = material::make_elastic(mat.rho, mat.e, mat.pr);
    block.element_id.reserve(element_indices.size());
    block.conn.reserve(element_indices.size() * 8);
    for (const std::size_t e : element_indices) {
      const auto& solid = model.solids[e];
      block.element_id.push_back(solid.id);
      for (int k = 0; k < 8; ++k) {
        block.conn.push_back(node_index.at(solid.nodes[k], solid.where, "N"));
      }
    }
    state.parts.push_back(
        PartInfo{pid, part.title, block.elform, static_cast<std::int64_t>(block.size())});
    state.hex_blocks.push_back(std::move(block));
  }

  const element::NodalView view{nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
                                nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
  for (auto& block : state.hex_blocks) {
    element::initialize_hex_block(block, view);
    element::add_hex_lumped_mass(block, nodes.mass);
  }

  // Node -> element-slot incidence, counted then filled (CSR).
  NodeIncidence& inc = state.incidence;
  inc.offset.assign(n + 1, 0);
  for (const auto& block : state.hex_blocks) {
    if (block.rigid) continue;
    for (const std::int32_t node : block.conn) ++inc.offset[node + 1];
  }
  for (std::size_t i = 0; i < n; ++i) inc.offset[i + 1] += inc.offset[i];
  inc.slot.resize(inc.offset[n]);
  inc.block.resize(inc.offset[n]);
  std::vector<std::int64_t> fill(inc.offset.begin(), inc.offset.end() - 1);
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    if (state.hex_blocks[b].rigid) continue;
    const auto& conn = state.hex_blocks[b].conn;
    for (std::size_t k = 0; k < conn.size(); ++k) {
      const std::int64_t pos = fill[conn[k]]++;
      inc.slot[pos] = static_cast<std::int64_t>(k) * 3;  // element*24 + local*3
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
    if (state.hex_blocks[b].rigid) continue;  // no force slots: ranges stay empty
    const auto& conn = state.hex_blocks[b].conn;
    const std::int64_t elements = static_cast<std::int64_t>(conn.size() / 8);
    total += elements;
    for (std::int64_t e = 0; e < elements; ++e) {
      for (int k = 0; k < 8; ++k) {
        const std::int64_t node = conn[8 * e + k];
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
      for (std::int64_t e = first; e < last; ++e) {
        for (int k = 0; k < 8; ++k) {
          const std::int64_t node = conn[8 * e + k];
          if (node < lo || node >= hi) continue;
          const double* f = force + 24 * e + 3 * k;
          fx[node] += f[0];
          fy[node] += f[1];
          fz[node] += f[2];
        }
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
