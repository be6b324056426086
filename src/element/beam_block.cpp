// Two-node beam and truss kernels for the explicit central-difference solver (issue 16).
//
// Both formulations are CO-ROTATIONAL: every step the element gets a local orthonormal frame
// (e1 along the current chord x2 - x1, e2 = s and e3 = t across it), deformations are measured
// relative to the rigid motion of that frame, and the resultants are stored as components in it.
// A rigid motion of the element therefore leaves the resultants unchanged (objectivity) without
// any stress rotation. References: Belytschko & Hsieh (1973), Belytschko & Schwer (1977, "Large
// displacement, transient analysis of space frames", IJNME 11:65) and the LS-DYNA Theory
// Manual, beam chapter (Belytschko resultant beam, truss); the chord-relative (natural
// deformation) form of the Timoshenko beam stiffness follows e.g. Przemieniecki, "Theory of
// Matrix Structural Analysis" (1968), sec. 5.4.
//
// STEP STRUCTURE. The solver hands us x^{n+1}, v^{n+1/2} and omega^{n+1/2}. The chord at the
// start of the step is c^n = c^{n+1} - dt (v2 - v1) (exact for central differences), so the
// increments below are differences between two configurations:
//   frame rotation     R_f = R(chi) R(theta_m): the stored frame turned by the mean nodal
//                      rotation theta_m = (dth_1 + dth_2) / 2, then by the smallest rotation
//                      chi that takes its turned axis onto the new chord e1 = c^{n+1}/|c^{n+1}| (1)
//   elongation         dL = |c^{n+1}| - |c^n|, axial strain increment dL / L_mid          (2)
//   nodal rotation     dth_I = omega_I dt                                                (3)
//   deformational rot. dphi_I = dth_I - theta_m - chi  (relative to the frame)            (4)
//   torsion increment  dtau = (dth_2 - dth_1) . e1                                       (5)
// For a rigid rotation R of the element, R(theta_m) = R already takes the old chord onto the
// new one, so chi = 0, the frame turns by exactly R, and (4), (5) vanish to round-off at any
// step size and about any axis (a decomposition "chord swing + twist" instead would leave an
// O(dt^2) error per step that accumulates for a beam spinning about an oblique axis). For a
// deforming element chi is the chord's rotation relative to the mean nodal rotation and (4) is
// the chord-relative rotation of Belytschko & Schwer to first order in the increment.
//
// FRAME (the s axis). The frame is carried from step to step in block.frame by (1): the
// cross-section turns with the mean nodal rotation about every axis (Radioss, for instance,
// corrects its beam's local y axis by the mean axial nodal rotation every cycle), and s is
// re-orthogonalised to e1 and renormalised every step, t = e1 x s.
//
// ELFORM 2, Belytschko-Schwer resultant beam (elastic). Incremental resultants in the local
// frame (N, Qs, Qt, T, Ms, Mt; block.resultant). With the chord-relative nodal rotations
// theta_a, theta_b about one local bending axis, the Timoshenko beam's end moments are (two-node
// element with cubic deflection and constant shear, Przemieniecki sec. 5.4)
//   M_a = k0 [(4 + phi) theta_a + (2 - phi) theta_b],  M_b = k0 [(2 - phi) theta_a + (4 + phi)
//   theta_b],   k0 = E I / (L (1 + phi)),   phi = 12 E I / (kappa G A L^2)               (6)
// (kappa A = SA, the shear area, or SHRF A). We store their two independent combinations
//   midpoint bending moment  M   = (M_b - M_a) / 2 = E I (theta_b - theta_a) / L        (7)
//   shear force              Q   = (M_a + M_b) / L = 6 E I (theta_a + theta_b)/(L^2(1+phi)) (8)
// and update them incrementally with dphi from (4) projected on the local axes. Axial force
// N += E A dL / L_mid (so that N = E A ln(L / L0) for a monotonic stretch: length-based, exact
// for any rotation), torsion T += G J dtau / L_mid. This element is exact for a linear elastic
// beam loaded at its nodes (nodal deflections of a cantilever are P L^3 / 3EI + P L / kGA
// with any number of elements).
//
// NODAL FORCES follow from the power of the resultants (W' = N L' + T tau' + sum M_I phi_I'),
// with phi_I' = omega_I . t - (v2 - v1) . s / L about t and omega_I . s + (v2 - v1) . t / L
// about s (the chord's angular velocity is e1 x (v2 - v1) / L):
//   f_2 = N e1 - Qs s + Qt t = -f_1,
//   m_I = M_tI t + M_sI s -/+ T e1,   M_t1,2 = Qs L / 2 -/+ Mt,  M_s1,2 = Qt L / 2 -/+ Ms.
// They balance exactly: sum f = 0 and (x2 - x1) x f_2 + m_1 + m_2 = 0 (tested).
// Sign conventions of the stored resultants (also what output should show): N > 0 in
// tension; T > 0 when node 2 is twisted positively about e1 relative to node 1; Mt (Ms) > 0
// when node 2 is turned about t (s) more than node 1, i.e. positive curvature about that axis;
// Qs (Qt) > 0 when the mean rotation of the nodes about t (s) relative to the chord is positive.
// In terms of the INTERNAL force slots: f_int,2 = N e1 - Qs s + Qt t = -f_int,1, and
// m_int,2 = (Qs L / 2 + Mt) t + (Qt L / 2 + Ms) s + T e1.
//
// ELFORM 3, truss: axial force only, N = sigma A, with the axial stress updated by the axial
// strain increment dL / L_mid (length-based: sigma = E ln(L / L0) for an elastic material); the
// cross-section area A is kept constant. No rotations.
//
// ELFORM 1, integrated beam (our substitute for LS-DYNA's Hughes-Liu beam, see below). The
// kinematics and the frame are those of (1)-(5); the element has ONE stress section at
// mid-length (like Hughes-Liu's single point along the axis) whose axial stress is integrated
// over section points:
//   rectangle (CST 0, sides TS along s and TT along t): 2 x 2 Gauss points at
//             (+-TS, +-TT) / (2 sqrt 3), weight A / 4 each;
//   tube      (CST 1, outer diameter TS, inner TT, TT = 0 a solid bar): a ring rule of 8
//             points equally spaced on the circle of radius r_p = sqrt((R^2 + r^2) / 2),
//             weight A / 8 each (integrates A, I = A (R^2 + r^2) / 4 and every linear strain
//             field exactly).
// The dimensions are the means of the two nodal values. Fibre strain increment at (s, t):
//   d eps = dL / L_mid - s dkappa_t + t dkappa_s,  dkappa = (dphi_2 - dphi_1) / L_mid     (11)
// (rotation about t turns the axis towards +s; about s towards -t), the uniaxial stress update
// per point, then N = sum w sigma, Mt = -sum w sigma s, Ms = sum w sigma t. Transverse shear
// and torsion stay elastic resultants: Q += kappa G A (dphi_1 + dphi_2) / 2 (constant shear
// strain of the one-point element, the phi -> infinity form of (8)), T += G J dtau / L_mid
// with J of the section (tube: pi (D^4 - d^4) / 32; rectangle: the Saint-Venant series of
// Timoshenko & Goodier, J = a b^3 (1/3 - 0.21 (b/a)(1 - (b/a)^4 / 12)), b <= a). The nodal
// forces are those of ELFORM 2 with these resultants. Differences from LS-DYNA's Hughes-Liu
// element (Hughes & Liu 1981, a degenerated continuum): no fibre-thickness update, transverse
// shear and torsion not integrated over the section (so they do not yield), and the frame and
// rotations are those of our co-rotational ELFORM 2. Like any one-point Timoshenko element it
// is stiffer in bending than ELFORM 2: a cantilever's tip deflection is
// P L^3 / 3EI (1 - 1 / (4 n^2)) + P L / kappa G A for n elements (tested).
//
// MATERIALS. ELFORM 2: *MAT_ELASTIC. Truss and ELFORM 1: *MAT_ELASTIC and the J2 materials
// (*MAT_PLASTIC_KINEMATIC, *MAT_PIECEWISE_LINEAR_PLASTICITY) in uniaxial stress: trial
// sigma_tr = sigma + E d eps, xi = sigma_tr - alpha; if |xi| > k sigma_y(eps_p) the plastic
// increment dl solves |xi| - (E + H_k) dl = k sigma_y(eps_p + dl) (the one-dimensional radial
// return, Simo & Hughes 1998, ch. 1, with mixed hardening), sigma = sigma_tr - E dl sign(xi),
// alpha += H_k dl sign(xi). The rate factor k of VP 0 (Cowper-Symonds, LCSR) uses the axial
// strain rate |d eps| / dt; viscoplastic VP 1 and failure strains are rejected at
// initialisation (not implemented for beams).
//
// MASS. Translational: rho A L0 / 2 to each node (all formulations). Rotational inertia of a
// beam node (ELFORM 1, 2), the same about every axis because the solver stores one scalar per
// rotational DOF set:
//   ELFORM 2: J = rho L0 max(1.5 max(Iss, Itt), 0.25 J_torsion)                          (9)
//   ELFORM 1: the larger of (9) and rho L0^3 kappa G A / (8 (E - kappa G))               (9')
// The physical lumped value about a transverse axis is rho I L0 / 2; (9) takes three times it
// (rotary inertia changes the low bending frequencies of a slender member by O((r/lambda)^2),
// a negligible amount, but it sets the highest element frequencies). With (9) the element's
// rotational frequencies stay below the axial one (see (10)), so for slender elements the step
// is LS-DYNA's axial beam step L / c, as for the truss. The one-point element's shear mode is
// stiffer (kappa G A L / 2 against 6 E I / L): (9') is the inertia that puts it at the axial
// frequency (E - kappa G is bounded below by 0.1 E for absurd SHRF), a rotary-inertia scaling
// of the kind explicit codes use for beams; it vanishes as L0^2 under mesh refinement. The
// free-vibration test of a 10-element cantilever finds the first frequency 0.55 % below
// Euler-Bernoulli with ELFORM 1 and 0.47 % below with ELFORM 2 (lumped mass, rate 2).
//
// TIME STEP. Truss: L / c, c = sqrt(E / rho) (LS-DYNA's rule). Beams: 2 / omega_max with
// omega_max the highest frequency of the free element (an upper bound of the mesh's highest
// frequency, Irons' theorem), which for the lumped masses m = rho A L0 / 2 and J is the
// largest of (derived from (6) in the chord-relative coordinates):
//   axial    omega^2 = 2 E A / (L m)            (-> dt = L / c)
//   torsion  omega^2 = 2 G J_t / (L J)
//   bending, per plane: antisymmetric  omega^2 = 2 E I / (L J)
//                       symmetric      omega^2 = K (1 / J + 4 / (m L^2))                 (10)
// with K = 6 k0 (ELFORM 2) or kappa G A L / 2 (ELFORM 1). For slender elements the axial value
// governs (dt = L / c, as LS-DYNA's beam step); stubby shear-stiff elements get a smaller step
// from the symmetric bending-shear mode (tested against a numerical eigen-analysis).
#include "element/beam_block.hpp"
#include "element/kernel_partials.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "material/j2_plasticity.hpp"
#include "material/registry.hpp"
#include "model/error.hpp"

