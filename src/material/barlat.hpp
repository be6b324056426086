// *MAT_3-PARAMETER_BARLAT (036): the plane-stress anisotropic yield function of Barlat and Lian
// for sheet metal, with isotropic hardening (linear, power law or curve), on shells only.
//
// Reference: F. Barlat, J. Lian, "Plastic behavior and stretchability of sheet metals. Part I:
// A yield function for orthotropic sheets under plane stress conditions", Int. J. Plasticity 5
// (1989) 51-66 (eq. 4 and the identification of a, c, h, p from R00, R45, R90).
//
// Yield function, stresses in the material frame (x rolling, y transverse, in the sheet):
//   f(s) = a |K1 + K2|^M + a |K1 - K2|^M + c |2 K2|^M = 2 sigma_y^M,
//   K1 = (s_xx + h s_yy) / 2,  K2 = sqrt(((s_xx - h s_yy) / 2)^2 + p^2 s_xy^2),
//   a = 2 - c,  c = 2 sqrt(R00 / (1 + R00) R90 / (1 + R90)),  h = sqrt(R00 / (1 + R00) (1 + R90) /
//   R90),
// and p such that uniaxial tension at 45 degrees has the plastic strain ratio R45 (solved
// numerically, as the paper says: R45 grows monotonically with p). Uniaxial tension along x
// gives f = (a + c) s^M = 2 s^M, so sigma_y is the yield stress in the rolling direction and the
// hardening law is that direction's stress against the effective plastic strain.
//
// The equivalent stress phi(s) = (f / 2)^(1/M) is homogeneous of degree 1. With the associated
// flow rule d eps^p = dl d phi / d s, the plastic work is s : d eps^p = dl phi = dl sigma_y, so
// dl is the increment of the effective plastic strain conjugate to sigma_y (the history field
// effective_plastic_strain).
//
// Return (backward Euler, closest point; J.C. Simo, T.J.R. Hughes, Computational Inelasticity,
// 1998, sec. 3.6): with the plane-stress elastic compliance D = C^-1 and the trial stress
// s_tr = s_n + C de, solve for s, dl >= 0
//   r_s = D (s - s_tr) + dl n(s) = 0,   r_f = phi(s) - sigma_y(eps_n + dl) = 0,
// n = d phi / d s, by Newton's method with the consistent linearisation
//   Xi = (D + dl dn/ds)^-1,  d(dl) = (r_f - n.Xi r_s) / (n.Xi n + H),  ds = -Xi (r_s + d(dl) n),
// and a backtracking line search on |r|^2 (Armijo). The first iterate from s_tr is the elastic
// predictor's cutting-plane step. Where Newton does not converge in 40 iterations the strain
// increment is split into 4, 16 or 64 substeps. Plane stress is exact: the in-plane update uses
// the plane-stress elastic law, so no thickness iteration is needed. The thickness strain rate
// (elastic -nu/E (ds_xx + ds_yy) plus the plastic -(dp_xx + dp_yy)) is not formed here: the
// shell's thickness update (*CONTROL_SHELL ISTUPD, shell_block.cpp section 12) takes it from
// the in-plane rates and the stress increment, which holds for this plastically incompressible
// flow with isotropic elasticity.
//
// Transverse shear stays elastic (shell_block.cpp), as for the J2 materials on shells.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "material/elastic.hpp"
#include "material/element_family.hpp"
#include "material/history.hpp"
#include "model/model.hpp"

