// The 10-node quadratic tetrahedron, LS-DYNA's *SECTION_SOLID ELFORM 16.
//
// REFERENCES. O. C. Zienkiewicz, R. L. Taylor & J. Z. Zhu, The Finite Element Method: Its Basis
// and Fundamentals, 7th ed. (2013), §6.4 (shape functions in volume coordinates) and Table 6.4
// (tetrahedron quadrature); T. J. R. Hughes, The Finite Element Method (1987; Dover 2000), §3.I
// and §7.3 (lumped mass, the "special lumping technique" of Hinton, Rock & Zienkiewicz,
// Earthquake Eng. Struct. Dyn. 4 (1976) 245-249).
//
// INTERPOLATION. Volume coordinates L_1 = 1 - xi - eta - zeta, L_2 = xi, L_3 = eta, L_4 = zeta;
// corners N_a = L_a (2 L_a - 1), a = 1..4; mid-side node of edge (i, j): N = 4 L_i L_j. Nodes in
// LS-DYNA's order N1..N4, N5 (1-2), N6 (2-3), N7 (3-1), N8 (1-4), N9 (2-4), N10 (3-4).
//
// QUADRATURE. The 4-point rule, L_q = alpha at point q and beta at the other three,
// alpha = (5 + 3 sqrt 5) / 20, beta = (5 - sqrt 5) / 20, weights 1/24 (the reference volume is
// 1/6): exact for quadratic polynomials (Zienkiewicz, Table 6.4), hence for the stiffness B^T C B
// of a straight-sided element, whose B is linear. Its stiffness has exactly the six rigid-body
// zero-energy modes (rank 24 of 30; tests/unit/tet10_test.cpp checks it): no hourglass control.
// (LS-DYNA's manual names ELFORM 16 a "4 or 5 point 10-noded tetrahedron"; the 5-point rule,
// with a negative centroid weight, adds nothing for straight-sided elements.)
//
// KINEMATICS (updated Lagrangian, as the 8-node kernels). At each point q the Jacobian
// J = sum_a x_a (dN_a / dxi)^T of the mid-step configuration x^{n+1/2} = x^{n+1} - dt/2 v^{n+1/2}
// gives the velocity gradient L = (sum_a v_a (dN_a/dxi)^T) J^-1, which the material integrates
// over dt (rate form with the spin W: the same update as the hexahedra, material/registry.hpp).
// The forces use the Jacobian at x^{n+1}: f_a = sum_q w_q det J_q (sigma_q - q_q I) J_q^-T
// dN_a/dxi(xi_q), with q_q the artificial bulk viscosity of the point's volumetric rate tr L.
//
// LUMPED MASS. Row-sum lumping of the quadratic tetrahedron gives the corners -1/20 of the mass
// (and the mid-side nodes 1/5): useless for an explicit method. HRZ lumping scales the diagonal
// of the consistent mass M_ab = rho int N_a N_b dV to the element mass: for a straight-sided
// element M_aa = rho V 6/420 at a corner and rho V 32/420 at a mid-side node, whose sum is
// rho V 216/420, so the corners get 6/216 = 1/36 and the mid-side nodes 32/216 = 4/27 of rho V
// (4/36 + 24/27 = 1: the total mass is exact, and the first moment too, since the fractions
// are symmetric). We use these fractions for curved elements as well (V by the 4-point rule).
//
// CRITICAL STEP. dt_e = l_e / c, c the dilatational wave speed, l_e = (1/4) min_q h_q with h_q
// = det J_q / max_a |c_a(J_q)| the smallest altitude of the affine tetrahedron spanned by the
// columns of J_q (c_1 = J_2 x J_3, c_2 = J_3 x J_1, c_3 = J_1 x J_2, c_0 = -(c_1 + c_2 + c_3):
// twice the face areas); for a straight-sided element h_q is the smallest altitude of the corner
// tetrahedron. The factor: the largest eigenvalue of M^-1 K (HRZ mass, 4-point stiffness) of a
// regular element gives 2 / omega_max = 0.320 h / c at nu = 0.3 and 0.275 h / c at nu = 0.49,
// and no smaller ratio than 0.275 over a few hundred randomly distorted elements (straight and
// curved edges, positive Jacobian); 1/4 keeps dt_e below 2 / omega_max with TSSFAC 1, and 0.9 of
// it at most 0.82 of the limit. tests/unit/tet10_test.cpp checks dt_e <= 2 / omega_max on
// distorted elements with the kernel's own stiffness.
#include "element/tet10_block.hpp"

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

