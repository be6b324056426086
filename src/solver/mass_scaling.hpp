// Mass scaling (*CONTROL_TIMESTEP DT2MS, MS1ST), the standard of forming and quasi-static decks:
// elements whose critical step is below a target get density added so that their step reaches
// it. An element's step is L / c with c = sqrt(E / rho), so multiplying its mass by
// s_e = (target / dt_e)^2 lengthens its step to the target (LS-DYNA keyword manual,
// *CONTROL_TIMESTEP DT2MS; Belytschko, Liu, Moran, "Nonlinear Finite Elements", 2nd ed., §6.3.6).
//
//   DT2MS < 0  the target is |DT2MS| (the run's step TSSFAC |DT2MS|); mass is only added, to the
//              elements below it (s_e >= 1), checked every cycle as the mesh deforms.
//   DT2MS > 0  at the start every deformable element gets s_e = (DT2MS / dt_e)^2, adding mass
//              to small elements and removing it from large ones, so that all start at the
//              same step; afterwards mass is only added, as for DT2MS < 0.
//   MS1ST 1    the masses are set at the first step and never changed again (the step may then
//              fall below the target as elements deform).
//
// The added mass goes to an element's nodes in the proportions of its lumped mass (and to the
// rotational inertia of shell and beam nodes in those of theirs), so a scaled element is the
// physical element with density s_e rho. Body loads (*LOAD_BODY) act on the physical mass only
// (LS-DYNA's EMSCL 0). Mass added during the run keeps the nodes' velocities, which is not an
// impulse: the kinetic energy gains 1/2 dm v^2 (booked as `mass_scaling_work`, part of the
// external work, so the energy balance closes) and the momentum changes by dm v, reported in
// glstat's `added_mass` and matsum's `added_mass` (docs/output.md).
#pragma once

#include <cstdint>
#include <vector>

#include "model/model.hpp"
#include "solver/state.hpp"

namespace rf::solver {

struct MassScaling {
  double target_step = 0.0;      // |DT2MS| (the element step, before TSSFAC); 0: off
  bool uniform_start = false;    // DT2MS > 0
  bool first_step_only = false;  // MS1ST 1
  bool started = false;          // the first scaling (t = 0) was done
  // Masses without mass scaling (lumped element masses, *ELEMENT_MASS...).
  std::vector<double> physical_mass;
  std::vector<double> physical_inertia;
  // s_e per element of each block (same order as State's blocks; empty: not scaled yet).
  std::vector<std::vector<double>> hex_factor, shell_factor, beam_factor;
  double added_mass = 0.0;           // sum of nodal mass minus physical mass, deformable nodes
  double mass_scaling_work = 0.0;    // kinetic energy given by mass added during the run
  std::int64_t rescaled_cycles = 0;  // cycles in which mass was added after the start
  // Work arrays of scale_masses, kept so that a cycle that adds mass allocates nothing once
  // they have their sizes.
  struct Scratch {
    std::vector<double> raw_step, added, added_inertia, excess, no_inertia;
  } scratch;

  bool active() const { return target_step > 0.0; }
};

// Reads *CONTROL_TIMESTEP and keeps the physical masses. Throws InputError for models mass
// scaling cannot treat (order > 1 hexahedra, flexible bodies).
MassScaling setup_mass_scaling(const model::Model& model, const State& state);

// Scales where needed: at the start always, later only when `element_dt` (the smallest scaled
// step the kernels reported) is below the target and MS1ST is 0. Updates nodal masses, rotational
// inertias, blocks' step_scale and `element_dt` (and `controlling` element index). Nodes of rigid
// bodies (`body_of_node` >= 0) keep their mass. Returns whether masses changed.
bool scale_masses(MassScaling& scaling, State& state, const std::vector<std::int32_t>& body_of_node,
                  double& element_dt, model::Id& controlling_element);

// Added mass of the deformable elements of part `part_id` (matsum).
double added_mass_of_part(const MassScaling& scaling, const State& state, model::Id part_id);

}  // namespace rf::solver
