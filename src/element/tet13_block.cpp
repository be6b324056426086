// The nodal-pressure tetrahedron, LS-DYNA's *SECTION_SOLID ELFORM 13 ("1 point nodal pressure
// tetrahedron", free of volumetric locking in plastic flow and near incompressibility).
//
// REFERENCES. J. Bonet & A. J. Burton, "A simple average nodal pressure tetrahedral element for
// incompressible and nearly incompressible dynamic explicit applications", Commun. Numer. Meth.
// Engng 14 (1998) 437-449; M. A. Puso & J. Solberg, "A stabilized nodally integrated
// tetrahedral", IJNME 67 (2006) 841-867 (the same nodal averaging, and its spurious modes);
// E. A. de Souza Neto et al., "Design of simple low order finite elements for large strain
// analysis of nearly incompressible solids", IJSS 33 (1996) 3277-3296 (F-bar).
//
// BONET & BURTON. The linear tetrahedron has one volume constraint per element, about five
// per node, and locks when the material is nearly incompressible. Bonet & Burton measure the
// volume at the nodes instead: node a owns a quarter of each element around it,
//   V_a = sum_{e at a} V_e / 4,   J_a = V_a / V_a^0,   p_a = p(J_a),                  (1)
// the volumetric energy is sum_a V_a^0 U(J_a), and its derivative gives each element the mean
// of its four nodal pressures and the element's own gradient:
//   pbar_e = (1/4) sum_{a in e} p_a,   f_a = V_e (s_e + pbar_e I) grad N_a,            (2)
// s_e the deviatoric stress of the element's own strain. One volume constraint per node.
//
// RATE FORM (our update). The materials here integrate rates (hypoelastic and J2 laws, the
// rubbers' left Cauchy-Green tensor), so we average the rate of (1): the volumetric strain rate
// of the nodal volume,
//   theta_a = (d/dt) ln V_a = sum_{e at a} dV_e/dt / sum_{e at a} V_e,  dV_e/dt = V_e tr L_e,
// and give each element's material the velocity gradient with its trace replaced by the mean
// of its nodes' rates,
//   Lbar_e = L_e + (thetabar_e - tr L_e) I / 3,   thetabar_e = (1/4) sum_{a in e} theta_a.  (3)
// The deviatoric part of the rate is the element's own. For a pressure linear in the logarithmic
// volume strain (p = K ln J: *MAT_ELASTIC, the J2 laws, whose pressure stays elastic) the
// element's pressure is then K (1/4) sum_a ln J_a = the mean of the nodal pressures, i.e.
// (2) with the nodal pressure K ln J_a, and the forces (2) are the derivative of the nodal
// volumetric energy: the element is Bonet & Burton's, integrated in rate form. For the rubbers
// (3) is the F-bar method with the nodally averaged volume change.
//
// PASSES. (i) every element of the block: the mid-step velocity gradient L_e and volume V_e
// (x^{n+1/2} = x^{n+1} - dt/2 v^{n+1/2}, as the hexahedra), kept in scratch; (ii) every node of
// the block: theta_a, gathered through the node's element list in ascending element order (the
// same sum for any thread count); (iii) every owned element: (3), the material update, the
// forces at x^{n+1}, the step. Averages are taken over the elements of the block (one part);
// eroded elements contribute nothing. In a distributed run every rank holds the replicated
// nodal state, so pass (i) runs over all elements on every rank and the averages need no
// exchange; pass (iii) runs over the rank's own elements.
//
// BULK VISCOSITY AND STEP. q of the averaged rate thetabar_e (the element's own rate would put
// back the per-element volume constraint, as a viscosity), l the smallest altitude 3 V / A_max;
// its work is booked with the element's own rate, which is the work its forces do. Critical
// step: the smallest altitude over the dilatational wave speed, as ELFORM 10 (docs/theory.md).
//
// GEOMETRY. Corners 0-3 (first appearances in the 8 connectivity entries), edges e_k = x_k - x_0,
// c_1 = e_2 x e_3, c_2 = e_3 x e_1, c_3 = e_1 x e_2, c_0 = -(c_1 + c_2 + c_3): 6 V = e_1 . c_1,
// grad N_a = c_a / (6 V), |c_a| = twice the area of the face opposite corner a. Hence
// L_ij = sum_a v_ai c_aj / (6 V), the forces f_a = (sigma - q I) c_a / 6, and
// 3 V / A_max = 6 V / max_a |c_a|.
#include "element/tet13_block.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "element/kernel_partials.hpp"
#include "element/solid_terms.hpp"
#include "material/elastic_update.hpp"
#include "material/registry.hpp"
#include "model/error.hpp"