namespace rf::element {
namespace {

using Partial = KernelPartial;
constexpr int kMaxThreads = kMaxKernelThreads;

KernelResult combine(const KernelPartials& partials, int threads) {
  return combine_partials(partials, threads);
}

inline int thread_count() {
  return kernel_thread_count();
}

inline double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
inline double norm(const double a[3]) {
  return std::sqrt(dot(a, a));
}

// Rotates v by the rotation vector th (Rodrigues' formula, exact finite rotation).
// Rotation by the rotation vector th in Rodrigues' form R v = v + a th x v + b th x (th x v),
// a = sin|th| / |th|, b = (1 - cos|th|) / |th|^2. Per-step rotations are tiny, so below
// |th| = 0.05 the coefficients come from their Taylor series, exact to round-off there (the
// first omitted terms are |th|^8 / 9! and |th|^8 / 10!), which avoids the libm calls.
struct Rotation {
  double th[3];
  double a, b;
};

inline Rotation make_rotation(const double th[3]) {
  Rotation r{{th[0], th[1], th[2]}, 1.0, 0.5};
  const double q = dot(th, th);
  if (q < 0.0025) {
    r.a = 1.0 - q / 6.0 * (1.0 - q / 20.0 * (1.0 - q / 42.0));
    r.b = 0.5 * (1.0 - q / 12.0 * (1.0 - q / 30.0 * (1.0 - q / 56.0)));
  } else {
    const double angle = std::sqrt(q);
    r.a = std::sin(angle) / angle;
    r.b = (1.0 - std::cos(angle)) / q;
  }
  return r;
}

inline void rotate(const Rotation& r, double v[3]) {
  double txv[3], txtxv[3];
  cross(r.th, v, txv);
  cross(r.th, txv, txtxv);
  for (int i = 0; i < 3; ++i) v[i] += r.a * txv[i] + r.b * txtxv[i];
}

// Rotation vector of the smallest rotation that turns direction a onto direction b (any
// lengths): angle atan2(|a x b|, a . b) about unit(a x b). Exact for any angle below pi; for
// small angles (x = |a x b| / a . b < 0.02) atan(x) / x from its series (first omitted term
// x^10 / 11).
inline void rotation_between(const double a[3], const double b[3], double out[3]) {
  cross(a, b, out);
  const double sn2 = dot(out, out);
  if (sn2 == 0.0) {
    out[0] = out[1] = out[2] = 0.0;
    return;
  }
  const double c = dot(a, b);
  double scale;
  if (c > 0.0 && sn2 < 4e-4 * c * c) {
    const double x2 = sn2 / (c * c);
    scale = (1.0 - x2 * (1.0 / 3.0 - x2 * (1.0 / 5.0 - x2 * (1.0 / 7.0 - x2 / 9.0)))) / c;
  } else {
    const double sn = std::sqrt(sn2);
    scale = std::atan2(sn, c) / sn;
  }
  for (int i = 0; i < 3; ++i) out[i] *= scale;
}

// A unit vector perpendicular to e1: the global axis least aligned with e1, orthogonalised.
inline void default_s_axis(const double e1[3], double s[3]) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(e1[i]) < std::fabs(e1[k])) k = i;
  s[0] = s[1] = s[2] = 0.0;
  s[k] = 1.0;
  const double p = dot(s, e1);
  for (int i = 0; i < 3; ++i) s[i] -= p * e1[i];
  const double n = norm(s);
  for (int i = 0; i < 3; ++i) s[i] /= n;
}

