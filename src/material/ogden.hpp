// *MAT_OGDEN_RUBBER (077_O): Ogden rubber with a decoupled volumetric part, as LS-DYNA writes
// it (LS-DYNA Keyword User's Manual, Vol. II, *MAT_077_O):
//   W = sum_{i=1..3} sum_{j=1..n} mu_j / alpha_j (lambda*_i^alpha_j - 1) + K (J - 1 - ln J),
// lambda*_i = J^{-1/3} lambda_i the deviatoric principal stretches. Small-strain shear modulus
// G = sum_j mu_j alpha_j / 2; K from G and PR as for linear elasticity,
// K = 2 G (1 + nu) / (3 (1 - 2 nu)) (what LS-DYNA does with PR for this material).
//
// Principal Kirchhoff stresses of the deviatoric part (Ogden 1972; Holzapfel, Nonlinear Solid
// Mechanics, 2000, sec. 6.5): tau_a = sum_j mu_j [lambda*_a^alpha_j - 1/3 sum_c lambda*_c^alpha_j];
// Cauchy sigma = p I + (1/J) sum_a tau_a n_a n_a^T with p = dU/dJ = K (1 - 1/J), n_a the
// eigenvectors of b = F F^T (hyperelastic.hpp carries b), lambda_a^2 its eigenvalues.
//
// The eigen-decomposition runs per stress point in scalar code (one lane after the other in the
// SIMD kernel): Eigen's closed-form 3x3 solver (trigonometric eigenvalues, cross-product
// eigenvectors) on b - I. Where two stretches nearly coincide their eigenvectors are only
// determined within their plane, but then tau_a are nearly equal too and the stress does not
// depend on the choice (the error is of order round-off times G).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cmath>

#include "material/element_family.hpp"
#include "material/hyperelastic.hpp"
#include "model/model.hpp"

namespace rf::material {

// Cauchy stress of the Ogden law at b = I + beta (one stress point).
inline void ogden_stress(const HyperelasticParameters& p, const double beta[6], double s[6]) {
  Eigen::Matrix3d m;
  m << beta[0], beta[3], beta[5], beta[3], beta[1], beta[4], beta[5], beta[4], beta[2];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(m);
  const Eigen::Vector3d& ev = es.eigenvalues();
  const double log_j = 0.5 * std::log(det_identity_plus(beta));
  const double j = std::exp(log_j);
  // ln lambda*_a = ln(1 + ev_a) / 2 - ln J / 3.
  double log_stretch[3];
  for (int a = 0; a < 3; ++a) log_stretch[a] = 0.5 * std::log1p(ev[a]) - log_j / 3.0;
  // tau_a = sum_j mu_j [(lambda*_a^alpha - 1) - mean_c (lambda*_c^alpha - 1)] (expm1: accurate
  // near the reference).
  double tau[3] = {0.0, 0.0, 0.0};
  for (int t = 0; t < p.terms; ++t) {
    double e[3];
    for (int a = 0; a < 3; ++a) e[a] = std::expm1(p.alpha[t] * log_stretch[a]);
    const double mean = (e[0] + e[1] + e[2]) / 3.0;
    for (int a = 0; a < 3; ++a) tau[a] += p.mu[t] * (e[a] - mean);
  }
  const double pressure = p.bulk * (j - 1.0) / j;
  const Eigen::Matrix3d& v = es.eigenvectors();
  Eigen::Matrix3d sig = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 3; ++a) sig += (tau[a] / j) * v.col(a) * v.col(a).transpose();
  s[0] = sig(0, 0) + pressure;
  s[1] = sig(1, 1) + pressure;
  s[2] = sig(2, 2) + pressure;
  s[3] = 0.5 * (sig(0, 1) + sig(1, 0));
  s[4] = 0.5 * (sig(1, 2) + sig(2, 1));
  s[5] = 0.5 * (sig(2, 0) + sig(0, 2));
}

struct OgdenMaterial {
  static constexpr model::MaterialKind kKind = model::MaterialKind::OgdenRubber;
  static constexpr unsigned kFamilies = kHex8 | kTet13 | kTet10;
  static constexpr std::array<HistoryField, 1> kHistory{{kLeftCauchyGreenField}};
  using Parameters = HyperelasticParameters;

  // h: b - I (6 components).
  template <class T>
  static void update(const ElasticConstants&, const HyperelasticParameters& p, const T d[6],
                     const T w[3], double dt, T s[6], T* h) {
    update_left_cauchy_green(d, w, dt, h);
    for (int l = 0; l < lane_count<T>(); ++l) {
      double beta[6], out[6];
      for (int c = 0; c < 6; ++c) beta[c] = get_lane(h[c], l);
      ogden_stress(p, beta, out);
      for (int c = 0; c < 6; ++c) set_lane(s[c], l, out[c]);
    }
  }
};

}  // namespace rf::material
