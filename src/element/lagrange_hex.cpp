// Lagrange hexahedra of order 2 and 3 on GLL points (see lagrange_hex.hpp for the formulation).
//
// Sum factorisation. With u_a nodal values in tensor order and D the 1D differentiation matrix,
// the reference gradient at GLL point q = (l, m, r) is
//   du/dxi   = sum_i D[l][i] u(i, m, r),  du/deta = sum_j D[m][j] u(l, j, r),
//   du/dzeta = sum_k D[r][k] u(l, m, k),
// because the Lagrange basis is a Kronecker delta at the nodes: (p+1)^4 multiply-adds per
// direction instead of (p+1)^6. The internal force f_a = sum_q W_q P_q grad_X N_a(q) is the
// transpose of that operator applied to G_q = W_q P_q J0_q^-T (W_q = w_l w_m w_r det J0_q):
//   f(i, j, k) = sum_l D[l][i] G_xi(l, j, k) + sum_m D[m][j] G_eta(i, m, k)
//              + sum_r D[r][k] G_zeta(i, j, r).
//
// Exactness. GLL with p+1 points integrates polynomials of degree 2p-1 exactly. On an element
// whose geometry is trilinear (straight-edged, as produced by mesh/p_order from 8-node hexahedra)
// the integrand det J0 grad_X N_a = cof(J0) grad_xi N_a has degree <= p+1 in each variable, so for
// p >= 2 a constant stress is integrated exactly and the patch test is passed exactly. Curved
// geometry (nodes moved onto a surface) adds a quadrature error of the usual spectral-element
// kind; a linear displacement field still gives exactly constant F (collocation), hence constant
// stress.
//
// Time step. Central differences are stable for dt <= 2 / omega_max (undamped). The element
// eigenvalue inequality (Irons & Treharne, IJNME 1971; Flanagan & Belytschko, IJNME 17, 1981)
// bounds the assembled omega^2_max by the largest element omega^2_max when the mass is lumped, so
// 2 / omega_max,e per element is a safe step. omega^2_max,e is the top eigenvalue of
// A = M^-1/2 K M^-1/2 (K small-strain stiffness at the reference configuration, M the GLL mass).
// We use Lanczos rather than power iteration: it needs far fewer operator applications for the
// same accuracy (Golub & Van Loan, Matrix Computations, ch. 10), and it gives a residual norm
// r = beta_k |s_k| for the top Ritz pair, so an eigenvalue lies in [theta - r, theta + r]
// (Parlett, The Symmetric Eigenvalue Problem, Thm 4.5.1). The Ritz value theta approaches
// omega^2_max from below; we return theta + r, which is above omega^2_max once theta approximates
// the top eigenvalue, and iterate until r <= 1e-4 theta, so the step is at most ~0.005% below the
// exact element bound 2 / omega_max rather than up to ~1% above it (unsafe) as a raw Rayleigh
// quotient of a short power iteration would be.
//
// During the run the step is the reference step times (current / reference smallest GLL node
// spacing): for a fixed material and mass, omega_max scales with the inverse of the element's
// smallest length, so this follows compression of the element at the cost of a few distances per
// element instead of an eigenvalue solve. It does not follow the neo-Hookean stiffening under
// strong volumetric compression (lambda (1 - ln J) / J^2 grows); TSSFAC covers moderate strains.
#include "element/kernel_partials.hpp"
#include "element/lagrange_hex.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "model/error.hpp"

