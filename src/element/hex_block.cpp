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
#include "element/kernel_partials.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "element/hex_geometry.hpp"
#include "element/solid_terms.hpp"
#include "element/tet13_block.hpp"
#include "material/elastic_update.hpp"
#include "material/registry.hpp"
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

// Characteristic length L_e = V / A_max (tetrahedra: the smallest altitude 3 V / A_max).
inline double element_length(const double x[3][8], double volume, HexShape shape) {
  const double amax2 = hex::max_face_area_squared(x);
  double length = volume / std::sqrt(amax2);
  if (shape == HexShape::kTetrahedron) length *= 3.0;  // smallest altitude
  return length;
}

inline double element_time_step(const double x[3][8], double volume, HexShape shape,
                                double wave_speed) {
  return element_length(x, volume, shape) / wave_speed;
}

using Partial = KernelPartial;
constexpr int kMaxThreads = kMaxKernelThreads;

KernelResult combine(const KernelPartials& partials, int threads) {
  return combine_partials(partials, threads);
}

inline int thread_count() {
  return kernel_thread_count();
}

// --- ELFORM 1 -----------------------------------------------------------------------------
//
// Batched evaluation. kLanes consecutive elements are processed together, each quantity held in
// a GCC vector with one element per lane, so that every arithmetic statement below is one SIMD
// instruction across elements (an element's own 3-vectors are too short to vectorise). The lane
// width follows the instruction set the file is compiled for; the generic x86-64 build uses SSE2.
//
// Everything is expressed through the base vectors A_k of hex_geometry.hpp instead of nodal
// B-matrices. With b_jI = dV/dx_jI = sum_k G_kj s_k(I) (G_k = dV/dA_k) and the monomials s_k
// orthogonal over the nodes (sum_I s_k(I) s_l(I) = 8 delta_kl):
//   velocity gradient  V L_ij = sum_I v_iI b_jI = sum_k Av_ki G_kj        (Av_k = A_k of v)
//   nodal forces       f_iI = sum_j P_ij b_jI = sum_k (P G_k)_i s_k(I)    (P = sigma - T below)
//   FB hourglass       qdot_ai = sum_I v_iI gamma_aI = Av_(4+a)i - L_ij A_(4+a)j
//                      sum_a Q_ai gamma_aI = sum_a Q_ai s_(4+a)(I) - T_ij b_jI,
//                      T_ij = (1/V) sum_a Q_ai A_(4+a)j
//   |b|^2              sum_jI b_jI^2 = 8 sum_k |G_k|^2
// so the element never forms its 3 x 8 B arrays: the rate costs 54 multiply-adds on the mid-step
// G and the forces 54 on the end-of-step G, plus one butterfly (expand_nodal) back to the nodes.
// The mid-step base vectors are A_k(x) - dt/2 A_k(v) (base_vectors is linear). The formulation
// (mid-step rate, end-of-step forces) is unchanged; only round-off differs from the per-node form.

#if defined(__AVX512F__)
constexpr int kLanes = 8;
#elif defined(__AVX__)
constexpr int kLanes = 4;
#else
constexpr int kLanes = 2;
#endif
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

inline Lanes lane_sqrt(Lanes a) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(a[l]);
  return r;
}

// Element indices, slot maps and gathered nodal data of one batch. Lanes past `count` (the tail
// of the block) repeat the last element; their results are discarded.
struct Batch {
  std::size_t first = 0;
  int count = 0;
  const int* slots[kLanes];
  Lanes x[3][8];  // x^{n+1}
  Lanes v[3][8];  // v^{n+1/2}
  std::size_t element(int l) const {
    return first + static_cast<std::size_t>(l < count ? l : count - 1);
  }
};

// Builds a vector from one value per lane: p[idx[l]]. The brace initialiser lets the compiler
// assemble the lanes in registers (element-wise stores followed by a vector load would stall
// store forwarding).
template <class Index, std::size_t... L>
inline Lanes load_lanes(const double* p, const Index* idx, std::index_sequence<L...>) {
  return Lanes{p[idx[L]]...};
}
template <class Index>
inline Lanes load_lanes(const double* p, const Index* idx) {
  return load_lanes(p, idx, std::make_index_sequence<kLanes>{});
}

