#include "sensor/sensor.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <unordered_map>

#include "element/hex_geometry.hpp"
#include "element/lagrange_hex.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"
#include "model/function.hpp"

namespace rf::sensor {

namespace {

using model::context_of;
using model::Id;

// Time comparisons (TIMWIN, TDELAY) tolerate the round-off of summed time steps.
bool reached(double time, double target) {
  return time >= target - 1e-12 * std::max({1.0, std::abs(time), std::abs(target)});
}

// Reference-volume average of the shape-function gradients, g_a = (1/V0) int dN_a/dX dV0, so
// that F_avg = sum_a x_a (x) g_a is the volume average of the deformation gradient.
std::vector<double> average_gradient(const element::HexBlock& block, std::size_t e,
                                     const solver::NodalState& nodes, const model::Sensor& s) {
  const int npe = block.nodes_per_element();
  std::vector<double> g(3 * static_cast<std::size_t>(npe), 0.0);
  const std::int32_t* conn = &block.conn[static_cast<std::size_t>(npe) * e];
  if (block.quadratic_tetrahedra()) {
    throw InputError(context_of(s.where, "ELEMID"),
                     fmt::format("element {} is a 10-node tetrahedron (ELFORM 16): element strain "
                                 "sensors serve hexahedra and 4-node tetrahedra only",
                                 s.element));
  }
  if (block.order == 1) {
    // The uniform-strain operator b_iI = (1/V) dV/dx_iI (Flanagan & Belytschko 1981) evaluated
    // on the reference coordinates is exactly this average for a trilinear hexahedron.
    double x[3][8];
    for (int a = 0; a < 8; ++a) {
      x[0][a] = nodes.x0.x[conn[a]];
      x[1][a] = nodes.x0.y[conn[a]];
      x[2][a] = nodes.x0.z[conn[a]];
    }
    element::hex::Geometry geometry;
    element::hex::compute_geometry(x, geometry);
    if (!(geometry.volume > 0.0)) {
      throw InputError(context_of(s.where, "ELEMID"),
                       fmt::format("element {} has reference volume {:.6g}; its strain is "
                                   "undefined",
                                   s.element, geometry.volume));
    }
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i) g[3 * a + i] = geometry.b[i][a] / geometry.volume;
    return g;
  }
  // Lagrange hexahedra: dN_a/dxi at GLL point q from the 1D differentiation matrix (node a and
  // point q in tensor order), mapped with the stored dxi/dX and weighted with w_q det J0.
  const element::GllRule& rule = element::gll_rule(block.order);
  const int n1 = block.order + 1;
  const double* jinv_all = &block.reference_inverse_jacobian[9 * static_cast<std::size_t>(npe) * e];
  const double* w_all = &block.reference_weight[static_cast<std::size_t>(npe) * e];
  double volume = 0.0;
  for (int q = 0; q < npe; ++q) {
    const int qi = q % n1, qj = (q / n1) % n1, qk = q / (n1 * n1);
    const double* jinv = jinv_all + 9 * q;  // jinv[3 d + c] = dxi_d / dX_c
    volume += w_all[q];
    for (int a = 0; a < npe; ++a) {
      const int ai = a % n1, aj = (a / n1) % n1, ak = a / (n1 * n1);
      const double d0 = (aj == qj && ak == qk) ? rule.derivative[qi * n1 + ai] : 0.0;
      const double d1 = (ai == qi && ak == qk) ? rule.derivative[qj * n1 + aj] : 0.0;
      const double d2 = (ai == qi && aj == qj) ? rule.derivative[qk * n1 + ak] : 0.0;
      if (d0 == 0.0 && d1 == 0.0 && d2 == 0.0) continue;
      for (int c = 0; c < 3; ++c) {
        g[3 * a + c] += w_all[q] * (d0 * jinv[c] + d1 * jinv[3 + c] + d2 * jinv[6 + c]);
      }
    }
  }
  if (!(volume > 0.0)) {
    throw InputError(context_of(s.where, "ELEMID"),
                     fmt::format("element {} has reference volume {:.6g}; its strain is undefined",
                                 s.element, volume));
  }
  for (double& v : g) v /= volume;
  return g;
}

double von_mises(const double t[6]) {
  const double a = t[0] - t[1], b = t[1] - t[2], c = t[2] - t[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5]));
}