namespace rf::element {
namespace {

// --- GLL rule -------------------------------------------------------------------------------

// Legendre P_{n-1}(x) and P_n(x) by the three-term recurrence (k+1) P_{k+1} = (2k+1) x P_k -
// k P_{k-1}.
void legendre(int n, double x, double& p_prev, double& p) {
  p_prev = 1.0;
  p = x;
  for (int k = 1; k < n; ++k) {
    const double next = ((2.0 * k + 1.0) * x * p - k * p_prev) / (k + 1.0);
    p_prev = p;
    p = next;
  }
}

GllRule make_rule(int p) {
  const int n = p + 1;
  GllRule r;
  r.order = p;
  r.points.assign(n, 0.0);
  r.weights.assign(n, 0.0);
  r.derivative.assign(n * n, 0.0);
  r.points[0] = -1.0;
  r.points[p] = 1.0;
  // Interior points: roots of q(x) = (1 - x^2) P_p'(x) = p (P_{p-1} - x P_p). Legendre's equation
  // gives q'(x) = -p (p+1) P_p, so Newton's step is dx = (x P_p - P_{p-1}) / ((p+1) P_p).
  // Chebyshev-Gauss-Lobatto points -cos(pi i / p) are close enough to converge quadratically. The
  // left half is computed and mirrored so that points[p-i] == -points[i] bit for bit (the mesh
  // elevation relies on the rule being symmetric when it reverses an edge).
  for (int i = 1; 2 * i < p; ++i) {
    double x = -std::cos(std::numbers::pi * i / p);
    for (int it = 0; it < 100; ++it) {
      double pm, pp;
      legendre(p, x, pm, pp);
      const double dx = (x * pp - pm) / ((p + 1.0) * pp);
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    r.points[i] = x;
    r.points[p - i] = -x;
  }
  if (p % 2 == 0) r.points[p / 2] = 0.0;
  // w_i = 2 / (p (p+1) P_p(x_i)^2) (Abramowitz & Stegun 25.4.32).
  for (int i = 0; i < n; ++i) {
    double pm, pp;
    legendre(p, r.points[i], pm, pp);
    r.weights[i] = 2.0 / (p * (p + 1.0) * pp * pp);
  }
  for (int i = 0; i < n / 2; ++i) r.weights[p - i] = r.weights[i];
  // Barycentric differentiation (Berrut & Trefethen, SIAM Rev. 46, 2004, eq. 9.4):
  // D_ij = (lambda_j / lambda_i) / (x_i - x_j), lambda_j = 1 / prod_{k != j} (x_j - x_k); the
  // diagonal as minus the row sum, so constants are differentiated to exactly zero.
  std::vector<double> lambda(n, 1.0);
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < n; ++k)
      if (k != j) lambda[j] *= r.points[j] - r.points[k];
    lambda[j] = 1.0 / lambda[j];
  }
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      const double d = (lambda[j] / lambda[i]) / (r.points[i] - r.points[j]);
      r.derivative[i * n + j] = d;
      sum += d;
    }
    r.derivative[i * n + i] = -sum;
  }
  return r;
}

// --- Small 3x3 helpers (row-major) ----------------------------------------------------------

// Cofactor matrix C (C = det(A) A^-T) and determinant.
inline double cofactor(const double a[9], double c[9]) {
  c[0] = a[4] * a[8] - a[5] * a[7];
  c[1] = a[5] * a[6] - a[3] * a[8];
  c[2] = a[3] * a[7] - a[4] * a[6];
  c[3] = a[2] * a[7] - a[1] * a[8];
  c[4] = a[0] * a[8] - a[2] * a[6];
  c[5] = a[1] * a[6] - a[0] * a[7];
  c[6] = a[1] * a[5] - a[2] * a[4];
  c[7] = a[2] * a[3] - a[0] * a[5];
  c[8] = a[0] * a[4] - a[1] * a[3];
  return a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
}

// --- Sum-factorised operators ---------------------------------------------------------------

// Reference gradient of one nodal field: g[d][q] = du/dxi_d at GLL point q.
template <int N>
inline void reference_gradient(const double* D, const double* u, double g[3][N * N * N]) {
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        double s0 = 0.0, s1 = 0.0, s2 = 0.0;
        for (int l = 0; l < N; ++l) {
          s0 += D[i * N + l] * u[l + N * (j + N * k)];
          s1 += D[j * N + l] * u[i + N * (l + N * k)];
          s2 += D[k * N + l] * u[i + N * (j + N * l)];
        }
        const int q = i + N * (j + N * k);
        g[0][q] = s0;
        g[1][q] = s1;
        g[2][q] = s2;
      }
}