// Section stiffnesses of a block.
struct SectionStiffness {
  double ea = 0.0, gj = 0.0, ei_s = 0.0, ei_t = 0.0, kga = 0.0;
};

inline SectionStiffness section_stiffness(const BeamBlock& b) {
  SectionStiffness k;
  k.ea = b.material.young * b.area;
  k.gj = b.material.shear * b.torsion;
  k.ei_s = b.material.young * b.iss;
  k.ei_t = b.material.young * b.itt;
  const double shear_area = b.shear_area > 0.0 ? b.shear_area : b.shear_factor * b.area;
  k.kga = b.material.shear * shear_area;
  return k;
}

// Lumped rotational inertia of one node, eqs. (9) and (9') of the header comment.
inline double node_rotational_inertia(const BeamBlock& b, double length0) {
  const double rho = b.material.rho;
  double j = rho * length0 * std::max(1.5 * std::max(b.iss, b.itt), 0.25 * b.torsion);
  if (b.elform == 1) {
    const SectionStiffness k = section_stiffness(b);
    const double e = b.material.young;
    const double kg = k.kga / b.area;
    j = std::max(j, rho * length0 * length0 * length0 * k.kga / (8.0 * std::max(e - kg, 0.1 * e)));
  }
  return j;
}

// Shear parameter phi = 12 E I / (kappa G A L^2) of eq. (6); 0 without shear flexibility.
inline double shear_parameter(double ei, double kga, double length) {
  return kga > 0.0 ? 12.0 * ei / (kga * length * length) : 0.0;
}