inline void gather_batch(const HexBlock& block, const NodalView& nv, Batch& b) {
  std::int32_t node[8][kLanes];
  for (int l = 0; l < kLanes; ++l) {
    const std::size_t e = b.element(l);
    const int* slots = slot_map(block, e);
    b.slots[l] = slots;
    const std::int32_t* c = &block.conn[8 * e];
    for (int k = 0; k < 8; ++k) node[k][l] = c[slots[k]];
  }
  for (int k = 0; k < 8; ++k) {
    b.x[0][k] = load_lanes(nv.x, node[k]);
    b.x[1][k] = load_lanes(nv.y, node[k]);
    b.x[2][k] = load_lanes(nv.z, node[k]);
    b.v[0][k] = load_lanes(nv.vx, node[k]);
    b.v[1][k] = load_lanes(nv.vy, node[k]);
    b.v[2][k] = load_lanes(nv.vz, node[k]);
  }
}

// Per-lane offsets into an element array with `stride` values per element.
inline void lane_offsets(const Batch& b, std::size_t stride, std::size_t off[kLanes]) {
  for (int l = 0; l < kLanes; ++l) off[l] = stride * b.element(l);
}

// Inputs of the hourglass forms and their results, all per lane.
struct HourglassTerms {
  const Lanes (*ax)[3];  // base vectors of x^{n+1}
  const Lanes (*av)[3];  // base vectors of v^{n+1/2}
  const Lanes (*g)[3];   // G_k = dV/dA_k at n+1
  Lanes volume;          // V^{n+1}
  Lanes w[3];            // mid-step spin
  Lanes q[4][3];         // OUT: generalised hourglass forces Q_a, global frame
  Lanes work;            // OUT: hourglass work this step
};

// Hourglass velocities qdot_a (mode-major). IHQ 1 projects on the plain Gamma_a; the other forms
// on gamma_a, which removes the linear part through the end-of-step velocity gradient.
template <bool kOrthogonal>
inline void hourglass_velocities(const HourglassTerms& h, Lanes qdot[4][3]) {
  if constexpr (!kOrthogonal) {
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) qdot[a][i] = h.av[4 + a][i];
  } else {
    const Lanes inv_v = 1.0 / h.volume;
    Lanes L[3][3];  // end-of-step velocity gradient
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Lanes s = h.av[1][i] * h.g[1][j];
        for (int k = 2; k <= 6; ++k) s += h.av[k][i] * h.g[k][j];
        L[i][j] = s * inv_v;
      }
    for (int a = 0; a < 4; ++a) {
      const Lanes* hx = h.ax[4 + a];
      for (int i = 0; i < 3; ++i)
        qdot[a][i] = h.av[4 + a][i] - (L[i][0] * hx[0] + L[i][1] * hx[1] + L[i][2] * hx[2]);
    }
  }
}

// Cube root of the volume ratio J = V / V0 without a libm call per element (std::cbrt was ~10%
// of a cycle). Start from the Taylor polynomial 1 + u/3 - u^2/9 (u = J - 1, error < 3% for
// J in [1/2, 2]) and take three Halley steps y <- y (y^3 + 2J) / (2 y^3 + J), each of which cubes
// the relative error: 3e-2 -> 1e-5 -> 1e-15 -> round-off. Lanes outside [1/2, 2] (strongly
// compressed or expanded elements) fall back to std::cbrt.
inline Lanes volume_ratio_cbrt(Lanes j) {
  const Lanes u = j - 1.0;
  Lanes y = 1.0 + u * (1.0 / 3.0) - u * u * (1.0 / 9.0);
  for (int it = 0; it < 3; ++it) {
    const Lanes y3 = y * y * y;
    y = y * (y3 + 2.0 * j) / (2.0 * y3 + j);
  }
  for (int l = 0; l < kLanes; ++l)
    if (!(j[l] >= 0.5 && j[l] <= 2.0)) y[l] = std::cbrt(j[l]);
  return y;
}