// Transpose of reference_gradient: f_a = sum_q sum_d G[d][q] dN_a/dxi_d(q).
template <int N>
inline void reference_gradient_transpose(const double* D, const double G[3][N * N * N], double* f) {
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        double s = 0.0;
        for (int l = 0; l < N; ++l) {
          s += D[l * N + i] * G[0][l + N * (j + N * k)];
          s += D[l * N + j] * G[1][i + N * (l + N * k)];
          s += D[l * N + k] * G[2][i + N * (j + N * l)];
        }
        f[i + N * (j + N * k)] = s;
      }
}

// Smallest squared distance between adjacent nodes along grid lines.
template <int N>
inline double min_spacing_squared(const double x[3][N * N * N]) {
  double m = std::numeric_limits<double>::infinity();
  auto dist2 = [&](int a, int b) {
    const double dx = x[0][a] - x[0][b], dy = x[1][a] - x[1][b], dz = x[2][a] - x[2][b];
    return dx * dx + dy * dy + dz * dz;
  };
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        const int a = i + N * (j + N * k);
        if (i + 1 < N) m = std::min(m, dist2(a, a + 1));
        if (j + 1 < N) m = std::min(m, dist2(a, a + N));
        if (k + 1 < N) m = std::min(m, dist2(a, a + N * N));
      }
  return m;
}

template <int N>
inline void gather(const std::int32_t* c, const double* px, const double* py, const double* pz,
                   double x[3][N * N * N]) {
  for (int a = 0; a < N * N * N; ++a) {
    x[0][a] = px[c[a]];
    x[1][a] = py[c[a]];
    x[2][a] = pz[c[a]];
  }
}

using Partial = KernelPartial;
constexpr int kMaxThreads = kMaxKernelThreads;

KernelResult combine(const KernelPartials& partials, int threads) {
  return combine_partials(partials, threads);
}

inline int thread_count() { return kernel_thread_count(); }

// --- Element kernels ------------------------------------------------------------------------

