// Measures of a plane compression shock running along a bar or strip of equal cells, read from
// each cell's pressure (-sigma_xx) in order from the piston (bulk_viscosity_test.cpp,
// shell_bulk_viscosity_test.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace rf::test::shock {

// Shock speed U of a piston at speed v into a hypoelastic bar whose update integrates
// sigma_xx = M ln(lambda) on this path (wave speed c = sqrt(M / rho0)): the jump conditions give
// rho0 U v = -M ln(1 - v / U), i.e. with the compression e = v / U, -e ln(1 - e) = (v / c)^2,
// increasing in e on (0, 1), solved by bisection.
inline double speed(double v, double c) {
  const double target = (v / c) * (v / c);
  double lo = 0.0, hi = 0.999;
  for (int it = 0; it < 200; ++it) {
    const double e = 0.5 * (lo + hi);
    (-e * std::log(1.0 - e) < target ? lo : hi) = e;
  }
  return v / (0.5 * (lo + hi));
}

// Mean pressure over the cells between fractions a and b of the distance the front ran.
inline double plateau(const std::vector<double>& p, double cell, double front, double a, double b) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t e = 0; e < p.size(); ++e) {
    const double x = (static_cast<double>(e) + 0.5) * cell;
    if (x > a * front && x < b * front) {
      sum += p[e];
      ++n;
    }
  }
  return n > 0 ? sum / n : 0.0;
}

// Front position by equal area: the distance over which the plateau pressure would give the
// same integral of pressure as the bar holds.
inline double front_position(const std::vector<double>& p, double cell, double plateau) {
  double area = 0.0;
  for (double q : p) area += q * cell;
  return area / plateau;
}

// Width of the front in cells: from the last cell (counting from the piston) above 90 % of the
// plateau to the first one below 10 %, interpolated linearly between cell centres.
inline double front_width(const std::vector<double>& p, double plateau) {
  auto crossing = [&](double level) {
    for (std::size_t e = p.size() - 1; e > 0; --e) {
      if (p[e - 1] >= level * plateau && p[e] < level * plateau) {
        const double f = (p[e - 1] - level * plateau) / (p[e - 1] - p[e]);
        return static_cast<double>(e - 1) + f;
      }
    }
    return 0.0;
  };
  return crossing(0.1) - crossing(0.9);
}

// Largest pressure behind the front relative to the plateau, minus 1.
inline double overshoot(const std::vector<double>& p, double plateau) {
  return *std::max_element(p.begin(), p.end()) / plateau - 1.0;
}

}  // namespace rf::test::shock
