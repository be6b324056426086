// *MAT_PIECEWISE_LINEAR_PLASTICITY (024): isotropic J2 plasticity with a piecewise-linear
// hardening law (SIGY/ETAN, the 8-point EPS/ES table or an LCSS curve), rate effects by
// Cowper-Symonds C/P or an LCSR scale curve (VP -1, 0: scaled yield; VP 1: viscoplastic with
// the additive SIGY (rate/C)^(1/P) overstress), failure strain FAIL. The return is
// j2_plasticity.hpp.
#pragma once

#include <array>

#include "material/element_family.hpp"
#include "material/history.hpp"
#include "material/j2_plasticity.hpp"
#include "model/model.hpp"

namespace rf::material {

struct PiecewiseLinearPlasticityMaterial {
  static constexpr model::MaterialKind kKind = model::MaterialKind::PiecewiseLinearPlasticity;
  static constexpr unsigned kFamilies =
      kHex8 | kShell | kBeam | kTet13 | kTet10;  // beams: truss and ELFORM 1
  static constexpr std::array<HistoryField, 1> kHistory{{{"effective_plastic_strain", 1, false}}};

  template <class T>
  static void update(const ElasticConstants& m, const PlasticParameters& p, const T d[6],
                     const T w[3], double dt, T s[6], T* h) {
    j2_update<T>(m, p, d, w, dt, s, h[0], nullptr);
  }
};

}  // namespace rf::material