// Internal forces, stresses and volume of element e. Returns false on J <= 0 or a non-finite
// result (forces are then zeroed). `spacing2` gets the smallest squared node spacing.
template <int P>
bool element_forces(HexBlock& block, std::size_t e, const NodalView& nv, const double* D,
                    double& volume, double& spacing2) {
  constexpr int N = P + 1, NN = N * N * N;
  const std::int32_t* c = &block.conn[NN * e];
  double x[3][NN];
  gather<N>(c, nv.x, nv.y, nv.z, x);
  spacing2 = min_spacing_squared<N>(x);
  double g[3][3][NN];  // g[c][d][q] = dx_c / dxi_d
  for (int comp = 0; comp < 3; ++comp) reference_gradient<N>(D, x[comp], g[comp]);

  const double mu = block.material.shear, lambda = block.material.lambda;
  const double* jinv_all = &block.reference_inverse_jacobian[9 * NN * e];
  const double* w_all = &block.reference_weight[NN * e];
  double* stress = &block.stress[6 * NN * e];
  // Point loops in three passes over struct-of-arrays data so that the first and last, which
  // have no calls or branches, vectorise across GLL points; only the logarithm is scalar.
  double F[9][NN], C[9][NN], J[NN];
  for (int q = 0; q < NN; ++q) {
    const double* jinv = jinv_all + 9 * q;  // jinv[3 d + e] = dxi_d / dX_e
    double f[9], cof[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        f[3 * i + j] = g[i][0][q] * jinv[j] + g[i][1][q] * jinv[3 + j] + g[i][2][q] * jinv[6 + j];
    J[q] = cofactor(f, cof);
    for (int s = 0; s < 9; ++s) {
      F[s][q] = f[s];
      C[s][q] = cof[s];
    }
  }
  double vol = 0.0;
  bool ok = true;
  double ln_j[NN];
  for (int q = 0; q < NN; ++q) {
    vol += w_all[q] * J[q];
    ok = ok && J[q] > 0.0;
  }
  volume = vol;
  double* out = &block.force[3 * NN * e];
  if (!ok) {
    for (int s = 0; s < 3 * NN; ++s) out[s] = 0.0;
    return false;
  }
  for (int q = 0; q < NN; ++q) ln_j[q] = std::log(J[q]);
  double G[3][3][NN];  // G[c][d][q] = W_q (P J0^-T)_cd
  for (int q = 0; q < NN; ++q) {
    const double* jinv = jinv_all + 9 * q;
    // P = mu F + (lambda ln J - mu) F^-T with F^-T = C / J.
    const double inv_j = 1.0 / J[q];
    const double diag = lambda * ln_j[q] - mu;
    const double a = diag * inv_j;
    double Pm[9];
    for (int s = 0; s < 9; ++s) Pm[s] = mu * F[s][q] + a * C[s][q];
    // Cauchy sigma = P F^T / J = (mu (F F^T - I) + lambda ln J I) / J, formed from b = F F^T
    // directly so that it is exactly symmetric.
    auto b = [&](int i, int j) {
      return F[3 * i][q] * F[3 * j][q] + F[3 * i + 1][q] * F[3 * j + 1][q] +
             F[3 * i + 2][q] * F[3 * j + 2][q];
    };
    double* sq = stress + 6 * q;
    sq[0] = (mu * b(0, 0) + diag) * inv_j;
    sq[1] = (mu * b(1, 1) + diag) * inv_j;
    sq[2] = (mu * b(2, 2) + diag) * inv_j;
    sq[3] = mu * b(0, 1) * inv_j;
    sq[4] = mu * b(1, 2) * inv_j;
    sq[5] = mu * b(2, 0) * inv_j;
    const double W = w_all[q];
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d)
        G[i][d][q] = W * (Pm[3 * i] * jinv[3 * d] + Pm[3 * i + 1] * jinv[3 * d + 1] +
                          Pm[3 * i + 2] * jinv[3 * d + 2]);
  }
  double f[3][NN];
  for (int comp = 0; comp < 3; ++comp) reference_gradient_transpose<N>(D, G[comp], f[comp]);
  double sum = 0.0;
  for (int a = 0; a < NN; ++a) {
    out[3 * a + 0] = f[0][a];
    out[3 * a + 1] = f[1][a];
    out[3 * a + 2] = f[2][a];
    sum += f[0][a] + f[1][a] + f[2][a];
  }
  return std::isfinite(sum) && std::isfinite(vol);
}

