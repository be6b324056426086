// The rotation of a node with rotational degrees of freedom over a step, as the energy balance
// takes it (Simulation::update_rotations) and matsum's part work repeats it (part_histories.cpp):
// dt_avg (omega^{n-1/2} + omega^{n+1/2}) / 2, and on a flexible body the body's turn
// dt_avg omega_mid plus the modes' share (their work velocity, solver/flexible_bodies.hpp), so
// that the moments' work equals what the body and its modes received.
#pragma once

#include <array>
#include <cstdint>

#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"

namespace rf::solver {

// `body_of` (nullptr: no rigid bodies) and `modal_work` (nullptr: no flexible body with rotations)
// are the rigid system's body_of_node and modal_rotation_work_velocity data.
inline std::array<double, 3> step_rotation(const RotationalState& rot, const RigidSystem& rigid,
                                           const std::int32_t* body_of, const double* modal_work,
                                           std::int64_t r, double dt_avg) {
  const std::int32_t i = rot.node[r];
  if (modal_work && body_of && body_of[i] >= 0) {
    const auto& w_mid = rigid.bodies[body_of[i]].mid_angular_velocity;
    return {dt_avg * (w_mid.x() + modal_work[3 * r]), dt_avg * (w_mid.y() + modal_work[3 * r + 1]),
            dt_avg * (w_mid.z() + modal_work[3 * r + 2])};
  }
  return {0.5 * dt_avg * (rot.w_previous.x[r] + rot.w.x[r]),
          0.5 * dt_avg * (rot.w_previous.y[r] + rot.w.y[r]),
          0.5 * dt_avg * (rot.w_previous.z[r] + rot.w.z[r])};
}

}  // namespace rf::solver