// The uniaxial stress update of the header comment (MATERIALS) at one point. eps_p and back
// are null for an elastic material.
struct Uniaxial {
  double young = 0.0;
  const material::PlasticParameters* plastic = nullptr;  // null: elastic
};

inline void uniaxial_update(const Uniaxial& m, double de, double dt, double& sigma, double* eps_p,
                            double* back) {
  // A point past its failure strain (FS, FAIL) carries no stress (solver/erosion.cpp).
  if (m.plastic && m.plastic->failure_strain > 0.0 && *eps_p >= m.plastic->failure_strain) {
    sigma = 0.0;
    return;
  }
  sigma += m.young * de;
  if (!m.plastic) return;
  const material::PlasticParameters& p = *m.plastic;
  const double xi = sigma - *back;
  const double magnitude = std::fabs(xi);
  // Yield stress at the step's strain rate (rate factor or rate table: yield_at).
  const double rate = dt > 0.0 ? std::fabs(de) / dt : 0.0;
  double slope = 0.0;
  const double yield = material::j2::yield_at(p, *eps_p, rate, &slope);
  if (magnitude <= yield) return;
  const double stiff = m.young + p.kinematic_modulus;
  // Newton on g(dl) = |xi| - stiff dl - sigma_y(eps_p + dl, rate), decreasing in dl for a
  // hardening curve; exact after one iteration for a linear law (piecewise linear: a few).
  double dl = (magnitude - yield) / (stiff + slope);
  for (int it = 0; it < 30; ++it) {
    double h = 0.0;
    const double g = magnitude - stiff * dl - material::j2::yield_at(p, *eps_p + dl, rate, &h);
    const double dg = stiff + h;
    if (!(dg > 0.0)) break;
    const double step = g / dg;
    dl = std::max(dl + step, 0.0);
    if (std::fabs(step) <= 1e-14 * (dl + 1e-300) || std::fabs(g) <= 1e-13 * yield) break;
  }
  const double sign = xi > 0.0 ? 1.0 : -1.0;
  sigma -= m.young * dl * sign;
  *back += p.kinematic_modulus * dl * sign;
  *eps_p += dl;
  if (p.failure_strain > 0.0 && *eps_p >= p.failure_strain) sigma = 0.0;
}

inline bool finite3(const double a[3]) {
  return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}

// Pointers to the per-point history of the J2 materials (null for elastic blocks).
struct HistoryPointers {
  double* eps_p = nullptr;
  double* back = nullptr;
};

// One element of any formulation. Returns false (forces zeroed) for a collapsed element or a
// non-finite result.