// Smallest det F over the element's points, and the smallest squared spacing.
template <int P>
double element_min_jacobian(const HexBlock& block, std::size_t e, const NodalView& nv,
                            const double* D, double& volume, double& spacing2) {
  constexpr int N = P + 1, NN = N * N * N;
  double x[3][NN];
  gather<N>(&block.conn[NN * e], nv.x, nv.y, nv.z, x);
  spacing2 = min_spacing_squared<N>(x);
  double g[3][3][NN];
  for (int comp = 0; comp < 3; ++comp) reference_gradient<N>(D, x[comp], g[comp]);
  const double* jinv_all = &block.reference_inverse_jacobian[9 * NN * e];
  double jmin = std::numeric_limits<double>::infinity(), vol = 0.0;
  for (int q = 0; q < NN; ++q) {
    const double* jinv = jinv_all + 9 * q;
    double F[9], C[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        F[3 * i + j] = g[i][0][q] * jinv[j] + g[i][1][q] * jinv[3 + j] + g[i][2][q] * jinv[6 + j];
    const double J = cofactor(F, C);
    vol += block.reference_weight[NN * e + q] * J;
    jmin = std::isnan(J) ? J : std::min(jmin, J);
  }
  volume = vol;
  return jmin;
}

// f = K u at the reference configuration (small strain): sigma = lambda tr(eps) I + 2 mu eps.
template <int P>
void linear_stiffness(const HexBlock& block, std::size_t e, const double* D, const double* u,
                      double* fout) {
  constexpr int N = P + 1, NN = N * N * N;
  double uc[3][NN];
  for (int a = 0; a < NN; ++a)
    for (int i = 0; i < 3; ++i) uc[i][a] = u[3 * a + i];
  double g[3][3][NN];
  for (int comp = 0; comp < 3; ++comp) reference_gradient<N>(D, uc[comp], g[comp]);
  const double mu = block.material.shear, lambda = block.material.lambda;
  const double* jinv_all = &block.reference_inverse_jacobian[9 * NN * e];
  const double* w_all = &block.reference_weight[NN * e];
  double G[3][3][NN];
  for (int q = 0; q < NN; ++q) {
    const double* jinv = jinv_all + 9 * q;
    double H[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        H[3 * i + j] = g[i][0][q] * jinv[j] + g[i][1][q] * jinv[3 + j] + g[i][2][q] * jinv[6 + j];
    const double tr = H[0] + H[4] + H[8];
    double S[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) S[3 * i + j] = mu * (H[3 * i + j] + H[3 * j + i]);
    S[0] += lambda * tr;
    S[4] += lambda * tr;
    S[8] += lambda * tr;
    const double W = w_all[q];
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d)
        G[i][d][q] = W * (S[3 * i] * jinv[3 * d] + S[3 * i + 1] * jinv[3 * d + 1] +
                          S[3 * i + 2] * jinv[3 * d + 2]);
  }
  double f[3][NN];
  for (int comp = 0; comp < 3; ++comp) reference_gradient_transpose<N>(D, G[comp], f[comp]);
  for (int a = 0; a < NN; ++a)
    for (int i = 0; i < 3; ++i) fout[3 * a + i] = f[i][a];
}

// Reference geometry of element e: inverse Jacobians, weights, volume, spacing. Returns the
// smallest det J0 and (through `worst`) the point where it occurs.
template <int P>
double element_reference(HexBlock& block, std::size_t e, const NodalView& nv, const GllRule& rule,
                         int& worst) {
  constexpr int N = P + 1, NN = N * N * N;
  double x[3][NN];
  gather<N>(&block.conn[NN * e], nv.x, nv.y, nv.z, x);
  double g[3][3][NN];
  for (int comp = 0; comp < 3; ++comp)
    reference_gradient<N>(rule.derivative.data(), x[comp], g[comp]);
  double* jinv_all = &block.reference_inverse_jacobian[9 * NN * e];
  double* w_all = &block.reference_weight[NN * e];
  double det_min = std::numeric_limits<double>::infinity(), vol = 0.0;
  worst = 0;
  for (int q = 0; q < NN; ++q) {
    double J0[9], C[9];
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d) J0[3 * i + d] = g[i][d][q];
    const double det = cofactor(J0, C);
    if (!(det >= det_min)) {
      det_min = det;
      worst = q;
    }
    // J0^-1 = C^T / det: (J0^-1)_{d c} = C_{c d} / det.
    for (int d = 0; d < 3; ++d)
      for (int c = 0; c < 3; ++c) jinv_all[9 * q + 3 * d + c] = C[3 * c + d] / det;
    const int i = q % N, j = (q / N) % N, k = q / (N * N);
    w_all[q] = rule.weights[i] * rule.weights[j] * rule.weights[k] * det;
    vol += w_all[q];
  }
  block.volume0[e] = vol;
  block.volume[e] = vol;
  block.reference_length[e] = std::sqrt(min_spacing_squared<N>(x));
  return det_min;
}

