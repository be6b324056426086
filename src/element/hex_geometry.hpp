// Geometry of the trilinear 8-node hexahedron: exact volume, uniform-strain (volume-averaged)
// gradient operator, Gauss-point shape-function gradients and face areas.
//
// Node numbering is LS-DYNA's: nodes 1-4 on the face zeta = -1 counter-clockwise seen from
// zeta = +1, nodes 5-8 above them. Coordinates are passed component-major, x[i][I] with i the
// direction and I the node (0-based).
//
// Exact volume and uniform-strain B (Flanagan & Belytschko, IJNME 17 (1981) 679-706, eqs. 14-16):
// the one-point operator is b_iI = (1/V) dV/dx_iI, which integrates the strain rate exactly over
// the element for any trilinear geometry. We evaluate dV/dx in a compact way derived here:
// write x(xi, eta, zeta) = (1/8) sum_k A_k s_k(xi, eta, zeta) with the base vectors
//   s_0 = 1, s_1 = xi, s_2 = eta, s_3 = zeta, s_4 = eta zeta, s_5 = zeta xi, s_6 = xi eta,
//   s_7 = xi eta zeta,  and  A_k = sum_I s_k(node I) x_I.
// Integrating det J = x_xi . (x_eta x x_zeta) over the bi-unit cube, only monomials with even
// powers survive, which leaves
//   V = [A1,A2,A3]/64 + ([A6,A2,A4] + [A5,A4,A3] + [A1,A6,A5])/192,   [a,b,c] = a.(b x c)
// (A7, the xi-eta-zeta term, drops out). Then dV/dx_I = sum_k (dV/dA_k) s_k(node I), with
// each dV/dA_k a sum of cross products. Cost: 9 cross products and 6 x 8 multiply-adds.
#pragma once

#include <cmath>