// IHQ 1-3: viscous, Q = C qdot with C = QM rho c V^{2/3} / 4 and rho = rho0 V0 / V;
// V^{2/3} = r^2 with r = V^{1/3} = V0^{1/3} J^{1/3} (element_length below).
template <bool kOrthogonal>
void viscous_hourglass(const HexBlock& block, double dt, Lanes r, Lanes density,
                       HourglassTerms& h) {
  Lanes qdot[4][3];
  hourglass_velocities<kOrthogonal>(h, qdot);
  const Lanes c = block.hourglass.qm * density * block.material.wave_speed * (r * r) * 0.25;
  Lanes wsum{};
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) {
      h.q[a][i] = c * qdot[a][i];
      wsum += h.q[a][i] * qdot[a][i];
    }
  h.work = wsum * dt;
}

// IHQ 4,5: incremental stiffness, Q += K qdot dt with K = QM (lambda + 2 mu) b.b / (8 V), the
// stored Q first rotated with the element spin. `state` holds the lanes' 12 values each.
void stiffness_hourglass(const HexBlock& block, double dt, Lanes state[4][3], HourglassTerms& h) {
  Lanes qdot[4][3];
  hourglass_velocities<true>(h, qdot);
  Lanes gg{};
  for (int k = 1; k <= 6; ++k) gg += hex::dot(h.g[k], h.g[k]);
  const material::ElasticConstants& m = block.material;
  // b.b / 8 = sum_k |G_k|^2.
  const Lanes stiff = block.hourglass.qm * (m.lambda + 2.0 * m.shear) * gg / h.volume;
  // Cayley rotation of the stored forces, as rotate_vector.
  Lanes p[3];
  for (int i = 0; i < 3; ++i) p[i] = 0.5 * dt * h.w[i];
  const Lanes kr = 2.0 / (1.0 + hex::dot(p, p));
  Lanes wsum{};
  for (int a = 0; a < 4; ++a) {
    Lanes* q = state[a];
    Lanes pu[3], ppu[3];
    hex::cross(p, q, pu);
    hex::cross(p, pu, ppu);
    for (int i = 0; i < 3; ++i) q[i] += kr * (pu[i] + ppu[i]);
    for (int i = 0; i < 3; ++i) {
      const Lanes old = q[i];
      q[i] = old + stiff * qdot[a][i] * dt;
      h.q[a][i] = q[i];
      wsum += 0.5 * (old + q[i]) * qdot[a][i];
    }
  }
  h.work = wsum * dt;
}

// IHQ 6: Belytschko-Bindeman co-rotational stiffness (see the header comment). `state` holds the
// generalised forces in the corotational frame.
void corotational_hourglass(const HexBlock& block, double dt, Lanes state[4][3],
                            HourglassTerms& h) {
  Lanes qdot[4][3];
  hourglass_velocities<true>(h, qdot);
  const Lanes(*a)[3] = h.ax;
  // Axes: e1 along A1, e2 = A2 orthogonalised, e3 = e1 x e2. Half-lengths h_j = |A_j| / 8 enter
  // only squared: 1 / h_j^2 = 64 / |A_j|^2.
  const Lanes len2[3] = {hex::dot(a[1], a[1]), hex::dot(a[2], a[2]), hex::dot(a[3], a[3])};
  Lanes e[3][3];
  const Lanes n1 = 1.0 / lane_sqrt(len2[0]);
  for (int i = 0; i < 3; ++i) e[0][i] = a[1][i] * n1;
  const Lanes pr = hex::dot(a[2], e[0]);
  for (int i = 0; i < 3; ++i) e[1][i] = a[2][i] - pr * e[0][i];
  const Lanes n2 = 1.0 / lane_sqrt(hex::dot(e[1], e[1]));
  for (int i = 0; i < 3; ++i) e[1][i] *= n2;
  hex::cross(e[0], e[1], e[2]);

  const material::ElasticConstants& m = block.material;
  const double E = m.young, mu = m.shear, qm = block.hourglass.qm;
  const Lanes inv2[3] = {64.0 / len2[0], 64.0 / len2[1], 64.0 / len2[2]};
  const Lanes inv_sum = inv2[0] + inv2[1] + inv2[2];
  const Lanes bend = qm * h.volume * (1.0 / 192.0);
  const Lanes tri = qm * h.volume * (1.0 / 576.0);
  Lanes K[4][3];
  for (int md = 0; md < 3; ++md)
    for (int j = 0; j < 3; ++j)
      K[md][j] = j != md ? bend * E * inv2[j] : bend * mu * (inv_sum - inv2[md]);
  for (int j = 0; j < 3; ++j) K[3][j] = tri * (E * inv2[j] + mu * (inv_sum - inv2[j]));

  Lanes wsum{};
  for (int md = 0; md < 4; ++md) {
    Lanes* q = state[md];
    for (int j = 0; j < 3; ++j) {
      const Lanes qd = hex::dot(e[j], qdot[md]);
      const Lanes old = q[j];
      q[j] = old + K[md][j] * qd * dt;
      wsum += 0.5 * (old + q[j]) * qd;
    }
    for (int i = 0; i < 3; ++i) h.q[md][i] = e[0][i] * q[0] + e[1][i] * q[1] + e[2][i] * q[2];
  }
  h.work = wsum * dt;
}

