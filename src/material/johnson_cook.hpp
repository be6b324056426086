// *MAT_JOHNSON_COOK (015) on 8-node hexahedra, with the pressure of *EOS_LINEAR_POLYNOMIAL (001)
// or, without an equation of state, a linear bulk modulus from the card's E and PR.
//
// Flow stress (Johnson & Cook, Proc. 7th Int. Symp. Ballistics, The Hague, 1983, 541-547):
//   sigma_y = (A + B eps_p^N) (1 + C ln rate*) (1 - T*^M),
//   rate* = max(rate / EPSO, 1): no softening below the reference rate (the rate term is 1
//           there, as Radioss' /MAT/LAW4 documents and Abaqus does), where rate is the total
//           effective strain rate sqrt(2/3 D:D) of the step for VP 0 and the effective plastic
//           strain rate d(eps_p)/dt, solved with the return, for VP 1;
//   T* = (T - TR) / (TM - TR), clamped to [0, 1] (TM blank: no thermal softening).
// Adiabatic heating: the plastic work of a step, sigma_y d(eps_p) per unit current volume, raises
// the temperature by sigma_y d(eps_p) / (rho CP) with rho = RO / V the current density (CP blank:
// isothermal). The temperature of the yield stress is the one at the start of the step (the
// thermal update is staggered one step behind the mechanical one, like LS-DYNA's adiabatic
// option; with explicit steps the lag is a fraction of a per cent of one step's heating).
//
// One step at a point:
//   1. the stress turns with the Hughes-Winget rotation of the mid-step spin (elastic_update.hpp);
//   2. deviatoric trial s_tr = s' + 2 G D' dt, J = sqrt(3/2 s_tr:s_tr);
//   3. if J > sigma_y(eps_p, rate, T), the increment dl of eps_p solves the scalar equation
//        f(dl) = J - 3 G dl - sigma_y(eps_p + dl, rate(dl), T) = 0
//      (radial return, Simo & Hughes 1998 box 3.2). f is strictly decreasing with f(0) > 0 and
//      f(J / 3G) <= 0, so Newton's method safeguarded by bisection on that bracket converges for
//      any N in (0, 1] (eps^N has an infinite slope at 0) and any rate term;
//      s' = s_tr (1 - 3 G dl / J);
//   4. pressure. The relative volume V = rho0 / rho is integrated from the rate of deformation,
//      V_{n+1} = V_n exp(tr D dt) (exact for the one-point element's mid-step rate to second
//      order), mu = 1 / V - 1. With an EOS, p = a(mu) + b(mu) E with a = C0 + C1 mu + C2 mu^2 +
//      C3 mu^3, b = C4 + C5 mu + C6 mu^2 (C2 and C6 terms zero for mu < 0), and the internal
//      energy per unit reference volume E is advanced with the trapezoidal (time-centred) rule
//        E_{n+1} = E_n - (p_n + p_{n+1}) / 2 dV + (s'_n + s'_{n+1}) / 2 : D dt V_{n+1/2},
//      dV = V_{n+1} - V_n,
//      which is implicit in p_{n+1} through E; as p is linear in E it is solved in closed form
//        E_{n+1} = [E_n - (p_n + a) dV / 2 + W_dev] / (1 + b dV / 2)
//      (Wilkins, "Calculation of elastic-plastic flow", Methods in Computational Physics 3, 1964;
//      Benson, Comput. Methods Appl. Mech. Eng. 99 (1992) 235, section 4.3). Without an EOS,
//      p_{n+1} = p_n - K tr D dt (hypoelastic, as *MAT_003) and E follows the same rule.
//      The bulk viscosity q of the element acts outside the material (hex_block.cpp): its work is
//      in the solver's internal energy (glstat) but not in this history variable.
//   5. tensile failure with PC = pmin <= 0 (LS-DYNA's SPALL types): 1: p >= pmin; 2: once the
//      largest principal stress reaches -pmin the point has spalled; 3: once p < pmin it has
//      spalled. A spalled point keeps no deviatoric stress and no tension (p >= 0) from then on.
//      The energy uses the pressure after the cutoff.
//   6. fracture (Johnson & Cook, Eng. Fract. Mech. 21 (1985) 31-48, eq. 4): with D1..D5 the
//      damage D += d(eps_p) / eps_f, eps_f = max(EFMIN, [D1 + D2 exp(D3 sigma*)]
//      [1 + D4 ln rate*] [1 + D5 T*]), sigma* = sigma_m / sigma_eq the triaxiality after the
//      step (sigma_m = -p), rate* = max(plastic rate / EPSO, 1), T* as above. At D >= 1 the
//      point has failed: it keeps no deviatoric stress and no tension (as a spalled point); with
//      EROD 0 the element is deleted (solver/erosion.cpp).
// History: effective plastic strain, temperature, internal energy per unit reference volume,
// relative volume V / V0, 1 for a spalled point (0 otherwise), damage D.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "material/elastic_update.hpp"
#include "material/element_family.hpp"
#include "material/history.hpp"
#include "material/j2_plasticity.hpp"
#include "model/model.hpp"