// Dispatch on the block's order to a kernel instantiated for P = 2, 3.
template <class Fn>
decltype(auto) by_order(int order, Fn&& fn) {
  switch (order) {
    case 2:
      return fn(std::integral_constant<int, 2>{});
    case 3:
      return fn(std::integral_constant<int, 3>{});
    default:
      throw SolverError(
          fmt::format("Lagrange hexahedra of order {} are not supported (orders 2 "
                      "to {})",
                      order, kMaxLagrangeHexOrder));
  }
}

// Deterministic, generic start vector for Lanczos: a low-discrepancy sequence with no symmetry
// of the element, so that it has a component along the top eigenvector whatever the element's
// symmetry (a symmetric start such as all ones is a rigid translation, in the null space).
double start_component(int s) {
  const double golden = 0.6180339887498949;
  const double t = std::fmod(golden * (s + 1) + 0.5 * std::sqrt(2.0) * (s % 7), 1.0);
  return t - 0.5 + 0.01 * (s % 3);
}

}  // namespace

const GllRule& gll_rule(int order) {
  if (order < 1 || order > 8)
    throw std::invalid_argument(fmt::format("GLL rule of order {} requested (1 to 8)", order));
  // Built once, thread-safe (static local initialisation), never modified afterwards.
  static const std::array<GllRule, 8> rules = [] {
    std::array<GllRule, 8> r;
    for (int p = 1; p <= 8; ++p) r[p - 1] = make_rule(p);
    return r;
  }();
  return rules[order - 1];
}

void apply_linear_stiffness(const HexBlock& block, std::size_t element, const double* u,
                            double* f) {
  const double* D = gll_rule(block.order).derivative.data();
  by_order(block.order,
           [&](auto p) { linear_stiffness<decltype(p)::value>(block, element, D, u, f); });
}

EigenEstimate estimate_max_eigenvalue_detail(const HexBlock& block, std::size_t element) {
  const int npe = block.nodes_per_element();
  const int n = 3 * npe;
  const double rho = block.material.rho;
  if (!(rho > 0.0))
    throw SolverError(fmt::format("part {}: density {} must be positive for Lagrange hexahedra",
                                  block.part_id, rho));
  // A = M^-1/2 K M^-1/2 with M = rho W_q on each of the node's three components.
  std::vector<double> scale(n);
  for (int a = 0; a < npe; ++a) {
    const double m = rho * block.reference_weight[static_cast<std::size_t>(npe) * element + a];
    for (int i = 0; i < 3; ++i) scale[3 * a + i] = 1.0 / std::sqrt(m);
  }
  const int max_steps = std::min(n, 80);
  const double tolerance = 1e-4;
  std::vector<double> basis(static_cast<std::size_t>(max_steps + 1) * n);
  std::vector<double> u(n), w(n);
  std::vector<double> alpha, beta;
  auto v = [&](int k) { return basis.data() + static_cast<std::size_t>(k) * n; };
  auto dot = [n](const double* a, const double* b) {
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += a[i] * b[i];
    return s;
  };
  double norm = 0.0;
  for (int i = 0; i < n; ++i) {
    v(0)[i] = start_component(i);
    norm += v(0)[i] * v(0)[i];
  }
  norm = std::sqrt(norm);
  for (int i = 0; i < n; ++i) v(0)[i] /= norm;

  EigenEstimate result;
  double tscale = 0.0;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> tri;
  for (int k = 0; k < max_steps; ++k) {
    for (int i = 0; i < n; ++i) u[i] = scale[i] * v(k)[i];
    apply_linear_stiffness(block, element, u.data(), w.data());
    for (int i = 0; i < n; ++i) w[i] *= scale[i];
    alpha.push_back(dot(w.data(), v(k)));
    // Full reorthogonalisation (twice, "twice is enough": Parlett) keeps the basis orthogonal so
    // no spurious copies of converged Ritz values appear; cheap at these sizes.
    for (int pass = 0; pass < 2; ++pass)
      for (int j = 0; j <= k; ++j) {
        const double h = dot(w.data(), v(j));
        for (int i = 0; i < n; ++i) w[i] -= h * v(j)[i];
      }
    const double b = std::sqrt(dot(w.data(), w.data()));
    // Invariant subspace found (b ~ 0), or test whether the top Ritz pair has converged. The test
    // (a dense eigen solve of T_k) costs about as much as a stiffness application, so it runs from
    // step 8 (an accidentally small early residual is not taken for convergence) every 4 steps.
    tscale = std::max({tscale, std::abs(alpha.back()), b});  // ~ norm of T_k
    const bool last = k + 1 == max_steps || b <= 1e-14 * tscale;
    if (last || (k + 1 >= std::min(8, n) && (k + 1) % 4 == 0)) {
      Eigen::VectorXd diag = Eigen::Map<Eigen::VectorXd>(alpha.data(), k + 1);
      Eigen::VectorXd sub = Eigen::Map<Eigen::VectorXd>(beta.data(), k);
      tri.computeFromTridiagonal(diag, sub, Eigen::ComputeEigenvectors);
      result.ritz = tri.eigenvalues()[k];
      result.residual = b * std::abs(tri.eigenvectors()(k, k));
      result.steps = k + 1;
      if (last || result.residual <= tolerance * result.ritz) break;
    }
    beta.push_back(b);
    for (int i = 0; i < n; ++i) v(k + 1)[i] = w[i] / b;
  }
  result.estimate = result.ritz + result.residual;
  return result;
}