// History of material M for a batch: the fields' components gathered lane by lane into
// h[0 .. history_size<M>()) in kHistory order, and written back for the lanes that hold real
// elements.
template <class M>
inline void load_history(const HexBlock& block, const Batch& b, Lanes* h) {
  int slot = 0;
  for (std::size_t f = 0; f < M::kHistory.size(); ++f) {
    const int nc = M::kHistory[f].components;
    std::size_t off[kLanes];
    lane_offsets(b, static_cast<std::size_t>(nc), off);
    const double* base = block.history[f].values.data();
    for (int c = 0; c < nc; ++c) h[slot++] = load_lanes(base + c, off);
  }
}

template <class M>
inline void store_history(HexBlock& block, std::size_t e, int lane, const Lanes* h) {
  int slot = 0;
  for (std::size_t f = 0; f < M::kHistory.size(); ++f) {
    const int nc = M::kHistory[f].components;
    double* out = block.history[f].values.data() + static_cast<std::size_t>(nc) * e;
    for (int c = 0; c < nc; ++c) out[c] = h[slot++][lane];
  }
}

// Current density rho0 V0 / V of the batch's elements.
inline Lanes current_density(const HexBlock& block, const Batch& b, Lanes volume) {
  std::size_t off[kLanes];
  lane_offsets(b, 1, off);
  return block.material.rho * load_lanes(block.volume0.data(), off) * (1.0 / volume);
}

// Current density rho0 V0 / V and length l = V^{1/3} = V0^{1/3} J^{1/3} of the batch's elements.
inline void density_and_length(const HexBlock& block, const Batch& b, Lanes volume, Lanes& density,
                               Lanes& length) {
  std::size_t off[kLanes];
  lane_offsets(b, 1, off);
  const Lanes v0 = load_lanes(block.volume0.data(), off);
  const Lanes r0 = load_lanes(block.volume0_cbrt.data(), off);
  density = block.material.rho * v0 * (1.0 / volume);
  length = r0 * volume_ratio_cbrt(volume / v0);
}

// The hourglass forms the kernel is instantiated for (IHQ 3 == 2, IHQ 5 == 4).
enum class HourglassForm { kViscousLsDyna, kViscousFB, kStiffnessFB, kBelytschkoBindeman };

inline HourglassForm hourglass_form(int ihq) {
  if (ihq == 1) return HourglassForm::kViscousLsDyna;
  if (ihq <= 3) return HourglassForm::kViscousFB;
  if (ihq <= 5) return HourglassForm::kStiffnessFB;
  return HourglassForm::kBelytschkoBindeman;
}