// Shape-function derivatives dN_a/dxi_k at the 4 integration points (and, for the geometry
// check, at the 10 nodes), computed once.
struct Tet10Rule {
  double point_derivative[kTet10Points][kTet10Nodes][3];
  double node_derivative[kTet10Nodes][kTet10Nodes][3];
};

// dN_a/dxi_k at volume coordinates L (L[0] = 1 - xi - eta - zeta).
void shape_derivatives(const double L[4], double dN[kTet10Nodes][3]) {
  // dL_i / dxi_k: L_1 -> -1, L_{k+2} -> 1 (k = 0, 1, 2).
  auto dL = [](int i, int k) { return i == 0 ? -1.0 : (i == k + 1 ? 1.0 : 0.0); };
  for (int k = 0; k < 3; ++k) {
    for (int a = 0; a < 4; ++a) dN[a][k] = (4.0 * L[a] - 1.0) * dL(a, k);
    for (int m = 0; m < 6; ++m) {
      const int i = kTet10Edge[m][0], j = kTet10Edge[m][1];
      dN[4 + m][k] = 4.0 * (L[j] * dL(i, k) + L[i] * dL(j, k));
    }
  }
}

const Tet10Rule& tet10_rule() {
  static const Tet10Rule rule = [] {
    Tet10Rule r{};
    const double alpha = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0;
    const double beta = (5.0 - std::sqrt(5.0)) / 20.0;
    for (int q = 0; q < kTet10Points; ++q) {
      double L[4];
      for (int i = 0; i < 4; ++i) L[i] = i == q ? alpha : beta;
      shape_derivatives(L, r.point_derivative[q]);
    }
    for (int a = 0; a < kTet10Nodes; ++a) {
      double L[4] = {0.0, 0.0, 0.0, 0.0};
      if (a < 4) {
        L[a] = 1.0;
      } else {
        L[kTet10Edge[a - 4][0]] = 0.5;
        L[kTet10Edge[a - 4][1]] = 0.5;
      }
      shape_derivatives(L, r.node_derivative[a]);
    }
    return r;
  }();
  return rule;
}

constexpr double kPointWeight = 1.0 / 24.0;

// J_ik = sum_a x_ai dN_ak; returns det J and writes J^-1.
inline double jacobian(const double x[kTet10Nodes][3], const double dN[kTet10Nodes][3],
                       double J[3][3], double inv[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      double s = 0.0;
      for (int a = 0; a < kTet10Nodes; ++a) s += x[a][i] * dN[a][k];
      J[i][k] = s;
    }
  inv[0][0] = J[1][1] * J[2][2] - J[1][2] * J[2][1];
  inv[0][1] = J[0][2] * J[2][1] - J[0][1] * J[2][2];
  inv[0][2] = J[0][1] * J[1][2] - J[0][2] * J[1][1];
  inv[1][0] = J[1][2] * J[2][0] - J[1][0] * J[2][2];
  inv[1][1] = J[0][0] * J[2][2] - J[0][2] * J[2][0];
  inv[1][2] = J[0][2] * J[1][0] - J[0][0] * J[1][2];
  inv[2][0] = J[1][0] * J[2][1] - J[1][1] * J[2][0];
  inv[2][1] = J[0][1] * J[2][0] - J[0][0] * J[2][1];
  inv[2][2] = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  const double det = J[0][0] * inv[0][0] + J[0][1] * inv[1][0] + J[0][2] * inv[2][0];
  const double r = 1.0 / det;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) inv[i][k] *= r;
  return det;
}

// Smallest altitude det J / max_a |c_a| of the affine tetrahedron spanned by J's columns.
inline double point_altitude(const double J[3][3], double det) {
  double col[3][3], c[4][3];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) col[k][i] = J[i][k];
  auto cross = [](const double* a, const double* b, double* out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
  };
  cross(col[1], col[2], c[1]);
  cross(col[2], col[0], c[2]);
  cross(col[0], col[1], c[3]);
  for (int i = 0; i < 3; ++i) c[0][i] = -(c[1][i] + c[2][i] + c[3][i]);
  double c_max2 = 0.0;
  for (int a = 0; a < 4; ++a)
    c_max2 = std::max(c_max2, c[a][0] * c[a][0] + c[a][1] * c[a][1] + c[a][2] * c[a][2]);
  return det / std::sqrt(c_max2);
}

