// Deformable <-> rigid part switching at run time (*DEFORMABLE_TO_RIGID*, LS-DYNA manual vol. I).
// A part switched to rigid joins a rigid body built from its nodes' current positions and
// lumped masses (or *DEFORMABLE_TO_RIGID_INERTIA) that carries exactly the linear and angular
// momentum its nodes had; the kinetic energy of the non-rigid part of the motion is removed and
// reported, the elements' stresses are frozen. Switched back, every node takes the body's
// velocity and the stresses return rotated by the body's rotation since the switch. Every element
// family switches (hexahedra, shells, beams: element/switch_state.hpp says what each family's
// frozen state needs); nodes with rotations bring their rotary inertia into the body and their
// spin I w into its angular momentum, and take the body's spin when released. The
// automatic switch sets (CODE 0, 1, 3, 5, pairing, delays) decide when. Theory and choices:
// docs/switching.md.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"
#include "switching/flexible_switching.hpp"

namespace rf::switching {

// What one switch did (a row of switch.csv).
struct SwitchEvent {
  double time = 0.0;
  model::Id swset = 0;  // 0: *DEFORMABLE_TO_RIGID at the start or a restart deck
  bool to_rigid = true;
  std::vector<model::Id> parts;
  // Of every node and body the switch touched, before and after (momenta are equal to
  // round-off: that is the point).
  double kinetic_energy_before = 0.0;
  double kinetic_energy_after = 0.0;
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_momentum = Eigen::Vector3d::Zero();  // about the global origin
  // Flexible bodies released to deformable (docs/flexible_bodies.md section 6): their modal
  // elastic energy 1/2 w^2 q^2 before, and the strain energy the restored stress increment
  // stores in the elements (booked as internal work; the difference goes to switch_energy).
  double modal_elastic_released = 0.0;
  double strain_energy_restored = 0.0;
};

// The block of a part, in its element family's list of solver::State.
struct PartBlock {
  enum class Family : std::uint8_t { kHex, kShell, kBeam };
  Family family = Family::kHex;
  int index = 0;
};

// Calls f with the part's block (element::HexBlock, ShellBlock or BeamBlock; const if the state
// is): the per-family dispatch of the switcher, once per part and switch.
template <class S, class F>
decltype(auto) with_block(S& state, PartBlock b, F&& f) {
  switch (b.family) {
    case PartBlock::Family::kShell:
      return f(state.shell_blocks[static_cast<std::size_t>(b.index)]);
    case PartBlock::Family::kBeam:
      return f(state.beam_blocks[static_cast<std::size_t>(b.index)]);
    case PartBlock::Family::kHex:
    default:
      return f(state.hex_blocks[static_cast<std::size_t>(b.index)]);
  }
}

// Runtime part switching on the solver's state and rigid system.
class PartSwitcher {
 public:
  PartSwitcher(const model::Model& model, const solver::State& state);

  // Switches the named parts (part sets expanded) to rigid. Parts with the same lead (LRB, or
  // none) that share nodes, and rigid bodies that share nodes with them, become one body.
  // Call between cycles: nodes at x^n with v^{n-1/2}, bodies at the same levels.
  SwitchEvent to_rigid(const std::vector<model::PartSwitch>& cards, double time,
                       solver::State& state, solver::RigidSystem& rigid);
  // Switches the named parts back to deformable.
  SwitchEvent to_deformable(const std::vector<model::PartSwitch>& cards, double time,
                            solver::State& state, solver::RigidSystem& rigid);

  // NRBF = 1: nodal rigid bodies that share no node with a body made by switching are
  // deleted (kept for NRBF = 2); their nodes go on with the body's velocity field.
  // NRBF = 2: deleted nodal rigid bodies are made again from their nodes' current state,
  // conserving momenta. Both return the kinetic energy change (<= 0 for activation).
  double delete_nodal_rigid_bodies(double time, solver::State& state, solver::RigidSystem& rigid);
  double activate_nodal_rigid_bodies(double time, solver::State& state, solver::RigidSystem& rigid);