namespace rf::element::hex {

inline constexpr double kXi[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
inline constexpr double kEta[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
inline constexpr double kZeta[8] = {-1, -1, -1, -1, 1, 1, 1, 1};

// Hourglass base vectors (Flanagan-Belytschko's Gamma): eta.zeta, zeta.xi, xi.eta, xi.eta.zeta
// evaluated at the nodes. They are orthogonal to each other and to 1, xi, eta, zeta.
inline constexpr double kHourglassBase[4][8] = {{1, 1, -1, -1, -1, -1, 1, 1},   // eta zeta
                                                {1, -1, -1, 1, -1, 1, 1, -1},   // zeta xi
                                                {1, -1, 1, -1, 1, -1, 1, -1},   // xi eta
                                                {-1, 1, -1, 1, 1, -1, 1, -1}};  // xi eta zeta

// Faces as node quadruples (0-based), outward normal by the right-hand rule.
inline constexpr int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

// The helpers below are templates over the scalar type so that the same code serves one element
// (double) and a batch of elements held in SIMD lanes (see hex_block.cpp).
template <class T>
inline void cross(const T a[3], const T b[3], T c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
template <class T>
inline T dot(const T a[3], const T b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

struct Geometry {
  double a[8][3];  // A_k = sum_I s_k(I) x_I, k = 0..7 (A_0 = sum of nodes)
  double b[3][8];  // dV/dx_iI (NOT divided by V): the uniform-strain B times the volume
  double volume;
};

// A-vectors only (cheap; used for Jacobians and corotational axes).
template <class T>
inline void base_vectors(const T x[3][8], T a[8][3]) {
  for (int i = 0; i < 3; ++i) {
    const T* p = x[i];
    // Butterflies over the node pattern keep this at ~ 3 x 24 additions.
    const T s01 = p[0] + p[1], d10 = p[1] - p[0], s23 = p[2] + p[3], d23 = p[2] - p[3];
    const T s45 = p[4] + p[5], d54 = p[5] - p[4], s67 = p[6] + p[7], d67 = p[6] - p[7];
    a[0][i] = s01 + s23 + s45 + s67;
    a[1][i] = d10 + d23 + d54 + d67;   // xi
    a[2][i] = -s01 + s23 - s45 + s67;  // eta
    a[3][i] = -s01 - s23 + s45 + s67;  // zeta
    a[4][i] = s01 - s23 - s45 + s67;   // eta zeta
    a[5][i] = -d10 - d23 + d54 + d67;  // zeta xi
    a[6][i] = -d10 + d23 - d54 + d67;  // xi eta
    a[7][i] = d10 - d23 - d54 + d67;   // xi eta zeta
  }
}

// Volume and its gradient with respect to the base vectors, G_k = dV/dA_k for k = 1..6
// (G_0 = G_7 = 0: V is translation invariant and A_7 drops out). From
//   V = [A1,A2,A3]/64 + ([A6,A2,A4] + [A5,A4,A3] + [A1,A6,A5])/192
// by the triple-product rule d[a,b,c]/da = b x c. Only a[1..6] are read.
template <class T>
inline void volume_gradient(const T a[8][3], T G[7][3], T& volume) {
  const T* A1 = a[1];
  const T* A2 = a[2];
  const T* A3 = a[3];
  const T* A4 = a[4];
  const T* A5 = a[5];
  const T* A6 = a[6];
  T c23[3], c31[3], c12[3], c65[3], c46[3], c54[3], c62[3], c35[3], c43[3], c16[3], c24[3], c51[3];
  cross(A2, A3, c23);
  cross(A3, A1, c31);
  cross(A1, A2, c12);
  cross(A6, A5, c65);
  cross(A4, A6, c46);
  cross(A5, A4, c54);
  cross(A6, A2, c62);
  cross(A3, A5, c35);
  cross(A4, A3, c43);
  cross(A1, A6, c16);
  cross(A2, A4, c24);
  cross(A5, A1, c51);
  constexpr double k64 = 1.0 / 64.0, k192 = 1.0 / 192.0;
  for (int i = 0; i < 3; ++i) {
    G[0][i] = T{};
    G[1][i] = k64 * c23[i] + k192 * c65[i];
    G[2][i] = k64 * c31[i] + k192 * c46[i];
    G[3][i] = k64 * c12[i] + k192 * c54[i];
    G[4][i] = k192 * (c62[i] + c35[i]);
    G[5][i] = k192 * (c43[i] + c16[i]);
    G[6][i] = k192 * (c24[i] + c51[i]);
  }
  volume = k64 * dot(A1, c23) + k192 * (dot(A6, c24) + dot(A5, c43) + dot(A1, c65));
}

// Nodal values from coefficients of the base monomials: f_I = sum_k s_k(node I) c_k, the
// transpose of base_vectors. Used for dV/dx_I = sum_k G_k s_k(I) and for nodal forces, which in
// the one-point element are all of this form. Butterfly: with zeta = -1 / +1 on nodes 0-3 / 4-7,
//   f = P(xi, eta) + zeta R(xi, eta),  P = (c0 + eta c2) + xi (c1 + eta c6),
//                                      R = (c3 + eta c4) + xi (c5 + eta c7),
// 24 additions per component instead of 56.
template <class T>
inline void expand_nodal(const T c[8][3], T f[3][8]) {
  for (int i = 0; i < 3; ++i) {
    const T up = c[0][i] + c[2][i], um = c[0][i] - c[2][i];
    const T tp = c[1][i] + c[6][i], tm = c[1][i] - c[6][i];
    const T rp = c[3][i] + c[4][i], rm = c[3][i] - c[4][i];
    const T zp = c[5][i] + c[7][i], zm = c[5][i] - c[7][i];
    const T p[4] = {um - tm, um + tm, up + tp,
                    up - tp};  // nodes (xi, eta) = (-,-) (+,-) (+,+) (-,+)
    const T r[4] = {rm - zm, rm + zm, rp + zp, rp - zp};
    for (int n = 0; n < 4; ++n) {
      f[i][n] = p[n] - r[n];
      f[i][n + 4] = p[n] + r[n];
    }
  }
}

inline void compute_geometry(const double x[3][8], Geometry& g) {
  base_vectors(x, g.a);
  double G[7][3];
  volume_gradient(g.a, G, g.volume);
  for (int i = 0; i < 3; ++i) {
    const double g1 = G[1][i], g2 = G[2][i], g3 = G[3][i], g4 = G[4][i], g5 = G[5][i], g6 = G[6][i];
    for (int n = 0; n < 8; ++n) {
      const double xi = kXi[n], eta = kEta[n], zeta = kZeta[n];
      g.b[i][n] =
          g1 * xi + g2 * eta + g3 * zeta + g4 * (eta * zeta) + g5 * (zeta * xi) + g6 * (xi * eta);
    }
  }
}

// Volume only.
inline double hex_volume(const double x[3][8]) {
  double a[8][3];
  base_vectors(x, a);
  double c23[3], c24[3], c43[3], c65[3];
  cross(a[2], a[3], c23);
  cross(a[2], a[4], c24);
  cross(a[4], a[3], c43);
  cross(a[6], a[5], c65);
  return dot(a[1], c23) / 64.0 + (dot(a[6], c24) + dot(a[5], c43) + dot(a[1], c65)) / 192.0;
}

// Largest face area squared. Each face area is half the norm of the cross product of its
// diagonals: exact for planar quadrilaterals and for quadrilaterals collapsed to triangles
// (two coincident nodes), zero for faces collapsed to an edge or a point.
inline double max_face_area_squared(const double x[3][8]) {
  double amax = 0.0;
  for (const auto& f : kFaces) {
    const double d1[3] = {x[0][f[2]] - x[0][f[0]], x[1][f[2]] - x[1][f[0]],
                          x[2][f[2]] - x[2][f[0]]};
    const double d2[3] = {x[0][f[3]] - x[0][f[1]], x[1][f[3]] - x[1][f[1]],
                          x[2][f[3]] - x[2][f[1]]};
    double c[3];
    cross(d1, d2, c);
    const double a2 = 0.25 * dot(c, c);
    amax = a2 > amax ? a2 : amax;
  }
  return amax;
}

// Largest face area squared from the base vectors (same quantity as max_face_area_squared). On
// the face zeta = z the map is x = (1/8)[(A0 + z A3) + xi (A1 + z A5) + eta (A2 + z A4) + ...],
// and the cross product of its diagonals is (1/32) (A1 + z A5) x (A2 + z A4), so
//   area^2 = |(A1 + z A5) x (A2 + z A4)|^2 / 256,
// and likewise for xi = +-1 (tangents A2 +- A6, A3 +- A5) and eta = +-1 (A1 +- A6, A3 +- A4).
template <class T>
inline T max_face_area_squared_from_base(const T a[8][3]) {
  // {first tangent, its face partner, second tangent, its face partner}
  constexpr int kPairs[3][4] = {{1, 5, 2, 4}, {2, 6, 3, 5}, {1, 6, 3, 4}};
  T amax{};
  for (const auto& pr : kPairs) {
    for (const double side : {-1.0, 1.0}) {
      T t1[3], t2[3], c[3];
      for (int i = 0; i < 3; ++i) {
        t1[i] = a[pr[0]][i] + side * a[pr[1]][i];
        t2[i] = a[pr[2]][i] + side * a[pr[3]][i];
      }
      cross(t1, t2, c);
      const T a2 = dot(c, c);
      amax = a2 > amax ? a2 : amax;
    }
  }
  return amax * (1.0 / 256.0);
}

// 2x2x2 Gauss rule (weights 1): point g has natural coordinates (kXi[g], kEta[g], kZeta[g])/sqrt3.
inline constexpr double kGauss = 0.57735026918962576451;

// Cartesian shape-function gradients dN_I/dx_i at Gauss point g from the base vectors a, and
// det J. The Jacobian columns are x_xi = (A1 + A5 zeta + A6 eta + A7 eta zeta)/8 etc.; the
// inverse is formed from cofactors (J^{-1} rows = x_eta x x_zeta, x_zeta x x_xi, x_xi x x_eta
// over det J).
inline double gauss_gradients(const double a[8][3], int g, double dndx[3][8]) {
  const double xi = kGauss * kXi[g], eta = kGauss * kEta[g], zeta = kGauss * kZeta[g];
  double jx[3], je[3], jz[3];
  for (int i = 0; i < 3; ++i) {
    jx[i] = 0.125 * (a[1][i] + a[5][i] * zeta + a[6][i] * eta + a[7][i] * eta * zeta);
    je[i] = 0.125 * (a[2][i] + a[4][i] * zeta + a[6][i] * xi + a[7][i] * xi * zeta);
    jz[i] = 0.125 * (a[3][i] + a[4][i] * eta + a[5][i] * xi + a[7][i] * xi * eta);
  }
  double r0[3], r1[3], r2[3];
  cross(je, jz, r0);
  cross(jz, jx, r1);
  cross(jx, je, r2);
  const double det = dot(jx, r0);
  const double inv = 1.0 / det;
  for (int n = 0; n < 8; ++n) {
    const double dxi = 0.125 * kXi[n] * (1.0 + kEta[n] * eta) * (1.0 + kZeta[n] * zeta);
    const double deta = 0.125 * kEta[n] * (1.0 + kXi[n] * xi) * (1.0 + kZeta[n] * zeta);
    const double dzeta = 0.125 * kZeta[n] * (1.0 + kXi[n] * xi) * (1.0 + kEta[n] * eta);
    for (int i = 0; i < 3; ++i) dndx[i][n] = (r0[i] * dxi + r1[i] * deta + r2[i] * dzeta) * inv;
  }
  return det;
}

}  // namespace rf::element::hex