inline bool beam_element(BeamBlock& b, std::size_t e, const NodalView& nv, const RotationalView& rv,
                         double dt, const SectionStiffness& k, const Uniaxial& um,
                         const HistoryPointers& hp) {
  double* f = &b.force[kBeamSlot * e];
  const std::int32_t n1 = b.conn[2 * e], n2 = b.conn[2 * e + 1];
  const double c1[3] = {nv.x[n2] - nv.x[n1], nv.y[n2] - nv.y[n1], nv.z[n2] - nv.z[n1]};
  const double dv[3] = {nv.vx[n2] - nv.vx[n1], nv.vy[n2] - nv.vy[n1], nv.vz[n2] - nv.vz[n1]};
  const double c0[3] = {c1[0] - dt * dv[0], c1[1] - dt * dv[1], c1[2] - dt * dv[2]};
  const double length1 = norm(c1), length0 = norm(c0);
  if (!(length1 > 0.0) || !(length0 > 0.0) || !std::isfinite(length1)) {
    for (int i = 0; i < kBeamSlot; ++i) f[i] = 0.0;
    b.length[e] = length1;
    return false;
  }
  b.length[e] = length1;
  const double e1[3] = {c1[0] / length1, c1[1] / length1, c1[2] / length1};
  const double length_mid = 0.5 * (length0 + length1);
  const double strain_increment = (length1 - length0) / length_mid;  // eq. (2)
  double* frame = &b.frame[9 * e];
  double* r = &b.resultant[6 * e];

  if (b.elform == 3) {
    double& sigma = b.stress[e];
    uniaxial_update(um, strain_increment, dt, sigma, hp.eps_p ? hp.eps_p + e : nullptr,
                    hp.back ? hp.back + e : nullptr);
    const double axial = sigma * b.area;
    r[0] = axial;
    for (int i = 0; i < 3; ++i) {
      f[i] = -axial * e1[i];
      f[3 + i] = 0.0;
      f[6 + i] = axial * e1[i];
      f[9 + i] = 0.0;
      frame[i] = e1[i];
    }
    return std::isfinite(axial);
  }

  // Nodal rotation increments (3) and their mean.
  const std::int32_t r1 = b.rotation_conn[2 * e], r2 = b.rotation_conn[2 * e + 1];
  const double th1[3] = {rv.wx[r1] * dt, rv.wy[r1] * dt, rv.wz[r1] * dt};
  const double th2[3] = {rv.wx[r2] * dt, rv.wy[r2] * dt, rv.wz[r2] * dt};
  const double mean[3] = {0.5 * (th1[0] + th2[0]), 0.5 * (th1[1] + th2[1]),
                          0.5 * (th1[2] + th2[2])};

  // Frame update (1): turn the stored frame by the mean nodal rotation, then by the smallest
  // rotation chi that takes the turned axis onto the new chord.
  double s[3] = {frame[3], frame[4], frame[5]};
  double chi[3];
  {
    double a[3] = {frame[0], frame[1], frame[2]};
    const Rotation turn = make_rotation(mean);
    rotate(turn, a);
    rotate(turn, s);
    rotation_between(a, e1, chi);
    rotate(make_rotation(chi), s);
    const double p = dot(s, e1);
    for (int i = 0; i < 3; ++i) s[i] -= p * e1[i];
    const double sn = norm(s);
    if (!(sn > 0.0) || !std::isfinite(sn)) {
      for (int i = 0; i < kBeamSlot; ++i) f[i] = 0.0;
      return false;
    }
    for (int i = 0; i < 3; ++i) s[i] /= sn;
  }
  double t[3];
  cross(e1, s, t);
  for (int i = 0; i < 3; ++i) {
    frame[i] = e1[i];
    frame[3 + i] = s[i];
    frame[6 + i] = t[i];
  }

  // Deformational rotations (4) in the local frame, torsion (5).
  double d1[3], d2[3];
  for (int i = 0; i < 3; ++i) {
    d1[i] = th1[i] - mean[i] - chi[i];
    d2[i] = th2[i] - mean[i] - chi[i];
  }
  const double ds1 = dot(d1, s), ds2 = dot(d2, s);
  const double dt1 = dot(d1, t), dt2 = dot(d2, t);
  const double dtau = dot(th2, e1) - dot(th1, e1);

  if (b.elform == 2) {
    // Resultant increments, eqs. (6)-(8) per bending plane.
    const double phi_s = shear_parameter(k.ei_s, k.kga, length_mid);  // bending about s
    const double phi_t = shear_parameter(k.ei_t, k.kga, length_mid);  // bending about t
    const double l2 = length_mid * length_mid;
    r[0] += k.ea * strain_increment;                            // N
    r[1] += 6.0 * k.ei_t / (l2 * (1.0 + phi_t)) * (dt1 + dt2);  // Qs (bending about t)
    r[2] += 6.0 * k.ei_s / (l2 * (1.0 + phi_s)) * (ds1 + ds2);  // Qt (bending about s)
    r[3] += k.gj * dtau / length_mid;                           // T
    r[4] += k.ei_s * (ds2 - ds1) / length_mid;                  // Ms
    r[5] += k.ei_t * (dt2 - dt1) / length_mid;                  // Mt
  } else {
    // ELFORM 1: section points, eq. (11); shear and torsion elastic resultants.
    const double dkappa_s = (ds2 - ds1) / length_mid, dkappa_t = (dt2 - dt1) / length_mid;
    const std::size_t np = b.section_weight.size();
    double* sigma = &b.stress[np * e];
    double axial = 0.0, ms = 0.0, mt = 0.0;
    for (std::size_t q = 0; q < np; ++q) {
      const double ps = b.section_s[q], pt = b.section_t[q], w = b.section_weight[q];
      const double de = strain_increment - ps * dkappa_t + pt * dkappa_s;
      uniaxial_update(um, de, dt, sigma[q], hp.eps_p ? hp.eps_p + np * e + q : nullptr,
                      hp.back ? hp.back + np * e + q : nullptr);
      axial += w * sigma[q];
      ms += w * sigma[q] * pt;
      mt -= w * sigma[q] * ps;
    }
    r[0] = axial;
    r[1] += 0.5 * k.kga * (dt1 + dt2);  // Qs
    r[2] += 0.5 * k.kga * (ds1 + ds2);  // Qt
    r[3] += k.gj * dtau / length_mid;   // T
    r[4] = ms;
    r[5] = mt;
  }

  // Nodal forces and moments from the power of the resultants (header comment).
  const double axial = r[0], qs = r[1], qt = r[2], torque = r[3], ms = r[4], mt = r[5];
  const double half = 0.5 * length1;
  const double mt1 = qs * half - mt, mt2 = qs * half + mt;
  const double ms1 = qt * half - ms, ms2 = qt * half + ms;
  for (int i = 0; i < 3; ++i) {
    const double f2 = axial * e1[i] - qs * s[i] + qt * t[i];
    f[i] = -f2;
    f[6 + i] = f2;
    f[3 + i] = mt1 * t[i] + ms1 * s[i] - torque * e1[i];
    f[9 + i] = mt2 * t[i] + ms2 * s[i] + torque * e1[i];
  }
  return finite3(f) && finite3(f + 3) && finite3(r) && finite3(r + 3);
}

}  // namespace

