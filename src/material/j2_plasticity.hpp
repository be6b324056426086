// Rate-independent and rate-dependent J2 (von Mises) plasticity with mixed isotropic/kinematic
// hardening, integrated in the co-rotational (Jaumann) frame of the hypoelastic update.
//
// One step (Simo & Hughes, Computational Inelasticity, 1998, box 3.2, radial return; Krieg &
// Key 1976):
//   1. objective rotation: stress s and back stress a turned by the Hughes-Winget rotation of the
//      mid-step spin (elastic_update.hpp), so a rigid rotation carries both unchanged in shape;
//   2. elastic predictor s_tr = s + C : D dt;
//   3. relative deviator xi = dev(s_tr) - a, J = sqrt(3/2 xi:xi); if J > sigma_y(eps_p, rate) the
//      plastic increment dl (effective plastic strain) solves
//        J - (3G + H_k) dl = sigma_y(eps_p + dl, rate),
//      with H_k the kinematic modulus; the flow direction n = 3/2 xi / J is fixed over the step,
//      so  s -= 3G dl xi / J,  a += H_k dl xi / J,  eps_p += dl.
// For the linear law with no rate term or a rate factor fixed by the total strain rate (VP 0)
// the equation is linear: dl = (J - k sigma_y) / (3G + H_k + k H_i) (k the rate factor, H_i
// the isotropic slope), evaluated across SIMD lanes. Piecewise-linear curves and the
// viscoplastic form (VP 1, rate = dl / dt) are solved per lane by the scalar routine below.
//
// The uniaxial answer: under uniaxial stress with eps_p growing, sigma = a + sigma_y; for the
// Jaumann rate with no rotation D is the rate of the logarithmic strain, so the stress follows
// the hardening law in true stress against logarithmic plastic strain to any strain.
//
// Plastic work needs no bookkeeping here: the solver's internal energy is the work of the
// internal nodal forces (f_int . dx), which includes the dissipated part.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "material/elastic_update.hpp"
#include "material/plastic_parameters.hpp"

namespace rf::material {

// Lane access that works for double and for GCC vectors of doubles.
template <class T>
constexpr int lane_count() {
  if constexpr (std::is_same_v<T, double>)
    return 1;
  else
    return static_cast<int>(sizeof(T) / sizeof(double));
}
template <class T>
inline double get_lane(const T& v, int l) {
  if constexpr (std::is_same_v<T, double>)
    return v;
  else
    return v[l];
}
template <class T>
inline void set_lane(T& v, int l, double x) {
  if constexpr (std::is_same_v<T, double>)
    v = x;
  else
    v[l] = x;
}

namespace j2 {

// Piecewise-linear interpolation through (x[i], y[i]) with the end segments extended.
inline double extrapolated(const std::vector<double>& x, const std::vector<double>& y, double t,
                           double* slope = nullptr) {
  const std::size_t n = x.size();
  std::size_t i = 0;
  if (t >= x[n - 1])
    i = n - 2;
  else if (t > x[0])
    i = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), t) - x.begin()) - 1;
  const double h = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
  if (slope) *slope = h;
  return y[i] + h * (t - x[i]);
}

// The same held constant beyond the ends (load-curve semantics, for LCSR).
inline double clamped(const std::vector<double>& x, const std::vector<double>& y, double t) {
  if (t <= x.front()) return y.front();
  if (t >= x.back()) return y.back();
  return extrapolated(x, y, t);
}

// Static (rate-free) yield radius and its slope at eps_p.
inline double static_yield(const PlasticParameters& p, double eps, double* slope) {
  if (p.linear) {
    *slope = p.isotropic_modulus;
    return p.sigy + p.isotropic_modulus * eps;
  }
  return extrapolated(p.strain, p.stress, eps, slope);
}

// Yield stress of a rate table (RateTable) at eps_p and strain rate `rate`, and its slope in
// eps_p at that rate.
inline double table_yield(const RateTable& t, double eps, double rate, double* slope) {
  const std::size_t n = t.rates.size();
  double x = rate;
  if (t.logarithmic) x = rate > 0.0 ? std::log(rate) : -HUGE_VAL;
  if (n == 1 || !(x > t.rates[0])) return extrapolated(t.strain[0], t.stress[0], eps, slope);
  if (x >= t.rates[n - 1]) return extrapolated(t.strain[n - 1], t.stress[n - 1], eps, slope);
  const std::size_t i = static_cast<std::size_t>(
                            std::upper_bound(t.rates.begin(), t.rates.end(), x) - t.rates.begin()) -
                        1;
  const double w = (x - t.rates[i]) / (t.rates[i + 1] - t.rates[i]);
  double h0 = 0.0, h1 = 0.0;
  const double s0 = extrapolated(t.strain[i], t.stress[i], eps, &h0);
  const double s1 = extrapolated(t.strain[i + 1], t.stress[i + 1], eps, &h1);
  *slope = (1.0 - w) * h0 + w * h1;
  return (1.0 - w) * s0 + w * s1;
}