template <HourglassForm kForm, class M>
void elform1_batch(HexBlock& block, std::size_t first, int count, const NodalView& nv, double dt,
                   Partial& part) {
  constexpr bool kStateful =
      kForm == HourglassForm::kStiffnessFB || kForm == HourglassForm::kBelytschkoBindeman;
  constexpr bool kOrthogonal = kForm != HourglassForm::kViscousLsDyna;
  Batch b;
  b.first = first;
  b.count = count;
  gather_batch(block, nv, b);

  Lanes ax[8][3], av[8][3], am[8][3];
  hex::base_vectors(b.x, ax);
  hex::base_vectors(b.v, av);
  const double half_dt = 0.5 * dt;
  for (int k = 1; k <= 6; ++k)
    for (int i = 0; i < 3; ++i) am[k][i] = ax[k][i] - half_dt * av[k][i];
  Lanes gm[7][3], g[7][3], vm, vol;
  hex::volume_gradient(am, gm, vm);
  hex::volume_gradient(ax, g, vol);

  // Rates on the mid-step configuration and the stress update.
  Lanes L[9];
  const Lanes inv_vm = 1.0 / vm;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Lanes s = av[1][i] * gm[1][j];
      for (int k = 2; k <= 6; ++k) s += av[k][i] * gm[k][j];
      L[3 * i + j] = s * inv_vm;
    }
  Lanes d[6], w[3], sig[6];
  material::split_velocity_gradient(L, d, w);
  std::size_t off[kLanes];
  lane_offsets(b, 6, off);
  for (int c = 0; c < 6; ++c) sig[c] = load_lanes(block.stress.data() + c, off);
  Lanes hist[history_slots<M>()];
  load_history<M>(block, b, hist);
  M::update(block.material, update_parameters<M>(block), d, w, dt, sig, hist);

  // Characteristic length L_e = V / A_max at n+1 (tetrahedra: 3 V / A_max): the critical
  // step L_e / c and the length of the bulk viscosity.
  Lanes shape_factor;
  for (int l = 0; l < kLanes; ++l)
    shape_factor[l] = block.shape[b.element(l)] == HexShape::kTetrahedron ? 3.0 : 1.0;
  const Lanes elem_length =
      vol * shape_factor / lane_sqrt(hex::max_face_area_squared_from_base(ax));

  // Density (and V^{1/3} for the viscous hourglass) at n+1; bulk viscosity pressure.
  const bool bulk = block.bulk_viscosity.on();
  Lanes density{}, length{}, q_bulk{}, ekk{};
  if constexpr (!kStateful) density_and_length(block, b, vol, density, length);
  if (bulk) {
    if constexpr (kStateful) density = current_density(block, b, vol);
    ekk = L[0] + L[4] + L[8];
    q_bulk = bulk_viscosity_pressure(block.bulk_viscosity, block.material.wave_speed, density,
                                     elem_length, ekk);
  }

  HourglassTerms h{ax, av, g, vol, {w[0], w[1], w[2]}, {}, {}};
  Lanes state[4][3];
  if constexpr (kStateful) {
    lane_offsets(b, 12, off);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        state[a][i] = load_lanes(block.hourglass_state.data() + 3 * a + i, off);
  }
  if constexpr (kForm == HourglassForm::kStiffnessFB)
    stiffness_hourglass(block, dt, state, h);
  else if constexpr (kForm == HourglassForm::kBelytschkoBindeman)
    corotational_hourglass(block, dt, state, h);
  else
    viscous_hourglass<kOrthogonal>(block, dt, length, density, h);

  // Nodal forces f_iI = sum_k (P G_k)_i s_k(I) + sum_a Q_ai s_(4+a)(I), P = sigma - T.
  const Lanes P0[3][3] = {
      {sig[0], sig[3], sig[5]}, {sig[3], sig[1], sig[4]}, {sig[5], sig[4], sig[2]}};
  Lanes P[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P[i][j] = P0[i][j];
  if (bulk)
    for (int i = 0; i < 3; ++i) P[i][i] -= q_bulk;
  if constexpr (kOrthogonal) {
    const Lanes inv_v = 1.0 / vol;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        P[i][j] -= inv_v * (h.q[0][i] * ax[4][j] + h.q[1][i] * ax[5][j] + h.q[2][i] * ax[6][j] +
                            h.q[3][i] * ax[7][j]);
  }
  Lanes coef[8][3], f[3][8];
  for (int i = 0; i < 3; ++i) {
    coef[0][i] = Lanes{};
    for (int k = 1; k <= 6; ++k)
      coef[k][i] = P[i][0] * g[k][0] + P[i][1] * g[k][1] + P[i][2] * g[k][2];
    coef[7][i] = Lanes{};
    for (int a = 0; a < 4; ++a) coef[4 + a][i] += h.q[a][i];
  }
  hex::expand_nodal(coef, f);

  // Critical step L_e / c, with bulk viscosity L_e / (Q + sqrt(Q^2 + c^2)).
  Lanes elem_dt = elem_length / block.material.wave_speed;
  Lanes bulk_work{};
  if (bulk) {
    elem_dt = viscous_time_step(block.bulk_viscosity, block.material.wave_speed, elem_length, ekk,
                                [](Lanes x) { return lane_sqrt(x); });
    bulk_work = -q_bulk * ekk * vm * dt;
  }
  Lanes fsum{};
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) fsum += f[i][n];

  // Write back lane by lane, in element order (keeps "first failure" and the work sum in the
  // same order as an element-by-element loop).
  for (int l = 0; l < count; ++l) {
    const std::size_t e = first + static_cast<std::size_t>(l);
    const auto ie = static_cast<std::int64_t>(e);
    block.volume[e] = vol[l];
    double* out = &block.force[24 * e];
    if (!(vm[l] > 0.0) || !(vol[l] > 0.0)) {
      part.record_failure(ie, vol[l] > 0.0 ? vm[l] : vol[l]);
      for (int s = 0; s < 24; ++s) out[s] = 0.0;
      continue;
    }
    double* s = &block.stress[6 * e];
    for (int c = 0; c < 6; ++c) s[c] = sig[c][l];
    store_history<M>(block, e, l, hist);
    if constexpr (kStateful) {
      double* q = &block.hourglass_state[12 * e];
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) q[3 * a + i] = state[a][i][l];
    }
    part.hourglass_work += h.work[l];
    part.bulk_viscosity_work += bulk_work[l];
    if (block.erosion.enabled) block.erosion.artificial_work[e] += h.work[l] + bulk_work[l];
    if (!std::isfinite(fsum[l])) part.record_failure(ie, vol[l]);
    if (b.slots[l] == kIdentitySlots) {
      for (int n = 0; n < 8; ++n)
        for (int i = 0; i < 3; ++i) out[3 * n + i] = f[i][n][l];
    } else {
      double fl[3][8];
      for (int i = 0; i < 3; ++i)
        for (int n = 0; n < 8; ++n) fl[i][n] = f[i][n][l];
      scatter_forces(b.slots[l], fl, out);
    }
    part.record_dt(scaled_step(block.step_scale, ie, elem_dt[l]), ie);
  }
}