namespace rf::material {

struct JohnsonCookParameters {
  double rho0 = 0.0;
  double a = 0.0, b = 0.0, n = 1.0, c = 0.0, m = 1.0;
  double tm = 0.0, tr = 0.0, epso = 1.0;
  double cp = 0.0;  // 0: isothermal
  int vp = 0;
  double pmin = 0.0;  // PC
  int spall = 2;
  bool eos = false;
  std::array<double, 7> eos_c{};  // C0 .. C6
  double e0 = 0.0;                // initial internal energy per unit reference volume
  double bulk = 0.0;              // without EOS: K from E, PR
  // Fracture (header comment, step 6): D1..D5, EFMIN; off when D1 = D2 = 0.
  bool fracture = false;
  std::array<double, 5> d{};
  double efmin = 1e-6;
};

namespace jc {

// (1 - T*^M) at temperature t; 1 when thermal softening is off.
inline double thermal_factor(const JohnsonCookParameters& p, double t) {
  if (!(p.tm > p.tr)) return 1.0;
  const double ts = (t - p.tr) / (p.tm - p.tr);
  if (ts <= 0.0) return 1.0;
  if (ts >= 1.0) return 0.0;
  return 1.0 - std::pow(ts, p.m);
}

// 1 + C ln max(rate / EPSO, 1) and its derivative with respect to rate.
inline double rate_factor(const JohnsonCookParameters& p, double rate, double* slope = nullptr) {
  const double r = rate / p.epso;
  if (p.c == 0.0 || !(r > 1.0)) {
    if (slope) *slope = 0.0;
    return 1.0;
  }
  if (slope) *slope = p.c / rate;
  return 1.0 + p.c * std::log(r);
}

// A + B eps^N and its slope (the slope is infinite at eps = 0 for N < 1: returned as a large
// number; the solver below then falls back on bisection).
inline double hardening(const JohnsonCookParameters& p, double eps, double* slope) {
  if (p.b == 0.0) {
    *slope = 0.0;
    return p.a;
  }
  if (!(eps > 0.0)) {
    *slope = p.n == 1.0 ? p.b : (p.n < 1.0 ? 1e300 : 0.0);
    return p.a;
  }
  const double pw = std::pow(eps, p.n);
  *slope = p.b * p.n * pw / eps;
  return p.a + p.b * pw;
}

// Plastic increment dl >= 0 for trial stress J (see the header comment, step 3). k0 is the VP 0
// rate factor (ignored for VP 1), theta the thermal factor.
inline double plastic_increment(const JohnsonCookParameters& p, double shear, double J, double eps,
                                double dt, double k0, double theta) {
  auto f = [&](double dl, double* df) {
    double hs = 0.0, ks = 0.0;
    const double h = hardening(p, eps + dl, &hs);
    const double k = p.vp == 1 ? rate_factor(p, dl / dt, &ks) : k0;
    if (p.vp == 1) ks /= dt;  // d/d(dl) of the rate term
    *df = -3.0 * shear - theta * (k * hs + ks * h);
    return J - 3.0 * shear * dl - theta * k * h;
  };
  double d0 = 0.0;
  if (!(f(0.0, &d0) > 0.0)) return 0.0;
  double lo = 0.0, hi = J / (3.0 * shear);
  double x = 0.5 * hi;
  for (int it = 0; it < 100; ++it) {
    double df = 0.0;
    const double fx = f(x, &df);
    if (fx > 0.0)
      lo = x;
    else
      hi = x;
    if (std::abs(fx) <= 1e-14 * J || hi - lo <= 1e-15 * J / shear) break;
    double next = x - fx / df;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // Newton left the bracket: bisect
    x = next;
  }
  return x;
}

// One step at one point; h = {eps_p, temperature, internal energy, relative volume, spalled,
// damage}.
inline void point_update(const ElasticConstants& el, const JohnsonCookParameters& p,
                         const double d[6], const double w[3], double dt, double s[6], double* h) {
  hughes_winget_rotate(w, dt, s);
  if (!(dt > 0.0)) return;  // no strain increment (e.g. forces of a part just released)
  const double G = el.shear;
  const double p_old = -(s[0] + s[1] + s[2]) / 3.0;
  const double trd = d[0] + d[1] + d[2];
  double sold[6], dev_d[6], st[6];
  for (int c = 0; c < 6; ++c) {
    sold[c] = s[c] + (c < 3 ? p_old : 0.0);
    dev_d[c] = d[c] - (c < 3 ? trd / 3.0 : 0.0);
    st[c] = sold[c] + 2.0 * G * dt * dev_d[c];
  }
  double& eps = h[0];
  double& temperature = h[1];
  double& energy = h[2];
  double& volume = h[3];
  double& spalled = h[4];
  double& damage = h[5];
  const double v_new = volume * std::exp(trd * dt);
  const double dv = v_new - volume;
  const double temperature_before = temperature;
  double dl = 0.0;

  if (spalled != 0.0) {
    for (double& c : st) c = 0.0;
  } else {
    const double ss = st[0] * st[0] + st[1] * st[1] + st[2] * st[2] +
                      2.0 * (st[3] * st[3] + st[4] * st[4] + st[5] * st[5]);
    const double J = std::sqrt(1.5 * ss);
    double k0 = 1.0;
    if (p.vp != 1) {
      const double dd =
          d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2.0 * (d[3] * d[3] + d[4] * d[4] + d[5] * d[5]);
      k0 = rate_factor(p, std::sqrt(2.0 / 3.0 * dd));
    }
    const double theta = thermal_factor(p, temperature);
    dl = J > 0.0 ? plastic_increment(p, G, J, eps, dt, k0, theta) : 0.0;
    if (dl > 0.0) {
      const double scale = 1.0 - 3.0 * G * dl / J;
      for (double& c : st) c *= scale;
      // Plastic work per unit current volume: the flow stress J - 3 G dl times dl.
      const double work = std::max(J - 3.0 * G * dl, 0.0) * dl;
      if (p.cp > 0.0) temperature += work * v_new / (p.rho0 * p.cp);
      eps += dl;
    }
  }

  // Deviatoric work per unit reference volume, mid-step stress and volume.
  double sd = 0.0;
  for (int c = 0; c < 6; ++c) sd += (sold[c] + st[c]) * dev_d[c] * (c < 3 ? 1.0 : 2.0);
  const double w_dev = 0.5 * sd * dt * 0.5 * (volume + v_new);

  double pressure = 0.0;
  if (p.eos) {
    const double mu = 1.0 / v_new - 1.0;
    const auto& C = p.eos_c;
    const double mu2 = mu > 0.0 ? mu * mu : 0.0;
    const double a = C[0] + C[1] * mu + C[2] * mu2 + C[3] * mu * mu * mu;
    const double b = C[4] + C[5] * mu + C[6] * mu2;
    const double e_new = (energy - 0.5 * (p_old + a) * dv + w_dev) / (1.0 + 0.5 * b * dv);
    pressure = a + b * e_new;
  } else {
    pressure = p_old - p.bulk * trd * dt;
  }
  // Tensile failure (header comment, step 5).
  if (spalled == 0.0) {
    if (p.spall == 1) {
      pressure = std::max(pressure, p.pmin);
    } else {
      double trial[6];
      for (int c = 0; c < 6; ++c) trial[c] = st[c] - (c < 3 ? pressure : 0.0);
      if ((p.spall == 2 && max_principal(trial) >= -p.pmin) ||
          (p.spall == 3 && pressure < p.pmin)) {
        spalled = 1.0;
        for (double& c : st) c = 0.0;
      }
    }
  }
  // Fracture (header comment, step 6), with the deviatoric stress and pressure of the step.
  if (p.fracture && dl > 0.0 && spalled == 0.0) {
    const double ss = st[0] * st[0] + st[1] * st[1] + st[2] * st[2] +
                      2.0 * (st[3] * st[3] + st[4] * st[4] + st[5] * st[5]);
    const double equivalent = std::sqrt(1.5 * ss);
    const double triaxiality = equivalent > 0.0 ? -pressure / equivalent : 0.0;
    double strain = p.d[0] + p.d[1] * std::exp(p.d[2] * triaxiality);
    if (p.d[3] != 0.0) strain *= 1.0 + p.d[3] * std::log(std::max(dl / dt / p.epso, 1.0));
    if (p.d[4] != 0.0 && p.tm > p.tr)
      strain *= 1.0 + p.d[4] * std::clamp((temperature_before - p.tr) / (p.tm - p.tr), 0.0, 1.0);
    damage += dl / std::max(strain, p.efmin);
    if (damage >= 1.0) {
      spalled = 1.0;
      for (double& c : st) c = 0.0;
    }
  }
  if (spalled != 0.0) pressure = std::max(pressure, 0.0);
  // Energy with the pressure actually taken (explicit once the pressure is fixed).
  double sd_final = 0.0;
  for (int c = 0; c < 6; ++c) sd_final += (sold[c] + st[c]) * dev_d[c] * (c < 3 ? 1.0 : 2.0);
  energy += -0.5 * (p_old + pressure) * dv + 0.5 * sd_final * dt * 0.5 * (volume + v_new);
  volume = v_new;
  for (int c = 0; c < 6; ++c) s[c] = st[c] - (c < 3 ? pressure : 0.0);
}

}  // namespace jc

struct JohnsonCookMaterial {
  static constexpr model::MaterialKind kKind = model::MaterialKind::JohnsonCook;
  static constexpr unsigned kFamilies = kHex8;
  static constexpr std::array<HistoryField, 6> kHistory{{{"effective_plastic_strain", 1, false},
                                                         {"temperature", 1, false},
                                                         {"internal_energy", 1, false},
                                                         {"relative_volume", 1, false},
                                                         {"spalled", 1, false},
                                                         {"damage", 1, false}}};
  using Parameters = JohnsonCookParameters;