// Multiplicative rate factor (VP 0, and VP 1 unless additive) at strain rate `rate`; 1 for a
// rate table, whose curves carry the rate effect themselves (yield_at).
inline double rate_factor(const PlasticParameters& p, double rate) {
  switch (p.rate_model) {
    case RateModel::kNone:
    case RateModel::kTable:
      return 1.0;
    case RateModel::kCowperSymonds:
      return rate > 0.0 ? 1.0 + std::pow(rate / p.rate_c, 1.0 / p.rate_p) : 1.0;
    case RateModel::kScaleCurve:
      return clamped(p.rate_curve_x, p.rate_curve_y, rate);
  }
  return 1.0;
}

// Yield stress at eps_p and strain rate `rate` with the rate effect of VP 0 (rate factor or
// table), and its slope in eps_p at that rate.
inline double yield_at(const PlasticParameters& p, double eps, double rate, double* slope) {
  if (p.rate_model == RateModel::kTable) return table_yield(p.table, eps, rate, slope);
  const double k = rate_factor(p, rate);
  const double s = static_yield(p, eps, slope);
  *slope *= k;
  return k * s;
}

// Yield stress at eps_p and plastic strain rate `rate` in the viscoplastic form (VP 1).
inline double viscoplastic_yield(const PlasticParameters& p, double eps, double rate) {
  double slope = 0.0;
  if (p.rate_model == RateModel::kTable) return table_yield(p.table, eps, rate, &slope);
  const double s = static_yield(p, eps, &slope);
  if (p.additive_overstress)
    return s + (rate > 0.0 ? p.overstress_scale * std::pow(rate / p.rate_c, 1.0 / p.rate_p) : 0.0);
  return s * rate_factor(p, rate);
}

// Root of g(dl) = J - stiff dl - yield(dl) on [0, J / stiff] for a yield stress that does not
// decrease with dl, given g(0) > 0: Illinois regula falsi to 1e-13 J.
template <class Yield>
inline double decreasing_root(double J, double stiff, const Yield& yield) {
  auto g = [&](double dl) { return J - stiff * dl - yield(dl); };
  double a = 0.0, b = J / stiff;
  double ga = g(a), gb = g(b);
  if (!(ga > 0.0)) return 0.0;
  int side = 0;
  double c = a;
  for (int it = 0; it < 200; ++it) {
    c = (a * gb - b * ga) / (gb - ga);
    const double gc = g(c);
    if (std::abs(gc) <= 1e-13 * J || (b - a) <= 1e-15 * (J / stiff)) break;
    if ((gc > 0.0) == (ga > 0.0)) {
      a = c;
      ga = gc;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      b = c;
      gb = gc;
      if (side == 1) ga *= 0.5;
      side = 1;
    }
  }
  return c;
}

// Plastic increment dl >= 0 for one point with relative effective trial stress J, accumulated
// eps_p, shear modulus G, step dt, (VP 0) rate factor k and strain rate `rate` (a rate table's
// argument). Scalar; used where the closed form does not apply.
inline double plastic_increment(const PlasticParameters& p, double shear, double J, double eps,
                                double dt, double k, double rate) {
  const double stiff = 3.0 * shear + p.kinematic_modulus;
  if (p.vp != 1 && p.rate_model == RateModel::kTable) {
    // The curve interpolated at this step's strain rate: piecewise linear in dl with the
    // breakpoints of both neighbouring curves, solved as a monotone root.
    return decreasing_root(J, stiff, [&](double dl) {
      double slope = 0.0;
      return table_yield(p.table, eps + dl, rate, &slope);
    });
  }
  if (p.vp != 1) {
    // g(dl) = J - stiff dl - k sigma_s(eps + dl) is piecewise linear and decreasing (checked
    // non-decreasing curves): walk the segments from eps.
    double slope = 0.0;
    double e = eps, dl = 0.0;
    double g = J - k * static_yield(p, e, &slope);
    if (!(g > 0.0)) return 0.0;
    for (;;) {
      const double step = g / (stiff + k * slope);
      // End of the segment that holds e (the last segment extends to infinity).
      const auto it = std::upper_bound(p.strain.begin(), p.strain.end(), e);
      if (p.linear || it == p.strain.end() || e + step <= *it) return dl + step;
      const double to_end = *it - e;
      g -= (stiff + k * slope) * to_end;
      dl += to_end;
      e = *it;
      static_yield(p, e, &slope);  // slope of the next segment (upper_bound picks it)
    }
  }
  // Viscoplastic: g(dl) = J - stiff dl - sigma_y(eps + dl, dl / dt), decreasing in dl with
  // g(0) > 0 and g(J / stiff) < 0.
  return decreasing_root(J, stiff,
                         [&](double dl) { return viscoplastic_yield(p, eps + dl, dl / dt); });
}

}  // namespace j2