double element_value(const detail::ElementSensor& s, const solver::State& state) {
  const element::HexBlock& block = state.hex_blocks[static_cast<std::size_t>(s.block)];
  const std::size_t e = static_cast<std::size_t>(s.element);
  double t[6] = {0, 0, 0, 0, 0, 0};  // xx yy zz xy yz zx
  if (s.quantity == model::ElementQuantity::Stress) {
    const std::size_t points = s.point_weight.size();
    if (block.stress.size() < 6 * points * (e + 1)) return 0.0;
    const double* stress = &block.stress[6 * points * e];
    for (std::size_t p = 0; p < points; ++p)
      for (int c = 0; c < 6; ++c) t[c] += s.point_weight[p] * stress[6 * p + c];
    return s.component == 6 ? von_mises(t) : t[s.component];
  }
  // Logarithmic (Hencky) strain of the average deformation gradient, in global axes:
  // e = 1/2 ln(F F^T). For a stretch without rotation it is the time integral of the rate of
  // deformation, the strain of LS-DYNA's rate-form solids; shear components are tensor
  // components (half the engineering shear strain).
  const auto npe = static_cast<std::size_t>(block.nodes_per_element());
  const std::int32_t* conn = &block.conn[npe * e];
  const auto& x = state.nodes.x;
  Eigen::Matrix3d f = Eigen::Matrix3d::Zero();
  for (std::size_t a = 0; a < npe; ++a) {
    const Eigen::Vector3d xa(x.x[conn[a]], x.y[conn[a]], x.z[conn[a]]);
    const Eigen::Vector3d ga(s.gradient[3 * a], s.gradient[3 * a + 1], s.gradient[3 * a + 2]);
    f += xa * ga.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(f * f.transpose());
  Eigen::Vector3d log_stretch;
  for (int k = 0; k < 3; ++k) {
    const double lambda2 = eigen.eigenvalues()[k];
    log_stretch[k] = lambda2 > 0.0 ? 0.5 * std::log(lambda2) : -1e300;
  }
  const Eigen::Matrix3d strain =
      eigen.eigenvectors() * log_stretch.asDiagonal() * eigen.eigenvectors().transpose();
  t[0] = strain(0, 0);
  t[1] = strain(1, 1);
  t[2] = strain(2, 2);
  t[3] = strain(0, 1);
  t[4] = strain(1, 2);
  t[5] = strain(2, 0);
  if (s.component < 6) return t[s.component];
  // Equivalent strain sqrt(2/3 e':e') of the deviator e'.
  const double mean = (t[0] + t[1] + t[2]) / 3.0;
  const double d0 = t[0] - mean, d1 = t[1] - mean, d2 = t[2] - mean;
  return std::sqrt(2.0 / 3.0 *
                   (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5])));
}

}  // namespace

