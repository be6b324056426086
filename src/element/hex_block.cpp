// 8-node hexahedron kernels for the explicit central-difference solver (updated Lagrangian).
//
// Step structure. The solver hands us x^{n+1} and v^{n+1/2}. Rates (strain rate D, spin W) are
// evaluated on the mid-step configuration x^{n+1/2} = x^{n+1} - dt/2 v^{n+1/2}: with the
// Hughes-Winget rotation this makes the update exactly objective (a rigid rotation gives D = 0
// and rotates the stress by exactly the incremental rotation), and it is second-order accurate
// in time. Internal forces f_int = integral B^T sigma dV use the geometry at n+1, where the
// stress now lives.
//
// ELFORM 1: one point, uniform-strain operator of Flanagan & Belytschko (1981) (see
// hex_geometry.hpp), plus hourglass control:
//   IHQ 1   LS-DYNA standard viscous form, base vectors Gamma (not orthogonalised). Cheapest; like
//           LS-DYNA it is NOT orthogonal to linear velocity fields on non-parallelepiped elements,
//           so it does not pass the patch test on distorted meshes.
//   IHQ 2,3 Flanagan-Belytschko viscous form with gamma_a = Gamma_a - (Gamma_a . x_i) b_i
//           (FB 1981, eq. 37), orthogonal to every linear field. LS-DYNA's IHQ 3 differs from 2
//           by using the exact-volume B in gamma; our B is always the exact one, so 2 == 3.
//   Viscous coefficient (LS-DYNA theory manual, hourglass section):
//           Q_ia = C qdot_ia,  C = QM rho c V^{2/3} / 4,  qdot_ia = sum_I v_iI gamma_aI,
//           f_iI += sum_a Q_ia gamma_aI   (rho current density rho0 V0 / V, c P-wave speed).
//   IHQ 4,5 Flanagan-Belytschko stiffness form, incremental: Q_ia += K qdot_ia dt with
//           K = QM (lambda + 2 mu) (B_jI B_jI) / (8 V)  (B = dV/dx; FB 1981 scale
//           (lambda+2mu) b.b V; our normalisation makes QM = 1/9 reproduce the exact bending
//           stiffness of a cube). Stored Q (hourglass_state, global frame) is rotated with the
//           element spin each step (Hughes-Winget) so rigid rotation leaves it objective.
//           IHQ 5 == IHQ 4 for the same reason as 3 == 2.
//   IHQ 6   Belytschko & Bindeman (1993, CMAME 105:225) assumed-strain co-rotational stiffness.
//           Corotational axes e_j from the element's A-vectors (e1 along A1, e2 = A2 made
//           orthogonal to e1, e3 = e1 x e2), half-lengths a_j = |A_j| / 8. Hourglass velocities
//           and the accumulated generalised forces live in that frame (objective). Diagonal
//           stiffness derived for the rectangular element from the assumed strain field
//           (parasitic shear removed, Poisson-locking-free bending -> uniaxial E):
//             bilinear mode in directions k,l (missing m), velocity along k:  E V / (192 a_k^2)
//             same mode, velocity along the missing direction m (twist):  mu V (1/a_k^2 +
//             1/a_l^2)/192 trilinear mode xi.eta.zeta, velocity along j: V (E/a_j^2 + mu sum_{n!=j}
//             1/a_n^2)/576
//           times QM. With QM = 1 a rectangular element in pure bending stores exactly
//           E I kappa^2 L / 2 (the exact beam energy, any nu). The coupling terms between modes
//           of B-B's full ASQBI matrix are not included (may be stiff in plate twisting).
//   Hourglass work: viscous sum Q.qdot dt; stiffness forms 0.5 (Q_old + Q_new) . qdot dt.
//
// ELFORM 2: selective-reduced. 2x2x2 Gauss points for the deviatoric part; the volumetric
// strain rate is replaced at each point by the element's mean dilatation (1/V dV/dt from the
// exact uniform B: B-bar, Hughes 1980), and the pressure enters the forces through the same
// uniform B: f_iI = sum_g detJ_g s_g,ij dN_I/dx_j + (sum_g detJ_g p_g) B_iI / V. No hourglass.
//
// Degenerate elements (LS-DYNA conventions, see hex_block.hpp). Wedges and pyramids are valid
// collapsed trilinear maps and need nothing special. The LS-DYNA tetrahedron pattern
// n1 n2 n3 n4 n4 n4 n4 n4 is NOT: the bilinear "face" n1 n2 n3 n4 is a saddle and the trilinear
// volume is half the tetrahedron's. We evaluate it as the collapsed hexahedron
// n1 n2 n3 n3 n4 n4 n4 n4 (planar triangle base, apex n4), which reproduces the linear tetrahedron
// exactly; forces of the remapped slots are summed back into the slots of block.conn (slots 5-8
// get zero). Lumped mass: rho V0 / (number of distinct nodes) to each distinct node.
// Time step: dt_e = L_e / c with L_e = V / A_max (LS-DYNA's solid rule); collapsed faces have zero
// or triangle area automatically; tetrahedra use the smallest altitude 3 V / A_max.
#include "element/hex_block.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <array>
#include <cmath>