void initialize_beam_block(BeamBlock& block, const NodalView& nodes) {
  const std::size_t n = block.size();
  const auto part_error = [&](const std::string& what) {
    return SolverError(
        fmt::format("part {} (beam, ELFORM {}): {}", block.part_id, block.elform, what));
  };
  if (block.conn.size() != 2 * n)
    throw part_error(fmt::format("{} elements but {} connectivity entries (expected 2 each)", n,
                                 block.conn.size()));
  if (block.elform != 1 && block.elform != 2 && block.elform != 3)
    throw part_error("unsupported beam formulation (supported: ELFORM 1, 2, 3)");
  const bool truss = block.elform == 3;
  const int elastic = material::material_index(model::MaterialKind::Elastic);
  const bool plastic =
      block.material_index == material::material_index(model::MaterialKind::PlasticKinematic) ||
      block.material_index ==
          material::material_index(model::MaterialKind::PiecewiseLinearPlasticity);
  if (!block.rigid) {
    if (block.elform == 2 && block.material_index != elastic)
      throw part_error(
          "the resultant beam supports *MAT_ELASTIC only (use ELFORM 1 or 3 for "
          "*MAT_PLASTIC_KINEMATIC and *MAT_PIECEWISE_LINEAR_PLASTICITY)");
    if (block.material_index != elastic && !plastic)
      throw part_error(
          "beams and trusses support *MAT_ELASTIC, *MAT_PLASTIC_KINEMATIC and "
          "*MAT_PIECEWISE_LINEAR_PLASTICITY only");
    if (plastic && (block.plastic.vp == 1 || block.plastic.additive_overstress))
      throw part_error("viscoplastic rate form VP = 1 is not implemented for beams");
  }
  if (block.elform == 1) {
    // Section points and properties, header comment (ELFORM 1).
    const auto mean_dimension = [](double d1, double d2) {
      return d2 > 0.0 ? 0.5 * (d1 + d2) : d1;
    };
    const double ds = mean_dimension(block.ts1, block.ts2),
                 dt = mean_dimension(block.tt1, block.tt2);
    block.section_s.clear();
    block.section_t.clear();
    block.section_weight.clear();
    if (block.cross_section == BeamCrossSection::kRectangular) {
      if (!(ds > 0.0) || !(dt > 0.0))
        throw part_error(fmt::format(
            "rectangular section (CST 0) needs positive TS1 and TT1; got {:.6g}, {:.6g}", block.ts1,
            block.tt1));
      block.area = ds * dt;
      block.iss = ds * dt * dt * dt / 12.0;
      block.itt = dt * ds * ds * ds / 12.0;
      const double a = std::max(ds, dt), b = std::min(ds, dt), r = b / a;
      block.torsion = a * b * b * b * (1.0 / 3.0 - 0.21 * r * (1.0 - r * r * r * r / 12.0));
      const double g = 1.0 / (2.0 * std::sqrt(3.0));
      for (const double gs : {-g, g})
        for (const double gt : {-g, g}) {
          block.section_s.push_back(gs * ds);
          block.section_t.push_back(gt * dt);
          block.section_weight.push_back(0.25 * block.area);
        }
    } else {
      const double outer = 0.5 * ds, inner = 0.5 * dt;
      if (!(outer > 0.0) || inner < 0.0 || !(inner < outer))
        throw part_error(fmt::format(
            "tubular section (CST 1) needs outer diameter TS1 > inner diameter TT1 >= 0; got "
            "{:.6g}, {:.6g}",
            block.ts1, block.tt1));
      const double pi = 3.14159265358979323846;
      block.area = pi * (outer * outer - inner * inner);
      block.iss = block.itt = 0.25 * block.area * (outer * outer + inner * inner);
      block.torsion = 2.0 * block.iss;
      const double rp = std::sqrt(0.5 * (outer * outer + inner * inner));
      for (int q = 0; q < 8; ++q) {
        const double angle = 2.0 * pi * q / 8.0;
        block.section_s.push_back(rp * std::cos(angle));
        block.section_t.push_back(rp * std::sin(angle));
        block.section_weight.push_back(block.area / 8.0);
      }
    }
  }
  if (!(block.area > 0.0))
    throw part_error(fmt::format("cross-section area A = {:.6g} must be positive", block.area));
  if (!truss) {
    if (block.rotation_conn.size() != 2 * n)
      throw part_error(fmt::format("{} elements but {} rotational indices (expected 2 each)", n,
                                   block.rotation_conn.size()));
    for (std::size_t i = 0; i < 2 * n; ++i)
      if (block.rotation_conn[i] < 0)
        throw part_error(fmt::format("element {} has no rotational index at its node {}",
                                     block.element_id[i / 2], i % 2 + 1));
    if (!(block.iss > 0.0) || !(block.itt > 0.0) || !(block.torsion > 0.0))
      throw part_error(
          fmt::format("the beam needs positive ISS, ITT and J (IRR); got {:.6g}, {:.6g}, {:.6g}",
                      block.iss, block.itt, block.torsion));
    if (block.shear_area < 0.0 || block.shear_factor < 0.0)
      throw part_error("shear area SA and shear factor SHRF must not be negative");
  }
  if (!block.orientation.empty() && block.orientation.size() != 3 * n)
    throw part_error(fmt::format("{} elements but {} orientation entries (expected 3 each)", n,
                                 block.orientation.size()));

  const std::size_t points = static_cast<std::size_t>(block.points_per_element()) * n;
  block.frame.assign(9 * n, 0.0);
  block.resultant.assign(6 * n, 0.0);
  block.stress.assign(points, 0.0);
  block.history.clear();
  if (plastic && !block.rigid && points > 0) {
    block.history.push_back({{"effective_plastic_strain", 1, false}, std::vector<double>(points)});
    block.history.push_back({{"uniaxial_back_stress", 1, false}, std::vector<double>(points)});
  }
  block.length0.assign(n, 0.0);
  block.length.assign(n, 0.0);
  block.force.assign(kBeamSlot * n, 0.0);
  for (std::size_t e = 0; e < n; ++e) {
    const std::int32_t n1 = block.conn[2 * e], n2 = block.conn[2 * e + 1];
    const double c[3] = {nodes.x[n2] - nodes.x[n1], nodes.y[n2] - nodes.y[n1],
                         nodes.z[n2] - nodes.z[n1]};
    const double length = norm(c);
    if (!(length > 0.0))
      throw SolverError(
          fmt::format("element {} of part {} (beam) has zero length: its nodes 1 and 2 coincide",
                      block.element_id[e], block.part_id));
    block.length0[e] = block.length[e] = length;
    const double e1[3] = {c[0] / length, c[1] / length, c[2] / length};
    double s[3];
    bool have_s = false;
    if (!block.orientation.empty()) {
      const double* o = &block.orientation[3 * e];
      const double p = o[0] * e1[0] + o[1] * e1[1] + o[2] * e1[2];
      for (int i = 0; i < 3; ++i) s[i] = o[i] - p * e1[i];
      const double sn = norm(s);
      const double on = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
      // An orientation (nearly) parallel to the axis defines no s axis.
      if (sn > 1e-8 * on && on > 0.0) {
        for (int i = 0; i < 3; ++i) s[i] /= sn;
        have_s = true;
      } else if (!truss && on > 0.0) {
        throw SolverError(fmt::format(
            "element {} of part {} (beam): the orientation (third node or vector) is parallel "
            "to the beam axis, so it defines no local s axis",
            block.element_id[e], block.part_id));
      }
    }
    if (!have_s) default_s_axis(e1, s);
    double t[3];
    cross(e1, s, t);
    double* frame = &block.frame[9 * e];
    for (int i = 0; i < 3; ++i) {
      frame[i] = e1[i];
      frame[3 + i] = s[i];
      frame[6 + i] = t[i];
    }
  }
}

