// *MAT_PLASTIC_KINEMATIC (003): bilinear J2 plasticity, isotropic/kinematic mix BETA,
// Cowper-Symonds rate scaling (SRC, SRP; VP 0 scaled yield, VP 1 viscoplastic), failure
// strain FS. Hardening: Ep = E ETAN / (E - ETAN) split into BETA Ep (radius) and
// (1 - BETA) Ep (Prager back stress). The return is j2_plasticity.hpp.
#pragma once

#include <array>

#include "material/element_family.hpp"
#include "material/history.hpp"
#include "material/j2_plasticity.hpp"
#include "model/model.hpp"

namespace rf::material {

struct PlasticKinematicMaterial {
  static constexpr model::MaterialKind kKind = model::MaterialKind::PlasticKinematic;
  static constexpr unsigned kFamilies =
      kHex8 | kShell | kBeam | kTet13 | kTet10;  // beams: truss and ELFORM 1
  static constexpr std::array<HistoryField, 2> kHistory{
      {{"effective_plastic_strain", 1, false}, {"back_stress", 6, true}}};

  // h: effective plastic strain, then the back stress (Voigt, tensor components).
  template <class T>
  static void update(const ElasticConstants& m, const PlasticParameters& p, const T d[6],
                     const T w[3], double dt, T s[6], T* h) {
    j2_update(m, p, d, w, dt, s, h[0], h + 1);
  }
};

}  // namespace rf::material
