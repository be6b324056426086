// *MAT_MOONEY-RIVLIN_RUBBER (027): compressible Mooney-Rivlin rubber in LS-DYNA's form
// (LS-DYNA Keyword User's Manual, Vol. II, *MAT_027):
//   W = A (I1 - 3) + B (I2 - 3) + C (I3^-2 - 1) + D (I3 - 1)^2,
//   C = A/2 + B,   D = [A (5 nu - 2) + B (11 nu - 5)] / [2 (1 - 2 nu)],
// I1, I2, I3 the invariants of C = F^T F (equal to those of b = F F^T). C makes the reference
// stress free; D gives the small-strain Poisson's ratio PR with shear modulus G = 2 (A + B)
// (checked in tests/unit/rubber_material_test.cpp by linearising the stress).
//
// Cauchy stress, sigma = (2/J) F dW/dC F^T with dI1/dC = I, dI2/dC = I1 I - C, dI3/dC = I3 C^-1:
//   sigma = (2/J) [ (A + B I1) b - B b^2 + I3 dW/dI3 I ],  I3 dW/dI3 = -2C I3^-2 + 2D I3 (I3 - 1).
// The stress is a function of b alone (hyperelastic.hpp carries b): the update overwrites s.
#pragma once

#include <array>

#include "material/element_family.hpp"
#include "material/hyperelastic.hpp"
#include "model/model.hpp"

namespace rf::material {

struct MooneyRivlinMaterial {
  static constexpr model::MaterialKind kKind = model::MaterialKind::MooneyRivlinRubber;
  static constexpr unsigned kFamilies = kHex8 | kTet13 | kTet10;
  static constexpr std::array<HistoryField, 1> kHistory{{kLeftCauchyGreenField}};
  using Parameters = HyperelasticParameters;

  // h: b - I (6 components).
  template <class T>
  static void update(const ElasticConstants&, const HyperelasticParameters& p, const T d[6],
                     const T w[3], double dt, T s[6], T* h) {
    update_left_cauchy_green(d, w, dt, h);
    stress(p, h, s);
  }

  template <class T>
  static void stress(const HyperelasticParameters& p, const T beta[6], T s[6]) {
    const T b0 = 1.0 + beta[0], b1 = 1.0 + beta[1], b2 = 1.0 + beta[2];
    const T b3 = beta[3], b4 = beta[4], b5 = beta[5];
    const T i1 = b0 + b1 + b2;
    const T i3 = det_identity_plus(beta);
    const T j = lane_sqrt_generic(i3);
    const T inv_i3 = 1.0 / i3;
    // b^2 (symmetric).
    const T q0 = b0 * b0 + b3 * b3 + b5 * b5;
    const T q1 = b3 * b3 + b1 * b1 + b4 * b4;
    const T q2 = b5 * b5 + b4 * b4 + b2 * b2;
    const T q3 = b0 * b3 + b3 * b1 + b5 * b4;
    const T q4 = b3 * b5 + b1 * b4 + b4 * b2;
    const T q5 = b5 * b0 + b4 * b3 + b2 * b5;
    const T c1 = p.a + p.b * i1;
    const T vol = -2.0 * p.c * inv_i3 * inv_i3 + 2.0 * p.d * i3 * (i3 - 1.0);
    const T k = 2.0 / j;
    s[0] = k * (c1 * b0 - p.b * q0 + vol);
    s[1] = k * (c1 * b1 - p.b * q1 + vol);
    s[2] = k * (c1 * b2 - p.b * q2 + vol);
    s[3] = k * (c1 * b3 - p.b * q3);
    s[4] = k * (c1 * b4 - p.b * q4);
    s[5] = k * (c1 * b5 - p.b * q5);
  }
};

}  // namespace rf::material
