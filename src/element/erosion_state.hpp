// Element erosion (issue 17): which elements of a block have failed and left the model, and the
// work their forces did before they left (the eroded internal energy of glstat).
//
// An eroded element keeps its place in the block (indices, IDs, output order and restart
// layout never change); it leaves the block's ElementOwnership (element_ownership.hpp), so the
// kernels, the time-step minimum and the assembly no longer see it, and its force slots hold
// zeros. Contact (contact/contact.hpp) drops its segments and exposes the faces of solids it
// uncovered; nodes whose every element has eroded are removed (NodalState::removed).
// docs/materials.md, "Failure and erosion".
#pragma once

#include <cstdint>
#include <vector>

namespace rf::element {

// The failure criteria of a block, resolved from its material and *MAT_ADD_EROSION
// (solver/erosion.cpp). A point fails by the material's own criterion (plastic strain FS/FAIL,
// Johnson-Cook damage) or by NCS of the *MAT_ADD_EROSION criteria at once; the element erodes
// when enough of its points have failed, or its step fell below TDEL.
struct ErosionCriteria {
  double plastic_strain = 0.0;  // FS (003), FAIL (024): a point fails at this plastic strain
  bool damage = false;          // Johnson-Cook D1-D5: a point fails at damage 1
  double tdel = 0.0;            // TDEL (024): the element erodes when its step is below this
  // *CONTROL_TIMESTEP ERODE names this family: the element erodes when its step (with mass
  // scaling) would bring the run's step below TSMIN (Erosion::set_minimum_step).
  bool below_minimum_step = false;
  // *MAT_ADD_EROSION (each off unless `has_*`): p = -tr(sigma)/3.
  bool has_max_pressure = false, has_min_pressure = false, has_principal_stress = false,
       has_von_mises = false, has_volumetric_strain = false, has_failure_time = false;
  double max_pressure = 0.0, min_pressure = 0.0, principal_stress = 0.0, von_mises = 0.0,
         volumetric_strain = 0.0, failure_time = 0.0;
  // Strain criteria on the logarithmic principal strains e1 >= e2 >= e3 of the point
  // (solids: from the deformation gradient; shells: the integrated in-plane strain `strain` of
  // the shell block with a volume-preserving thickness strain; trusses: ln(L/L0) with
  // volume-preserving lateral strains): e1 >= MXEPS, e3 <= MNEPS, sqrt(2/3 e':e') >= EFFEPS,
  // (e1 - e3)/2 >= EPSSH.
  bool has_max_principal_strain = false, has_min_principal_strain = false,
       has_effective_strain = false, has_shear_strain = false;
  double max_principal_strain = 0.0, min_principal_strain = 0.0, effective_strain = 0.0,
         shear_strain = 0.0;
  // Tuler-Butcher (SIGTH, IMPULSE): the point's stress impulse int max(0, sigma_1 - sigma_0)^2
  // dt (ErosionState::impulse) >= stress_impulse.
  bool has_tuler_butcher = false;
  double threshold_stress = 0.0, stress_impulse = 0.0;
  int criteria_at_once = 1;    // NCS
  double failed_points = 1.0;  // NUMFIP (< 0: percentage of the element's points, shells)
  bool strain_criteria() const {
    return has_max_principal_strain || has_min_principal_strain || has_effective_strain ||
           has_shear_strain;
  }
  int defined() const {
    return has_max_pressure + has_min_pressure + has_principal_stress + has_von_mises +
           has_volumetric_strain + has_failure_time + has_max_principal_strain +
           has_min_principal_strain + has_effective_strain + has_shear_strain + has_tuler_butcher;
  }
  bool add_erosion() const { return defined() > 0; }
};

struct ErosionState {
  // The block has a criterion that deletes elements (FS, FAIL, TDEL, Johnson-Cook damage,
  // *MAT_ADD_EROSION). False: every array below is empty and the block never erodes.
  bool enabled = false;
  ErosionCriteria criteria;
  // Per element: the time it eroded, -1 while it is in the model (a double so that the restart
  // dump carries it like every other element array).
  std::vector<double> time;
  // Per element: work of its nodal forces (and moments) since t = 0, with the displacement of
  // the step that glstat's balance uses; frozen at erosion (its eroded internal energy).
  std::vector<double> work;
  // Per element: the part of `work` done by its hourglass and bulk viscosity forces (the kernels
  // add it, hex_block.cpp, shell_block.cpp): it stays in glstat's hourglass and bulk viscosity
  // columns when the element erodes, the rest becomes eroded internal energy.
  std::vector<double> artificial_work;
  // Per stress point (Tuler-Butcher only, else empty): the stress impulse so far.
  std::vector<double> impulse;
  std::int64_t count = 0;  // eroded elements of the block

  bool is_eroded(std::size_t e) const { return enabled && time[e] >= 0.0; }
  void allocate(std::size_t n) {
    time.assign(n, -1.0);
    work.assign(n, 0.0);
    artificial_work.assign(n, 0.0);
    count = 0;
  }
};

}  // namespace rf::element
