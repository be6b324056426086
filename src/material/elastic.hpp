// Isotropic linear elasticity (*MAT_ELASTIC, type 001).
#pragma once

#include <cmath>

namespace rf::material {

struct ElasticConstants {
  double rho = 0.0;
  double young = 0.0;
  double poisson = 0.0;
  double lambda = 0.0;     // Lame's first parameter
  double shear = 0.0;      // mu
  double bulk = 0.0;       // K
  double wave_speed = 0.0; // dilatational (P-wave) speed sqrt((lambda + 2 mu) / rho)
};

inline ElasticConstants make_elastic(double rho, double young, double poisson) {
  ElasticConstants c;
  c.rho = rho;
  c.young = young;
  c.poisson = poisson;
  c.shear = young / (2.0 * (1.0 + poisson));
  c.lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  c.bulk = young / (3.0 * (1.0 - 2.0 * poisson));
  c.wave_speed = std::sqrt((c.lambda + 2.0 * c.shear) / rho);
  return c;
}

}  // namespace rf::material