namespace rf::material {

enum class BarlatHardening {
  kLinear,  // HR 1: sigma_y = sigy + modulus eps_p (modulus = E Et / (E - Et))
  kPower,   // HR 2: sigma_y = k (e0 + eps_p)^n
  kCurve,   // HR 3: piecewise linear through (strain[i], stress[i]), end slopes extended
};

// Material axes of a shell element (AOPT): the angle psi from the element's side 1-2 (the
// co-rotational e1) to the rolling direction, about the element normal, fixed at the reference
// configuration (the axes then turn with the element).
enum class BarlatAxes {
  kElement,  // AOPT 0: side 1-2, turned by BETA
  kVectorA,  // AOPT 2: vector A projected on the shell
  kVectorV,  // AOPT 3: V x normal, turned by BETA
};

struct BarlatParameters {
  double m = 2.0;
  double a = 1.0, c = 1.0, h = 1.0, p = 1.0;
  BarlatHardening hardening = BarlatHardening::kLinear;
  double sigy = 0.0, modulus = 0.0;    // linear
  double k = 0.0, e0 = 0.0, n = 0.0;   // power law
  std::vector<double> strain, stress;  // curve
  BarlatAxes axes = BarlatAxes::kElement;
  std::array<double, 3> vector{1.0, 0.0, 0.0};  // A (AOPT 2) or V (AOPT 3), global
  double beta = 0.0;                            // radians (AOPT 0, 3)
};

namespace barlat {

// Yield stress sigma_y(eps_p) and its slope.
inline double yield_stress(const BarlatParameters& p, double eps, double* slope) {
  switch (p.hardening) {
    case BarlatHardening::kLinear:
      *slope = p.modulus;
      return p.sigy + p.modulus * eps;
    case BarlatHardening::kPower: {
      const double x = p.e0 + eps;
      const double s = p.k * std::pow(x, p.n);
      *slope = p.n * s / x;
      return s;
    }
    case BarlatHardening::kCurve: {
      const std::size_t n = p.strain.size();
      std::size_t i = 0;
      if (eps >= p.strain[n - 1])
        i = n - 2;
      else if (eps > p.strain[0])
        i = static_cast<std::size_t>(std::upper_bound(p.strain.begin(), p.strain.end(), eps) -
                                     p.strain.begin()) -
            1;
      const double h = (p.stress[i + 1] - p.stress[i]) / (p.strain[i + 1] - p.strain[i]);
      *slope = h;
      return p.stress[i] + h * (eps - p.strain[i]);
    }
  }
  *slope = 0.0;
  return 0.0;
}

// Equivalent stress phi, gradient n = d phi / d s and (optionally) its derivative dn = d n / d s
// at s = (s_xx, s_yy, s_xy) in the material frame (s_xy the tensor shear component; n[2] is
// d phi / d s_xy, so that s.n = phi).
struct Surface {
  double phi = 0.0;
  double n[3] = {0.0, 0.0, 0.0};
  double dn[3][3] = {};
};

inline void surface(const BarlatParameters& p, const double s[3], bool hessian, Surface& out) {
  const double scale = std::max({std::abs(s[0]), std::abs(s[1]), std::abs(s[2])});
  out = Surface{};
  if (!(scale > 0.0)) return;
  const double M = p.m;
  // Scaled stresses keep |.|^M within range for any M and stress unit.
  const double u[3] = {s[0] / scale, s[1] / scale, s[2] / scale};
  const double k1 = 0.5 * (u[0] + p.h * u[1]);
  const double d = 0.5 * (u[0] - p.h * u[1]);
  const double k2 = std::sqrt(d * d + p.p * p.p * u[2] * u[2]);
  auto g = [M](double x) { return std::pow(std::abs(x), M); };
  auto g1 = [M](double x) {
    const double ax = std::abs(x);
    return ax > 0.0 ? std::copysign(M * std::pow(ax, M - 1.0), x) : 0.0;
  };
  // |x|^(M-2) is unbounded at 0 for M < 2: floored (only the Newton matrix sees it).
  auto g2 = [M](double x) {
    return M * (M - 1.0) * std::pow(std::max(std::abs(x), 1e-8), M - 2.0);
  };
  const double A = k1 + k2, B = k1 - k2, C2 = 2.0 * k2;
  const double f = p.a * (g(A) + g(B)) + p.c * g(C2);
  const double phi_u = std::pow(0.5 * f, 1.0 / M);
  out.phi = scale * phi_u;
  if (!(phi_u > 0.0)) return;
  const double f1 = p.a * (g1(A) + g1(B));
  const double f2 = p.a * (g1(A) - g1(B)) + 2.0 * p.c * g1(C2);
  const double dk1[3] = {0.5, 0.5 * p.h, 0.0};
  double dk2[3] = {0.0, 0.0, 0.0};
  const bool cone = !(k2 > 1e-12);  // K2 = 0: its gradient drops out (f2 -> 0 there)
  if (!cone) {
    dk2[0] = 0.5 * d / k2;
    dk2[1] = -0.5 * p.h * d / k2;
    dk2[2] = p.p * p.p * u[2] / k2;
  }
  const double to_phi = 1.0 / (2.0 * M * std::pow(phi_u, M - 1.0));
  for (int i = 0; i < 3; ++i) out.n[i] = to_phi * (f1 * dk1[i] + f2 * dk2[i]);
  if (!hessian) return;
  const double f11 = p.a * (g2(A) + g2(B));
  const double f12 = p.a * (g2(A) - g2(B));
  const double f22 = f11 + 4.0 * p.c * g2(C2);
  // f2 / K2 (finite as K2 -> 0: the limit 2 a g''(K1) + 4 c g''(0)).
  const double f2k = cone ? 2.0 * p.a * g2(k1) + 4.0 * p.c * g2(0.0) : f2 / k2;
  const double q2[3][3] = {
      {0.25, -0.25 * p.h, 0.0}, {-0.25 * p.h, 0.25 * p.h * p.h, 0.0}, {0.0, 0.0, p.p * p.p}};
  const double inv_scale = 1.0 / scale;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double hf = f11 * dk1[i] * dk1[j] + f12 * (dk1[i] * dk2[j] + dk2[i] * dk1[j]) +
                        (f22 - f2k) * dk2[i] * dk2[j] + f2k * q2[i][j];
      out.dn[i][j] = inv_scale * (to_phi * hf - (M - 1.0) * out.n[i] * out.n[j] / phi_u);
    }
}

inline bool invert3(const double a[3][3], double inv[3][3]) {
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  const double r = 1.0 / det;
  inv[0][0] = c00 * r;
  inv[1][0] = c01 * r;
  inv[2][0] = c02 * r;
  inv[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * r;
  inv[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * r;
  inv[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * r;
  inv[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * r;
  inv[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * r;
  inv[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * r;
  return true;
}

// Plane-stress elasticity s = C e, e = D s for s = (xx, yy, xy) and the engineering strains
// e = (xx, yy, 2 xy), so that s.e is the work and the plastic strain increment is dl n.
struct PlaneElasticity {
  double C[3][3];
  double D[3][3];
  double young;
};

inline PlaneElasticity plane_elasticity(const ElasticConstants& m) {
  PlaneElasticity e{};
  const double ep = m.young / (1.0 - m.poisson * m.poisson);
  e.C[0][0] = e.C[1][1] = ep;
  e.C[0][1] = e.C[1][0] = m.poisson * ep;
  e.C[2][2] = m.shear;
  e.D[0][0] = e.D[1][1] = 1.0 / m.young;
  e.D[0][1] = e.D[1][0] = -m.poisson / m.young;
  e.D[2][2] = 1.0 / m.shear;
  e.young = m.young;
  return e;
}

// One backward-Euler step from s (material frame, updated in place) with the strain increment
// de (engineering components) at accumulated eps; returns false where Newton did not converge (s
// and dl then untouched). dl: the effective plastic strain increment.
inline bool return_step(const BarlatParameters& p, const PlaneElasticity& el, const double de[3],
                        double eps, double s[3], double& dl) {
  double trial[3];
  for (int i = 0; i < 3; ++i)
    trial[i] = s[i] + el.C[i][0] * de[0] + el.C[i][1] * de[1] + el.C[i][2] * de[2];
  Surface sf;
  surface(p, trial, false, sf);
  double slope = 0.0;
  const double sy0 = yield_stress(p, eps, &slope);
  dl = 0.0;
  if (!(sf.phi > sy0)) {
    for (int i = 0; i < 3; ++i) s[i] = trial[i];
    return true;
  }
  double sig[3] = {trial[0], trial[1], trial[2]};
  double lam = 0.0;
  const double ref = sy0;  // stress scale of the residual
  const double strain_ref = ref / el.young;
  auto residual = [&](const double x[3], double l, Surface& at, double& sy, double& hh,
                      double rs[3], double& rf) {
    surface(p, x, true, at);
    sy = yield_stress(p, eps + l, &hh);
    for (int i = 0; i < 3; ++i) {
      const double ds[3] = {x[0] - trial[0], x[1] - trial[1], x[2] - trial[2]};
      rs[i] = el.D[i][0] * ds[0] + el.D[i][1] * ds[1] + el.D[i][2] * ds[2] + l * at.n[i];
    }
    rf = at.phi - sy;
    double m = (rf / ref) * (rf / ref);
    for (int i = 0; i < 3; ++i) m += (rs[i] / strain_ref) * (rs[i] / strain_ref);
    return 0.5 * m;
  };
  double rs[3], rf, sy, hh;
  double merit = residual(sig, lam, sf, sy, hh, rs, rf);
  for (int it = 0; it < 40; ++it) {
    if (std::abs(rf) <= 1e-10 * ref && std::abs(rs[0]) <= 1e-10 * strain_ref &&
        std::abs(rs[1]) <= 1e-10 * strain_ref && std::abs(rs[2]) <= 1e-10 * strain_ref) {
      for (int i = 0; i < 3; ++i) s[i] = sig[i];
      dl = lam;
      return true;
    }
    double jac[3][3], xi[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) jac[i][j] = el.D[i][j] + lam * sf.dn[i][j];
    if (!invert3(jac, xi)) return false;
    double xin[3], xir[3];
    for (int i = 0; i < 3; ++i) {
      xin[i] = xi[i][0] * sf.n[0] + xi[i][1] * sf.n[1] + xi[i][2] * sf.n[2];
      xir[i] = xi[i][0] * rs[0] + xi[i][1] * rs[1] + xi[i][2] * rs[2];
    }
    const double nxn = sf.n[0] * xin[0] + sf.n[1] * xin[1] + sf.n[2] * xin[2];
    const double nxr = sf.n[0] * xir[0] + sf.n[1] * xir[1] + sf.n[2] * xir[2];
    const double ddl = (rf - nxr) / (nxn + hh);
    double dsig[3];
    for (int i = 0; i < 3; ++i) dsig[i] = -(xir[i] + ddl * xin[i]);
    // Backtracking: full step first, halved until |r|^2 decreases enough (Armijo, slope -2 merit).
    double alpha = 1.0;
    double next[3], lnext = lam;
    Surface sn;
    double rsn[3], rfn = 0.0, syn = 0.0, hn = 0.0, mn = 0.0;
    for (int ls = 0; ls < 12; ++ls) {
      for (int i = 0; i < 3; ++i) next[i] = sig[i] + alpha * dsig[i];
      lnext = std::max(0.0, lam + alpha * ddl);
      mn = residual(next, lnext, sn, syn, hn, rsn, rfn);
      if (mn <= (1.0 - 2e-4 * alpha) * merit) break;
      alpha *= 0.5;
    }
    if (!std::isfinite(mn)) return false;
    for (int i = 0; i < 3; ++i) {
      sig[i] = next[i];
      rs[i] = rsn[i];
    }
    lam = lnext;
    sf = sn;
    rf = rfn;
    sy = syn;
    hh = hn;
    merit = mn;
  }
  return false;
}

// The step over the strain increment de (engineering components, material frame), split into 4, 16
// or 64 equal substeps where one Newton solve does not converge. Returns the effective plastic
// strain increment; false only if even 64 substeps fail (s then holds the elastic trial).
inline bool update(const BarlatParameters& p, const PlaneElasticity& el, const double de[3],
                   double s[3], double& eps) {
  double dl = 0.0;
  if (return_step(p, el, de, eps, s, dl)) {
    eps += dl;
    return true;
  }
  for (int parts = 4; parts <= 64; parts *= 4) {
    double sub[3] = {s[0], s[1], s[2]};
    double e = eps;
    const double step[3] = {de[0] / parts, de[1] / parts, de[2] / parts};
    bool ok = true;
    for (int k = 0; k < parts && ok; ++k) {
      ok = return_step(p, el, step, e, sub, dl);
      e += dl;
    }
    if (ok) {
      for (int i = 0; i < 3; ++i) s[i] = sub[i];
      eps = e;
      return true;
    }
  }
  for (int i = 0; i < 3; ++i) s[i] += el.C[i][0] * de[0] + el.C[i][1] * de[1] + el.C[i][2] * de[2];
  return false;
}

// Plastic strain ratio width / thickness of uniaxial tension at 45 degrees to the rolling
// direction for the coefficients in p (the stress state (1, 1, 1) / 2 in the material frame).
inline double r45_of(const BarlatParameters& p) {
  const double s[3] = {0.5, 0.5, 0.5};
  Surface sf;
  surface(p, s, false, sf);
  // Plastic rates (n_xx, n_yy, n_xy) with n_xy the engineering shear rate. Width direction
  // (-1, 1) / sqrt(2): e_w = (n_xx + n_yy) / 2 - n_xy / 2; thickness e_t = -(n_xx + n_yy).
  const double sum = sf.n[0] + sf.n[1];
  return (sf.n[2] - sum) / (2.0 * sum);
}

}  // namespace barlat

struct BarlatMaterial {
  static constexpr model::MaterialKind kKind = model::MaterialKind::ThreeParameterBarlat;
  static constexpr unsigned kFamilies = kShell;  // a plane-stress criterion: shells only
  static constexpr std::array<HistoryField, 1> kHistory{{{"effective_plastic_strain", 1, false}}};
  using Parameters = BarlatParameters;
  // Shells call plane_stress_update instead of a 3D update (shell_block.cpp).
  static constexpr bool kPlaneStressOnly = true;

  // One step at a shell point: s = (xx, yy, xy) in the element's co-rotational frame, d = (d_x,
  // d_y, 2 d_xy) its rates over dt, (cs, sn) = (cos, sin) of the angle psi from the element's e1
  // to the rolling direction; h[0] the effective plastic strain. Returns false where the return
  // did not converge even in substeps (the element kernel reports the element as failed).
  static bool plane_stress_update(const ElasticConstants& m, const BarlatParameters& p, double cs,
                                  double sn, const double d[3], double dt, double s[3], double* h) {
    // Components in the material frame (x' along the rolling direction at psi from e1):
    // a' = R^T a R with R the rotation by psi; the engineering shear is twice the tensor one.
    const double c2 = cs * cs, s2 = sn * sn, cssn = cs * sn;
    auto to_material = [&](double xx, double yy, double xy, double out[3]) {
      out[0] = c2 * xx + s2 * yy + 2.0 * cssn * xy;
      out[1] = s2 * xx + c2 * yy - 2.0 * cssn * xy;
      out[2] = cssn * (yy - xx) + (c2 - s2) * xy;
    };
    double sm[3], em[3];
    to_material(s[0], s[1], s[2], sm);
    to_material(d[0] * dt, d[1] * dt, 0.5 * d[2] * dt, em);
    em[2] *= 2.0;
    const barlat::PlaneElasticity el = barlat::plane_elasticity(m);
    const bool ok = barlat::update(p, el, em, sm, h[0]);
    // Back to the element frame (rotation by -psi).
    s[0] = c2 * sm[0] + s2 * sm[1] - 2.0 * cssn * sm[2];
    s[1] = s2 * sm[0] + c2 * sm[1] + 2.0 * cssn * sm[2];
    s[2] = cssn * (sm[0] - sm[1]) + (c2 - s2) * sm[2];
    return ok;
  }
};

}  // namespace rf::material
