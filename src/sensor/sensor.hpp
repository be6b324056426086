// LS-DYNA sensors at run time: *SENSOR_DEFINE_NODE / _ELEMENT / _FUNCTION give values,
// *SENSOR_SWITCH (_CALC-LOGIC) turn them into true/false, *SENSOR_CONTROL counts switch events
// into an ON/OFF status. Only TYPE DEF2RIG controls exist (the reader rejects the others); their
// status changes are handed to the deformable/rigid part switching as Def2RigEvent.
//
// Everything is resolved to dense indices once (build_sensor_system); evaluate_sensors does no
// allocation and no virtual calls: it loops over one vector per sensor kind, then over switches
// and controls in dependency order. Semantics, with sources and decisions: docs/sensors.md.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <vector>

#include "model/model.hpp"
#include "solver/build_state.hpp"
#include "solver/state.hpp"

namespace rf::model {
class ArgumentFunction;
}

namespace rf::sensor {

// A DEF2RIG control whose status changed in the last evaluation: TYPEID, the SWSET of the
// *DEFORMABLE_TO_RIGID_AUTOMATIC (CODE 5) it drives, and the new status. The first evaluation
// (t = 0) reports every control whose status is then ON, so that ON always means "switch set
// applied" relative to the model as read (docs/sensors.md).
struct Def2RigEvent {
  model::Id swset = 0;
  bool status_on = false;
};

// Implementation types; read them through the functions at the end of this header.
namespace detail {

struct NodeSensor {
  int slot = 0;            // into SensorSystem::values
  std::int32_t node1 = 0;  // dense node indices; node2 -1 when the card has none
  std::int32_t node2 = -1;
  model::NodeQuantity quantity = model::NodeQuantity::Coordinate;
  bool magnitude = true;  // VID 0
  std::array<double, 3> direction{};
  // ACC: half-step velocity v^{n+1/2} of NODE1 and NODE2 at the previous evaluation.
  std::array<double, 3> previous_velocity1{}, previous_velocity2{};
};

struct ElementSensor {
  int slot = 0;
  int block = 0;             // index into State::hex_blocks
  std::int64_t element = 0;  // index within the block
  model::ElementQuantity quantity = model::ElementQuantity::Stress;
  int component = 0;  // 0..5 xx yy zz xy yz zx, 6 von Mises
  // Stress: weight of each stress point (sum 1). Strain: F = sum_a x_a (x) gradient_a, the
  // reference-volume average of the deformation gradient (3 entries per element node).
  std::vector<double> point_weight;
  std::vector<double> gradient;
};

struct FunctionSensor {
  int slot = 0;
  const model::ArgumentFunction* function = nullptr;
  std::vector<int> input_slots;
  std::vector<double> arguments;  // scratch, sized once
};

struct Switch {
  model::Id id = 0;
  bool calc_logic = false;
  bool time = false;
  bool greater = false;
  int sensor_slot = -1;
  double value = 0.0;
  double time_window = 0.0;
  double delay = 0.0;
  std::vector<int> inputs;  // CALC-LOGIC: indices into SensorSystem::switches (evaluated before)
  bool any = false;         // CALC-LOGIC: OR (negative IDs) instead of AND
  // Evolving state.
  bool condition = false;        // comparison true at this evaluation
  double condition_since = 0.0;  // time of the first evaluation of the current true run
  bool windowed = false;         // condition held for TIMWIN
  bool pending = false;          // a rising edge waits for TDELAY
  double due = 0.0;
  bool holding = false;  // fired and the condition still holds
  bool output = false;
};

struct Control {
  model::Id id = 0;
  model::Id swset = 0;
  bool on = true;
  std::vector<int> switches;  // indices into SensorSystem::switches
  int next = 0;               // the switch being watched
  int passes_done = 0;
  int passes = 1;  // -1: without end
  bool finished = false;
};

}  // namespace detail

struct SensorSystem {
  // Sensor values, one slot per sensor in ascending ID order.
  std::vector<model::Id> sensor_ids;
  std::vector<double> values;
  std::vector<detail::NodeSensor> node_sensors;
  std::vector<detail::ElementSensor> element_sensors;
  std::vector<double> element_share;  // distributed runs: this rank's element values, then sums
  std::vector<detail::FunctionSensor> function_sensors;  // in dependency order
  std::vector<detail::Switch> switches;                  // in dependency order
  std::vector<detail::Control> controls;                 // ascending ID
  std::vector<Def2RigEvent> events;                      // capacity = controls.size()
  std::map<model::Id, int> slot_of_sensor, index_of_switch, index_of_control;
  double previous_mid_time = 0.0;  // time of previous_velocity (ACC)
  double time = 0.0;               // of the last evaluation
  bool evaluated = false;
  bool changed = false;  // a switch output or control status changed in the last evaluation

  bool empty() const { return sensor_ids.empty() && switches.empty() && controls.empty(); }
};

// Resolves the model's sensors, switches and controls against the solver's mesh. Throws
// rf::InputError naming the card for references the reader could not check (models built in
// code) and for inverted reference geometry of a strain-sensed element.
SensorSystem build_sensor_system(const model::Model& model, const solver::NodeIndex& node_index,
                                 const solver::State& state);

// Once per cycle, after the forces at t^{n+1} are known and before the next step is chosen
// (state.dt is then the step dt^{n+1/2} just taken, state.dt_prev the one before; at t = 0 both
// are 0). Node values refer to t^{n+1}: COORD x^{n+1}; VEL v^{n+1/2} + dt/2 a^n; ACC a^n, the
// acceleration of the last velocity update, (v^{n+1/2} - v^{n-1/2}) / dt_avg (at t = 0 the
// unconstrained (f_ext - f_int) / m). Element values are those the kernels stored at t^{n+1}.
//
// Distributed runs (docs/parallel.md) pass `ranks`: an element sensor's value is computed by the
// rank that owns the element (only it has the element's stresses), zero elsewhere, and summed
// over the ranks, so every rank sees the same value and fires the same switches.
struct RankShare {
  std::function<bool(int block, std::int64_t element)> owns;   // hexahedron block, element index
  std::function<void(double* values, std::size_t count)> sum;  // in place, over the ranks
};
void evaluate_sensors(SensorSystem& system, const solver::State& state, double time,
                      const RankShare* ranks = nullptr);

// DEF2RIG controls: switch set IDs whose control changed status this cycle, with the new status.
std::span<const Def2RigEvent> def2rig_events(const SensorSystem& system);

// For output and tests. Throw std::out_of_range for an unknown ID.
double sensor_value(const SensorSystem& system, model::Id sensor);
bool switch_status(const SensorSystem& system, model::Id switch_id);
bool control_status(const SensorSystem& system, model::Id control);

}  // namespace rf::sensor
