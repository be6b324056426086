// Part switching of a flexible body: a part that is deformable in the input and named by
// *PART_MODES becomes a flexible rigid body when it is switched to rigid (*DEFORMABLE_TO_RIGID,
// an automatic D2R set) and a deformable part again when it is switched back (an automatic R2D
// set). Theory, choices and energy bookkeeping: docs/flexible_bodies.md section 6.
//
// To rigid: the current (deformed) shape is the body's rigid shape, as LS-DYNA keeps it for any
// switched part; the database modes (global axes, reference configuration) are turned by the
// best-fit rotation of the current shape relative to the reference and describe small
// perturbations about it, q = 0 (the deformation present at the switch stays in the frozen
// element stresses), and the modal velocities are the projection of the non-rigid nodal
// velocities, s = Phi^T M R^T (v - v_rigid). Kinetic energy the modes cannot carry goes to
// switch_energy. To deformable: the nodes get the reconstructed positions and velocities (rigid +
// modal), the element stresses get the increment of the modal displacement (computed by the
// element kernel itself, so every element formulation is served), and the strain energy that
// increment stores is booked as internal work; what the modal elastic energy and the modal
// kinetic energy do not match goes to switch_energy.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <map>
#include <vector>

#include "model/model.hpp"
#include "solver/flexible_bodies.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"

namespace rf::switching {

class FlexibleSwitching {
 public:
  // Reads the mode database of every part that is deformable in the input and named by
  // *PART_MODES, matches its nodes by ID and selects the modes; rf::InputError at the card for
  // a missing database, missing nodes, another geometry or too few modes.
  FlexibleSwitching(const model::Model& model, const solver::State& state,
                    const solver::ModeLoader& loader);

  bool has_modes(model::Id pid) const { return parts_.count(pid) != 0; }
  bool empty() const { return parts_.empty(); }

  // Makes rigid body `body_index` (just made from part `pid` alone by the switcher, node
  // velocities already set to its rigid field) a flexible body. `velocities` are the nodes'
  // velocities before the switch, 3 per node of the body (in body.nodes order). Returns the
  // modal kinetic energy 1/2 |s|^2 it took over.
  double attach(model::Id pid, int body_index, const std::vector<double>& velocities,
                solver::State& state, solver::RigidSystem& rigid);

  // Restart: makes body `body_index` (restored from a dump) the flexible body of part `pid`
  // again with the mode frame it had (frames()); the modal state is read from the dump after.
  void rebuild(model::Id pid, int body_index, const Eigen::Matrix3d& frame,
               const solver::State& state, solver::RigidSystem& rigid);
  // The mode frame R0 = Q^T R of each part that is a flexible body now (restart dumps).
  std::map<model::Id, Eigen::Matrix3d>& frames() { return frames_; }

  // Before a flexible body's part is released: places its nodes at x_c + R (X + Phi q) and adds
  // the stress increment of the modal displacement R Phi q to `block` (whose frozen stresses
  // are already rotated by the body's rotation). Returns the strain energy the increment
  // stored, 1/2 (f_before + f_after) . du over the block's nodes.
  double restore_modal_stresses(const solver::RigidBody& body, const modal::FlexibleBody& f,
                                element::HexBlock& block, solver::State& state) const;

  // The released nodes' velocities: v_c + w x r_i + R Phi_i s_half (s_half = (q^n - q^{n-1}) /
  // dt_prev, the leapfrog-consistent half-step modal velocity), then a rigid rotation about x_c
  // that restores the body's angular momentum exactly (the modes carry a little of it when
  // deformed, O(q)). Removes the flexible body from `rigid` (indices kept consistent).
  void release_velocities(int body_index, double dt_prev, solver::State& state,
                          solver::RigidSystem& rigid);

 private:
  struct PartModes {
    const model::PartModes* card = nullptr;
    std::vector<std::int32_t> nodes;  // the part's nodes, ascending (dense indices)
    std::vector<double> mass;         // their lumped masses
    std::vector<int> file_modes;      // 1-based database mode numbers kept
    std::vector<double> eigenvalues;  // per kept mode
    std::vector<double> damping;      // per kept mode
    std::vector<double> shapes;       // mode c, node k, direction d at [c 3N + 3 k + d] (global)
    std::vector<std::int32_t> hexahedra;  // FORM 0 stiffening: positions in `nodes`
    double lame_lambda = 0.0;
    double lame_mu = 0.0;
  };
  modal::FlexibleBody prepare(model::Id pid, const solver::RigidBody& body,
                              const Eigen::Matrix3d& frame, double time) const;
  std::map<model::Id, PartModes> parts_;
  std::map<model::Id, Eigen::Matrix3d> frames_;
};

}  // namespace rf::switching