inline void gather(const std::int32_t* conn, const double* px, const double* py, const double* pz,
                   double out[kTet10Nodes][3]) {
  for (int a = 0; a < kTet10Nodes; ++a) {
    out[a][0] = px[conn[a]];
    out[a][1] = py[conn[a]];
    out[a][2] = pz[conn[a]];
  }
}

// Element e with material M: material update at the 4 points, forces, step.
template <class M>
void element_forces(HexBlock& block, std::size_t e, const NodalView& nv, double dt,
                    KernelPartial& part) {
  const Tet10Rule& rule = tet10_rule();
  const auto ie = static_cast<std::int64_t>(e);
  const std::int32_t* conn = &block.conn[kTet10Nodes * e];
  double* out = &block.force[3 * kTet10Nodes * e];
  std::fill_n(out, 3 * kTet10Nodes, 0.0);
  double x[kTet10Nodes][3], v[kTet10Nodes][3], xm[kTet10Nodes][3];
  gather(conn, nv.x, nv.y, nv.z, x);
  gather(conn, nv.vx, nv.vy, nv.vz, v);
  const double half_dt = 0.5 * dt;
  for (int a = 0; a < kTet10Nodes; ++a)
    for (int i = 0; i < 3; ++i) xm[a][i] = x[a][i] - half_dt * v[a][i];

  const double speed = block.material.wave_speed;
  const BulkViscositySettings& bv = block.bulk_viscosity;
  double volume = 0.0, min_altitude = 1e300, step = 1e300;
  for (int q = 0; q < kTet10Points; ++q) {
    const double(*dN)[3] = rule.point_derivative[q];
    double Jm[3][3], invm[3][3], J[3][3], inv[3][3];
    const double det_mid = jacobian(xm, dN, Jm, invm);
    const double det = jacobian(x, dN, J, inv);
    if (!(det_mid > 0.0) || !(det > 0.0)) {
      part.record_failure(ie, det > 0.0 ? det_mid * kPointWeight : det * kPointWeight);
      std::fill_n(out, 3 * kTet10Nodes, 0.0);
      block.volume[e] = det * kPointWeight;
      return;
    }
    // L = (sum_a v_a dN_a^T) J_mid^-1.
    double G[3][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        double s = 0.0;
        for (int a = 0; a < kTet10Nodes; ++a) s += v[a][i] * dN[a][k];
        G[i][k] = s;
      }
    double L[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        L[3 * i + j] = G[i][0] * invm[0][j] + G[i][1] * invm[1][j] + G[i][2] * invm[2][j];
    double d[6], w[3];
    material::split_velocity_gradient(L, d, w);

    const std::size_t point = kTet10Points * e + static_cast<std::size_t>(q);
    double* stress = &block.stress[6 * point];
    double h[history_slots<M>()];
    int slot = 0;
    for (std::size_t f = 0; f < M::kHistory.size(); ++f) {
      const int nc = M::kHistory[f].components;
      const double* in = block.history[f].values.data() + static_cast<std::size_t>(nc) * point;
      for (int k = 0; k < nc; ++k) h[slot++] = in[k];
    }
    M::update(block.material, update_parameters<M>(block), d, w, dt, stress, h);
    slot = 0;
    for (std::size_t f = 0; f < M::kHistory.size(); ++f) {
      const int nc = M::kHistory[f].components;
      double* hist = block.history[f].values.data() + static_cast<std::size_t>(nc) * point;
      for (int k = 0; k < nc; ++k) hist[k] = h[slot++];
    }

    const double weight = kPointWeight * det;
    volume += weight;
    const double altitude = point_altitude(J, det);
    min_altitude = std::min(min_altitude, altitude);
    const double length = 0.25 * altitude;
    const double ekk = L[0] + L[4] + L[8];
    double q_visc = 0.0;
    if (bv.on()) {
      // Density at the point: rho V0 over the volume the point represents, 4 w det J (the
      // element's volume when it deforms uniformly).
      const double density = block.material.rho * block.volume0[e] / (4.0 * weight);
      q_visc = bulk_viscosity_pressure(bv, speed, density, length, ekk);
      step = std::min(step, viscous_time_step(bv, speed, length, ekk));
      const double work = -q_visc * ekk * kPointWeight * det_mid * dt;
      part.bulk_viscosity_work += work;
      if (block.erosion.enabled) block.erosion.artificial_work[e] += work;
    }

    // f_a += w det J (sigma - q I) J^-T dN_a.
    const double sxx = stress[0] - q_visc, syy = stress[1] - q_visc, szz = stress[2] - q_visc;
    const double sxy = stress[3], syz = stress[4], szx = stress[5];
    for (int a = 0; a < kTet10Nodes; ++a) {
      // grad N_a = J^-T dN_a: g_j = sum_k dN_ak inv_kj.
      const double g0 = dN[a][0] * inv[0][0] + dN[a][1] * inv[1][0] + dN[a][2] * inv[2][0];
      const double g1 = dN[a][0] * inv[0][1] + dN[a][1] * inv[1][1] + dN[a][2] * inv[2][1];
      const double g2 = dN[a][0] * inv[0][2] + dN[a][1] * inv[1][2] + dN[a][2] * inv[2][2];
      double* fa = out + 3 * a;
      fa[0] += weight * (sxx * g0 + sxy * g1 + szx * g2);
      fa[1] += weight * (sxy * g0 + syy * g1 + syz * g2);
      fa[2] += weight * (szx * g0 + syz * g1 + szz * g2);
    }
  }
  block.volume[e] = volume;
  if (!bv.on()) step = 0.25 * min_altitude / speed;
  double sum = 0.0;
  for (int k = 0; k < 3 * kTet10Nodes; ++k) sum += out[k];
  if (!std::isfinite(sum)) part.record_failure(ie, volume);
  part.record_dt(scaled_step(block.step_scale, ie, step), ie);
}

std::string point_name(int q) {
  return fmt::format("integration point {}", q + 1);
}

}  // namespace