#include "element/hex_geometry.hpp"
#include "material/elastic_update.hpp"
#include "model/error.hpp"

namespace rf::element {
namespace {

constexpr int kIdentitySlots[8] = {0, 1, 2, 3, 4, 5, 6, 7};
constexpr int kTetSlots[8] = {0, 1, 2, 2, 3, 3, 3, 3};

inline const int* slot_map(const HexBlock& block, std::size_t e) {
  if (block.shape[e] == HexShape::kTetrahedron) {
    const std::int32_t* c = &block.conn[8 * e];
    if (c[2] != c[3] && c[3] == c[4]) return kTetSlots;
  }
  return kIdentitySlots;
}

inline void gather_coordinates(const std::int32_t* c, const int* slots, const NodalView& nv,
                               double x[3][8]) {
  for (int k = 0; k < 8; ++k) {
    const std::int32_t n = c[slots[k]];
    x[0][k] = nv.x[n];
    x[1][k] = nv.y[n];
    x[2][k] = nv.z[n];
  }
}

inline void gather_velocities(const std::int32_t* c, const int* slots, const NodalView& nv,
                              double v[3][8]) {
  for (int k = 0; k < 8; ++k) {
    const std::int32_t n = c[slots[k]];
    v[0][k] = nv.vx[n];
    v[1][k] = nv.vy[n];
    v[2][k] = nv.vz[n];
  }
}

inline void scatter_forces(const int* slots, const double f[3][8], double* out) {
  if (slots == kIdentitySlots) {
    for (int k = 0; k < 8; ++k) {
      out[3 * k + 0] = f[0][k];
      out[3 * k + 1] = f[1][k];
      out[3 * k + 2] = f[2][k];
    }
    return;
  }
  for (int s = 0; s < 24; ++s) out[s] = 0.0;
  for (int k = 0; k < 8; ++k)
    for (int i = 0; i < 3; ++i) out[3 * slots[k] + i] += f[i][k];
}

inline double element_time_step(const double x[3][8], double volume, HexShape shape,
                                double wave_speed) {
  const double amax2 = hex::max_face_area_squared(x);
  double length = volume / std::sqrt(amax2);
  if (shape == HexShape::kTetrahedron) length *= 3.0;  // smallest altitude
  return length / wave_speed;
}

// Rotates a vector by the Cayley transform of the spin (same Q as the stress update).
inline void rotate_vector(const double w[3], double dt, double u[3]) {
  const double p[3] = {0.5 * dt * w[0], 0.5 * dt * w[1], 0.5 * dt * w[2]};
  const double k = 2.0 / (1.0 + hex::dot(p, p));
  double pu[3], ppu[3];
  hex::cross(p, u, pu);
  hex::cross(p, pu, ppu);
  for (int i = 0; i < 3; ++i) u[i] += k * (pu[i] + ppu[i]);
}

struct alignas(64) Partial {
  double hourglass_work = 0.0;
  double min_dt = 1e300;
  std::int64_t min_dt_element = -1;
  std::int64_t failed_element = -1;
  double failed_volume = 0.0;

