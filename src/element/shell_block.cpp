// Belytschko-Lin-Tsay shell (LS-DYNA ELFORM 2): co-rotational, one point in the plane, Mindlin
// kinematics, plane stress at each through-thickness point, hourglass control. The fully
// integrated shell (ELFORM 16) shares its frame, materials, step and mass: section 11.
//
// References: T. Belytschko, J.I. Lin, C.S. Tsay, "Explicit algorithms for the nonlinear
// dynamics of shells", CMAME 42 (1984) 225-251 (BLT); T. Belytschko, B.L. Wong, H.Y. Chiang,
// "Advances in one-point quadrature shell elements", CMAME 96 (1992) 93-107 (BWC); LS-DYNA
// Theory Manual, shell chapter (Belytschko-Tsay shell, its hourglass control and the shell time
// step); T. Belytschko, W.K. Liu, B. Moran, "Nonlinear finite elements for continua and
// structures", Wiley 2000, sec. 9.5-9.6.
//
// 1. Co-rotational frame (BLT sec. 2). With the element nodes x_I (I = 1..4):
//      e3 = (x3 - x1) x (x4 - x2) / |.|          (normal from the diagonals)
//      e1 = s / |s|, s = (x2 - x1) - ((x2 - x1).e3) e3     (side 1-2 projected on the plane)
//      e2 = e3 x e1.
//    Local coordinates xh_I = e . (x_I - x_c), x_c the mean of the four nodes. Because both
//    diagonals are normal to e3, the heights are z_I = z (1, -1, 1, -1): the warping of the
//    element. The projected area A = |(x3 - x1) x (x4 - x2)| / 2, and the one-point gradient
//    operator (the mean of dN/dx over the projected quadrilateral)
//      B1 = [y24, y31, y42, y13] / (2A),  B2 = [x42, x13, x24, x31] / (2A)   (BLT eq. 15)
//    (yIJ = y_I - y_J) satisfies B1.x = B2.y = 1, B1.y = B2.x = 0, sum B = 0 exactly.
//
// 2. Velocity strains (BLT eq. 19-21). With the Mindlin kinematics v(z) = v + omega x (z e3),
//    local components vh, thh of the nodal velocities and angular velocities, and a point at
//    height z = zeta t / 2:
//      d_x   = B1 vh_x + z B1 thh_y
//      d_y   = B2 vh_y - z B2 thh_x
//      2 d_xy = B2 vh_x + B1 vh_y + z (B2 thh_y - B1 thh_x)
//      2 d_yz = B2 vh_z - N_I thh_xI,   2 d_zx = B1 vh_z + N_I thh_yI
//    with N_I = 1/4 at the element centre (triangles: 1/3 per distinct node). The frame turns
//    with the element, so the stresses stored in it need no objective rate; the in-plane spin
//    relative to side 1-2 is neglected, as in BLT. The rates are evaluated on the mid-step
//    configuration x^{n+1/2} = x^{n+1} - dt/2 v^{n+1/2} (as the hexahedra do): a rigid rotation
//    by a finite step then gives d = 0 exactly (the velocity is the Cayley-skew field of the
//    mid-step positions), so stresses stay unchanged to round-off however large the rotation.
//
// 3. Stress update per through-thickness point zeta_p (block.zeta, block.weight: Gauss or
//    Lobatto, NIP 1 = membrane only, no bending stiffness):
//      elastic: closed-form plane stress, s_xx += E/(1-nu^2) (d_x + nu d_y) dt, etc.;
//      J2 materials (*MAT_003, *MAT_024): their 3D update with w = 0, with the thickness rate
//      d_zz iterated (one elastic-tangent step, then secant steps) until |sigma_zz| <=
//      1e-10 (|sigma| + SIGY); at most 30 evaluations. Transverse shear (yz, zx) stays
//      elastic: s_yz += SHRF G 2 d_yz dt in every material, outside the yield function.
//    The thickness t is block.element_thickness: the mean of the nodal T1..T4, constant with
//    ISTUPD 0, else updated once per step (section 12).
//
// 4. Resultants and nodal forces (BLT eq. 25-27), INTERNAL sign as the hexahedra:
//      N = sum_p (t/2) w_p s_p,  M = sum_p (t/2) w_p z_p s_p,  Q = sum_p (t/2) w_p s_p (yz, zx)
//      f_xI = A (B1 N_x + B2 N_xy),  f_yI = A (B2 N_y + B1 N_xy),  f_zI = A (B1 Q_zx + B2 Q_yz)
//      m_xI = -A (B2 M_y + B1 M_xy) - A N_I Q_yz,  m_yI = A (B1 M_x + B2 M_xy) + A N_I Q_zx
//    at the end-of-step geometry (A, B, frame of x^{n+1}), then rotated to global axes. These
//    are exactly the derivatives of the internal power A sum (t/2) w s : d with respect to the
//    nodal (angular) velocities, so rigid-body modes do no work and the element is in force and
//    moment balance (sum f = 0, sum x_I x f_I + m_I = 0). There is no drilling stiffness
//    (m_z = 0 in the element frame), as in BLT and LS-DYNA: a node's rotation about the shell
//    normal is carried only by its inertia.
//
// 5. Warping correction (block.warping_correction, BWC sec. 3 in spirit): each node is tied by
//    a rigid link to its projection x_I - z_I e3 on the element plane. The projected flat
//    element sees the velocities vh - thh x (z_I e3), i.e. vh_x - z_I thh_y, vh_y + z_I thh_x,
//    and its in-plane forces pass back to the node with the link moment (-z_I e3) x f:
//    m_x += z_I f_y, m_y -= z_I f_x. Rigid motions stay strain-free and hourglass-free on a
//    warped element, and the moment balance holds with the hourglass forces included. Off
//    (LS-DYNA's default), a warped element feels spurious in-plane hourglass rates in a rigid
//    rotation about an in-plane axis (the one-point strains are unaffected: B annihilates the
//    warping pattern).
//
// 6. Hourglass control (Belytschko & Tsay 1983, LS-DYNA theory manual). Shape vector
//      tau_I = h_I - (h.xh) B1_I - (h.yh) B2_I,  h = (1, -1, 1, -1),
//    orthogonal to every linear field. Five generalised rates (mid-step, local frame):
//      membrane qd_1 = tau.vh_x, qd_2 = tau.vh_y;
//      out-of-plane qd_3 = tau.vh_z + cx.thh_x + cy.thh_y;
//      rotational qd_4 = tau.thh_x, qd_5 = tau.thh_y,
//    resisted by generalised forces Q_k that act on the same weights (f_zI += Q_3 tau_I,
//    m_xI += Q_3 cx_I, m_yI += Q_3 cy_I, the others Q_k tau_I), so that Q.qd is their power.
//    The rotation weights of qd_3 (issue 16) make it vanish for every Kirchhoff state of
//    constant curvature, w = (k1 x^2 + 2 k12 xy + k2 y^2) / 2 with thh_x = w_,y, thh_y = -w_,x,
//    which the one-point curvature already represents exactly: tau.w alone does not vanish for
//    the twist (on a rectangle, w = xy at the nodes IS the pattern h), so the w mode resisted
//    every element's twist with a transverse-shear stiffness and a kicked plate put most of its
//    energy into "hourglass". With cx = sum cx_I = 0 and likewise cy (rigid rotations stay free),
//    cy.x = (tau.x^2) / 2 and cx.y = -(tau.y^2) / 2 (the k1, k2 states), cx.x - cy.y = -tau.xy
//    (the twist), the choice in the span of B1, B2:
//      cx = -[(tau.y^2) B2 + (tau.xy) B1] / 2,  cy = [(tau.x^2) B1 + (tau.xy) B2] / 2.
//    What remains of the w mode is the part of the w pattern that the rotations do not account
//    for (on a rectangle: w = h with thh = 0, the zero-energy mode of the one-point shear).
//    Stiffness (derived here, E' = E/(1-nu^2), BB = sum_I B1_I^2 + B2_I^2): QM = 1 reproduces
//    the strain energy of each mode on a square element (membrane mode: in-plane bending
//    energy; w mode: transverse shear energy of w = xy with thh = 0; rotational: bending
//    energy),
//      K_m = QM t A BB (E' + G) / 24,  K_w = QM SHRF G t A BB / 6,
//      K_r = QM t^3 A BB (E' + G) / 288.
//    IHQ 4, 5 (stiffness): Q += K qd dt, stored in hourglass_state in the co-rotational frame
//    (objective). IHQ 1-3 (viscous, all three the same for shells, as in LS-DYNA):
//    Q = QM sqrt(K_k M_k) qd with K_k the QM = 1 stiffness and M_k the lumped mass of the mode
//    (m_node tau.tau; rotations: the nodal rotary inertia), i.e. QM/2 of critical damping of the
//    mode; the last Q is kept in hourglass_state. Both forms report the work
//    0.5 (Q_old + Q_new) qd dt: summed over steps it telescopes to the work the solver books for
//    the hourglass forces, sum_n f^n . dt (v^{n-1/2} + v^{n+1/2}) / 2, up to the last step's
//    term (tests/unit/shell_kernel_test.cpp, ShellEnergy). Triangles: no hourglass (see 7).
//
// 7. Triangles (N3 = N4): the quadrilateral's degeneration. The one-point B of the collapsed
//    quadrilateral is exactly the constant-strain triangle's gradient (slots 3 and 4 sum to
//    node 3's), the transverse-shear weights N are 1/3 per distinct node, and the hourglass is
//    off for the element (a triangle has no hourglass modes). This is the membrane CST with
//    constant-curvature bending (not Belytschko-Stolarski-Tsay's C0 triangle).
//
// 8. Critical step (LS-DYNA theory manual, shell time step, ISDO 0): dt = L_s / c with
//    L_s = (1 + beta) A / max(L_1..L_4) (beta 0 quadrilateral, 1 triangle) and the plate
//    wave speed c = sqrt(E / (rho (1 - nu^2))).
//
// 9. Lumped mass: rho t A0 / 4 per node (triangles: / 3 per distinct node). Rotary inertia per
//    node m (A0 / 4 + t^2 / 12): the t^2/12 part is the physical rotary inertia of the slab, the
//    A0 / 4 part scales it up (as BLT and LS-DYNA scale shell rotary inertia) so that the
//    rotational frequencies, the transverse-shear one N_I-coupled over the element being the
//    highest (about SHRF G t A / (4 I)), stay below the membrane frequency: checked in
//    tests/unit/shell_kernel_test.cpp (RotationsDoNotGovernTheStep). A0 / 8 was enough for a
//    free element but not for a clamped strip one element wide at TSSFAC 0.9 (the uniform-
//    rotation shear mode then sits at about 0.91 of the membrane limit, sqrt(8 SHRF G / rho) / h
//    against 2 c / h, and coupled with w it went unstable): A0 / 4 puts it at 0.65.
//
// 10. Bulk viscosity (*CONTROL_BULK_VISCOSITY TYPE -1/-2; block.bulk_viscosity). LS-DYNA lists
//    shells under TYPE -1/-2 but publishes no shell formula, so this is our own, the solids'
//    von Neumann-Richtmyer/Landshoff pressure (solid_terms.hpp) carried over to the membrane:
//      q = rho l (Q1 l e_A^2 - Q2 c e_A)  while e_A < 0,  q = 0 otherwise,
//    with e_A = d_x + d_y the mid-surface area rate (the dilatation of a plane-stress membrane:
//    its in-plane compression waves are what steepen into shocks), c the plate wave speed and
//    l = L_s the step length of section 8 at x^{n+1}, rho = rho0 A0 t0 / (A t) (mass conserved;
//    t = t0 without a thickness update).
//    q acts as a pressure on the in-plane normal stresses through the thickness, N_x and N_y
//    -= q t; sigma_zz stays 0 and the stored stresses never see q. Bending is left alone (a
//    compression-only viscosity per thickness point would make the bending response
//    asymmetric). Its power is -q e_A t A >= 0 (mid-step A, where e_A is taken), reported as
//    bulk viscosity work. For a 1-D membrane element this is the solids' damped element with c
//    and L_e replaced by the plate speed and L_s, so the same stable step holds:
//    dt = L_s / (Q + sqrt(Q^2 + c^2)), Q = Q2 c + Q1 L_s |e_A| while e_A < 0.
//
// 11. Fully integrated shell (ELFORM 16; shell16_batch). References: K.-J. Bathe, E.N. Dvorkin,
//    "A four-node plate bending element based on Mindlin/Reissner plate theory and a mixed
//    interpolation", IJNME 21 (1985) 367-383 (MITC4); E.N. Dvorkin, K.-J. Bathe, "A continuum
//    mechanics based four-node shell element for general nonlinear analysis", Eng. Comput. 1
//    (1984) 77-88; LS-DYNA Theory Manual, "Fully integrated shell (type 16)".
//    Frame: one co-rotational frame per element, section 1's, at x^{n+1/2} for the rates and at
//    x^{n+1} for the forces (as section 2). The element is the projection of the nodes on the
//    frame's plane, with the warping link of section 5 always on (a rigid rotation of a warped
//    element then stays strain-free at every point: the 2x2 points, unlike the one-point B,
//    see the warping pattern z_I = z h_I).
//    Points: 2x2 Gauss points (xi, eta) = (+-1/sqrt 3, +-1/sqrt 3) in the plane, point g next to
//    node g, weight det J; NIP points through the thickness at each. Stress and history index:
//    point (e, g, q) is (4 e + g) NIP + q (ShellBlock::points_per_element() = 4 NIP per element).
//    Rates at a point at height z: section 2's with the point's bilinear gradients dN/dx, dN/dy
//    in place of B1, B2 (membrane and curvature rates, full integration: no hourglass modes and
//    no hourglass control; *HOURGLASS IHQ/QM are ignored, as LS-DYNA does for type 16).
//    Transverse shear (assumed natural strain, MITC4): with beta_x = thh_y, beta_y = -thh_x the
//    covariant strains gamma_xi = w_,xi + beta . x_,xi at the edge midpoints A (eta = -1) and C
//    (eta = 1), gamma_eta at D (xi = -1) and B (xi = 1), each exact for the edge's chord:
//      gamma_edge = (w_R - w_P) / 2 + (x_R - x_P) / 2 . (beta_P + beta_R) / 2,
//    interpolated gamma_xi = (1 - eta)/2 A + (1 + eta)/2 C, gamma_eta = (1 - xi)/2 D +
//    (1 + xi)/2 B, and turned to Cartesian components by J^-1 at the point:
//    (2 d_zx, 2 d_yz) = J^-1 (gamma_xi, gamma_eta), J = [[x_xi, y_xi], [x_eta, y_eta]]. A
//    Kirchhoff state (w quadratic, beta linear) has zero shear at every point, so a thin plate
//    does not lock in shear; the constant states pass the patch test.
//    Stress update per point: section 3 unchanged (elastic closed form, J2 plane stress, Barlat),
//    the point's own history. Resultants N, M, Q per in-plane point (section 4's sums), and the
//    forces the transpose of the end-of-step rate operators, f = sum_g det J_g B_g^T (N, M, Q)_g,
//    so that they are the exact derivative of the internal power sum_g det J_g sum_p (t/2) w_p
//    s : d (rigid motions do no work; force and moment balance hold).
//    Drilling: none (m_z = 0), as section 4. A free element has 10 zero-energy modes: 6 rigid
//    and the 4 nodal drilling rotations.
//    Triangles: refused at initialisation naming the element (LS-DYNA would run them as its C0
//    triangle, which this code does not have); put them in an ELFORM 2 part.
//    Step and mass: sections 8 and 9 unchanged (the bilinear element's highest frequency is the
//    membrane dilatation mode, which the one-point element has too).
//    Bulk viscosity (TYPE -1/-2): section 10's q from the element's mean area rate
//    e_A = sum_g det J_g (d_x + d_y)_g / A (the exact rate of the mid-step area), applied on the
//    in-plane normal resultants of every point; power -q e_A t A as section 10.
//    Thickness update: one thickness per element (section 12), from the det J-weighted mean of
//    the four points' through-thickness strain increments.
//
// 12. Thickness update (*CONTROL_SHELL ISTUPD 1 and 4; block.thickness_update). LS-DYNA's
//    Keyword User's Manual (*CONTROL_SHELL): ISTUPD 1, "membrane straining causes thickness
//    change" of 3- and 4-node shells; 4, the same with the elastic strains neglected, for the
//    elastic-plastic materials whose elastic response is isotropic. The manuals give no formula;
//    ours: at each through-thickness point the thickness strain rate d_zz follows from plane
//    stress with isotropic (hypo)elasticity and plastically incompressible flow (J2 *MAT_003,
//    *MAT_024; Barlat *MAT_036, whose plane-stress flow has d^p_zz = -(d^p_xx + d^p_yy)):
//      d_zz = d^e_zz + d^p_zz = -nu/E (sigma_xx + sigma_yy)' - (d^p_xx + d^p_yy), and with the
//      in-plane elastic rates (d^e_xx + d^e_yy) = (1 - nu)/E (sigma_xx + sigma_yy)',
//      d_zz dt = -(d_x + d_y) dt + c Delta(sigma_xx + sigma_yy),
//    c = (1 - 2 nu)/E for ISTUPD 1 (the bulk compliance 1/(3K): the volume changes only
//    elastically) and c = (1 - nu)/E for ISTUPD 4 (d^p_zz alone). Delta is the point's stress
//    increment of this step in the co-rotational frame (the material's own: the bulk viscosity
//    never enters the stored stress), so no material needs to report its d_zz; for the elastic
//    law this is exactly -nu/(1 - nu) (d_x + d_y), and the J2 update's iterated d_zz (section 3)
//    agrees with it to the plane-stress tolerance. ISTUPD 4 leaves an elastic material's
//    thickness alone (nothing but elastic strain to neglect).
//    Element thickness strain increment: the weighted mean over the points, sum_p (w_p / 2)
//    d_zz,p dt (ELFORM 16: and over the in-plane points by det J); the bending part of d_x + d_y
//    cancels in the mean (symmetric rules), what remains is -(e_x + e_y) dt of the mid-surface
//    plus the stress term. Update t^{n+1} = t^n exp(Delta eps_zz): the logarithmic thickness
//    strain ln(t / t0) is then exactly the sum of the increments (the midpoint rates of section
//    2 integrate ln of the stretches), whatever the step, and t stays positive.
//    Which t where: the point heights z = zeta t^n / 2 of the rates (the start of the step; the
//    increment depends on the stress update, so t^{n+1} is known only after it), the
//    resultants at x^{n+1} with t^{n+1} (N, Q scaled by t^{n+1} / t^n, M by its square, as the
//    forces use the area and frame of x^{n+1}); the hourglass stiffnesses (K_m, K_w ~ t,
//    K_r ~ t^3) and the bulk viscosity's q t with t^{n+1}. Mass, rotary inertia and the masses
//    of the viscous hourglass modes keep t0 (mass is conserved; the nodal inertia is not
//    reassembled): with the stiffness ~ t and the inertia fixed, the rotational and shear
//    frequencies of section 9 move by sqrt(t / t0), below the membrane limit for any
//    thinning and for thickening up to (1 / 0.65)^2 = 2.4 times. The critical step (section 8)
//    does not depend on t.
#include "element/shell_block.hpp"

