#include "solver/mass_scaling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "element/beam_block.hpp"
#include "element/hex_block.hpp"
#include "element/shell_block.hpp"
#include "element/tet10_block.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"

namespace rf::solver {

namespace {

// Mass of one element without scaling (the sum of its lumped shares).
double element_mass(const element::HexBlock& b, std::size_t e) {
  return b.material.rho * b.volume0[e];
}
double element_mass(const element::ShellBlock& b, std::size_t e) {
  return b.material.rho * b.element_thickness0[e] * b.area0[e];  // initial t: mass conserved
}
double element_mass(const element::BeamBlock& b, std::size_t e) {
  return b.material.rho * b.area * b.length0[e];
}

element::KernelResult critical_steps(const element::HexBlock& b, const element::NodalView& v,
                                     std::vector<double>* raw) {
  if (b.quadratic_tetrahedra()) return element::tet10_critical_timestep(b, v, raw);
  return element::hex_critical_timestep(b, v, raw);
}
element::KernelResult critical_steps(const element::ShellBlock& b, const element::NodalView& v,
                                     std::vector<double>* raw) {
  return element::shell_critical_timestep(b, v, raw);
}
element::KernelResult critical_steps(const element::BeamBlock& b, const element::NodalView& v,
                                     std::vector<double>* raw) {
  return element::beam_critical_timestep(b, v, raw);
}

}  // namespace

MassScaling setup_mass_scaling(const model::Model& model, const State& state) {
  MassScaling s;
  const double dt2ms = model.timestep.dt2ms;
  if (dt2ms == 0.0) return s;
  const InputErrorContext where = model::context_of(model.timestep.where, "DT2MS");
  for (const auto& block : state.hex_blocks) {
    if (block.order > 1) {
      throw InputError(where, fmt::format("mass scaling is not supported with hexahedra of order "
                                          "{} (part {}, *CHANGE_P-ORDER)",
                                          block.order, block.part_id));
    }
  }
  if (!model.part_modes.empty()) {
    throw InputError(where,
                     "mass scaling is not supported with flexible bodies (*PART_MODES): "
                     "their modes belong to the physical mass");
  }
  s.target_step = std::abs(dt2ms);
  s.uniform_start = dt2ms > 0.0;
  s.first_step_only = model.timestep.ms1st == 1;
  s.physical_mass = state.nodes.mass;
  s.physical_inertia = state.rotations.inertia;
  return s;
}

bool scale_masses(MassScaling& scaling, State& state, const std::vector<std::int32_t>& body_of_node,
                  double& element_dt, model::Id& controlling_element) {
  if (!scaling.active()) return false;
  const bool start = !scaling.started;
  // A relative margin so that a step the scaling itself set (target up to round-off) does not
  // start another pass.
  const double threshold = scaling.target_step * (1.0 - 1e-9);
  if (!start && (scaling.first_step_only || !(element_dt < threshold))) return false;
  scaling.started = true;

  const element::NodalView view = view_of(state.nodes);
  const double target = scaling.target_step;
  bool changed = false;
  double min_step = std::numeric_limits<double>::infinity();
  double old_min_step = std::numeric_limits<double>::infinity();
  model::Id min_element = controlling_element;
  std::vector<double>& raw = scaling.scratch.raw_step;
  auto rescale = [&](auto& blocks, std::vector<std::vector<double>>& factors) {
    factors.resize(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      auto& block = blocks[b];
      if (block.rigid) continue;  // moved by its body: no step, its factors wait
      critical_steps(block, view, &raw);
      std::vector<double>& s = factors[b];
      if (s.empty()) s.assign(block.size(), 1.0);
      if (block.step_scale.empty()) block.step_scale.assign(block.size(), 1.0);
      for (std::size_t e = 0; e < block.size(); ++e) {
        if (!(raw[e] > 0.0)) continue;  // a failed element: the breakdown check reports it
        old_min_step = std::min(old_min_step, raw[e] * block.step_scale[e]);
        const double needed = (target / raw[e]) * (target / raw[e]);
        const double factor = start && scaling.uniform_start ? needed : std::max(s[e], needed);
        if (factor != s[e]) {
          s[e] = factor;
          block.step_scale[e] = std::sqrt(factor);
          changed = true;
        }
        const double step = raw[e] * block.step_scale[e];
        if (step < min_step) {
          min_step = step;
          min_element = block.element_id[e];
        }
      }
    }
  };
  rescale(state.hex_blocks, scaling.hex_factor);
  rescale(state.shell_blocks, scaling.shell_factor);
  rescale(state.beam_blocks, scaling.beam_factor);
  if (!changed) return false;  // the kernels' step stands (it may include bulk viscosity)
  // The kernels' step is the elastic step times the bulk viscosity's reduction of a compressing
  // element (hex_block.cpp); the steps here are elastic only. The reduction seen at the
  // smallest step is carried over to the new smallest step, so the step never exceeds what the
  // kernels would report.
  const double viscous_share = std::isfinite(element_dt) && old_min_step > 0.0
                                   ? std::min(1.0, element_dt / old_min_step)
                                   : 1.0;
  element_dt = min_step * viscous_share;
  controlling_element = min_element;

  // Nodal masses and inertias from scratch: physical plus every element's (s_e - 1) shares.
  NodalState& nodes = state.nodes;
  RotationalState& rot = state.rotations;
  std::vector<double>& added = scaling.scratch.added;
  std::vector<double>& added_inertia = scaling.scratch.added_inertia;
  std::vector<double>& excess = scaling.scratch.excess;
  added.assign(nodes.size(), 0.0);  // same sizes every time: no allocation after the first
  added_inertia.assign(rot.inertia.size(), 0.0);
  auto minus_one = [&](const std::vector<double>& s) {
    excess.resize(s.size());
    for (std::size_t e = 0; e < s.size(); ++e) excess[e] = s[e] - 1.0;
    return &excess;
  };
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
    if (scaling.hex_factor[b].empty()) continue;
    if (state.hex_blocks[b].quadratic_tetrahedra())
      element::add_tet10_lumped_mass(state.hex_blocks[b], added, minus_one(scaling.hex_factor[b]));
    else
      element::add_hex_lumped_mass(state.hex_blocks[b], added, minus_one(scaling.hex_factor[b]));
  }
  std::vector<double>& no_inertia = scaling.scratch.no_inertia;  // trusses without rotations
  auto& inertia_sink = rot.empty() ? no_inertia : added_inertia;
  for (std::size_t b = 0; b < state.shell_blocks.size(); ++b) {
    if (scaling.shell_factor[b].empty()) continue;
    element::add_shell_lumped_mass(state.shell_blocks[b], added, inertia_sink,
                                   minus_one(scaling.shell_factor[b]));
  }
  for (std::size_t b = 0; b < state.beam_blocks.size(); ++b) {
    if (scaling.beam_factor[b].empty()) continue;
    element::add_beam_lumped_mass(state.beam_blocks[b], added, inertia_sink,
                                  minus_one(scaling.beam_factor[b]));
  }
  const bool has_bodies = !body_of_node.empty();
  double work = 0.0, total_added = 0.0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (has_bodies && body_of_node[i] >= 0) continue;  // the body's mass is its own
    const double m = scaling.physical_mass[i] + added[i];
    const double v2 =
        nodes.v.x[i] * nodes.v.x[i] + nodes.v.y[i] * nodes.v.y[i] + nodes.v.z[i] * nodes.v.z[i];
    work += 0.5 * (m - nodes.mass[i]) * v2;
    nodes.mass[i] = m;
    total_added += added[i];
  }
  for (std::size_t r = 0; r < rot.size(); ++r) {
    const auto i = static_cast<std::size_t>(rot.node[r]);
    if (has_bodies && body_of_node[i] >= 0) continue;
    const double I = scaling.physical_inertia[r] + added_inertia[r];
    const double w2 = rot.w.x[r] * rot.w.x[r] + rot.w.y[r] * rot.w.y[r] + rot.w.z[r] * rot.w.z[r];
    work += 0.5 * (I - rot.inertia[r]) * w2;
    rot.inertia[r] = I;
  }
  scaling.added_mass = total_added;
  // At the start the model simply begins with the scaled masses (the initial kinetic energy is
  // taken afterwards); later additions give the kinetic energy 1/2 dm v^2.
  if (!start) {
    scaling.mass_scaling_work += work;
    ++scaling.rescaled_cycles;
  }
  return true;
}

double added_mass_of_part(const MassScaling& scaling, const State& state, model::Id part_id) {
  double sum = 0.0;
  auto add = [&](const auto& blocks, const std::vector<std::vector<double>>& factors) {
    for (std::size_t b = 0; b < factors.size(); ++b) {
      if (blocks[b].part_id != part_id || factors[b].empty()) continue;
      for (std::size_t e = 0; e < factors[b].size(); ++e) {
        sum += (factors[b][e] - 1.0) * element_mass(blocks[b], e);
      }
    }
  };
  add(state.hex_blocks, scaling.hex_factor);
  add(state.shell_blocks, scaling.shell_factor);
  add(state.beam_blocks, scaling.beam_factor);
  return sum;
}

}  // namespace rf::solver