  void record_dt(double dt, std::int64_t e) {
    if (dt < min_dt) {
      min_dt = dt;
      min_dt_element = e;
    }
  }
  void record_failure(std::int64_t e, double volume) {
    if (failed_element < 0) {
      failed_element = e;
      failed_volume = volume;
    }
  }
};

constexpr int kMaxThreads = 256;

// Combines per-thread partials in thread order: with a static schedule thread t owns a
// contiguous, increasing range of elements, so the result is deterministic for a fixed thread
// count and "first" means "lowest element index".
KernelResult combine(const std::array<Partial, kMaxThreads>& partials, int threads) {
  KernelResult r;
  for (int t = 0; t < threads; ++t) {
    const Partial& p = partials[t];
    r.hourglass_work += p.hourglass_work;
    if (p.min_dt < r.min_dt) {
      r.min_dt = p.min_dt;
      r.min_dt_element = p.min_dt_element;
    }
    if (!r.failed && p.failed_element >= 0) {
      r.failed = true;
      r.failed_element = p.failed_element;
      r.failed_volume = p.failed_volume;
    }
  }
  return r;
}

inline int thread_count() {
  const int n = omp_get_max_threads();
  return n < kMaxThreads ? n : kMaxThreads;
}

// --- ELFORM 1 -----------------------------------------------------------------------------

inline void hourglass_forces(const HexBlock& block, const hex::Geometry& g, const double v[3][8],
                             const double w[3], double dt, double density, double* hg_state,
                             double f[3][8], double& work) {
  const int ihq = block.hourglass.ihq;
  const double qm = block.hourglass.qm;
  const material::ElasticConstants& m = block.material;
  const double volume = g.volume;

  double gam[4][8];
  if (ihq == 1) {
    for (int a = 0; a < 4; ++a)
      for (int n = 0; n < 8; ++n) gam[a][n] = hex::kHourglassBase[a][n];
  } else {
    // gamma_a = Gamma_a - (Gamma_a . x_i) b_i; Gamma_a . x_i is the A-vector of that mode.
    const double inv_v = 1.0 / volume;
    for (int a = 0; a < 4; ++a) {
      const double* hx = g.a[4 + a];
      for (int n = 0; n < 8; ++n)
        gam[a][n] = hex::kHourglassBase[a][n] -
                    inv_v * (hx[0] * g.b[0][n] + hx[1] * g.b[1][n] + hx[2] * g.b[2][n]);
    }
  }
  double qdot[4][3];  // hourglass velocities, mode-major
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) {
      double s = 0.0;
      for (int n = 0; n < 8; ++n) s += v[i][n] * gam[a][n];
      qdot[a][i] = s;
    }