double estimate_max_eigenvalue(const HexBlock& block, std::size_t element) {
  return estimate_max_eigenvalue_detail(block, element).estimate;
}

void initialize_lagrange_hex_block(HexBlock& block, const NodalView& nodes) {
  if (block.order < 2 || block.order > kMaxLagrangeHexOrder)
    throw SolverError(
        fmt::format("part {}: Lagrange hexahedra of order {} are not supported "
                    "(orders 2 to {})",
                    block.part_id, block.order, kMaxLagrangeHexOrder));
  const std::size_t n = block.size();
  const std::size_t npe = static_cast<std::size_t>(block.nodes_per_element());
  if (block.conn.size() != npe * n)
    throw SolverError(
        fmt::format("part {}: order-{} hexahedron block has {} elements but {} "
                    "connectivity entries (expected {} per element)",
                    block.part_id, block.order, n, block.conn.size(), npe));
  block.stress.assign(6 * npe * n, 0.0);
  block.force.assign(3 * npe * n, 0.0);
  block.hourglass_state.clear();
  block.volume0.assign(n, 0.0);
  block.volume0_cbrt.assign(n, 0.0);
  block.volume.assign(n, 0.0);
  block.shape.assign(n, HexShape::kHexahedron);
  block.reference_inverse_jacobian.assign(9 * npe * n, 0.0);
  block.reference_weight.assign(npe * n, 0.0);
  block.reference_dt.assign(n, 0.0);
  block.reference_length.assign(n, 0.0);
  const GllRule& rule = gll_rule(block.order);

  // Elements are independent: parallel, with the lowest failing element reported (an exception
  // may not leave an OpenMP region).
  const std::int64_t count = static_cast<std::int64_t>(n);
  std::int64_t bad = count;
#pragma omp parallel for schedule(dynamic, 16) reduction(min : bad) num_threads(thread_count())
  for (std::int64_t ie = 0; ie < count; ++ie) {
    const std::size_t e = static_cast<std::size_t>(ie);
    int worst = 0;
    const double det = by_order(block.order, [&](auto p) {
      return element_reference<decltype(p)::value>(block, e, nodes, rule, worst);
    });
    if (!(det > 0.0)) {
      bad = std::min(bad, ie);
      continue;
    }
    block.volume0_cbrt[e] = std::cbrt(block.volume0[e]);
    const double lambda_max = estimate_max_eigenvalue(block, e);
    block.reference_dt[e] = lambda_max > 0.0 ? 2.0 / std::sqrt(lambda_max) : 1e300;
  }
  if (bad < count) {
    const std::size_t e = static_cast<std::size_t>(bad);
    int worst = 0;
    const double det = by_order(block.order, [&](auto p) {
      return element_reference<decltype(p)::value>(block, e, nodes, rule, worst);
    });
    const int m = block.order + 1;
    throw SolverError(fmt::format(
        "element {} of part {} (order {}): det(dX/dxi) = {:.6g} <= 0 at GLL point ({}, {}, {}): "
        "the element is inverted or folded; check that nodes 1-4 run counter-clockwise seen from "
        "nodes 5-8 and that nodes moved onto curved surfaces keep the element convex enough",
        block.element_id[e], block.part_id, block.order, det, worst % m, (worst / m) % m,
        worst / (m * m)));
  }
}