SensorSystem build_sensor_system(const model::Model& model, const solver::NodeIndex& node_index,
                                 const solver::State& state) {
  SensorSystem sys;
  for (const auto& [id, s] : model.sensors) {
    sys.slot_of_sensor[id] = static_cast<int>(sys.sensor_ids.size());
    sys.sensor_ids.push_back(id);
  }
  sys.values.assign(sys.sensor_ids.size(), 0.0);
  const auto slot_of = [&](Id id, const model::SourceLocation& where, const char* field) {
    const auto it = sys.slot_of_sensor.find(id);
    if (it == sys.slot_of_sensor.end()) {
      throw InputError(context_of(where, field), fmt::format("sensor {} is not defined", id));
    }
    return it->second;
  };

  // Element user ID -> (block, index), built only when element sensors exist.
  std::unordered_map<Id, std::pair<int, std::int64_t>> element_at;
  for (const auto& [id, s] : model.sensors) {
    if (s.kind != model::SensorKind::Element) continue;
    if (element_at.empty()) {
      for (std::size_t b = 0; b < state.hex_blocks.size(); ++b) {
        const auto& ids = state.hex_blocks[b].element_id;
        for (std::size_t e = 0; e < ids.size(); ++e) {
          element_at.emplace(ids[e], std::pair{static_cast<int>(b), static_cast<std::int64_t>(e)});
        }
      }
    }
    break;
  }

  std::vector<Id> function_ids;
  for (const auto& [id, s] : model.sensors) {
    const int slot = sys.slot_of_sensor.at(id);
    switch (s.kind) {
      case model::SensorKind::Node: {
        detail::NodeSensor n;
        n.slot = slot;
        n.node1 = node_index.at(s.node1, s.where, "NODE1");
        n.node2 = s.node2 != 0 ? node_index.at(s.node2, s.where, "NODE2") : -1;
        n.quantity = s.node_quantity;
        if (s.vid != 0) {
          const auto v = model.vectors.find(s.vid);
          if (v == model.vectors.end()) {
            throw InputError(context_of(s.where, "VID"),
                             fmt::format("vector {} is not defined (*DEFINE_VECTOR)", s.vid));
          }
          n.magnitude = false;
          n.direction = v->second.direction;
        }
        sys.node_sensors.push_back(n);
        break;
      }
      case model::SensorKind::Element: {
        const auto at = element_at.find(s.element);
        if (at == element_at.end()) {
          throw InputError(context_of(s.where, "ELEMID"),
                           fmt::format("solid element {} is not defined", s.element));
        }
        detail::ElementSensor es;
        es.slot = slot;
        es.block = at->second.first;
        es.element = at->second.second;
        es.quantity = s.element_quantity;
        es.component = s.component;
        const element::HexBlock& block = state.hex_blocks[static_cast<std::size_t>(es.block)];
        const auto e = static_cast<std::size_t>(es.element);
        const int points = block.points_per_element();
        es.point_weight.assign(static_cast<std::size_t>(points), 1.0 / points);
        if (block.order > 1 &&
            block.reference_weight.size() >= static_cast<std::size_t>(points) * (e + 1)) {
          // GLL points carry w_q det J0: the stress average is over the reference volume.
          double total = 0.0;
          for (int q = 0; q < points; ++q) total += block.reference_weight[points * e + q];
          for (int q = 0; q < points; ++q) {
            es.point_weight[q] = block.reference_weight[points * e + q] / total;
          }
        }
        if (es.quantity == model::ElementQuantity::Strain) {
          es.gradient = average_gradient(block, e, state.nodes, s);
        }
        sys.element_sensors.push_back(std::move(es));
        break;
      }
      case model::SensorKind::Function:
        function_ids.push_back(id);
        break;
    }
  }

  // Function sensors after the sensors they read (the reader rejects cycles).
  std::unordered_map<Id, int> mark;
  std::function<void(Id)> add_function = [&](Id id) {
    if (mark[id] != 0) return;
    mark[id] = 1;
    const model::Sensor& s = model.sensors.at(id);
    for (const Id input : s.inputs) {
      const auto it = model.sensors.find(input);
      if (it != model.sensors.end() && it->second.kind == model::SensorKind::Function) {
        if (mark[input] == 1) {
          throw InputError(context_of(s.where, "SENS1"),
                           fmt::format("function sensors form a cycle through sensor {}", id));
        }
        add_function(input);
      }
    }
    detail::FunctionSensor fs;
    fs.slot = sys.slot_of_sensor.at(id);
    const auto f = model.defined_functions.find(s.function);
    if (f == model.defined_functions.end() || !f->second.evaluator) {
      throw InputError(context_of(s.where, "FUNC"),
                       fmt::format("function {} is not defined or cannot be compiled "
                                   "(*DEFINE_FUNCTION)",
                                   s.function));
    }
    fs.function = f->second.evaluator.get();
    if (fs.function->arguments().size() != s.inputs.size()) {
      throw InputError(context_of(s.where, "FUNC"),
                       fmt::format("function {} takes {} argument(s) but {} sensor(s) are given",
                                   s.function, fs.function->arguments().size(), s.inputs.size()));
    }
    for (std::size_t k = 0; k < s.inputs.size(); ++k) {
      fs.input_slots.push_back(slot_of(s.inputs[k], s.where, "SENS1"));
    }
    fs.arguments.assign(s.inputs.size(), 0.0);
    sys.function_sensors.push_back(std::move(fs));
    mark[id] = 2;
  };
  for (const Id id : function_ids) add_function(id);

  // Comparison switches first, then CALC-LOGIC switches after their inputs.
  for (const auto& [id, w] : model.sensor_switches) {
    if (w.calc_logic) continue;
    detail::Switch sw;
    sw.id = id;
    sw.time = w.time;
    sw.greater = w.greater;
    sw.value = w.value;
    sw.time_window = w.time_window;
    sw.delay = w.delay;
    if (!w.time) sw.sensor_slot = slot_of(w.sensor, w.where, "SENSID");
    sys.index_of_switch[id] = static_cast<int>(sys.switches.size());
    sys.switches.push_back(std::move(sw));
  }
  std::unordered_map<Id, int> logic_mark;
  std::function<void(Id)> add_logic = [&](Id id) {
    if (sys.index_of_switch.count(id)) return;
    const auto it = model.sensor_switches.find(id);
    const model::SensorSwitch& w = it->second;
    if (logic_mark[id] == 1) {
      throw InputError(context_of(w.where, "SWIT1"),
                       fmt::format("*SENSOR_SWITCH_CALC-LOGIC switches form a cycle through "
                                   "switch {}",
                                   id));
    }
    logic_mark[id] = 1;
    detail::Switch sw;
    sw.id = id;
    sw.calc_logic = true;
    sw.any = !w.logic_inputs.empty() && w.logic_inputs.front() < 0;
    for (const Id signed_input : w.logic_inputs) {
      const Id input = std::abs(signed_input);
      if (!model.sensor_switches.count(input)) {
        throw InputError(context_of(w.where, "SWIT1"),
                         fmt::format("switch {} is not defined (*SENSOR_SWITCH)", input));
      }
      add_logic(input);
      sw.inputs.push_back(sys.index_of_switch.at(input));
    }
    sys.index_of_switch[id] = static_cast<int>(sys.switches.size());
    sys.switches.push_back(std::move(sw));
  };
  for (const auto& [id, w] : model.sensor_switches) {
    if (w.calc_logic) add_logic(id);
  }

  for (const auto& [id, c] : model.sensor_controls) {
    if (c.type != "DEF2RIG") {
      throw InputError(context_of(c.where, "TYPE"),
                       fmt::format("TYPE {} is not supported yet (supported: DEF2RIG)", c.type));
    }
    detail::Control control;
    control.id = id;
    control.swset = c.type_id;
    control.on = c.initially_on;
    control.passes = c.nrep == -1 ? -1 : std::max(c.nrep, 1);
    for (std::size_t k = 0; k < c.switches.size(); ++k) {
      const auto it = sys.index_of_switch.find(c.switches[k]);
      if (it == sys.index_of_switch.end()) {
        throw InputError(context_of(c.where, fmt::format("SWIT{}", k + 1).c_str()),
                         fmt::format("switch {} is not defined (*SENSOR_SWITCH)", c.switches[k]));
      }
      control.switches.push_back(it->second);
    }
    control.finished = control.switches.empty();
    sys.index_of_control[id] = static_cast<int>(sys.controls.size());
    sys.controls.push_back(std::move(control));
  }
  sys.events.reserve(sys.controls.size());
  return sys;
}