  double Q[4][3];  // generalised hourglass forces, global frame
  if (ihq <= 3) {
    const double v23 = std::cbrt(volume * volume);
    const double c = qm * density * m.wave_speed * v23 * 0.25;
    double wsum = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        Q[a][i] = c * qdot[a][i];
        wsum += Q[a][i] * qdot[a][i];
      }
    work += wsum * dt;
  } else if (ihq <= 5) {
    double bb = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int n = 0; n < 8; ++n) bb += g.b[i][n] * g.b[i][n];
    const double k = qm * (m.lambda + 2.0 * m.shear) * bb / (8.0 * volume);
    double wsum = 0.0;
    for (int a = 0; a < 4; ++a) {
      double* q = hg_state + 3 * a;
      rotate_vector(w, dt, q);
      for (int i = 0; i < 3; ++i) {
        const double old = q[i];
        q[i] = old + k * qdot[a][i] * dt;
        Q[a][i] = q[i];
        wsum += 0.5 * (old + q[i]) * qdot[a][i];
      }
    }
    work += wsum * dt;
  } else {
    // Corotational frame.
    double e[3][3];
    double h[3];
    for (int j = 0; j < 3; ++j) h[j] = 0.125 * std::sqrt(hex::dot(g.a[1 + j], g.a[1 + j]));
    const double n1 = 1.0 / (8.0 * h[0]);
    for (int i = 0; i < 3; ++i) e[0][i] = g.a[1][i] * n1;
    const double p = hex::dot(g.a[2], e[0]);
    for (int i = 0; i < 3; ++i) e[1][i] = g.a[2][i] - p * e[0][i];
    const double n2 = 1.0 / std::sqrt(hex::dot(e[1], e[1]));
    for (int i = 0; i < 3; ++i) e[1][i] *= n2;
    hex::cross(e[0], e[1], e[2]);

    const double E = m.young, mu = m.shear;
    const double inv2[3] = {1.0 / (h[0] * h[0]), 1.0 / (h[1] * h[1]), 1.0 / (h[2] * h[2])};
    const double bend = qm * volume / 192.0;
    double K[4][3];
    for (int a = 0; a < 3; ++a)
      for (int j = 0; j < 3; ++j)
        K[a][j] = j != a ? bend * E * inv2[j] : bend * mu * (inv2[0] + inv2[1] + inv2[2] - inv2[a]);
    const double tri = qm * volume / 576.0;
    for (int j = 0; j < 3; ++j)
      K[3][j] = tri * (E * inv2[j] + mu * (inv2[0] + inv2[1] + inv2[2] - inv2[j]));

    double wsum = 0.0;
    for (int a = 0; a < 4; ++a) {
      double* q = hg_state + 3 * a;
      double ql[3];
      for (int j = 0; j < 3; ++j) {
        const double qd = hex::dot(e[j], qdot[a]);
        const double old = q[j];
        q[j] = old + K[a][j] * qd * dt;
        wsum += 0.5 * (old + q[j]) * qd;
        ql[j] = q[j];
      }
      for (int i = 0; i < 3; ++i) Q[a][i] = e[0][i] * ql[0] + e[1][i] * ql[1] + e[2][i] * ql[2];
    }
    work += wsum * dt;
  }
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n)
      f[i][n] +=
          Q[0][i] * gam[0][n] + Q[1][i] * gam[1][n] + Q[2][i] * gam[2][n] + Q[3][i] * gam[3][n];
}

inline bool finite_forces(const double f[3][8]) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) s += f[i][n];
  return std::isfinite(s);
}

void elform1_element(HexBlock& block, std::size_t e, const NodalView& nv, double dt,
                     Partial& part) {
  const int* slots = slot_map(block, e);
  const std::int32_t* c = &block.conn[8 * e];
  double x[3][8], v[3][8], f[3][8];
  gather_coordinates(c, slots, nv, x);
  gather_velocities(c, slots, nv, v);

  // Rates on the mid-step configuration.
  double xm[3][8];
  const double half_dt = 0.5 * dt;
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) xm[i][n] = x[i][n] - half_dt * v[i][n];
  hex::Geometry gm;
  hex::compute_geometry(xm, gm);

  hex::Geometry g;
  hex::compute_geometry(x, g);
  block.volume[e] = g.volume;
  double* out = &block.force[24 * e];
  if (!(gm.volume > 0.0) || !(g.volume > 0.0)) {
    part.record_failure(static_cast<std::int64_t>(e), g.volume > 0.0 ? gm.volume : g.volume);
    for (int s = 0; s < 24; ++s) out[s] = 0.0;
    return;
  }

  double L[9];
  const double inv_vm = 1.0 / gm.volume;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int n = 0; n < 8; ++n) s += v[i][n] * gm.b[j][n];
      L[3 * i + j] = s * inv_vm;
    }
  double d[6], w[3];
  material::split_velocity_gradient(L, d, w);
  double* sig = &block.stress[6 * e];
  material::elastic_jaumann_update(block.material, d, w, dt, sig);

  // f_iI = sigma_ij dV/dx_jI  (= V sigma_ij b_jI).
  const double sxx = sig[0], syy = sig[1], szz = sig[2], sxy = sig[3], syz = sig[4], szx = sig[5];
  for (int n = 0; n < 8; ++n) {
    const double bx = g.b[0][n], by = g.b[1][n], bz = g.b[2][n];
    f[0][n] = sxx * bx + sxy * by + szx * bz;
    f[1][n] = sxy * bx + syy * by + syz * bz;
    f[2][n] = szx * bx + syz * by + szz * bz;
  }

  double work = 0.0;
  // The viscous coefficient uses the current density rho0 V0 / V (mass conservation).
  const double density = block.material.rho * block.volume0[e] / g.volume;
  hourglass_forces(block, g, v, w, dt, density, &block.hourglass_state[12 * e], f, work);
  part.hourglass_work += work;

  if (!finite_forces(f)) part.record_failure(static_cast<std::int64_t>(e), g.volume);
  scatter_forces(slots, f, out);
  part.record_dt(element_time_step(x, g.volume, block.shape[e], block.material.wave_speed),
                 static_cast<std::int64_t>(e));
}