namespace {

// Critical step of element e at the current length (no TSSFAC): L / c for a truss, else
// 2 / omega_max of the free element with its lumped masses m and J, eq. (10).
double beam_element_step(const BeamBlock& block, std::size_t e, double length,
                         const SectionStiffness& k) {
  if (block.elform == 3) return length / std::sqrt(block.material.young / block.material.rho);
  const double length0 = block.length0[e];
  const double m = 0.5 * block.material.rho * block.area * length0;
  const double j = node_rotational_inertia(block, length0);
  double w2 = 2.0 * k.ea / (length * m);
  w2 = std::max(w2, 2.0 * k.gj / (length * j));
  for (const double ei : {k.ei_s, k.ei_t}) {
    const double phi = shear_parameter(ei, k.kga, length);
    const double symmetric =
        block.elform == 1 ? 0.5 * k.kga * length : 6.0 * ei / (length * (1.0 + phi));
    w2 = std::max(w2, 2.0 * ei / (length * j));
    w2 = std::max(w2, symmetric * (1.0 / j + 4.0 / (m * length * length)));
  }
  return 2.0 / std::sqrt(w2);
}

}  // namespace

KernelResult compute_beam_forces(BeamBlock& block, const NodalView& nodes,
                                 const RotationalView& rotations, double dt) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  const SectionStiffness k = section_stiffness(block);
  Uniaxial um;
  um.young = block.material.young;
  HistoryPointers hp;
  if (block.history.size() == 2) {
    um.plastic = &block.plastic;
    hp.eps_p = block.history[0].values.data();
    hp.back = block.history[1].values.data();
  }
  int threads = 1;