namespace rf::element {
namespace {

inline void cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

inline double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The vectors c_a = 6 V grad N_a of the header comment; returns 6 V.
inline double area_vectors(const double x[4][3], double c[4][3]) {
  double e[3][3];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) e[k][i] = x[k + 1][i] - x[0][i];
  cross(e[1], e[2], c[1]);
  cross(e[2], e[0], c[2]);
  cross(e[0], e[1], c[3]);
  for (int i = 0; i < 3; ++i) c[0][i] = -(c[1][i] + c[2][i] + c[3][i]);
  return dot(e[0], c[1]);
}

inline void gather_corners(const NodalAveraging& avg, std::size_t e, const double* px,
                           const double* py, const double* pz, double out[4][3]) {
  for (int a = 0; a < 4; ++a) {
    const std::int32_t n = avg.node[static_cast<std::size_t>(avg.corner[4 * e + a])];
    out[a][0] = px[n];
    out[a][1] = py[n];
    out[a][2] = pz[n];
  }
}

// Pass (i): mid-step velocity gradient, volume and volume rate of element e (zeros for an
// eroded or inverted element; pass (iii) reports the inverted one).
void mid_step_rates(HexBlock& block, std::size_t e, const NodalView& nv, double dt) {
  NodalAveraging& avg = block.nodal_averaging;
  double* L = &avg.velocity_gradient[9 * e];
  if (block.erosion.is_eroded(e)) {
    std::fill_n(L, 9, 0.0);
    avg.mid_volume[e] = 0.0;
    avg.volume_rate[e] = 0.0;
    return;
  }
  double x[4][3], v[4][3], c[4][3];
  gather_corners(avg, e, nv.x, nv.y, nv.z, x);
  gather_corners(avg, e, nv.vx, nv.vy, nv.vz, v);
  const double half_dt = 0.5 * dt;
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) x[a][i] -= half_dt * v[a][i];
  const double six_v = area_vectors(x, c);
  if (!(six_v > 0.0)) {
    std::fill_n(L, 9, 0.0);
    avg.mid_volume[e] = six_v / 6.0;
    avg.volume_rate[e] = 0.0;
    return;
  }
  const double inv = 1.0 / six_v;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      L[3 * i + j] =
          inv * (v[0][i] * c[0][j] + v[1][i] * c[1][j] + v[2][i] * c[2][j] + v[3][i] * c[3][j]);
  const double volume = six_v / 6.0;
  avg.mid_volume[e] = volume;
  avg.volume_rate[e] = volume * (L[0] + L[4] + L[8]);
}

// Pass (ii): the volumetric strain rate of block-local node k's volume.
inline void node_rate(NodalAveraging& avg, std::size_t k) {
  double rate = 0.0, volume = 0.0;
  for (std::int32_t i = avg.offset[k]; i < avg.offset[k + 1]; ++i) {
    const auto e = static_cast<std::size_t>(avg.element[static_cast<std::size_t>(i)]);
    const double vm = avg.mid_volume[e];
    if (vm > 0.0) {
      rate += avg.volume_rate[e];
      volume += vm;
    }
  }
  avg.node_rate[k] = volume > 0.0 ? rate / volume : 0.0;
}

