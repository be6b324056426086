// *MAT_ELASTIC (001) in the material registry: hypoelastic, Jaumann rate, no history.
#pragma once

#include <array>

#include "material/elastic_update.hpp"
#include "material/element_family.hpp"
#include "material/history.hpp"
#include "material/plastic_parameters.hpp"
#include "model/model.hpp"

namespace rf::material {

struct ElasticMaterial {
  static constexpr model::MaterialKind kKind = model::MaterialKind::Elastic;
  // The 8-node hexahedra use this update; the p > 1 Lagrange hexahedra are total-Lagrangian
  // and use their own neo-Hookean law with the same Lame constants (lagrange_hex.hpp); shells
  // use the plane-stress closed form with the same E, nu (shell_block.cpp).
  static constexpr unsigned kFamilies = kHex8 | kLagrangeHex | kShell | kBeam | kTet13 | kTet10;
  static constexpr std::array<HistoryField, 0> kHistory{};

  template <class T>
  static void update(const ElasticConstants& m, const PlasticParameters&, const T d[6],
                     const T w[3], double dt, T s[6], T*) {
    elastic_jaumann_update(m, d, w, dt, s);
  }
};

}  // namespace rf::material