#pragma omp parallel num_threads(thread_count())
  {
    Partial local;
    const std::int64_t items = block.owned.count(n);  // one process: every element
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < items; ++i) {
      const std::int64_t e = block.owned.element(i);
      const std::size_t ue = static_cast<std::size_t>(e);
      if (!beam_element(block, ue, nodes, rotations, dt, k, um, hp)) {
        local.record_failure(e, block.length[ue]);
        continue;
      }
      // The step at the new length (beam_element stored it), as the other families report it.
      local.record_dt(
          scaled_step(block.step_scale, e, beam_element_step(block, ue, block.length[ue], k)), e);
    }
    partials[omp_get_thread_num()] = local;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine(partials, threads);
}

KernelResult beam_critical_timestep(const BeamBlock& block, const NodalView& nodes,
                                    std::vector<double>* raw_steps) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  if (raw_steps) raw_steps->assign(block.size(), 0.0);
  const SectionStiffness k = section_stiffness(block);
  int threads = 1;
#pragma omp parallel num_threads(thread_count())
  {
    Partial local;
#pragma omp for schedule(static)
    for (std::int64_t e = 0; e < n; ++e) {
      const std::size_t ue = static_cast<std::size_t>(e);
      if (block.erosion.is_eroded(ue)) continue;  // left the model
      const std::int32_t n1 = block.conn[2 * ue], n2 = block.conn[2 * ue + 1];
      const double ch[3] = {nodes.x[n2] - nodes.x[n1], nodes.y[n2] - nodes.y[n1],
                            nodes.z[n2] - nodes.z[n1]};
      const double length = norm(ch);
      if (!(length > 0.0) || !std::isfinite(length)) {
        local.record_failure(e, length);
        continue;
      }
      const double step = beam_element_step(block, ue, length, k);
      if (raw_steps) (*raw_steps)[ue] = step;
      local.record_dt(scaled_step(block.step_scale, e, step), e);
    }
    partials[omp_get_thread_num()] = local;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine(partials, threads);
}

void add_beam_lumped_mass(const BeamBlock& block, std::vector<double>& nodal_mass,
                          std::vector<double>& rotational_inertia,
                          const std::vector<double>* element_factor) {
  const bool truss = block.elform == 3;
  for (std::size_t e = 0; e < block.size(); ++e) {
    const double factor = element_factor ? (*element_factor)[e] : 1.0;
    const double share = factor * 0.5 * block.material.rho * block.area * block.length0[e];
    nodal_mass[static_cast<std::size_t>(block.conn[2 * e])] += share;
    nodal_mass[static_cast<std::size_t>(block.conn[2 * e + 1])] += share;
    if (truss) continue;
    const double j = factor * node_rotational_inertia(block, block.length0[e]);
    for (int a = 0; a < 2; ++a) {
      const std::int32_t r = block.rotation_conn[2 * e + a];
      if (r >= 0) rotational_inertia[static_cast<std::size_t>(r)] += j;
    }
  }
}

}  // namespace rf::element