// --- ELFORM 2 -----------------------------------------------------------------------------

void elform2_element(HexBlock& block, std::size_t e, const NodalView& nv, double dt,
                     Partial& part) {
  const int* slots = slot_map(block, e);
  const std::int32_t* c = &block.conn[8 * e];
  double x[3][8], v[3][8], f[3][8];
  gather_coordinates(c, slots, nv, x);
  gather_velocities(c, slots, nv, v);

  double xm[3][8];
  const double half_dt = 0.5 * dt;
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) xm[i][n] = x[i][n] - half_dt * v[i][n];
  hex::Geometry gm;
  hex::compute_geometry(xm, gm);
  hex::Geometry g;
  hex::compute_geometry(x, g);
  block.volume[e] = g.volume;
  double* out = &block.force[24 * e];
  if (!(gm.volume > 0.0) || !(g.volume > 0.0)) {
    part.record_failure(static_cast<std::int64_t>(e), g.volume > 0.0 ? gm.volume : g.volume);
    for (int s = 0; s < 24; ++s) out[s] = 0.0;
    return;
  }

  // Mean dilatation (1/V) dV/dt on the mid-step configuration.
  double div_bar = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) div_bar += v[i][n] * gm.b[i][n];
  div_bar /= gm.volume;

  double* stress = &block.stress[48 * e];
  double dndx[3][8];
  bool inverted = false;
  for (int gp = 0; gp < 8; ++gp) {
    const double det = hex::gauss_gradients(gm.a, gp, dndx);
    inverted |= !(det > 0.0);
    double L[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double s = 0.0;
        for (int n = 0; n < 8; ++n) s += v[i][n] * dndx[j][n];
        L[3 * i + j] = s;
      }
    const double corr = (div_bar - (L[0] + L[4] + L[8])) / 3.0;
    L[0] += corr;
    L[4] += corr;
    L[8] += corr;
    double d[6], w[3];
    material::split_velocity_gradient(L, d, w);
    material::elastic_jaumann_update(block.material, d, w, dt, stress + 6 * gp);
  }

  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) f[i][n] = 0.0;
  double pressure_volume = 0.0;  // sum_g detJ_g p_g
  for (int gp = 0; gp < 8; ++gp) {
    const double det = hex::gauss_gradients(g.a, gp, dndx);
    inverted |= !(det > 0.0);
    const double* s = stress + 6 * gp;
    const double p = (s[0] + s[1] + s[2]) / 3.0;
    pressure_volume += det * p;
    const double dxx = det * (s[0] - p), dyy = det * (s[1] - p), dzz = det * (s[2] - p);
    const double dxy = det * s[3], dyz = det * s[4], dzx = det * s[5];
    for (int n = 0; n < 8; ++n) {
      const double bx = dndx[0][n], by = dndx[1][n], bz = dndx[2][n];
      f[0][n] += dxx * bx + dxy * by + dzx * bz;
      f[1][n] += dxy * bx + dyy * by + dyz * bz;
      f[2][n] += dzx * bx + dyz * by + dzz * bz;
    }
  }
  const double pbar = pressure_volume / g.volume;
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) f[i][n] += pbar * g.b[i][n];

  if (inverted || !finite_forces(f)) part.record_failure(static_cast<std::int64_t>(e), g.volume);
  scatter_forces(slots, f, out);
  part.record_dt(element_time_step(x, g.volume, block.shape[e], block.material.wave_speed),
                 static_cast<std::int64_t>(e));
}