// Pass (iii) for element e with material M.
template <class M>
void element_forces(HexBlock& block, std::size_t e, const NodalView& nv, double dt,
                    KernelPartial& part) {
  NodalAveraging& avg = block.nodal_averaging;
  const auto ie = static_cast<std::int64_t>(e);
  double* out = &block.force[24 * e];
  double x[4][3], c[4][3];
  gather_corners(avg, e, nv.x, nv.y, nv.z, x);
  const double six_v = area_vectors(x, c);
  const double volume = six_v / 6.0;
  const double vm = avg.mid_volume[e];
  block.volume[e] = volume;
  if (!(vm > 0.0) || !(volume > 0.0)) {
    part.record_failure(ie, volume > 0.0 ? vm : volume);
    std::fill_n(out, 24, 0.0);
    return;
  }

  // Rate with the averaged volumetric part, eq. (3).
  double L[9];
  std::copy_n(&avg.velocity_gradient[9 * e], 9, L);
  double theta = 0.0;
  for (int a = 0; a < 4; ++a)
    theta += avg.node_rate[static_cast<std::size_t>(avg.corner[4 * e + a])];
  theta *= 0.25;
  const double ekk = L[0] + L[4] + L[8];
  const double correction = (theta - ekk) / 3.0;
  L[0] += correction;
  L[4] += correction;
  L[8] += correction;
  double d[6], w[3];
  material::split_velocity_gradient(L, d, w);

  double* stress = &block.stress[6 * e];
  double h[history_slots<M>()];
  int slot = 0;
  for (std::size_t f = 0; f < M::kHistory.size(); ++f) {
    const int nc = M::kHistory[f].components;
    const double* in = block.history[f].values.data() + static_cast<std::size_t>(nc) * e;
    for (int k = 0; k < nc; ++k) h[slot++] = in[k];
  }
  M::update(block.material, update_parameters<M>(block), d, w, dt, stress, h);
  slot = 0;
  for (std::size_t f = 0; f < M::kHistory.size(); ++f) {
    const int nc = M::kHistory[f].components;
    double* hist = block.history[f].values.data() + static_cast<std::size_t>(nc) * e;
    for (int k = 0; k < nc; ++k) hist[k] = h[slot++];
  }

  // Smallest altitude 3 V / A_max = 6 V / max |c_a|.
  double c_max2 = 0.0;
  for (int a = 0; a < 4; ++a) c_max2 = std::max(c_max2, dot(c[a], c[a]));
  const double length = six_v / std::sqrt(c_max2);
  const double speed = block.material.wave_speed;
  const BulkViscositySettings& bv = block.bulk_viscosity;
  double q = 0.0, step = length / speed;
  if (bv.on()) {
    const double density = block.material.rho * block.volume0[e] / volume;
    q = bulk_viscosity_pressure(bv, speed, density, length, theta);
    step = viscous_time_step(bv, speed, length, theta);
    const double work = -q * ekk * vm * dt;
    part.bulk_viscosity_work += work;
    if (block.erosion.enabled) block.erosion.artificial_work[e] += work;
  }

  // f_a = (sigma - q I) c_a / 6, into the slot of the corner's first appearance.
  const double sxx = stress[0] - q, syy = stress[1] - q, szz = stress[2] - q;
  const double sxy = stress[3], syz = stress[4], szx = stress[5];
  std::fill_n(out, 24, 0.0);
  double sum = 0.0;
  for (int a = 0; a < 4; ++a) {
    const double* ca = c[a];
    double* fa = out + 3 * avg.corner_slot[4 * e + a];
    fa[0] = (sxx * ca[0] + sxy * ca[1] + szx * ca[2]) * (1.0 / 6.0);
    fa[1] = (sxy * ca[0] + syy * ca[1] + syz * ca[2]) * (1.0 / 6.0);
    fa[2] = (szx * ca[0] + syz * ca[1] + szz * ca[2]) * (1.0 / 6.0);
    sum += fa[0] + fa[1] + fa[2];
  }
  if (!std::isfinite(sum)) part.record_failure(ie, volume);
  part.record_dt(scaled_step(block.step_scale, ie, step), ie);
}

}  // namespace