template <HourglassForm kForm, class M>
void elform1_range(HexBlock& block, std::int64_t batches, const NodalView& nv, double dt,
                   Partial& part) {
  const std::size_t n = block.size();
  const ElementOwnership& owned = block.owned;  // one process: batches of [0, n)
#pragma omp for schedule(static)
  for (std::int64_t bi = 0; bi < batches; ++bi) {
    std::size_t first = static_cast<std::size_t>(bi) * kLanes;
    int count = static_cast<int>(std::min<std::size_t>(kLanes, n - std::min(n, first)));
    if (owned.partitioned) {
      first = static_cast<std::size_t>(owned.batches[static_cast<std::size_t>(bi)].first);
      count = owned.batches[static_cast<std::size_t>(bi)].count;
    }
    elform1_batch<kForm, M>(block, first, count, nv, dt, part);
  }
}

// --- ELFORM 2 -----------------------------------------------------------------------------

inline bool finite_forces(const double f[3][8]) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) s += f[i][n];
  return std::isfinite(s);
}

template <class M>
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
    // History of point gp: gathered, updated, written back (8 points per element).
    double h[history_slots<M>()];
    int slot = 0;
    for (std::size_t f = 0; f < M::kHistory.size(); ++f) {
      const int nc = M::kHistory[f].components;
      const double* in =
          block.history[f].values.data() + static_cast<std::size_t>(nc) * (8 * e + gp);
      for (int c = 0; c < nc; ++c) h[slot++] = in[c];
    }
    M::update(block.material, update_parameters<M>(block), d, w, dt, stress + 6 * gp, h);
    slot = 0;
    for (std::size_t f = 0; f < M::kHistory.size(); ++f) {
      const int nc = M::kHistory[f].components;
      double* out = block.history[f].values.data() + static_cast<std::size_t>(nc) * (8 * e + gp);
      for (int c = 0; c < nc; ++c) out[c] = h[slot++];
    }
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
  double pbar = pressure_volume / g.volume;
  // Bulk viscosity on the mean dilatation (see bulk_viscosity_pressure).
  const BulkViscositySettings& bv = block.bulk_viscosity;
  double q_bulk = 0.0;
  const double length = element_length(x, g.volume, block.shape[e]);
  if (bv.on()) {
    const double density = block.material.rho * block.volume0[e] / g.volume;
    q_bulk = bulk_viscosity_pressure(bv, block.material.wave_speed, density, length, div_bar);
    pbar -= q_bulk;
    part.bulk_viscosity_work += -q_bulk * div_bar * gm.volume * dt;
    if (block.erosion.enabled)
      block.erosion.artificial_work[e] += -q_bulk * div_bar * gm.volume * dt;
  }
  for (int i = 0; i < 3; ++i)
    for (int n = 0; n < 8; ++n) f[i][n] += pbar * g.b[i][n];

  if (inverted || !finite_forces(f)) part.record_failure(static_cast<std::int64_t>(e), g.volume);
  scatter_forces(slots, f, out);
  const double speed = block.material.wave_speed;
  part.record_dt(
      scaled_step(block.step_scale, static_cast<std::int64_t>(e),
                  bv.on() ? viscous_time_step(bv, speed, length, div_bar) : length / speed),
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

const material::HistoryArray* find_history(const HexBlock& block, std::string_view name) {
  for (const auto& h : block.history)
    if (h.field.name == name) return &h;
  return nullptr;
}

void allocate_history(HexBlock& block) {
  block.history.clear();
  const std::size_t points = static_cast<std::size_t>(block.points_per_element()) * block.size();
  for (const material::HistoryField& f : material::history_fields(block.material_index))
    block.history.push_back(
        {f, std::vector<double>(points * static_cast<std::size_t>(f.components), 0.0)});
  // A material may start its history away from zero (M::initial_history: a temperature, a
  // relative volume of 1).
  material::with_material(block.material_index, [&]<class M>(std::type_identity<M>) {
    if constexpr (requires { M::initial_history(update_parameters<M>(block), nullptr); }) {
      double h[material::history_size<M>()];
      M::initial_history(update_parameters<M>(block), h);
      int slot = 0;
      for (auto& array : block.history) {
        const int nc = array.field.components;
        for (std::size_t k = 0; k < points; ++k)
          for (int c = 0; c < nc; ++c) array.values[k * nc + c] = h[slot + c];
        slot += nc;
      }
    }
  });
}

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
  if (is_nodal_pressure_tetrahedron(block)) {
    initialize_tet13_block(block, nodes);
    return;
  }
  const std::size_t n = block.size();
  if (block.conn.size() != 8 * n)
    throw SolverError(
        fmt::format("part {}: hexahedron block has {} elements but {} connectivity "
                    "entries (expected 8 per element)",
                    block.part_id, n, block.conn.size()));
  block.stress.assign(6 * static_cast<std::size_t>(block.points_per_element()) * n, 0.0);
  block.hourglass_state.assign(12 * n, 0.0);
  allocate_history(block);
  block.force.assign(24 * n, 0.0);
  block.volume0.assign(n, 0.0);
  block.volume0_cbrt.assign(n, 0.0);
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
    block.volume0_cbrt[e] = std::cbrt(v);
    block.volume[e] = v;
  }
}

