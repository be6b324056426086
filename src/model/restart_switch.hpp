// Part switching requested by a restart deck (LS-DYNA small restart: *DEFORMABLE_TO_RIGID and
// *RIGID_TO_DEFORMABLE, Keyword User's Manual Vol. I, "Restart Input Data"). The restart deck
// reader resolves part sets, the solver applies the switches to the restored state
// (Simulation::apply_restart_switches).
#pragma once

#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace rf::model {

struct RestartSwitch {
  enum class Direction : std::uint8_t { kDeformableToRigid, kRigidToDeformable };
  Direction direction = Direction::kDeformableToRigid;
  // Part IDs to switch: the card's PID, or every part of part set PID when PTYPE is PSET.
  std::vector<Id> parts;
  // *DEFORMABLE_TO_RIGID LRB (MRB in older manuals): the rigid part the switched parts merge
  // into. 0: each part becomes an independent rigid body (or the lead of later merges).
  Id lead_rigid_body = 0;
  SourceLocation where;  // the card, for messages
};

}  // namespace rf::model