void evaluate_sensors(SensorSystem& sys, const solver::State& state, double time,
                      const RankShare* ranks) {
  sys.events.clear();
  sys.changed = false;
  const bool first = !sys.evaluated;
  const solver::NodalState& nodes = state.nodes;

  // Node sensors. v holds v^{n+1/2}, dt is dt^{n+1/2}: its mid time is t^{n+1} - dt/2.
  const double mid_time = time - 0.5 * state.dt;
  const double dt_average = mid_time - sys.previous_mid_time;
  for (auto& s : sys.node_sensors) {
    double q[3] = {0.0, 0.0, 0.0};
    if (s.quantity == model::NodeQuantity::Coordinate) {
      const std::int32_t i = s.node1;
      q[0] = nodes.x.x[i];
      q[1] = nodes.x.y[i];
      q[2] = nodes.x.z[i];
      if (s.node2 >= 0) {
        q[0] -= nodes.x.x[s.node2];
        q[1] -= nodes.x.y[s.node2];
        q[2] -= nodes.x.z[s.node2];
      }
    } else {
      if (!first && !(dt_average > 0.0)) continue;  // same time again: nothing new
      for (int which = 0; which < 2; ++which) {
        const std::int32_t i = which == 0 ? s.node1 : s.node2;
        if (i < 0) continue;
        auto& previous = which == 0 ? s.previous_velocity1 : s.previous_velocity2;
        const double v[3] = {nodes.v.x[i], nodes.v.y[i], nodes.v.z[i]};
        double a[3];
        if (first) {
          const double m = nodes.mass[i];
          const double inv_m = m > 0.0 ? 1.0 / m : 0.0;
          a[0] = (nodes.f_ext.x[i] - nodes.f_int.x[i]) * inv_m;
          a[1] = (nodes.f_ext.y[i] - nodes.f_int.y[i]) * inv_m;
          a[2] = (nodes.f_ext.z[i] - nodes.f_int.z[i]) * inv_m;
        } else {
          for (int k = 0; k < 3; ++k) a[k] = (v[k] - previous[k]) / dt_average;
        }
        const double sign = which == 0 ? 1.0 : -1.0;
        for (int k = 0; k < 3; ++k) {
          q[k] += sign * (s.quantity == model::NodeQuantity::Velocity ? v[k] + 0.5 * state.dt * a[k]
                                                                      : a[k]);
          previous[k] = v[k];
        }
      }
    }
    sys.values[s.slot] =
        s.magnitude ? std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2])
                    : q[0] * s.direction[0] + q[1] * s.direction[1] + q[2] * s.direction[2];
  }
  sys.previous_mid_time = mid_time;

  if (ranks && !sys.element_sensors.empty()) {
    std::vector<double>& share = sys.element_share;
    share.assign(sys.element_sensors.size(), 0.0);
    for (std::size_t k = 0; k < share.size(); ++k) {
      const auto& s = sys.element_sensors[k];
      if (ranks->owns(s.block, s.element)) share[k] = element_value(s, state);
    }
    ranks->sum(share.data(), share.size());
    for (std::size_t k = 0; k < share.size(); ++k)
      sys.values[sys.element_sensors[k].slot] = share[k];
  } else {
    for (const auto& s : sys.element_sensors) sys.values[s.slot] = element_value(s, state);
  }

  for (auto& s : sys.function_sensors) {
    for (std::size_t k = 0; k < s.input_slots.size(); ++k)
      s.arguments[k] = sys.values[s.input_slots[k]];
    sys.values[s.slot] = (*s.function)(s.arguments, time);
  }

  for (auto& sw : sys.switches) {
    const bool before = sw.output;
    if (sw.calc_logic) {
      bool out = !sw.any;
      for (const int input : sw.inputs) {
        const bool v = sys.switches[static_cast<std::size_t>(input)].output;
        out = sw.any ? (out || v) : (out && v);
      }
      sw.output = out;
    } else {
      const double v = sw.time ? time : sys.values[static_cast<std::size_t>(sw.sensor_slot)];
      const bool condition = sw.greater ? v > sw.value : v < sw.value;
      if (condition && !sw.condition) sw.condition_since = time;
      sw.condition = condition;
      // TIMWIN: the condition must have held at every evaluation for the window.
      const bool windowed = condition && (sw.time_window <= 0.0 ||
                                          reached(time, sw.condition_since + sw.time_window));
      // TDELAY: the rising edge takes effect that much later, whatever happens meanwhile.
      if (windowed && !sw.windowed && !sw.pending) {
        sw.pending = true;
        sw.due = time + sw.delay;
      }
      sw.windowed = windowed;
      bool fired = false;
      if (sw.pending && reached(time, sw.due)) {
        sw.pending = false;
        sw.holding = true;
        fired = true;
      }
      sw.output = fired || (sw.holding && windowed);
      if (!sw.output) sw.holding = false;
    }
    sys.changed |= (sw.output != before);
  }

  for (auto& c : sys.controls) {
    bool changed = false;
    if (!c.finished && sys.switches[static_cast<std::size_t>(c.switches[c.next])].output) {
      // SWITn changes the status set by SWITn-1; at most one change per control and cycle.
      c.on = !c.on;
      changed = true;
      if (++c.next == static_cast<int>(c.switches.size())) {
        ++c.passes_done;
        if (c.passes == -1 || c.passes_done < c.passes) {
          c.next = 0;
        } else {
          c.finished = true;
        }
      }
    }
    sys.changed |= changed;
    if (first ? c.on : changed) sys.events.push_back({c.swset, c.on});
  }
  sys.time = time;
  sys.evaluated = true;
}

std::span<const Def2RigEvent> def2rig_events(const SensorSystem& system) {
  return system.events;
}

double sensor_value(const SensorSystem& system, model::Id sensor) {
  return system.values.at(static_cast<std::size_t>(system.slot_of_sensor.at(sensor)));
}

bool switch_status(const SensorSystem& system, model::Id switch_id) {
  return system.switches.at(static_cast<std::size_t>(system.index_of_switch.at(switch_id))).output;
}

bool control_status(const SensorSystem& system, model::Id control) {
  return system.controls.at(static_cast<std::size_t>(system.index_of_control.at(control))).on;
}

}  // namespace rf::sensor