// One J2 step at a batch of points. `alpha` is the back stress (6, deviatoric) or nullptr when
// the material has no kinematic hardening.
template <class T>
inline void j2_update(const ElasticConstants& m, const PlasticParameters& p, const T d[6],
                      const T w[3], double dt, T s[6], T& eps, T* alpha) {
  hughes_winget_rotate(w, dt, s);
  if (alpha) hughes_winget_rotate(w, dt, alpha);
  add_elastic_increment(m, d, dt, s);
  if (!(dt > 0.0)) return;  // no strain increment (e.g. forces of a part just released)

  const T mean = (s[0] + s[1] + s[2]) * (1.0 / 3.0);
  T xi[6];
  for (int c = 0; c < 6; ++c) xi[c] = s[c] - (c < 3 ? mean : T{});
  if (alpha)
    for (int c = 0; c < 6; ++c) xi[c] -= alpha[c];
  const T xx = xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] +
               2.0 * (xi[3] * xi[3] + xi[4] * xi[4] + xi[5] * xi[5]);
  T J;
  constexpr int kLanes = lane_count<T>();
  for (int l = 0; l < kLanes; ++l) set_lane(J, l, std::sqrt(1.5 * get_lane(xx, l)));

  // Rate factor of VP 0 / -1 from the strain rate of the step (a rate table takes the rate).
  T k = T{} + 1.0, rate = T{};
  if (p.rate_model != RateModel::kNone && p.vp != 1) {
    T dd;
    if (p.vp == -1) {
      const T tr3 = (d[0] + d[1] + d[2]) * (1.0 / 3.0);
      const T a0 = d[0] - tr3, a1 = d[1] - tr3, a2 = d[2] - tr3;
      dd = a0 * a0 + a1 * a1 + a2 * a2 + 2.0 * (d[3] * d[3] + d[4] * d[4] + d[5] * d[5]);
    } else {
      dd =
          d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2.0 * (d[3] * d[3] + d[4] * d[4] + d[5] * d[5]);
    }
    for (int l = 0; l < kLanes; ++l) {
      const double r = std::sqrt(2.0 / 3.0 * get_lane(dd, l));
      set_lane(rate, l, r);
      set_lane(k, l, j2::rate_factor(p, r));
    }
  }

  const double shear = m.shear;
  T dl;
  if (p.linear && p.vp != 1) {
    const T f = J - k * (p.sigy + p.isotropic_modulus * eps);
    const T pos = f > 0.0 ? f : T{};
    dl = pos / (3.0 * shear + p.kinematic_modulus + k * p.isotropic_modulus);
  } else {
    for (int l = 0; l < kLanes; ++l)
      set_lane(dl, l,
               j2::plastic_increment(p, shear, get_lane(J, l), get_lane(eps, l), dt, get_lane(k, l),
                                     get_lane(rate, l)));
  }
  // Radial correction along xi / J (lanes with dl == 0 are unchanged).
  const T safe_j = J > 0.0 ? J : T{} + 1.0;
  const T inv_j = dl / safe_j;
  const T ds = (3.0 * shear) * inv_j;
  for (int c = 0; c < 6; ++c) s[c] -= ds * xi[c];
  if (alpha) {
    const T da = p.kinematic_modulus * inv_j;
    for (int c = 0; c < 6; ++c) alpha[c] += da * xi[c];
  }
  eps += dl;
  // A point whose plastic strain reached the failure strain (FS, FAIL) carries no stress from
  // then on; the erosion phase deletes the element once enough of its points have failed
  // (solver/erosion.cpp: at once for solids, with the last layer through the thickness of a
  // shell), so a shell loses its stiffness layer by layer as in LS-DYNA.
  if (p.failure_strain > 0.0) {
    const T alive = eps < p.failure_strain ? T{} + 1.0 : T{};
    for (int c = 0; c < 6; ++c) s[c] *= alive;
  }
}

}  // namespace rf::material