void initialize_tet13_block(HexBlock& block, const NodalView& nodes) {
  const std::size_t n = block.size();
  if (block.conn.size() != 8 * n)
    throw SolverError(
        fmt::format("part {}: tetrahedron block has {} elements but {} connectivity "
                    "entries (expected 8 per element)",
                    block.part_id, n, block.conn.size()));
  block.stress.assign(6 * n, 0.0);
  block.hourglass_state.clear();  // no hourglass modes
  allocate_history(block);
  block.force.assign(24 * n, 0.0);
  block.volume0.assign(n, 0.0);
  block.volume0_cbrt.assign(n, 0.0);
  block.volume.assign(n, 0.0);
  block.shape.assign(n, HexShape::kTetrahedron);

  NodalAveraging& avg = block.nodal_averaging;
  avg.corner.assign(4 * n, 0);
  avg.corner_slot.assign(4 * n, 0);
  std::vector<std::int32_t> dense(4 * n);
  for (std::size_t e = 0; e < n; ++e) {
    const std::int32_t* c = &block.conn[8 * e];
    int found = 0;
    for (int k = 0; k < 8; ++k) {
      bool seen = false;
      for (int j = 0; j < k; ++j) seen |= c[j] == c[k];
      if (seen) continue;
      if (found < 4) {
        dense[4 * e + found] = c[k];
        avg.corner_slot[4 * e + found] = static_cast<std::uint8_t>(k);
      }
      ++found;
    }
    if (found != 4)
      throw SolverError(fmt::format(
          "element {} of part {} has {} distinct nodes, but its section is ELFORM 13, the "
          "4-node nodal-pressure tetrahedron",
          block.element_id[e], block.part_id, found));
    double x[4][3], cv[4][3];
    for (int a = 0; a < 4; ++a) {
      const std::int32_t node = dense[4 * e + a];
      x[a][0] = nodes.x[node];
      x[a][1] = nodes.y[node];
      x[a][2] = nodes.z[node];
    }
    const double v = area_vectors(x, cv) / 6.0;
    if (!(v > 0.0))
      throw SolverError(fmt::format(
          "element {} of part {} has non-positive volume {:.6g}: a tetrahedron n1 n2 n3 n4 must "
          "have n1 n2 n3 counter-clockwise seen from n4",
          block.element_id[e], block.part_id, v));
    block.volume0[e] = v;
    block.volume0_cbrt[e] = std::cbrt(v);
    block.volume[e] = v;
  }

  // Block-local nodes (ascending dense index) and the node -> element lists.
  avg.node = dense;
  std::sort(avg.node.begin(), avg.node.end());
  avg.node.erase(std::unique(avg.node.begin(), avg.node.end()), avg.node.end());
  const std::size_t local = avg.node.size();
  avg.offset.assign(local + 1, 0);
  for (std::size_t k = 0; k < 4 * n; ++k) {
    const auto it = std::lower_bound(avg.node.begin(), avg.node.end(), dense[k]);
    avg.corner[k] = static_cast<std::int32_t>(it - avg.node.begin());
    ++avg.offset[static_cast<std::size_t>(avg.corner[k]) + 1];
  }
  for (std::size_t k = 0; k < local; ++k) avg.offset[k + 1] += avg.offset[k];
  avg.element.assign(4 * n, 0);
  std::vector<std::int32_t> fill(avg.offset.begin(), avg.offset.end() - 1);
  for (std::size_t k = 0; k < 4 * n; ++k)  // ascending element order within each node
    avg.element[static_cast<std::size_t>(fill[static_cast<std::size_t>(avg.corner[k])]++)] =
        static_cast<std::int32_t>(k / 4);

  avg.velocity_gradient.assign(9 * n, 0.0);
  avg.mid_volume.assign(n, 0.0);
  avg.volume_rate.assign(n, 0.0);
  avg.node_rate.assign(local, 0.0);
}

KernelResult compute_tet13_forces(HexBlock& block, const NodalView& nodes, double dt) {
  KernelPartials partials;
  const auto n = static_cast<std::int64_t>(block.size());
  const auto local = static_cast<std::int64_t>(block.nodal_averaging.node_count());
  const std::int64_t items = block.owned.count(n);
  int threads = 1;
#pragma omp parallel num_threads(kernel_thread_count())
  {
    KernelPartial part;
    // (i) every element: on every rank of a distributed run, so that (ii) sees all of them.
#pragma omp for schedule(static)
    for (std::int64_t e = 0; e < n; ++e)
      mid_step_rates(block, static_cast<std::size_t>(e), nodes, dt);
      // (ii) every node of the block, gathered in a fixed order.
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < local; ++k)
      node_rate(block.nodal_averaging, static_cast<std::size_t>(k));
    // (iii) the owned elements; the material is chosen once per block.
    material::with_material(block.material_index, [&]<class M>(std::type_identity<M>) {
      if constexpr (material::serves_family<M>(material::kTet13)) {
#pragma omp for schedule(static)
        for (std::int64_t i = 0; i < items; ++i)
          element_forces<M>(block, static_cast<std::size_t>(block.owned.element(i)), nodes, dt,
                            part);
      }
    });
    partials[static_cast<std::size_t>(omp_get_thread_num())] = part;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine_partials(partials, threads);
}

}  // namespace rf::element
