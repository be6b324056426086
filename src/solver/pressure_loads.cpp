#include "solver/pressure_loads.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>

#include "model/error.hpp"
#include "model/error_context.hpp"
#include "solver/boundary.hpp"

namespace rf::solver {

namespace {

using model::context_of;

// Segments this many or more are computed in parallel (below, the threads cost more than
// they save).
constexpr std::size_t kParallelSegments = 4096;

const char* id_field(model::PressureTarget target) {
  switch (target) {
    case model::PressureTarget::Segment:
      return "N1";
    case model::PressureTarget::SegmentSet:
      return "SSID";
    case model::PressureTarget::Shell:
      return "EID";
    case model::PressureTarget::ShellSet:
      return "ESID";
  }
  return "";
}

// Dense nodes of segment `q` (IDs), checked: N3 = N4 is the only repetition allowed.
std::array<std::int32_t, 4> dense_segment(const NodeIndex& node_index,
                                          const std::array<model::Id, 4>& q,
                                          const model::PressureLoad& load, const char* field,
                                          const char* what) {
  std::array<model::Id, 4> ids = q;
  if (ids[3] == 0) ids[3] = ids[2];
  for (std::size_t a = 0; a < 4; ++a) {
    for (std::size_t b = a + 1; b < 4; ++b) {
      if (ids[a] == ids[b] && !(a == 2 && b == 3)) {
        throw InputError(context_of(load.where, field),
                         fmt::format("{} {} {} {} {} has node {} twice (only N3 = N4 is allowed: "
                                     "a triangle)",
                                     what, ids[0], ids[1], ids[2], ids[3], ids[b]));
      }
    }
  }
  std::array<std::int32_t, 4> out{};
  for (std::size_t a = 0; a < 4; ++a) out[a] = node_index.at(ids[a], load.where, field);
  return out;
}

}  // namespace

double PressureLoads::History::operator()(double t) const {
  if (t < at) return 0.0;
  return sf * load_curve_value(*curve, t - at);  // SIDR: dynamic relaxation or transient
}

void segment_pressure_forces(const double x[4][3], double p, double f[4][3]) {
  // Corner values of x_xi x x_eta (each the cross product of the corner's two edges, / 4):
  // corner 1: (x2 - x1) x (x4 - x1), 2: (x2 - x1) x (x3 - x2), 3: (x3 - x4) x (x3 - x2),
  // 4: (x3 - x4) x (x4 - x1).
  double e12[3], e43[3], e14[3], e23[3];
  for (int k = 0; k < 3; ++k) {
    e12[k] = x[1][k] - x[0][k];
    e43[k] = x[2][k] - x[3][k];
    e14[k] = x[3][k] - x[0][k];
    e23[k] = x[2][k] - x[1][k];
  }
  auto cross = [](const double* a, const double* b, double* c) {
    c[0] = 0.25 * (a[1] * b[2] - a[2] * b[1]);
    c[1] = 0.25 * (a[2] * b[0] - a[0] * b[2]);
    c[2] = 0.25 * (a[0] * b[1] - a[1] * b[0]);
  };
  double A[4][3];
  cross(e12, e14, A[0]);
  cross(e12, e23, A[1]);
  cross(e43, e23, A[2]);
  cross(e43, e14, A[3]);
  // f_a = -p sum_b M_ab A_b with M = [4 2 1 2; 2 4 2 1; 1 2 4 2; 2 1 2 4] / 9.
  const double s = -p / 9.0;
  for (int k = 0; k < 3; ++k) {
    const double a0 = A[0][k], a1 = A[1][k], a2 = A[2][k], a3 = A[3][k];
    f[0][k] = s * (4.0 * a0 + 2.0 * a1 + a2 + 2.0 * a3);
    f[1][k] = s * (2.0 * a0 + 4.0 * a1 + 2.0 * a2 + a3);
    f[2][k] = s * (a0 + 2.0 * a1 + 4.0 * a2 + 2.0 * a3);
    f[3][k] = s * (2.0 * a0 + a1 + 2.0 * a2 + 4.0 * a3);
  }
}

PressureLoads resolve_pressure_loads(const model::Model& model, const NodeIndex& node_index) {
  PressureLoads out;
  if (model.pressure_loads.empty()) return out;
  std::unordered_map<model::Id, std::size_t> shell_of_id;
  for (std::size_t e = 0; e < model.shells.size(); ++e) shell_of_id.emplace(model.shells[e].id, e);
  for (const auto& load : model.pressure_loads) {
    const auto curve = model.curves.find(load.lcid);
    if (curve == model.curves.end()) {
      throw InputError(context_of(load.where, "LCID"),
                       fmt::format("load curve {} is not defined", load.lcid));
    }
    const auto history = static_cast<std::int32_t>(out.histories.size());
    out.histories.push_back({&curve->second, load.sf, load.at});
    const char* field = id_field(load.target);
    auto add = [&](const std::array<model::Id, 4>& q, const char* what) {
      out.nodes.push_back(dense_segment(node_index, q, load, field, what));
      out.history_of_segment.push_back(history);
    };
    auto add_shell = [&](model::Id eid, const char* f) {
      const auto it = shell_of_id.find(eid);
      if (it == shell_of_id.end()) {
        throw InputError(context_of(load.where, f),
                         fmt::format("shell element {} is not defined (*ELEMENT_SHELL)", eid));
      }
      add(model.shells[it->second].nodes, "shell with nodes");
    };
    switch (load.target) {
      case model::PressureTarget::Segment:
        add(load.nodes, "the segment");
        break;
      case model::PressureTarget::SegmentSet: {
        const auto it = model.segment_sets.find(load.id);
        if (it == model.segment_sets.end()) {
          throw InputError(context_of(load.where, "SSID"),
                           fmt::format("segment set {} is not defined (*SET_SEGMENT)", load.id));
        }
        for (const auto& q : it->second.segments) add(q, "segment");
        break;
      }
      case model::PressureTarget::Shell:
        add_shell(load.id, "EID");
        break;
      case model::PressureTarget::ShellSet: {
        const auto it = model.shell_sets.find(load.id);
        if (it == model.shell_sets.end()) {
          throw InputError(context_of(load.where, "ESID"),
                           fmt::format("shell set {} is not defined (*SET_SHELL)", load.id));
        }
        for (const model::Id eid : it->second.elements) add_shell(eid, "ESID");
        break;
      }
    }
  }
  // Gather plan: (node, slot) pairs sorted by node, then slot.
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  pairs.reserve(4 * out.nodes.size());
  for (std::size_t s = 0; s < out.nodes.size(); ++s) {
    for (int a = 0; a < 4; ++a) {
      pairs.emplace_back(out.nodes[s][a], static_cast<std::int32_t>(4 * s + a));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  out.slot_start.push_back(0);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (k == 0 || pairs[k].first != pairs[k - 1].first) {
      if (k > 0) out.slot_start.push_back(static_cast<std::int64_t>(k));
      out.loaded_nodes.push_back(pairs[k].first);
    }
    out.slots.push_back(pairs[k].second);
  }
  out.slot_start.push_back(static_cast<std::int64_t>(pairs.size()));
  out.pressure.assign(out.histories.size(), 0.0);
  out.slot_force.assign(12 * out.nodes.size(), 0.0);
  return out;
}

void add_pressure_forces(const PressureLoads& loads, double t, State& state) {
  if (loads.empty()) return;
  for (std::size_t h = 0; h < loads.histories.size(); ++h)
    loads.pressure[h] = loads.histories[h](t);
  NodalState& nodes = state.nodes;
  const double* px = nodes.x.x.data();
  const double* py = nodes.x.y.data();
  const double* pz = nodes.x.z.data();
  const double* pressure = loads.pressure.data();
  double* slot = loads.slot_force.data();
  const auto count = static_cast<std::int64_t>(loads.size());
#pragma omp parallel for schedule(static) if (loads.size() >= kParallelSegments)
  for (std::int64_t s = 0; s < count; ++s) {
    const double p = pressure[loads.history_of_segment[s]];
    double(*f)[3] = reinterpret_cast<double(*)[3]>(slot + 12 * s);
    if (p == 0.0) {
      std::fill(slot + 12 * s, slot + 12 * s + 12, 0.0);
      continue;
    }
    double x[4][3];
    const auto& q = loads.nodes[s];
    for (int a = 0; a < 4; ++a) {
      x[a][0] = px[q[a]];
      x[a][1] = py[q[a]];
      x[a][2] = pz[q[a]];
    }
    segment_pressure_forces(x, p, f);
  }
  double* fx = nodes.f_ext.x.data();
  double* fy = nodes.f_ext.y.data();
  double* fz = nodes.f_ext.z.data();
  const auto loaded = static_cast<std::int64_t>(loads.loaded_nodes.size());
#pragma omp parallel for schedule(static) if (loads.size() >= kParallelSegments)
  for (std::int64_t j = 0; j < loaded; ++j) {
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (auto k = loads.slot_start[j]; k < loads.slot_start[j + 1]; ++k) {
      const double* f = slot + 3 * static_cast<std::int64_t>(loads.slots[k]);
      sx += f[0];
      sy += f[1];
      sz += f[2];
    }
    const std::int32_t i = loads.loaded_nodes[j];
    fx[i] += sx;
    fy[i] += sy;
    fz[i] += sz;
  }
}

}  // namespace rf::solver