  // Strain energy held by the elements of parts that are rigid by switching (computed from
  // their frozen stresses, linear elasticity).
  double frozen_energy() const;
  bool is_switched_rigid(model::Id pid) const { return switched_.count(pid) != 0; }
  // The block of a part (any family), or null when the part has no elements.
  const PartBlock* block_of_part(model::Id pid) const {
    const auto it = block_of_part_.find(pid);
    return it == block_of_part_.end() ? nullptr : &it->second;
  }
  // Notices met while switching (parts already in the requested state, constraints that do
  // not act on rigid nodes); the solver shows them.
  std::vector<std::string> notices;

  // The state carried between cycles, for restart dumps.
  struct SwitchedPart {
    model::Id body_id = 0;            // the body it belongs to (its first part's ID)
    Eigen::Matrix3d rotation_offset;  // Q = Phi_body * offset: rotation since the switch
    double frozen_energy = 0.0;
  };
  std::map<model::Id, SwitchedPart>& switched_parts() { return switched_; }
  std::vector<solver::RigidBody>& deleted_nodal_bodies() { return deleted_nodal_; }

  // Parts that are deformable in the input and named by *PART_MODES become flexible bodies when
  // switched to rigid (switching/flexible_switching.hpp). Without this call such a switch is an
  // error.
  void enable_flexible_bodies(const solver::ModeLoader& loader, const solver::State& state);
  FlexibleSwitching* flexible_bodies() { return flexible_.get(); }  // null: none

 private:
  std::vector<model::Id> expand(const std::vector<model::PartSwitch>& cards) const;
  const model::Model& model_;
  std::map<model::Id, PartBlock> block_of_part_;
  std::map<model::Id, SwitchedPart> switched_;
  std::vector<solver::RigidBody> deleted_nodal_;  // NRBF = 1, for NRBF = 2
  std::unique_ptr<FlexibleSwitching> flexible_;
};

// Physical rotation of a body since its reference (R R0^T): continuous across re-definitions
// of the body's principal axes (switching keeps it so).
Eigen::Matrix3d body_rotation(const solver::RigidBody& body);

// The automatic switch sets: which fire now.
struct AutomaticSwitchState {
  bool armed = true;       // may fire (paired: its turn)
  bool time_used = false;  // CODE 0: the crossing of TIME1 happened (it happens once)
  int fired = 0;
};

// Answers the force conditions of CODE 1 and 3: |wall force| of rigid wall `number` in the
// last cycle (negative: no such wall), and whether any of the given nodes lies within
// `offset` of it.
struct SwitchQueries {
  std::function<double(model::Id number)> wall_force;
  std::function<bool(model::Id number, double offset, const std::vector<model::Id>& parts)>
      wall_within_offset;
  // CODE 2 and 4: |resultant contact force| of the contact with ID `id` at the last evaluation
  // (negative: no such contact), and whether a node of the given parts lies within `offset` of
  // the other side of that contact (contact/contact.hpp).
  std::function<double(model::Id id)> contact_force;
  std::function<bool(model::Id id, double offset, const std::vector<model::Id>& parts)>
      contact_within_offset;
  // CODE 5: the sensor control of switch set `swset` turned ON this cycle.
  std::function<bool(model::Id swset)> sensor_triggered;
};

class AutomaticSwitching {
 public:
  explicit AutomaticSwitching(const std::vector<model::AutomaticSwitchSet>& sets);
  // Indices of the sets whose conditions hold at time t (in deck order) into `out` (cleared;
  // no allocation once it has grown). Call once per cycle.
  void due(double t, const SwitchQueries& queries, std::vector<int>& out) const;
  // Records that set k fired at time t: delay and pairing.
  void fired(int k, double t);
  bool empty() const { return sets_.empty(); }
  const std::vector<AutomaticSwitchState>& states() const { return state_; }
  // Restart dumps.
  std::vector<AutomaticSwitchState>& mutable_states() { return state_; }
  double blocked_until() const { return blocked_until_; }
  void set_blocked_until(double t) { blocked_until_ = t; }

 private:
  const std::vector<model::AutomaticSwitchSet>& sets_;
  std::vector<AutomaticSwitchState> state_;
  std::vector<std::vector<model::Id>> released_parts_;  // R2D part IDs per set (OFFSET test)
  double blocked_until_ = -1e300;                       // TIME3 of the last switch
};

}  // namespace rf::switching
