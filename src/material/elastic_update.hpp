// Objective stress update for hypoelastic *MAT_ELASTIC (MAT_001) in solid elements.
//
// Rate form: the Jaumann rate of Cauchy stress is linear in the rate of deformation,
//   sigma^del = C : D,   sigma^del = dsigma/dt - W sigma + sigma W.
// This is what LS-DYNA does by default for MAT_001 in solids (hypoelastic, Jaumann rate).
// Integration over a step uses the Hughes-Winget (1980) incremental rotation: the stored stress
// is rotated by the Cayley transform of the mid-step spin,
//   Q = (I - W dt/2)^{-1} (I + W dt/2),        (Hughes & Winget, IJNME 15 (1980), eq. 33)
// which is exactly orthogonal for any step, and then the elastic increment C : D dt is added.
// When W and D are evaluated on the mid-step configuration x^{n+1/2}, a rigid rotation of the
// element gives D = 0 exactly and Q equal to the incremental rotation R^{n+1} R^{n,T}, so the
// stress rotates objectively and its invariants are preserved to round-off.
//
// Conventions used by every function here:
//   stress s, Voigt order xx, yy, zz, xy, yz, zx (tensor components);
//   rate of deformation d, same order, TENSOR shear components d_xy = (L_xy + L_yx) / 2;
//   spin vector w with W a = w x a, i.e. w = (W_zy, W_xz, W_yx).
// The functions are templates over the scalar type: T = double for one material point, or a
// GCC vector of doubles when the element kernels process a batch of elements in SIMD lanes.
#pragma once

#include <algorithm>
#include <cmath>

#include "material/elastic.hpp"

namespace rf::material {

// Rotates symmetric stress s (6 components) by Q = Cayley(W dt / 2). The closed form of the
// Cayley transform of a skew matrix [psi]x is Q = I + 2/(1+|psi|^2) ([psi]x + [psi]x^2); it avoids
// the 3x3 inverse.
template <class T>
inline void hughes_winget_rotate(const T w[3], double dt, T s[6]) {
  const T p1 = 0.5 * dt * w[0], p2 = 0.5 * dt * w[1], p3 = 0.5 * dt * w[2];
  const T pp = p1 * p1 + p2 * p2 + p3 * p3;
  const T k = 2.0 / (1.0 + pp);
  const T q11 = 1.0 + k * (p1 * p1 - pp), q22 = 1.0 + k * (p2 * p2 - pp),
          q33 = 1.0 + k * (p3 * p3 - pp);
  const T q12 = k * (p1 * p2 - p3), q21 = k * (p1 * p2 + p3);
  const T q13 = k * (p1 * p3 + p2), q31 = k * (p1 * p3 - p2);
  const T q23 = k * (p2 * p3 - p1), q32 = k * (p2 * p3 + p1);
  const T sxx = s[0], syy = s[1], szz = s[2], sxy = s[3], syz = s[4], szx = s[5];
  // T = Q sigma
  const T t11 = q11 * sxx + q12 * sxy + q13 * szx;
  const T t12 = q11 * sxy + q12 * syy + q13 * syz;
  const T t13 = q11 * szx + q12 * syz + q13 * szz;
  const T t21 = q21 * sxx + q22 * sxy + q23 * szx;
  const T t22 = q21 * sxy + q22 * syy + q23 * syz;
  const T t23 = q21 * szx + q22 * syz + q23 * szz;
  const T t31 = q31 * sxx + q32 * sxy + q33 * szx;
  const T t32 = q31 * sxy + q32 * syy + q33 * syz;
  const T t33 = q31 * szx + q32 * syz + q33 * szz;
  // sigma' = T Q^T
  s[0] = t11 * q11 + t12 * q12 + t13 * q13;
  s[1] = t21 * q21 + t22 * q22 + t23 * q23;
  s[2] = t31 * q31 + t32 * q32 + t33 * q33;
  s[3] = t11 * q21 + t12 * q22 + t13 * q23;
  s[4] = t21 * q31 + t22 * q32 + t23 * q33;
  s[5] = t31 * q11 + t32 * q12 + t33 * q13;
}

// Adds the isotropic elastic increment C : D dt = (lambda tr(D) I + 2 mu D) dt.
template <class T>
inline void add_elastic_increment(const ElasticConstants& m, const T d[6], double dt, T s[6]) {
  const double two_mu_dt = 2.0 * m.shear * dt;
  const T lam_tr = m.lambda * (d[0] + d[1] + d[2]) * dt;
  s[0] += lam_tr + two_mu_dt * d[0];
  s[1] += lam_tr + two_mu_dt * d[1];
  s[2] += lam_tr + two_mu_dt * d[2];
  s[3] += two_mu_dt * d[3];
  s[4] += two_mu_dt * d[4];
  s[5] += two_mu_dt * d[5];
}

// Full hypoelastic Jaumann update over one step: rotate, then add C : D dt.
template <class T>
inline void elastic_jaumann_update(const ElasticConstants& m, const T d[6], const T w[3], double dt,
                                   T s[6]) {
  hughes_winget_rotate(w, dt, s);
  add_elastic_increment(m, d, dt, s);
}

// Splits a velocity gradient L (row-major, L[i*3+j] = dv_i/dx_j) into d (Voigt, tensor shear)
// and the spin vector w.
template <class T>
inline void split_velocity_gradient(const T L[9], T d[6], T w[3]) {
  d[0] = L[0];
  d[1] = L[4];
  d[2] = L[8];
  d[3] = 0.5 * (L[1] + L[3]);
  d[4] = 0.5 * (L[5] + L[7]);
  d[5] = 0.5 * (L[6] + L[2]);
  w[0] = 0.5 * (L[7] - L[5]);  // W_zy
  w[1] = 0.5 * (L[2] - L[6]);  // W_xz
  w[2] = 0.5 * (L[3] - L[1]);  // W_yx
}

// The three eigenvalues of a symmetric 3x3 (Voigt xx yy zz xy yz zx) in descending order,
// trigonometric closed form (Smith, Commun. ACM 4 (1961) 168): q + 2 p cos(phi/3 + 2 pi k/3), the
// middle one from the trace. *MAT_ADD_EROSION strain criteria.
inline void principal_values(const double s[6], double out[3]) {
  const double q = (s[0] + s[1] + s[2]) / 3.0;
  const double a = s[0] - q, b = s[1] - q, c = s[2] - q;
  const double off = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  const double p2 = (a * a + b * b + c * c + 2.0 * off) / 6.0;
  if (!(p2 > 0.0)) {
    out[0] = out[1] = out[2] = q;
    return;
  }
  const double pp = std::sqrt(p2);
  const double det =
      a * (b * c - s[4] * s[4]) - s[3] * (s[3] * c - s[4] * s[5]) + s[5] * (s[3] * s[4] - b * s[5]);
  const double r = std::clamp(det / (2.0 * pp * pp * pp), -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  constexpr double kThird = 2.0943951023931954923;  // 2 pi / 3
  out[0] = q + 2.0 * pp * std::cos(phi);
  out[2] = q + 2.0 * pp * std::cos(phi + kThird);
  out[1] = 3.0 * q - out[0] - out[2];
}

// Largest eigenvalue (Johnson-Cook spall, *MAT_ADD_EROSION SIGP1).
inline double max_principal(const double s[6]) {
  double values[3];
  principal_values(s, values);
  return values[0];
}

}  // namespace rf::material
