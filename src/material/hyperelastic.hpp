// Shared kinematics of the hyperelastic (rubber) materials: the left Cauchy-Green tensor
// b = F F^T carried as history and advanced with the element's mid-step velocity gradient.
//
// Why b and not a stress rate. A hyperelastic material's stress is a function of the current
// deformation, not of its history; integrating a stress rate (as the hypoelastic materials do)
// would make the stress path dependent and the work done over a closed cycle nonzero. The
// kernels give each material the mid-step rate of deformation d and spin w, not F, so the
// material keeps b itself, updated each step with the incremental deformation gradient
//   Delta = (I - dt/2 L)^{-1} (I + dt/2 L),   L = d + W,   b <- Delta b Delta^T,
// the same Cayley (Hughes-Winget 1980) map that rotates the hypoelastic stress, here applied to
// the full velocity gradient. With L the velocity gradient on the mid-step configuration
// x^{n+1/2} = (x^n + x^{n+1})/2 (hex_block.cpp), and a homogeneous (affine) motion,
// L = (F^{n+1} - F^n)/dt (F^{n+1/2})^{-1}, so (I - dt/2 L) F^{n+1/2} = F^n and
// (I + dt/2 L) F^{n+1/2} = F^{n+1}: Delta = F^{n+1} (F^n)^{-1} exactly, for any step size. The
// update then carries b without drift through uniform stretching and exact rigid rotations
// (objectivity is exact, not approximate), and only the trilinear element's non-uniform part of
// the motion enters through its averaged L.
//
// Storage: the field holds b - I (zero at the reference state, which is how history arrays are
// allocated, and accurate to round-off at small strain), in the stress's Voigt order xx yy zz
// xy yz zx, marked symmetric_tensor: a part switched rigid and back turns it as Q (b - I) Q^T =
// Q b Q^T - I, which is what a rigid rotation does to b. Restart dumps carry it by name.
#pragma once

#include <array>
#include <cmath>

#include "material/history.hpp"
#include "material/j2_plasticity.hpp"  // lane_count, get_lane, set_lane

namespace rf::material {

// Resolved constants of *MAT_027 and *MAT_077_O (build_state fills them from the card).
struct HyperelasticParameters {
  // Mooney-Rivlin, LS-DYNA form W = A(I1 - 3) + B(I2 - 3) + C(I3^-2 - 1) + D(I3 - 1)^2 with the
  // invariants of C = F^T F, C = A/2 + B (stress-free reference), D from A, B and PR.
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
  // Ogden: W = sum_j mu_j/alpha_j sum_i (lambda_i*^alpha_j - 1) + K (J - 1 - ln J) with the
  // deviatoric stretches lambda* = J^{-1/3} lambda.
  int terms = 0;
  std::array<double, 8> mu{};
  std::array<double, 8> alpha{};
  double bulk = 0.0;  // K
};

// The history field both rubber materials carry.
inline constexpr HistoryField kLeftCauchyGreenField{"left_cauchy_green_minus_identity", 6, true};

template <class T>
inline T lane_sqrt_generic(const T& a) {
  T r = a;
  for (int l = 0; l < lane_count<T>(); ++l) set_lane(r, l, std::sqrt(get_lane(a, l)));
  return r;
}

// beta = b - I (Voigt, tensor components) <- Delta b Delta^T - I for one step. With
// E = Delta - I = 2h (I - hL)^{-1} L, h = dt/2:  beta' = Delta beta Delta^T + E + E^T + E E^T,
// which keeps small strains accurate (no 1 + small - 1 cancellation).
template <class T>
inline void update_left_cauchy_green(const T d[6], const T w[3], double dt, T beta[6]) {
  const double h = 0.5 * dt;
  // L = d + W; W a = w x a, i.e. W_zy = w0, W_xz = w1, W_yx = w2.
  const T l00 = d[0], l11 = d[1], l22 = d[2];
  const T l01 = d[3] - w[2], l10 = d[3] + w[2];
  const T l12 = d[4] - w[0], l21 = d[4] + w[0];
  const T l20 = d[5] - w[1], l02 = d[5] + w[1];
  // A = I - hL and its adjugate (A^{-1} = adj(A) / det A).
  const T a00 = 1.0 - h * l00, a11 = 1.0 - h * l11, a22 = 1.0 - h * l22;
  const T a01 = -h * l01, a02 = -h * l02, a10 = -h * l10, a12 = -h * l12, a20 = -h * l20,
          a21 = -h * l21;
  const T c00 = a11 * a22 - a12 * a21, c01 = a02 * a21 - a01 * a22, c02 = a01 * a12 - a02 * a11;
  const T c10 = a12 * a20 - a10 * a22, c11 = a00 * a22 - a02 * a20, c12 = a02 * a10 - a00 * a12;
  const T c20 = a10 * a21 - a11 * a20, c21 = a01 * a20 - a00 * a21, c22 = a00 * a11 - a01 * a10;
  const T det = a00 * c00 + a01 * c10 + a02 * c20;
  const T k = (2.0 * h) / det;
  // E = k adj(A) L.
  T e[3][3];
  const T c[3][3] = {{c00, c01, c02}, {c10, c11, c12}, {c20, c21, c22}};
  const T l[3][3] = {{l00, l01, l02}, {l10, l11, l12}, {l20, l21, l22}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      e[i][j] = k * (c[i][0] * l[0][j] + c[i][1] * l[1][j] + c[i][2] * l[2][j]);
  const T bm[3][3] = {
      {beta[0], beta[3], beta[5]}, {beta[3], beta[1], beta[4]}, {beta[5], beta[4], beta[2]}};
  // Delta beta = beta + E beta, then (Delta beta) Delta^T = that + (that) E^T.
  T db[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      db[i][j] = bm[i][j] + e[i][0] * bm[0][j] + e[i][1] * bm[1][j] + e[i][2] * bm[2][j];
  auto entry = [&](int i, int j) {
    const T dbdt = db[i][j] + db[i][0] * e[j][0] + db[i][1] * e[j][1] + db[i][2] * e[j][2];
    const T eet = e[i][0] * e[j][0] + e[i][1] * e[j][1] + e[i][2] * e[j][2];
    return dbdt + e[i][j] + e[j][i] + eet;
  };
  const T n0 = entry(0, 0), n1 = entry(1, 1), n2 = entry(2, 2);
  // Off-diagonal: the mean of (i, j) and (j, i) keeps beta exactly symmetric.
  const T n3 = 0.5 * (entry(0, 1) + entry(1, 0));
  const T n4 = 0.5 * (entry(1, 2) + entry(2, 1));
  const T n5 = 0.5 * (entry(2, 0) + entry(0, 2));
  beta[0] = n0;
  beta[1] = n1;
  beta[2] = n2;
  beta[3] = n3;
  beta[4] = n4;
  beta[5] = n5;
}

// det(I + beta) accurate for small beta: 1 + tr + (second invariant) + det(beta).
template <class T>
inline T det_identity_plus(const T beta[6]) {
  const T tr = beta[0] + beta[1] + beta[2];
  const T i2 = beta[0] * beta[1] + beta[1] * beta[2] + beta[2] * beta[0] - beta[3] * beta[3] -
               beta[4] * beta[4] - beta[5] * beta[5];
  const T i3 = beta[0] * (beta[1] * beta[2] - beta[4] * beta[4]) -
               beta[3] * (beta[3] * beta[2] - beta[4] * beta[5]) +
               beta[5] * (beta[3] * beta[4] - beta[1] * beta[5]);
  return 1.0 + tr + i2 + i3;
}

}  // namespace rf::material