std::string tet10_geometry_problem(const double x[kTet10Nodes][3]) {
  for (int m = 0; m < 6; ++m) {
    const int i = kTet10Edge[m][0], j = kTet10Edge[m][1];
    double edge2 = 0.0, off2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double e = x[j][k] - x[i][k];
      const double o = x[4 + m][k] - 0.5 * (x[i][k] + x[j][k]);
      edge2 += e * e;
      off2 += o * o;
    }
    if (!(edge2 > 0.0))
      return fmt::format("corners N{} and N{} coincide (degenerate element)", i + 1, j + 1);
    if (off2 > kTet10MidsideTolerance * kTet10MidsideTolerance * edge2)
      return fmt::format(
          "mid-side node N{} is {:.4g} from the midpoint of edge N{}-N{} (length {:.4g}; at most "
          "{} of the length is accepted as a curved edge): LS-DYNA's order is N5 on edge 1-2, N6 "
          "2-3, N7 3-1, N8 1-4, N9 2-4, N10 3-4",
          m + 5, std::sqrt(off2), i + 1, j + 1, std::sqrt(edge2), kTet10MidsideTolerance);
  }
  const Tet10Rule& rule = tet10_rule();
  double J[3][3], inv[3][3];
  for (int a = 0; a < kTet10Nodes; ++a) {
    const double det = jacobian(x, rule.node_derivative[a], J, inv);
    if (!(det > 0.0))
      return fmt::format(
          "the Jacobian determinant is {:.6g} at node N{} (inverted, degenerate or too curved; "
          "N1 N2 N3 must be counter-clockwise seen from N4)",
          det, a + 1);
  }
  for (int q = 0; q < kTet10Points; ++q) {
    const double det = jacobian(x, rule.point_derivative[q], J, inv);
    if (!(det > 0.0))
      return fmt::format("the Jacobian determinant is {:.6g} at {} (inverted or too curved)", det,
                         point_name(q));
  }
  return {};
}

double tet10_characteristic_length(const double x[kTet10Nodes][3]) {
  const Tet10Rule& rule = tet10_rule();
  double h = 1e300;
  for (int q = 0; q < kTet10Points; ++q) {
    double J[3][3], inv[3][3];
    const double det = jacobian(x, rule.point_derivative[q], J, inv);
    if (!(det > 0.0)) return det;
    h = std::min(h, point_altitude(J, det));
  }
  return 0.25 * h;
}