HexShape detect_shape(const std::int32_t* c) {
  const int distinct = distinct_node_count(c);
  if (distinct == 8) return HexShape::kHexahedron;
  if (distinct == 6 && c[4] == c[5] && c[6] == c[7]) return HexShape::kWedge;
  if (distinct == 5 && c[4] == c[5] && c[5] == c[6] && c[6] == c[7]) return HexShape::kPyramid;
  if (distinct == 4) return HexShape::kTetrahedron;
  return HexShape::kOtherDegenerate;
}

}  // namespace

int distinct_node_count(const std::int32_t* c) {
  int count = 0;
  for (int k = 0; k < 8; ++k) {
    bool seen = false;
    for (int j = 0; j < k; ++j) seen |= c[j] == c[k];
    count += seen ? 0 : 1;
  }
  return count;
}

void initialize_hex_block(HexBlock& block, const NodalView& nodes) {
  const std::size_t n = block.size();
  if (block.conn.size() != 8 * n)
    throw SolverError(
        fmt::format("part {}: hexahedron block has {} elements but {} connectivity "
                    "entries (expected 8 per element)",
                    block.part_id, n, block.conn.size()));
  block.stress.assign(6 * static_cast<std::size_t>(block.points_per_element()) * n, 0.0);
  block.hourglass_state.assign(12 * n, 0.0);
  block.force.assign(24 * n, 0.0);
  block.volume0.assign(n, 0.0);
  block.volume.assign(n, 0.0);
  block.shape.assign(n, HexShape::kHexahedron);
  for (std::size_t e = 0; e < n; ++e) {
    block.shape[e] = detect_shape(&block.conn[8 * e]);
    double x[3][8];
    gather_coordinates(&block.conn[8 * e], slot_map(block, e), nodes, x);
    const double v = hex::hex_volume(x);
    if (!(v > 0.0))
      throw SolverError(fmt::format(
          "element {} of part {} has non-positive volume {:.6g}: check that nodes 1-4 run "
          "counter-clockwise seen from nodes 5-8 (for degenerate elements use the LS-DYNA "
          "patterns n1 n2 n3 n4 n4 n4 n4 n4, n1..n5 n5 n5 n5, n1 n2 n3 n4 n5 n5 n6 n6)",
          block.element_id[e], block.part_id, v));
    block.volume0[e] = v;
    block.volume[e] = v;
  }
}

KernelResult compute_hex_forces(HexBlock& block, const NodalView& nodes, double dt) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  int threads = 1;
  const bool elform2 = block.elform == 2;
#pragma omp parallel num_threads(thread_count())
  {
    Partial local;
#pragma omp for schedule(static)
    for (std::int64_t e = 0; e < n; ++e) {
      if (elform2)
        elform2_element(block, static_cast<std::size_t>(e), nodes, dt, local);
      else
        elform1_element(block, static_cast<std::size_t>(e), nodes, dt, local);
    }
    partials[omp_get_thread_num()] = local;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine(partials, threads);
}

KernelResult hex_critical_timestep(const HexBlock& block, const NodalView& nodes) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  int threads = 1;
#pragma omp parallel num_threads(thread_count())
  {
    Partial local;
#pragma omp for schedule(static)
    for (std::int64_t e = 0; e < n; ++e) {
      double x[3][8];
      const std::size_t ue = static_cast<std::size_t>(e);
      gather_coordinates(&block.conn[8 * ue], slot_map(block, ue), nodes, x);
      const double v = hex::hex_volume(x);
      if (!(v > 0.0)) {
        local.record_failure(e, v);
        continue;
      }
      local.record_dt(element_time_step(x, v, block.shape[ue], block.material.wave_speed), e);
    }
    partials[omp_get_thread_num()] = local;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine(partials, threads);
}

void add_hex_lumped_mass(const HexBlock& block, std::vector<double>& nodal_mass) {
  for (std::size_t e = 0; e < block.size(); ++e) {
    const std::int32_t* c = &block.conn[8 * e];
    const int distinct = distinct_node_count(c);
    const double share = block.material.rho * block.volume0[e] / distinct;
    for (int k = 0; k < 8; ++k) {
      bool seen = false;
      for (int j = 0; j < k; ++j) seen |= c[j] == c[k];
      if (!seen) nodal_mass[static_cast<std::size_t>(c[k])] += share;
    }
  }
}

}  // namespace rf::element