  // Values of the history fields before the first step (kHistory order).
  static void initial_history(const Parameters& p, double* h) {
    h[0] = 0.0;
    h[1] = p.tr;
    h[2] = p.eos ? p.e0 : 0.0;
    h[3] = 1.0;
    h[4] = 0.0;
    h[5] = 0.0;
  }

  // The law is pow/log per point: lanes are updated one at a time.
  template <class T>
  static void update(const ElasticConstants& m, const Parameters& p, const T d[6], const T w[3],
                     double dt, T s[6], T* h) {
    constexpr int kLanes = lane_count<T>();
    for (int l = 0; l < kLanes; ++l) {
      double dl[6], wl[3], sl[6], hl[6];
      for (int c = 0; c < 6; ++c) {
        dl[c] = get_lane(d[c], l);
        sl[c] = get_lane(s[c], l);
      }
      for (int c = 0; c < 3; ++c) wl[c] = get_lane(w[c], l);
      for (int c = 0; c < 6; ++c) hl[c] = get_lane(h[c], l);
      jc::point_update(m, p, dl, wl, dt, sl, hl);
      for (int c = 0; c < 6; ++c) set_lane(s[c], l, sl[c]);
      for (int c = 0; c < 6; ++c) set_lane(h[c], l, hl[c]);
    }
  }
};

}  // namespace rf::material