KernelResult compute_lagrange_hex_forces(HexBlock& block, const NodalView& nodes, double dt) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t items = block.owned.count(static_cast<std::int64_t>(block.size()));
  const double* D = gll_rule(block.order).derivative.data();
  int threads = 1;
  by_order(block.order, [&](auto p) {
#pragma omp parallel num_threads(thread_count())
    {
      Partial local;
#pragma omp for schedule(static)
      for (std::int64_t i = 0; i < items; ++i) {
        const std::int64_t ie = block.owned.element(i);
        const std::size_t e = static_cast<std::size_t>(ie);
        double volume = 0.0, spacing2 = 0.0;
        const bool ok = element_forces<decltype(p)::value>(block, e, nodes, D, volume, spacing2);
        block.volume[e] = volume;
        if (!ok) {
          local.record_failure(ie, volume);
          continue;
        }
        local.record_dt(block.reference_dt[e] * std::sqrt(spacing2) / block.reference_length[e],
                        ie);
      }
      partials[omp_get_thread_num()] = local;
#pragma omp single
      threads = omp_get_num_threads();
    }
  });
  return combine(partials, threads);
}

KernelResult lagrange_hex_critical_timestep(const HexBlock& block, const NodalView& nodes) {
  std::array<Partial, kMaxThreads> partials;
  const std::int64_t n = static_cast<std::int64_t>(block.size());
  const double* D = gll_rule(block.order).derivative.data();
  int threads = 1;
  by_order(block.order, [&](auto p) {
#pragma omp parallel num_threads(thread_count())
    {
      Partial local;
#pragma omp for schedule(static)
      for (std::int64_t ie = 0; ie < n; ++ie) {
        const std::size_t e = static_cast<std::size_t>(ie);
        double volume = 0.0, spacing2 = 0.0;
        const double jmin =
            element_min_jacobian<decltype(p)::value>(block, e, nodes, D, volume, spacing2);
        if (!(jmin > 0.0) || !std::isfinite(volume)) {
          local.record_failure(ie, volume);
          continue;
        }
        local.record_dt(block.reference_dt[e] * std::sqrt(spacing2) / block.reference_length[e],
                        ie);
      }
      partials[omp_get_thread_num()] = local;
#pragma omp single
      threads = omp_get_num_threads();
    }
  });
  return combine(partials, threads);
}

void add_lagrange_hex_lumped_mass(const HexBlock& block, std::vector<double>& nodal_mass) {
  // conn and reference_weight share the slot order (element-major, node a at GLL point a).
  for (std::size_t s = 0; s < block.conn.size(); ++s)
    nodal_mass[static_cast<std::size_t>(block.conn[s])] +=
        block.material.rho * block.reference_weight[s];
}

}  // namespace rf::element