#include "element/kernel_partials.hpp"
#include "element/solid_terms.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "material/registry.hpp"
#include "model/error.hpp"

namespace rf::element {
namespace {

constexpr double kHourglassPattern[4] = {1.0, -1.0, 1.0, -1.0};

// Batched evaluation (as the hexahedra, hex_block.cpp): the elastic kernel processes kLanes
// consecutive elements at once, every quantity a GCC vector with one element per lane, so each
// arithmetic statement is one SIMD instruction across elements. T is double (one element: the
// J2 materials, whose plane-stress iteration branches per point) or Lanes. The same templated
// code serves both; branches per element become lane-wise selects.
#if defined(__AVX512F__)
constexpr int kLanes = 8;
#elif defined(__AVX__)
constexpr int kLanes = 4;
#else
constexpr int kLanes = 2;
#endif
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

template <class T>
constexpr int lanes_of() {
  return material::lane_count<T>();
}

template <class T>
inline T tsqrt(T a) {
  if constexpr (std::is_same_v<T, double>) {
    return std::sqrt(a);
  } else {
    T r;
    for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(a[l]);
    return r;
  }
}

template <class T>
inline T texp(T a) {
  if constexpr (std::is_same_v<T, double>) {
    return std::exp(a);
  } else {
    T r;
    for (int l = 0; l < kLanes; ++l) r[l] = std::exp(a[l]);
    return r;
  }
}

// p[idx[l]] in lane l.
template <class T, std::size_t... L>
inline T gather_lanes(const double* p, const std::size_t* idx, std::index_sequence<L...>) {
  return T{p[idx[L]]...};
}
template <class T>
inline T gather(const double* p, const std::size_t* idx) {
  if constexpr (std::is_same_v<T, double>)
    return p[idx[0]];
  else
    return gather_lanes<T>(p, idx, std::make_index_sequence<kLanes>{});
}

// Co-rotational frame and flat-element geometry of an element (a batch) at one configuration.
// A collapsed element (area 0) gets finite placeholder values; the caller checks `area`.
template <class T>
struct Frame {
  T e[3][3];  // e[k] = e_{k+1}, global components
  T x[4], y[4], z[4];
  T area;
  T b1[4], b2[4];
};

template <class T>
inline void make_frame(const T p[4][3], Frame<T>& f) {
  T c[3], d31[3], d42[3], s[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = 0.25 * (p[0][i] + p[1][i] + p[2][i] + p[3][i]);
    d31[i] = p[2][i] - p[0][i];
    d42[i] = p[3][i] - p[1][i];
    s[i] = p[1][i] - p[0][i];
  }
  const T n[3] = {d31[1] * d42[2] - d31[2] * d42[1], d31[2] * d42[0] - d31[0] * d42[2],
                  d31[0] * d42[1] - d31[1] * d42[0]};
  T nn = tsqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  f.area = 0.5 * nn;
  const T one = T{} + 1.0;
  nn = nn > 0.0 ? nn : one;
  const T inv_n = 1.0 / nn;
  for (int i = 0; i < 3; ++i) f.e[2][i] = n[i] * inv_n;
  const T sn = s[0] * f.e[2][0] + s[1] * f.e[2][1] + s[2] * f.e[2][2];
  for (int i = 0; i < 3; ++i) s[i] -= sn * f.e[2][i];
  T ss = tsqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  f.area = ss > 0.0 ? f.area : T{};  // side 1-2 collapsed: degenerate
  ss = ss > 0.0 ? ss : one;
  const T inv_s = 1.0 / ss;
  for (int i = 0; i < 3; ++i) f.e[0][i] = s[i] * inv_s;
  const T* a = f.e[2];
  const T* b = f.e[0];
  f.e[1][0] = a[1] * b[2] - a[2] * b[1];
  f.e[1][1] = a[2] * b[0] - a[0] * b[2];
  f.e[1][2] = a[0] * b[1] - a[1] * b[0];
  for (int I = 0; I < 4; ++I) {
    const T r0 = p[I][0] - c[0], r1 = p[I][1] - c[1], r2 = p[I][2] - c[2];
    f.x[I] = f.e[0][0] * r0 + f.e[0][1] * r1 + f.e[0][2] * r2;
    f.y[I] = f.e[1][0] * r0 + f.e[1][1] * r1 + f.e[1][2] * r2;
    f.z[I] = f.e[2][0] * r0 + f.e[2][1] * r1 + f.e[2][2] * r2;
  }
  const T inv2a = inv_n;  // 1 / (2A)
  f.b1[0] = (f.y[1] - f.y[3]) * inv2a;
  f.b1[1] = (f.y[2] - f.y[0]) * inv2a;
  f.b1[2] = (f.y[3] - f.y[1]) * inv2a;
  f.b1[3] = (f.y[0] - f.y[2]) * inv2a;
  f.b2[0] = (f.x[3] - f.x[1]) * inv2a;
  f.b2[1] = (f.x[0] - f.x[2]) * inv2a;
  f.b2[2] = (f.x[1] - f.x[3]) * inv2a;
  f.b2[3] = (f.x[2] - f.x[0]) * inv2a;
}

// Hourglass shape vector tau (section 6 of the header comment).
template <class T>
inline void hourglass_shape(const Frame<T>& f, T tau[4]) {
  const T hx = f.x[0] - f.x[1] + f.x[2] - f.x[3];
  const T hy = f.y[0] - f.y[1] + f.y[2] - f.y[3];
  for (int I = 0; I < 4; ++I) tau[I] = kHourglassPattern[I] - hx * f.b1[I] - hy * f.b2[I];
}

// Rotation weights of the out-of-plane hourglass rate (section 6 of the header comment):
// qd_3 = tau.vh_z + cx.thh_x + cy.thh_y vanishes for every Kirchhoff state of constant curvature
// (w quadratic, thh_x = w_,y, thh_y = -w_,x), the constant twist included, and (sum cx = sum cy
// = 0) for rigid rotations.
template <class T>
inline void twist_weights(const Frame<T>& f, const T tau[4], T cx[4], T cy[4]) {
  T txx{}, tyy{}, txy{};
  for (int I = 0; I < 4; ++I) {
    txx += tau[I] * f.x[I] * f.x[I];
    tyy += tau[I] * f.y[I] * f.y[I];
    txy += tau[I] * f.x[I] * f.y[I];
  }
  for (int I = 0; I < 4; ++I) {
    cx[I] = -0.5 * (tyy * f.b2[I] + txy * f.b1[I]);
    cy[I] = 0.5 * (txx * f.b1[I] + txy * f.b2[I]);
  }
}

// Largest squared side length (a triangle's fourth side has length zero).
template <class T>
inline T max_side_squared(const T p[4][3]) {
  T m{};
  for (int I = 0; I < 4; ++I) {
    const int J = (I + 1) & 3;
    const T a = p[J][0] - p[I][0], b = p[J][1] - p[I][1], c = p[J][2] - p[I][2];
    const T s = a * a + b * b + c * c;
    m = s > m ? s : m;
  }
  return m;
}

inline double plate_wave_speed(const material::ElasticConstants& m) {
  return std::sqrt(m.young / (m.rho * (1.0 - m.poisson * m.poisson)));
}

using Partial = KernelPartial;
constexpr int kMaxThreads = kMaxKernelThreads;

KernelResult combine(const KernelPartials& partials, int threads) {
  return combine_partials(partials, threads);
}

inline int thread_count() {
  return kernel_thread_count();
}

// Constants of a block that every element uses.
struct BlockConstants {
  double plane_modulus;  // E / (1 - nu^2)
  double nu;
  double shear;              // G
  double transverse_shear;   // SHRF G
  double wave_speed;         // plate wave speed
  double shear_to_membrane;  // sqrt(K_w / K_m) = sqrt(4 SHRF G / (E' + G))
  int ihq;
  double qm;
  // Section 12: c of the thickness strain increment -(d_x + d_y) dt + c Delta(s_xx + s_yy)
  // (0 without a thickness update).
  double thickness_compliance;
};

BlockConstants block_constants(const ShellBlock& b) {
  BlockConstants k;
  const auto& m = b.material;
  k.nu = m.poisson;
  k.plane_modulus = m.young / (1.0 - m.poisson * m.poisson);
  k.shear = m.shear;
  k.transverse_shear = b.shear_factor * m.shear;
  k.wave_speed = plate_wave_speed(m);
  k.shear_to_membrane = std::sqrt(4.0 * k.transverse_shear / (k.plane_modulus + k.shear));
  k.ihq = b.hourglass.ihq;
  k.qm = b.hourglass.qm;
  k.thickness_compliance = b.thickness_update == 1   ? (1.0 - 2.0 * m.poisson) / m.young
                           : b.thickness_update == 4 ? (1.0 - m.poisson) / m.young
                                                     : 0.0;
  return k;
}

// Plane-stress update of the in-plane stress s = (xx, yy, xy) at one point for a J2 material M
// with history h (kHistory order), strain rates d = (d_x, d_y, 2 d_xy) over dt: the material's
// 3D update with w = 0 (the frame is co-rotational) and d_zz iterated to sigma_zz = 0. (The
// elastic law is in closed form in shell_batch.)
template <class M>
inline void plane_stress_update(const ShellBlock& block, const BlockConstants& k, const double d[3],
                                double dt, double s[3], double* h) {
  {
    constexpr int kH = material::history_size<M>() > 0 ? material::history_size<M>() : 1;
    const material::ElasticConstants& m = block.material;
    const double w[3] = {0.0, 0.0, 0.0};
    double h0[kH];
    for (int c = 0; c < material::history_size<M>(); ++c) h0[c] = h[c];
    double trial[6], ht[kH];
    // sigma_zz after the 3D update with thickness rate dzz (the other components to `trial`).
    auto evaluate = [&](double dzz) {
      double dd[6] = {d[0], d[1], dzz, 0.5 * d[2], 0.0, 0.0};
      trial[0] = s[0];
      trial[1] = s[1];
      trial[2] = 0.0;
      trial[3] = s[2];
      trial[4] = 0.0;
      trial[5] = 0.0;
      for (int c = 0; c < material::history_size<M>(); ++c) ht[c] = h0[c];
      // Materials with other constants (rubber) do not serve shells (compute_shell_forces).
      if constexpr (material::takes_plastic_parameters<M>())
        M::update(m, block.plastic, dd, w, dt, trial, ht);
      return trial[2];
    };
    const double stiff = (m.lambda + 2.0 * m.shear) * dt;
    // Elastic plane-stress thickness rate as the first guess: exact while the point is elastic.
    double z0 = -m.lambda / (m.lambda + 2.0 * m.shear) * (d[0] + d[1]);
    double f0 = evaluate(z0);
    const double scale =
        std::abs(s[0]) + std::abs(s[1]) + std::abs(s[2]) + block.plastic.sigy + 1e-300;
    const double tol = 1e-10 * scale;
    if (std::abs(f0) > tol && stiff > 0.0) {
      // Elastic-tangent step, then secant steps on sigma_zz(dzz) (continuous, increasing).
      double z1 = z0 - f0 / stiff;
      double f1 = evaluate(z1);
      for (int it = 0; it < 28 && std::abs(f1) > tol; ++it) {
        const double df = f1 - f0;
        const double z2 = df != 0.0 ? z1 - f1 * (z1 - z0) / df : z1 - f1 / stiff;
        z0 = z1;
        f0 = f1;
        z1 = z2;
        f1 = evaluate(z1);
      }
    }
    s[0] = trial[0];
    s[1] = trial[1];
    s[2] = trial[3];
    for (int c = 0; c < material::history_size<M>(); ++c) h[c] = ht[c];
  }
}

// The nodes of a batch of elements: x^{n+1} (p), the mid-step x^{n+1/2} = x^{n+1} - dt/2
// v^{n+1/2} (pm), v^{n+1/2} (v) and omega^{n+1/2} (w), 4 nodes x 3 components, and the elements'
// thickness and reference area (ELFORM 2 and 16 alike). Into the caller's own arrays: wrapped in
// a struct they cost the kernels 2 % (BM_ShellBltNip2Ihq1, BM_ShellFullNip2).
template <class T, std::size_t L>
inline void gather_batch_nodes(const ShellBlock& block, const std::size_t (&elem)[L],
                               const NodalView& nv, const RotationalView& rv, double dt,
                               T (&p)[4][3], T (&pm)[4][3], T (&v)[4][3], T (&w)[4][3],
                               T& thickness, T& area0) {
  const double half_dt = 0.5 * dt;
  for (int I = 0; I < 4; ++I) {
    std::size_t n[L], r[L];
    for (std::size_t l = 0; l < L; ++l) {
      n[l] = static_cast<std::size_t>(block.conn[4 * elem[l] + static_cast<std::size_t>(I)]);
      r[l] =
          static_cast<std::size_t>(block.rotation_conn[4 * elem[l] + static_cast<std::size_t>(I)]);
    }
    p[I][0] = gather<T>(nv.x, n);
    p[I][1] = gather<T>(nv.y, n);
    p[I][2] = gather<T>(nv.z, n);
    v[I][0] = gather<T>(nv.vx, n);
    v[I][1] = gather<T>(nv.vy, n);
    v[I][2] = gather<T>(nv.vz, n);
    w[I][0] = gather<T>(rv.wx, r);
    w[I][1] = gather<T>(rv.wy, r);
    w[I][2] = gather<T>(rv.wz, r);
    for (int i = 0; i < 3; ++i) pm[I][i] = p[I][i] - half_dt * v[I][i];
  }
  thickness = gather<T>(block.element_thickness.data(), elem);
  area0 = gather<T>(block.area0.data(), elem);
}

// One thickness point of a batch (section 3; ELFORM 2 and 16): the strain the erosion criteria
// integrate (when allocated), then the in-plane stress update by the block's material, sp =
// (xx, yy, xy, yz, zx) in the co-rotational frame (the transverse shear is the caller's).
// `point` is the point's index within its element, points_per_element() per element.
template <class M, class T, std::size_t L>
inline void update_point(ShellBlock& block, const BlockConstants& k, const std::size_t (&elem)[L],
                         int count, std::size_t point, const T d[3], double dt, T sp[5],
                         Partial& part) {
  constexpr int kHist = material::history_size<M>();
  const std::size_t ppe = static_cast<std::size_t>(block.points_per_element());
  if (!block.strain.empty()) {
    // The strain criteria of erosion: integral of the rate of deformation in the co-rotational
    // frame (midpoint rule, like the stress), tensor shear d_xy = (2 d_xy) / 2.
    for (int l = 0; l < count; ++l) {
      double* e = block.strain.data() + 3 * (ppe * elem[l] + point);
      e[0] += dt * material::get_lane(d[0], l);
      e[1] += dt * material::get_lane(d[1], l);
      e[2] += 0.5 * dt * material::get_lane(d[2], l);
    }
  }
  if constexpr (kHist > 0) {
    double h[kHist];
    const std::size_t index = ppe * elem[0] + point;
    int slot = 0;
    for (std::size_t fi = 0; fi < M::kHistory.size(); ++fi) {
      const int nc = M::kHistory[fi].components;
      const double* in = block.history[fi].values.data() + static_cast<std::size_t>(nc) * index;
      for (int cc = 0; cc < nc; ++cc) h[slot++] = in[cc];
    }
    if constexpr (material::plane_stress_only<M>()) {
      // Plane-stress laws (Barlat 1989) in the material frame, at the element's axes angle.
      const double* ax = &block.material_axes[2 * elem[0]];
      if (!M::plane_stress_update(block.material, block.barlat, ax[0], ax[1], d, dt, sp, h))
        part.record_failure(static_cast<std::int64_t>(elem[0]), 0.0);
    } else {
      plane_stress_update<M>(block, k, d, dt, sp, h);
    }
    slot = 0;
    for (std::size_t fi = 0; fi < M::kHistory.size(); ++fi) {
      const int nc = M::kHistory[fi].components;
      double* o = block.history[fi].values.data() + static_cast<std::size_t>(nc) * index;
      for (int cc = 0; cc < nc; ++cc) o[cc] = h[slot++];
    }
  } else {
    // Elastic plane stress in closed form.
    const double a = k.plane_modulus * dt;
    sp[0] += a * (d[0] + k.nu * d[1]);
    sp[1] += a * (d[1] + k.nu * d[0]);
    sp[2] += (k.shear * dt) * d[2];
  }
}

// Section 12: whether the block's thickness changes with material M (ISTUPD 4 leaves an elastic
// material alone: it has only elastic strains to neglect).
template <class M>
inline bool thickness_changes(const ShellBlock& block) {
  return block.thickness_update == 1 ||
         (block.thickness_update == 4 && material::history_size<M>() > 0);
}

// Section 12: t^{n+1} = t^n exp(strain) from the element's thickness strain increment, to the
// block for the batch's elements; returns t^{n+1} / t^n.
template <class T, std::size_t L>
inline T update_thickness(ShellBlock& block, const std::size_t (&elem)[L], int count, T t,
                          T strain) {
  const T ratio = texp(strain);
  const T updated = t * ratio;
  for (int l = 0; l < count; ++l) block.element_thickness[elem[l]] = material::get_lane(updated, l);
  return ratio;
}

// The end of a batch, ELFORM 2 and 16 alike: the critical step of section 8 at x^{n+1}
// (L_s = (1 + beta) A / max side, beta = `tri`), section 10's while the area shrinks, squared
// (one square root per block, after the minimum: compute_shell_forces); then lane by lane in
// element order (first failure and the work sums as an element loop) the area, the forces,
// the hourglass and bulk viscosity work, failures and the steps with the mass scale.
template <class T, std::size_t L>
inline void finish_batch(ShellBlock& block, const BlockConstants& k, const std::size_t (&elem)[L],
                         int count, const Frame<T>& fm, const Frame<T>& f, const T (&p)[4][3],
                         T tri, bool bulk, T step_length, T area_rate, const T (&out)[kShellSlot],
                         T hourglass_work, T bulk_work, T sum, Partial& part) {
  const T A = f.area;
  const T length = A + tri * A;  // (1 + beta) A
  T dt2 = length * length / (max_side_squared(p) * (k.wave_speed * k.wave_speed));
  if (bulk) {  // section 10: L_s / (Q + sqrt(Q^2 + c^2)) while the area shrinks
    const T step = viscous_time_step(block.bulk_viscosity, k.wave_speed, step_length, area_rate,
                                     [](T x) { return tsqrt(x); });
    dt2 = step * step;
  }
  for (int l = 0; l < count; ++l) {
    const std::size_t e = elem[l];
    const auto ie = static_cast<std::int64_t>(e);
    const double area_end = material::get_lane(f.area, l);
    const double area_mid = material::get_lane(fm.area, l);
    block.area[e] = area_end;
    double* o = &block.force[kShellSlot * e];
    if (!(area_mid > 0.0) || !(area_end > 0.0)) {
      part.record_failure(ie, area_end > 0.0 ? area_mid : area_end);
      for (int c = 0; c < kShellSlot; ++c) o[c] = 0.0;
      continue;
    }
    for (int c = 0; c < kShellSlot; ++c) o[c] = material::get_lane(out[c], l);
    part.hourglass_work += material::get_lane(hourglass_work, l);
    part.bulk_viscosity_work += material::get_lane(bulk_work, l);
    if (block.erosion.enabled)
      block.erosion.artificial_work[e] +=
          material::get_lane(hourglass_work, l) + material::get_lane(bulk_work, l);
    if (!std::isfinite(material::get_lane(sum, l))) part.record_failure(ie, area_end);
    // Squared steps here: the mass scale enters squared.
    const double scale = block.step_scale.empty() ? 1.0 : block.step_scale[e];
    part.record_dt(material::get_lane(dt2, l) * (scale * scale), ie);
  }
}

// A batch of elements [first, first + count) (count <= lanes of T; lanes past count repeat the
// last element and are discarded): rates on the mid-step geometry, stress update, forces at
// x^{n+1}.
template <class M, class T>
void shell_batch(ShellBlock& block, const BlockConstants& k, std::size_t first, int count,
                 const NodalView& nv, const RotationalView& rv, double dt, Partial& part) {
  constexpr int L = lanes_of<T>();
  constexpr int kHist = material::history_size<M>();
  static_assert(kHist == 0 || std::is_same_v<T, double>, "J2 materials run one element at a time");
  std::size_t elem[L];
  for (int l = 0; l < L; ++l) elem[l] = first + static_cast<std::size_t>(l < count ? l : count - 1);

  T p[4][3], pm[4][3], v[4][3], w[4][3], t, area0;
  gather_batch_nodes(block, elem, nv, rv, dt, p, pm, v, w, t, area0);
  T tri;  // 1 for triangles
  if constexpr (std::is_same_v<T, double>) {
    tri = block.triangle[elem[0]] ? 1.0 : 0.0;
  } else {
    for (int l = 0; l < L; ++l) tri[l] = block.triangle[elem[l]] ? 1.0 : 0.0;
  }
  Frame<T> fm, f;
  make_frame(pm, fm);
  make_frame(p, f);
  // Transverse-shear weights N_I: 1/4, or 1/3 per distinct node of a triangle (1/6 in each of
  // the two slots of node 3).
  const T nw01 = 0.25 + tri * (1.0 / 12.0), nw23 = 0.25 - tri * (1.0 / 12.0);
  const T nw[4] = {nw01, nw01, nw23, nw23};
  const bool warp = block.warping_correction;

  // Local velocities on the mid-step frame.
  T vl[4][3], wl[4][3];
  for (int I = 0; I < 4; ++I)
    for (int a = 0; a < 3; ++a) {
      vl[I][a] = fm.e[a][0] * v[I][0] + fm.e[a][1] * v[I][1] + fm.e[a][2] * v[I][2];
      wl[I][a] = fm.e[a][0] * w[I][0] + fm.e[a][1] * w[I][1] + fm.e[a][2] * w[I][2];
    }
  if (warp)
    for (int I = 0; I < 4; ++I) {
      vl[I][0] -= fm.z[I] * wl[I][1];
      vl[I][1] += fm.z[I] * wl[I][0];
    }

  // Membrane rates (d_x, d_y, 2 d_xy), curvature rates, transverse shear (2 d_yz, 2 d_zx).
  T em[3] = {}, kp[3] = {}, gyz{}, gzx{};
  for (int I = 0; I < 4; ++I) {
    const T b1 = fm.b1[I], b2 = fm.b2[I];
    em[0] += b1 * vl[I][0];
    em[1] += b2 * vl[I][1];
    em[2] += b2 * vl[I][0] + b1 * vl[I][1];
    kp[0] += b1 * wl[I][1];
    kp[1] -= b2 * wl[I][0];
    kp[2] += b2 * wl[I][1] - b1 * wl[I][0];
    gyz += b2 * vl[I][2] - nw[I] * wl[I][0];
    gzx += b1 * vl[I][2] + nw[I] * wl[I][1];
  }

  // Through-thickness points: stress update and resultants.
  const int nip = block.nip;
  const std::size_t stride = static_cast<std::size_t>(kShellStress * nip);
  T N[3] = {}, Mr[3] = {}, Q[2] = {};
  const T half_t = 0.5 * t;
  const double gs_dt = k.transverse_shear * dt;
  const bool thin = thickness_changes<M>(block);
  T trace_change{};  // section 12: sum_p w_p Delta(s_xx + s_yy)
  for (int q = 0; q < nip; ++q) {
    std::size_t off[L];
    for (int l = 0; l < L; ++l)
      off[l] = stride * elem[l] + static_cast<std::size_t>(kShellStress * q);
    T sp[5];
    for (int c = 0; c < 5; ++c) sp[c] = gather<T>(block.stress.data() + c, off);
    const T z = block.zeta[q] * half_t;
    const T d[3] = {em[0] + z * kp[0], em[1] + z * kp[1], em[2] + z * kp[2]};
    const T trace = sp[0] + sp[1];
    update_point<M>(block, k, elem, count, static_cast<std::size_t>(q), d, dt, sp, part);
    if (thin) trace_change += block.weight[q] * (sp[0] + sp[1] - trace);
    sp[3] += gs_dt * gyz;
    sp[4] += gs_dt * gzx;
    for (int l = 0; l < count; ++l) {
      double* o = block.stress.data() + off[l];
      for (int c = 0; c < 5; ++c) o[c] = material::get_lane(sp[c], l);
    }
    const T wt = half_t * block.weight[q];
    const T wz = wt * z;
    N[0] += wt * sp[0];
    N[1] += wt * sp[1];
    N[2] += wt * sp[2];
    Mr[0] += wz * sp[0];
    Mr[1] += wz * sp[1];
    Mr[2] += wz * sp[2];
    Q[0] += wt * sp[3];
    Q[1] += wt * sp[4];
  }
  // Section 12: t^{n+1}, and the resultants with it; the initial t0 for the masses below.
  T t0 = t;
  if (thin) {
    const T ratio =
        update_thickness(block, elem, count, t,
                         (k.thickness_compliance * 0.5) * trace_change - (em[0] + em[1]) * dt);
    for (int c = 0; c < 3; ++c) {
      N[c] *= ratio;
      Mr[c] *= ratio * ratio;
    }
    Q[0] *= ratio;
    Q[1] *= ratio;
    t *= ratio;
    t0 = gather<T>(block.element_thickness0.data(), elem);
  }

  // Membrane bulk viscosity (section 10), its length the step's L_s at x^{n+1} (section 8).
  const bool bulk = block.bulk_viscosity.on();
  T step_length{}, area_rate{}, bulk_work{};
  if (bulk) {
    step_length = (f.area + tri * f.area) / tsqrt(max_side_squared(p));
    area_rate = em[0] + em[1];
    T density = block.material.rho * area0 / f.area;
    if (thin) density *= t0 / t;
    const T q = bulk_viscosity_pressure(block.bulk_viscosity, k.wave_speed, density, step_length,
                                        area_rate);
    N[0] -= q * t;
    N[1] -= q * t;
    bulk_work = -q * area_rate * t * fm.area * dt;
  }

  // Hourglass generalised forces (quadrilaterals only: scaled by 1 - tri).
  T hq[5] = {};
  T work{};
  const bool hourglass = k.qm > 0.0;
  if (hourglass) {
    const T quad = 1.0 - tri;
    T tau[4], cx[4], cy[4];
    hourglass_shape(fm, tau);
    twist_weights(fm, tau, cx, cy);
    T qd[5] = {}, tt{}, bb{};
    for (int I = 0; I < 4; ++I) {
      qd[0] += tau[I] * vl[I][0];
      qd[1] += tau[I] * vl[I][1];
      qd[2] += tau[I] * vl[I][2] + cx[I] * wl[I][0] + cy[I] * wl[I][1];
      qd[3] += tau[I] * wl[I][0];
      qd[4] += tau[I] * wl[I][1];
      tt += tau[I] * tau[I];
      bb += fm.b1[I] * fm.b1[I] + fm.b2[I] * fm.b2[I];
    }
    const T abb = fm.area * bb * quad;
    // QM = 1 stiffness of the membrane modes (header comment, section 6); the others follow.
    const T km = t * abb * ((k.plane_modulus + k.shear) / 24.0);
    if (k.ihq == 4 || k.ihq == 5) {
      const T kk[5] = {km, km, km * (k.shear_to_membrane * k.shear_to_membrane), km * t * t / 12.0,
                       km * t * t / 12.0};
      std::size_t off[L];
      for (int l = 0; l < L; ++l) off[l] = 5 * elem[l];
      for (int m = 0; m < 5; ++m) {
        const T old = gather<T>(block.hourglass_state.data() + m, off);
        hq[m] = old + (k.qm * dt) * kk[m] * qd[m];
        work += 0.5 * (old + hq[m]) * qd[m] * dt;
        for (int l = 0; l < count; ++l)
          block.hourglass_state[off[l] + static_cast<std::size_t>(m)] =
              material::get_lane(hq[m], l);
      }
    } else {
      // sqrt(K_k M_k), M_k the lumped mass (inertia) of the mode: K_w / K_m and the inertia
      // per mass factored out so that one element needs two square roots.
      // Mass and inertia with the initial thickness t0 (section 12), the stiffness with t.
      const T mass = block.material.rho * 0.25 * t0 * area0;
      const T cm = k.qm * tsqrt(km * mass * tt);
      const T cw = cm * k.shear_to_membrane;
      const T cr = cm * t * tsqrt((area0 * (1.0 / 4.0) + t0 * t0 * (1.0 / 12.0)) * (1.0 / 12.0));
      const T cc[5] = {cm, cm, cw, cr, cr};
      // The previous step's generalised forces are kept in hourglass_state so that the work is
      // the trapezoidal 0.5 (Q_old + Q_new) qd dt, as for the stiffness forms (header comment,
      // section 6). Q_new qd dt instead drifts away from the work the solver books for these
      // forces wherever the rates change sign from step to step (20 % of the hourglass energy
      // of a kicked plate, ShellEnergy tests).
      std::size_t off[L];
      for (int l = 0; l < L; ++l) off[l] = 5 * elem[l];
      for (int m = 0; m < 5; ++m) {
        const T old = gather<T>(block.hourglass_state.data() + m, off);
        hq[m] = cc[m] * qd[m];
        work += 0.5 * (old + hq[m]) * qd[m] * dt;
        for (int l = 0; l < count; ++l)
          block.hourglass_state[off[l] + static_cast<std::size_t>(m)] =
              material::get_lane(hq[m], l);
      }
    }
  }

  // Local forces and moments at x^{n+1}, rotated to global axes.
  const T A = f.area;
  T tau[4] = {}, cx[4] = {}, cy[4] = {};
  if (hourglass) {
    hourglass_shape(f, tau);
    twist_weights(f, tau, cx, cy);
  }
  T out[24];
  T sum{};
  for (int I = 0; I < 4; ++I) {
    const T b1 = f.b1[I], b2 = f.b2[I];
    T fl[3], ml[2];
    fl[0] = A * (b1 * N[0] + b2 * N[2]) + hq[0] * tau[I];
    fl[1] = A * (b2 * N[1] + b1 * N[2]) + hq[1] * tau[I];
    fl[2] = A * (b1 * Q[1] + b2 * Q[0]) + hq[2] * tau[I];
    ml[0] = -A * (b2 * Mr[1] + b1 * Mr[2]) - A * nw[I] * Q[0] + hq[3] * tau[I] + hq[2] * cx[I];
    ml[1] = A * (b1 * Mr[0] + b2 * Mr[2]) + A * nw[I] * Q[1] + hq[4] * tau[I] + hq[2] * cy[I];
    if (warp) {
      ml[0] += f.z[I] * fl[1];
      ml[1] -= f.z[I] * fl[0];
    }
    T* o = out + 6 * I;
    for (int i = 0; i < 3; ++i) {
      o[i] = f.e[0][i] * fl[0] + f.e[1][i] * fl[1] + f.e[2][i] * fl[2];
      o[3 + i] = f.e[0][i] * ml[0] + f.e[1][i] * ml[1];
      sum += o[i] + o[3 + i];
    }
  }
  finish_batch(block, k, elem, count, fm, f, p, tri, bulk, step_length, area_rate, out, work,
               bulk_work, sum, part);
}

// ---- ELFORM 16: fully integrated shell (header comment, section 11) ----------------------------

// Natural coordinates of the nodes and of the 2x2 Gauss points (point g nearest node g).
constexpr double kXiNode[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double kEtaNode[4] = {-1.0, -1.0, 1.0, 1.0};
constexpr double kGaussCoordinate = 0.57735026918962576451;  // 1 / sqrt(3)

// Operators of one in-plane point on the projected flat element of a frame: bilinear gradients
// dN/dx, dN/dy, the Jacobian determinant (the Gauss weight, 1, included) and the assumed
// natural transverse shear strains (MITC4) as nodal coefficients:
//   2 d_zx = sum_I zx_w[I] vz_I + zx_b[I][0] beta_xI + zx_b[I][1] beta_yI, likewise 2 d_yz,
// with the rotations beta_x = thh_y, beta_y = -thh_x (u = z beta_x, v = z beta_y).
template <class T>
struct PointOps {
  T dnx[4], dny[4];
  T jac;
  T zx_w[4], zx_b[4][2];
  T yz_w[4], yz_b[4][2];
};

template <class T>
inline void point_operators(const Frame<T>& f, int g, PointOps<T>& o) {
  const double xi = kXiNode[g] * kGaussCoordinate, eta = kEtaNode[g] * kGaussCoordinate;
  double nxi[4], neta[4];
  for (int I = 0; I < 4; ++I) {
    nxi[I] = 0.25 * kXiNode[I] * (1.0 + kEtaNode[I] * eta);
    neta[I] = 0.25 * kEtaNode[I] * (1.0 + kXiNode[I] * xi);
  }
  T x_xi{}, y_xi{}, x_eta{}, y_eta{};
  for (int I = 0; I < 4; ++I) {
    x_xi += nxi[I] * f.x[I];
    y_xi += nxi[I] * f.y[I];
    x_eta += neta[I] * f.x[I];
    y_eta += neta[I] * f.y[I];
  }
  o.jac = x_xi * y_eta - x_eta * y_xi;
  const T one = T{} + 1.0;
  const T inv_j = 1.0 / (o.jac > 0.0 ? o.jac : one);
  for (int I = 0; I < 4; ++I) {
    o.dnx[I] = (y_eta * nxi[I] - y_xi * neta[I]) * inv_j;
    o.dny[I] = (x_xi * neta[I] - x_eta * nxi[I]) * inv_j;
  }
  // Covariant shear strains at the tying points (Bathe and Dvorkin 1985): along an edge from
  // node P to node R (the natural coordinate increasing), gamma = (w_R - w_P) / 2 +
  // (x_R - x_P) / 2 . (beta_P + beta_R) / 2. Edges A (eta = -1, 1 -> 2) and C (eta = 1,
  // 4 -> 3) carry gamma_xi; D (xi = -1, 1 -> 4) and B (xi = 1, 2 -> 3) carry gamma_eta.
  // gamma_xi = (1 - eta) / 2 A + (1 + eta) / 2 C; gamma_eta = (1 - xi) / 2 D + (1 + xi) / 2 B;
  // Cartesian: [gamma_xi, gamma_eta] = J [gamma_xz, gamma_yz], J = [[x_xi, y_xi], [x_eta, y_eta]].
  const T ga = (y_eta * inv_j), gb = -(y_xi * inv_j);  // gamma_xz = ga gamma_xi + gb gamma_eta
  const T gc = -(x_eta * inv_j), gd = (x_xi * inv_j);  // gamma_yz = gc gamma_xi + gd gamma_eta
  for (int I = 0; I < 4; ++I) {
    o.zx_w[I] = T{};
    o.yz_w[I] = T{};
    o.zx_b[I][0] = o.zx_b[I][1] = o.yz_b[I][0] = o.yz_b[I][1] = T{};
  }
  struct Edge {
    int p, r;
    double weight;
    bool xi;  // carries gamma_xi (else gamma_eta)
  };
  const Edge edges[4] = {{0, 1, 0.5 * (1.0 - eta), true},
                         {3, 2, 0.5 * (1.0 + eta), true},
                         {0, 3, 0.5 * (1.0 - xi), false},
                         {1, 2, 0.5 * (1.0 + xi), false}};
  for (const Edge& e : edges) {
    const T czx = e.weight * (e.xi ? ga : gb);
    const T cyz = e.weight * (e.xi ? gc : gd);
    const T dx = 0.25 * (f.x[e.r] - f.x[e.p]), dy = 0.25 * (f.y[e.r] - f.y[e.p]);
    o.zx_w[e.r] += 0.5 * czx;
    o.zx_w[e.p] -= 0.5 * czx;
    o.yz_w[e.r] += 0.5 * cyz;
    o.yz_w[e.p] -= 0.5 * cyz;
    for (const int I : {e.p, e.r}) {
      o.zx_b[I][0] += czx * dx;
      o.zx_b[I][1] += czx * dy;
      o.yz_b[I][0] += cyz * dx;
      o.yz_b[I][1] += cyz * dy;
    }
  }
}

// A batch of ELFORM 16 elements, as shell_batch: rates on the mid-step geometry, stress update
// at the 4 x nip points, forces at x^{n+1}. Quadrilaterals only (initialize_shell_block).
// kThin: the block's thickness changes (section 12; thickness_changes<M>), a template argument:
// with the runtime test inside the point loop this kernel was 1-2 % slower without the update.
template <class M, class T, bool kThin>
void shell16_batch(ShellBlock& block, const BlockConstants& k, std::size_t first, int count,
                   const NodalView& nv, const RotationalView& rv, double dt, Partial& part) {
  constexpr int L = lanes_of<T>();
  constexpr int kHist = material::history_size<M>();
  static_assert(kHist == 0 || std::is_same_v<T, double>, "J2 materials run one element at a time");
  std::size_t elem[L];
  for (int l = 0; l < L; ++l) elem[l] = first + static_cast<std::size_t>(l < count ? l : count - 1);

  T p[4][3], pm[4][3], v[4][3], w[4][3], t, area0;
  gather_batch_nodes(block, elem, nv, rv, dt, p, pm, v, w, t, area0);
  Frame<T> fm, f;
  make_frame(pm, fm);
  make_frame(p, f);

  // Local velocities on the mid-step frame, with the warping link of section 5 (always on).
  T vl[4][3], wl[4][3];
  for (int I = 0; I < 4; ++I)
    for (int a = 0; a < 3; ++a) {
      vl[I][a] = fm.e[a][0] * v[I][0] + fm.e[a][1] * v[I][1] + fm.e[a][2] * v[I][2];
      wl[I][a] = fm.e[a][0] * w[I][0] + fm.e[a][1] * w[I][1] + fm.e[a][2] * w[I][2];
    }
  for (int I = 0; I < 4; ++I) {
    vl[I][0] -= fm.z[I] * wl[I][1];
    vl[I][1] += fm.z[I] * wl[I][0];
  }

  const int nip = block.nip;
  const std::size_t ppe = static_cast<std::size_t>(4 * nip);
  const T half_t = 0.5 * t;
  const double gs_dt = k.transverse_shear * dt;

  // Rates at the four points (mid-step operators); area rate for the bulk viscosity (and the
  // thickness update, section 12).
  T em[4][3], kp[4][3], gyz[4], gzx[4], jac_mid[4];
  T area_rate{};
  for (int g = 0; g < 4; ++g) {
    PointOps<T> o;
    point_operators(fm, g, o);
    if constexpr (kThin) jac_mid[g] = o.jac;
    T e0{}, e1{}, e2{}, k0{}, k1{}, k2{}, yz{}, zx{};
    for (int I = 0; I < 4; ++I) {
      const T bx = o.dnx[I], by = o.dny[I];
      e0 += bx * vl[I][0];
      e1 += by * vl[I][1];
      e2 += by * vl[I][0] + bx * vl[I][1];
      k0 += bx * wl[I][1];
      k1 -= by * wl[I][0];
      k2 += by * wl[I][1] - bx * wl[I][0];
      // beta_x = thh_y, beta_y = -thh_x.
      zx += o.zx_w[I] * vl[I][2] + o.zx_b[I][0] * wl[I][1] - o.zx_b[I][1] * wl[I][0];
      yz += o.yz_w[I] * vl[I][2] + o.yz_b[I][0] * wl[I][1] - o.yz_b[I][1] * wl[I][0];
    }
    em[g][0] = e0, em[g][1] = e1, em[g][2] = e2;
    kp[g][0] = k0, kp[g][1] = k1, kp[g][2] = k2;
    gyz[g] = yz;
    gzx[g] = zx;
    area_rate += o.jac * (e0 + e1);
  }
  area_rate = area_rate / (fm.area > 0.0 ? fm.area : T{} + 1.0);  // element mean of d_x + d_y

  // Stress update and resultants per in-plane point.
  T N[4][3] = {}, Mr[4][3] = {}, Q[4][2] = {};
  constexpr bool thin = kThin;
  T trace_change{};  // section 12: sum_g det J_g sum_p w_p Delta(s_xx + s_yy)
  for (int g = 0; g < 4; ++g) {
    for (int q = 0; q < nip; ++q) {
      const std::size_t point_in_element = static_cast<std::size_t>(g * nip + q);
      std::size_t off[L];
      for (int l = 0; l < L; ++l) off[l] = kShellStress * (ppe * elem[l] + point_in_element);
      T sp[5];
      for (int c = 0; c < 5; ++c) sp[c] = gather<T>(block.stress.data() + c, off);
      const T z = block.zeta[q] * half_t;
      const T d[3] = {em[g][0] + z * kp[g][0], em[g][1] + z * kp[g][1], em[g][2] + z * kp[g][2]};
      T trace{};
      if constexpr (thin) trace = sp[0] + sp[1];
      update_point<M>(block, k, elem, count, point_in_element, d, dt, sp, part);
      if constexpr (thin) trace_change += (jac_mid[g] * block.weight[q]) * (sp[0] + sp[1] - trace);
      sp[3] += gs_dt * gyz[g];
      sp[4] += gs_dt * gzx[g];
      for (int l = 0; l < count; ++l) {
        double* o = block.stress.data() + off[l];
        for (int c = 0; c < 5; ++c) o[c] = material::get_lane(sp[c], l);
      }
      const T wt = half_t * block.weight[q];
      const T wz = wt * z;
      for (int c = 0; c < 3; ++c) {
        N[g][c] += wt * sp[c];
        Mr[g][c] += wz * sp[c];
      }
      Q[g][0] += wt * sp[3];
      Q[g][1] += wt * sp[4];
    }
  }
  // Section 12: one thickness per element from the det J-weighted mean of the points'
  // increments (area_rate is that mean of d_x + d_y); the resultants with t^{n+1}.
  T t0 = t;
  if constexpr (thin) {
    const T jac_sum = jac_mid[0] + jac_mid[1] + jac_mid[2] + jac_mid[3];
    const T mean_change = trace_change / (jac_sum > 0.0 ? jac_sum : T{} + 1.0);
    const T ratio = update_thickness(block, elem, count, t,
                                     (k.thickness_compliance * 0.5) * mean_change - area_rate * dt);
    for (int g = 0; g < 4; ++g) {
      for (int c = 0; c < 3; ++c) {
        N[g][c] *= ratio;
        Mr[g][c] *= ratio * ratio;
      }
      Q[g][0] *= ratio;
      Q[g][1] *= ratio;
    }
    t *= ratio;
    t0 = gather<T>(block.element_thickness0.data(), elem);
  }

  // Membrane bulk viscosity (section 10 with the element's mean area rate, section 11).
  const bool bulk = block.bulk_viscosity.on();
  T step_length{}, bulk_work{};
  if (bulk) {
    step_length = f.area / tsqrt(max_side_squared(p));
    T density = block.material.rho * area0 / f.area;
    if constexpr (thin) density *= t0 / t;
    const T q = bulk_viscosity_pressure(block.bulk_viscosity, k.wave_speed, density, step_length,
                                        area_rate);
    for (int g = 0; g < 4; ++g) {
      N[g][0] -= q * t;
      N[g][1] -= q * t;
    }
    bulk_work = -q * area_rate * t * fm.area * dt;
  }

  // Nodal forces and moments at x^{n+1}: the transpose of the rate operators of the end-of-step
  // geometry, weighted by the points' Jacobians.
  T fl[4][3] = {}, ml[4][2] = {};
  for (int g = 0; g < 4; ++g) {
    PointOps<T> o;
    point_operators(f, g, o);
    const T j = o.jac;
    const T n0 = j * N[g][0], n1 = j * N[g][1], n2 = j * N[g][2];
    const T m0 = j * Mr[g][0], m1 = j * Mr[g][1], m2 = j * Mr[g][2];
    const T qyz = j * Q[g][0], qzx = j * Q[g][1];
    for (int I = 0; I < 4; ++I) {
      const T bx = o.dnx[I], by = o.dny[I];
      fl[I][0] += bx * n0 + by * n2;
      fl[I][1] += by * n1 + bx * n2;
      fl[I][2] += qzx * o.zx_w[I] + qyz * o.yz_w[I];
      ml[I][0] += -(by * m1 + bx * m2) - (qzx * o.zx_b[I][1] + qyz * o.yz_b[I][1]);
      ml[I][1] += bx * m0 + by * m2 + qzx * o.zx_b[I][0] + qyz * o.yz_b[I][0];
    }
  }
  T out[24];
  T sum{};
  for (int I = 0; I < 4; ++I) {
    ml[I][0] += f.z[I] * fl[I][1];
    ml[I][1] -= f.z[I] * fl[I][0];
    T* o = out + 6 * I;
    for (int i = 0; i < 3; ++i) {
      o[i] = f.e[0][i] * fl[I][0] + f.e[1][i] * fl[I][1] + f.e[2][i] * fl[I][2];
      o[3 + i] = f.e[0][i] * ml[I][0] + f.e[1][i] * ml[I][1];
      sum += o[i] + o[3 + i];
    }
  }
  finish_batch(block, k, elem, count, fm, f, p, T{}, bulk, step_length, area_rate, out, T{},
               bulk_work, sum, part);
}

// Legendre polynomial P_n and its derivative at x.
inline void legendre(int n, double x, double& p, double& dp) {
  double p0 = 1.0, p1 = x;
  if (n == 0) {
    p = 1.0;
    dp = 0.0;
    return;
  }
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  p = p1;
  dp = n * (x * p1 - p0) / (x * x - 1.0);
}

int distinct_nodes(const std::int32_t* c) {
  return c[2] == c[3] ? 3 : 4;
}

}  // namespace

bool through_thickness_points(ThroughThicknessRule rule, int nip, std::vector<double>& zeta,
                              std::vector<double>& weight) {
  zeta.assign(static_cast<std::size_t>(std::max(nip, 0)), 0.0);
  weight.assign(zeta.size(), 0.0);
  if (nip < 1 || nip > 10) return false;
  if (nip == 1) {
    if (rule == ThroughThicknessRule::kLobatto) return false;  // needs both surfaces
    zeta[0] = 0.0;
    weight[0] = 2.0;
    return true;
  }
  const double pi = std::acos(-1.0);
  if (rule == ThroughThicknessRule::kGauss) {
    // Roots of P_n by Newton from the Chebyshev-like estimate; w = 2 / ((1 - x^2) P_n'^2).
    for (int i = 0; i < nip; ++i) {
      double x = -std::cos(pi * (i + 0.75) / (nip + 0.5));
      double p = 0.0, dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        legendre(nip, x, p, dp);
        const double dx = p / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      legendre(nip, x, p, dp);
      zeta[i] = x;
      weight[i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
  } else {
    // Gauss-Lobatto: the ends and the roots of P_{n-1}'; w = 2 / (n (n-1) P_{n-1}(x)^2).
    const int m = nip - 1;
    const double wend = 2.0 / (nip * (nip - 1.0));
    zeta[0] = -1.0;
    zeta[nip - 1] = 1.0;
    weight[0] = weight[nip - 1] = wend;
    for (int i = 1; i < nip - 1; ++i) {
      double x = -std::cos(pi * i / m);
      for (int it = 0; it < 100; ++it) {
        double p = 0.0, dp = 0.0;
        legendre(m, x, p, dp);
        const double d2p = (2.0 * x * dp - m * (m + 1.0) * p) / (1.0 - x * x);
        const double dx = dp / d2p;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      double p = 0.0, dp = 0.0;
      legendre(m, x, p, dp);
      zeta[i] = x;
      weight[i] = wend / (p * p);
    }
  }
  for (int i = 0; i < nip / 2; ++i) {  // exact symmetry
    const double zs = 0.5 * (zeta[nip - 1 - i] - zeta[i]);
    const double ws = 0.5 * (weight[i] + weight[nip - 1 - i]);
    zeta[i] = -zs;
    zeta[nip - 1 - i] = zs;
    weight[i] = weight[nip - 1 - i] = ws;
  }
  if (nip % 2 == 1) zeta[nip / 2] = 0.0;
  return true;
}

const material::HistoryArray* find_history(const ShellBlock& block, std::string_view name) {
  for (const auto& h : block.history)
    if (h.field.name == name) return &h;
  return nullptr;
}

namespace {

// Angle psi from the element's e1 (side 1-2) to the rolling direction of an anisotropic
// material (material/barlat.hpp, BarlatAxes), stored as (cos psi, sin psi).
void set_material_axes(ShellBlock& block, const Frame<double>& f, std::size_t e) {
  const material::BarlatParameters& p = block.barlat;
  double psi = p.beta;
  if (p.axes != material::BarlatAxes::kElement) {
    const auto& v = p.vector;
    double w[3] = {v[0], v[1], v[2]};                // AOPT 2: A, projected below
    if (p.axes == material::BarlatAxes::kVectorV) {  // AOPT 3: V x normal
      const double* n3 = f.e[2];
      w[0] = v[1] * n3[2] - v[2] * n3[1];
      w[1] = v[2] * n3[0] - v[0] * n3[2];
      w[2] = v[0] * n3[1] - v[1] * n3[0];
    }
    const double x = w[0] * f.e[0][0] + w[1] * f.e[0][1] + w[2] * f.e[0][2];
    const double y = w[0] * f.e[1][0] + w[1] * f.e[1][1] + w[2] * f.e[1][2];
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(std::hypot(x, y) > 1e-6 * len))
      throw SolverError(fmt::format(
          "shell element {} of part {}: the material axes vector ({:.6g}, {:.6g}, {:.6g}) of "
          "AOPT {} gives no direction in the element's plane (it is along the shell normal)",
          block.element_id[e], block.part_id, v[0], v[1], v[2],
          p.axes == material::BarlatAxes::kVectorA ? 2 : 3));
    psi += std::atan2(y, x);
  }
  block.material_axes[2 * e] = std::cos(psi);
  block.material_axes[2 * e + 1] = std::sin(psi);
}

}  // namespace

void initialize_shell_block(ShellBlock& block, const NodalView& nodes) {
  const std::size_t n = block.size();
  if (block.conn.size() != 4 * n || block.rotation_conn.size() != 4 * n ||
      block.thickness.size() != 4 * n)
    throw SolverError(fmt::format(
        "part {}: shell block has {} elements but {} nodes, {} rotational indices and {} "
        "thicknesses (expected 4 per element each)",
        block.part_id, n, block.conn.size(), block.rotation_conn.size(), block.thickness.size()));
  if (block.elform != 2 && block.elform != 16)
    throw SolverError(fmt::format(
        "part {}: shell ELFORM {} has no kernel (supported: 2, Belytschko-Lin-Tsay; 16, fully "
        "integrated)",
        block.part_id, block.elform));
  // *MAT_RIGID blocks have no stress update (the body moves them) but need areas and masses.
  if (!block.rigid && !material::serves(block.material_index, material::kShell))
    throw SolverError(
        fmt::format("part {}: the part's material does not run on shell elements", block.part_id));
  const ThroughThicknessRule rule = block.nip == 1 ? ThroughThicknessRule::kGauss : block.rule;
  if (!through_thickness_points(rule, block.nip, block.zeta, block.weight))
    throw SolverError(fmt::format(
        "part {}: {} through-thickness points NIP = {} not supported (Gauss 1-10, Lobatto 2-10)",
        block.part_id, block.rule == ThroughThicknessRule::kGauss ? "Gauss" : "Lobatto",
        block.nip));
  const std::size_t points = static_cast<std::size_t>(block.points_per_element()) * n;
  block.stress.assign(kShellStress * points, 0.0);
  block.history.clear();
  for (const material::HistoryField& f : material::history_fields(block.material_index))
    block.history.push_back(
        {f, std::vector<double>(points * static_cast<std::size_t>(f.components), 0.0)});
  block.hourglass_state.assign(5 * n, 0.0);
  block.force.assign(kShellSlot * n, 0.0);
  block.area0.assign(n, 0.0);
  block.area.assign(n, 0.0);
  block.element_thickness.assign(n, 0.0);
  block.element_thickness0.assign(n, 0.0);
  block.triangle.assign(n, 0);
  const bool anisotropic =
      !block.rigid &&
      block.material_index == material::material_index(model::MaterialKind::ThreeParameterBarlat);
  block.material_axes.assign(anisotropic ? 2 * n : 0, 0.0);
  for (std::size_t e = 0; e < n; ++e) {
    const std::int32_t* c = &block.conn[4 * e];
    block.triangle[e] = c[2] == c[3] ? 1 : 0;
    const int distinct = distinct_nodes(c);
    if (distinct == 3 && block.elform == 16)
      throw SolverError(fmt::format(
          "shell element {} of part {} is a triangle (N3 = N4): the fully integrated shell "
          "ELFORM 16 takes quadrilaterals only; put triangles in a part with ELFORM 2",
          block.element_id[e], block.part_id));
    double tsum = 0.0;
    for (int I = 0; I < distinct; ++I) {
      const double ti = block.thickness[4 * e + static_cast<std::size_t>(I)];
      if (!(ti > 0.0))
        throw SolverError(
            fmt::format("shell element {} of part {}: thickness T{} = {:.6g} is not "
                        "positive",
                        block.element_id[e], block.part_id, I + 1, ti));
      tsum += ti;
    }
    block.element_thickness[e] = tsum / distinct;
    block.element_thickness0[e] = block.element_thickness[e];
    double p[4][3];
    for (int I = 0; I < 4; ++I) {
      p[I][0] = nodes.x[c[I]];
      p[I][1] = nodes.y[c[I]];
      p[I][2] = nodes.z[c[I]];
    }
    Frame<double> f;
    make_frame(p, f);
    if (!(f.area > 0.0))
      throw SolverError(fmt::format(
          "shell element {} of part {} is degenerate (area {:.6g}): check that its nodes are "
          "distinct (a triangle repeats N3 as N4) and not collinear",
          block.element_id[e], block.part_id, f.area));
    block.area0[e] = f.area;
    block.area[e] = f.area;
    if (anisotropic) set_material_axes(block, f, e);
  }
}

KernelResult compute_shell_forces(ShellBlock& block, const NodalView& nodes,
                                  const RotationalView& rotations, double dt) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  const BlockConstants k = block_constants(block);
  const ElementOwnership& owned = block.owned;  // one process: every element
  if (owned.partitioned) block.owned.prepare_batches(kLanes);
  const bool full = block.elform == 16;
  int threads = 1;
#pragma omp parallel num_threads(thread_count())
  {
    Partial local;
    material::with_material(block.material_index, [&]<class M>(std::type_identity<M>) {
      const bool thin = thickness_changes<M>(block);  // section 12
      if constexpr (material::history_size<M>() == 0) {
        // Elastic: batches of kLanes elements; a static schedule over batches still gives each
        // thread a contiguous element range.
        const std::int64_t batches = owned.partitioned
                                         ? static_cast<std::int64_t>(owned.batches.size())
                                         : (n + kLanes - 1) / kLanes;
#pragma omp for schedule(static)
        for (std::int64_t bi = 0; bi < batches; ++bi) {
          std::size_t first = static_cast<std::size_t>(bi) * kLanes;
          int count = static_cast<int>(std::min<std::int64_t>(kLanes, n - bi * kLanes));
          if (owned.partitioned) {
            first = static_cast<std::size_t>(owned.batches[static_cast<std::size_t>(bi)].first);
            count = owned.batches[static_cast<std::size_t>(bi)].count;
          }
          if (full && thin)
            shell16_batch<M, Lanes, true>(block, k, first, count, nodes, rotations, dt, local);
          else if (full)
            shell16_batch<M, Lanes, false>(block, k, first, count, nodes, rotations, dt, local);
          else
            shell_batch<M, Lanes>(block, k, first, count, nodes, rotations, dt, local);
        }
      } else {
        const std::int64_t items = owned.count(n);
#pragma omp for schedule(static)
        for (std::int64_t i = 0; i < items; ++i) {
          const auto e = static_cast<std::size_t>(owned.element(i));
          if (full && thin)
            shell16_batch<M, double, true>(block, k, e, 1, nodes, rotations, dt, local);
          else if (full)
            shell16_batch<M, double, false>(block, k, e, 1, nodes, rotations, dt, local);
          else
            shell_batch<M, double>(block, k, e, 1, nodes, rotations, dt, local);
        }
      }
    });
    partials[omp_get_thread_num()] = local;
#pragma omp single
    threads = omp_get_num_threads();
  }
  KernelResult r = combine(partials, threads);
  if (r.min_dt_element >= 0) r.min_dt = std::sqrt(r.min_dt);  // partials hold squared steps
  return r;
}

KernelResult shell_critical_timestep(const ShellBlock& block, const NodalView& nodes,
                                     std::vector<double>* raw_steps) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  if (raw_steps) raw_steps->assign(block.size(), 0.0);
  const double c = plate_wave_speed(block.material);
  int threads = 1;
#pragma omp parallel num_threads(thread_count())
  {
    Partial local;
#pragma omp for schedule(static)
    for (std::int64_t e = 0; e < n; ++e) {
      if (block.erosion.is_eroded(static_cast<std::size_t>(e))) continue;  // left the model
      const std::int32_t* cn = &block.conn[4 * static_cast<std::size_t>(e)];
      double p[4][3];
      for (int I = 0; I < 4; ++I) {
        p[I][0] = nodes.x[cn[I]];
        p[I][1] = nodes.y[cn[I]];
        p[I][2] = nodes.z[cn[I]];
      }
      Frame<double> f;
      make_frame(p, f);
      if (!(f.area > 0.0)) {
        local.record_failure(e, f.area);
        continue;
      }
      const double beta = cn[2] == cn[3] ? 1.0 : 0.0;
      const double step = (1.0 + beta) * f.area / (std::sqrt(max_side_squared(p)) * c);
      if (raw_steps) (*raw_steps)[static_cast<std::size_t>(e)] = step;
      local.record_dt(scaled_step(block.step_scale, e, step), e);
    }
    partials[omp_get_thread_num()] = local;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine(partials, threads);
}

void add_shell_lumped_mass(const ShellBlock& block, std::vector<double>& nodal_mass,
                           std::vector<double>& rotational_inertia,
                           const std::vector<double>* element_factor) {
  for (std::size_t e = 0; e < block.size(); ++e) {
    const std::int32_t* c = &block.conn[4 * e];
    const std::int32_t* rc = &block.rotation_conn[4 * e];
    const int distinct = distinct_nodes(c);
    const double t = block.element_thickness0[e];  // mass is conserved (section 12)
    const double a = block.area0[e];
    const double factor = element_factor ? (*element_factor)[e] : 1.0;
    const double m = factor * block.material.rho * t * a / distinct;
    const double inertia = m * (a / 4.0 + t * t / 12.0);
    for (int I = 0; I < distinct; ++I) {
      nodal_mass[static_cast<std::size_t>(c[I])] += m;
      rotational_inertia[static_cast<std::size_t>(rc[I])] += inertia;
    }
  }
}

}  // namespace rf::element