void initialize_tet10_block(HexBlock& block, const NodalView& nodes) {
  const std::size_t n = block.size();
  if (block.conn.size() != kTet10Nodes * n)
    throw SolverError(fmt::format(
        "part {}: 10-node tetrahedron block has {} elements but {} connectivity entries "
        "(expected 10 per element)",
        block.part_id, n, block.conn.size()));
  block.stress.assign(6 * kTet10Points * n, 0.0);
  block.hourglass_state.clear();  // no hourglass modes
  allocate_history(block);
  block.force.assign(3 * kTet10Nodes * n, 0.0);
  block.volume0.assign(n, 0.0);
  block.volume0_cbrt.assign(n, 0.0);
  block.volume.assign(n, 0.0);
  block.shape.assign(n, HexShape::kTetrahedron);
  const Tet10Rule& rule = tet10_rule();
  for (std::size_t e = 0; e < n; ++e) {
    double x[kTet10Nodes][3];
    gather(&block.conn[kTet10Nodes * e], nodes.x, nodes.y, nodes.z, x);
    const std::string problem = tet10_geometry_problem(x);
    if (!problem.empty())
      throw SolverError(fmt::format("element {} of part {} (ELFORM 16): {}", block.element_id[e],
                                    block.part_id, problem));
    double volume = 0.0;
    for (int q = 0; q < kTet10Points; ++q) {
      double J[3][3], inv[3][3];
      volume += kPointWeight * jacobian(x, rule.point_derivative[q], J, inv);
    }
    block.volume0[e] = volume;
    block.volume0_cbrt[e] = std::cbrt(volume);
    block.volume[e] = volume;
  }
}

KernelResult compute_tet10_forces(HexBlock& block, const NodalView& nodes, double dt) {
  KernelPartials partials;
  const std::int64_t items = block.owned.count(static_cast<std::int64_t>(block.size()));
  int threads = 1;
#pragma omp parallel num_threads(kernel_thread_count())
  {
    KernelPartial part;
    // The material is chosen once per block.
    material::with_material(block.material_index, [&]<class M>(std::type_identity<M>) {
      if constexpr (material::serves_family<M>(material::kTet10)) {
#pragma omp for schedule(static)
        for (std::int64_t i = 0; i < items; ++i) {
          const auto e = static_cast<std::size_t>(block.owned.element(i));
          if (block.erosion.is_eroded(e)) continue;
          element_forces<M>(block, e, nodes, dt, part);
        }
      }
    });
    partials[static_cast<std::size_t>(omp_get_thread_num())] = part;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine_partials(partials, threads);
}

KernelResult tet10_critical_timestep(const HexBlock& block, const NodalView& nodes,
                                     std::vector<double>* raw_steps) {
  KernelPartials partials;
  const auto n = static_cast<std::int64_t>(block.size());
  if (raw_steps) raw_steps->assign(block.size(), 0.0);
  int threads = 1;
#pragma omp parallel num_threads(kernel_thread_count())
  {
    KernelPartial part;
#pragma omp for schedule(static)
    for (std::int64_t e = 0; e < n; ++e) {
      const auto ue = static_cast<std::size_t>(e);
      if (block.erosion.is_eroded(ue)) continue;
      double x[kTet10Nodes][3];
      gather(&block.conn[kTet10Nodes * ue], nodes.x, nodes.y, nodes.z, x);
      const double length = tet10_characteristic_length(x);
      if (!(length > 0.0)) {
        part.record_failure(e, length);
        continue;
      }
      const double step = length / block.material.wave_speed;
      if (raw_steps) (*raw_steps)[ue] = step;
      part.record_dt(scaled_step(block.step_scale, e, step), e);
    }
    partials[static_cast<std::size_t>(omp_get_thread_num())] = part;
#pragma omp single
    threads = omp_get_num_threads();
  }
  return combine_partials(partials, threads);
}

void add_tet10_lumped_mass(const HexBlock& block, std::vector<double>& nodal_mass,
                           const std::vector<double>* element_factor) {
  for (std::size_t e = 0; e < block.size(); ++e) {
    const double factor = element_factor ? (*element_factor)[e] : 1.0;
    const double mass = factor * block.material.rho * block.volume0[e];
    const std::int32_t* c = &block.conn[kTet10Nodes * e];
    for (int a = 0; a < kTet10Nodes; ++a)
      nodal_mass[static_cast<std::size_t>(c[a])] +=
          mass * (a < 4 ? kTet10CornerMass : kTet10MidsideMass);
  }
}

}  // namespace rf::element