KernelResult compute_hex_forces(HexBlock& block, const NodalView& nodes, double dt) {
  if (is_nodal_pressure_tetrahedron(block)) return compute_tet13_forces(block, nodes, dt);
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  int threads = 1;
  const bool elform2 = block.elform == 2;
  if (block.owned.partitioned) block.owned.prepare_batches(kLanes);
  const std::int64_t batches = block.owned.partitioned
                                   ? static_cast<std::int64_t>(block.owned.batches.size())
                                   : (n + kLanes - 1) / kLanes;
  const std::int64_t items = block.owned.count(n);  // ELFORM 2: one element per item
  const HourglassForm form = hourglass_form(block.hourglass.ihq);
#pragma omp parallel num_threads(thread_count())
  {
    Partial local;
    // One instantiation per (hourglass form, material): chosen here once per block.
    material::with_material(block.material_index, [&]<class M>(std::type_identity<M>) {
      // Shell-only materials never reach here (build_state checks the families).
      if constexpr (!material::serves_family<M>(material::kHex8)) {
        return;
      } else if (elform2) {
#pragma omp for schedule(static)
        for (std::int64_t i = 0; i < items; ++i)
          elform2_element<M>(block, static_cast<std::size_t>(block.owned.element(i)), nodes, dt,
                             local);
      } else {
        // Static schedule over batches: each thread still owns a contiguous element range.
        switch (form) {
          case HourglassForm::kViscousLsDyna:
            elform1_range<HourglassForm::kViscousLsDyna, M>(block, batches, nodes, dt, local);
            break;
          case HourglassForm::kViscousFB:
            elform1_range<HourglassForm::kViscousFB, M>(block, batches, nodes, dt, local);
            break;
          case HourglassForm::kStiffnessFB:
            elform1_range<HourglassForm::kStiffnessFB, M>(block, batches, nodes, dt, local);
            break;
          case HourglassForm::kBelytschkoBindeman:
            elform1_range<HourglassForm::kBelytschkoBindeman, M>(block, batches, nodes, dt, local);
            break;
        }
      }
    });
    partials[omp_get_thread_num()] = local;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine(partials, threads);
}

KernelResult hex_critical_timestep(const HexBlock& block, const NodalView& nodes,
                                   std::vector<double>* raw_steps) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  if (raw_steps) raw_steps->assign(block.size(), 0.0);
  int threads = 1;
#pragma omp parallel num_threads(thread_count())
  {
    Partial local;
#pragma omp for schedule(static)
    for (std::int64_t e = 0; e < n; ++e) {
      double x[3][8];
      const std::size_t ue = static_cast<std::size_t>(e);
      if (block.erosion.is_eroded(ue)) continue;  // left the model
      gather_coordinates(&block.conn[8 * ue], slot_map(block, ue), nodes, x);
      const double v = hex::hex_volume(x);
      if (!(v > 0.0)) {
        local.record_failure(e, v);
        continue;
      }
      const double step = element_time_step(x, v, block.shape[ue], block.material.wave_speed);
      if (raw_steps) (*raw_steps)[ue] = step;
      local.record_dt(scaled_step(block.step_scale, e, step), e);
    }
    partials[omp_get_thread_num()] = local;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine(partials, threads);
}

void add_hex_lumped_mass(const HexBlock& block, std::vector<double>& nodal_mass,
                         const std::vector<double>* element_factor) {
  for (std::size_t e = 0; e < block.size(); ++e) {
    const std::int32_t* c = &block.conn[8 * e];
    const int distinct = distinct_node_count(c);
    const double factor = element_factor ? (*element_factor)[e] : 1.0;
    const double share = factor * block.material.rho * block.volume0[e] / distinct;
    for (int k = 0; k < 8; ++k) {
      bool seen = false;
      for (int j = 0; j < k; ++j) seen |= c[j] == c[k];
      if (!seen) nodal_mass[static_cast<std::size_t>(c[k])] += share;
    }
  }
}

}  // namespace rf::element
