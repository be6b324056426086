// Higher-order hexahedra: tensor-product Lagrange interpolation of order p on the
// Gauss-Lobatto-Legendre (GLL) points, integrated with the GLL rule on the same points (the
// spectral-element choice: Patera, J. Comput. Phys. 54, 1984; Komatitsch & Tromp, GJI 139, 1999).
// Because quadrature points and nodes coincide, the consistent mass integrated by that rule is
// diagonal: the lumped mass is exact for the rule, not an approximation added on top.
//
// Kinematics are total-Lagrangian: F = dx/dX at every GLL point from the current coordinates and
// the reference Jacobian stored at set-up. The material is a compressible neo-Hookean solid whose
// small-strain limit is *MAT_ELASTIC's linear elasticity with the same lambda and mu:
//   P = mu (F - F^-T) + lambda ln(J) F^-T
// (Bonet & Wood, Nonlinear Continuum Mechanics for FEA, 2nd ed., eq. 6.28 for the Cauchy stress
// sigma = (mu (b - I) + lambda ln(J) I) / J, pulled back by P = J sigma F^-T). It is objective
// under any rotation: a rigid rotation gives P = 0 exactly.
//
// Gradients and internal forces use sum factorisation: the 1D differentiation matrix D is applied
// along grid lines, O(p^4) per element instead of O(p^6) with stored B matrices (Orszag, J.
// Comput. Phys. 37, 1980).
//
// Node numbering of an element: tensor order i + (p+1) (j + (p+1) k), i along xi (hex node 1 to
// 2), j along eta (1 to 4), k along zeta (1 to 5); i = 0 is xi = -1. Node a sits at GLL point a.
#pragma once

#include <cstddef>
#include <vector>

#include "element/hex_block.hpp"

namespace rf::element {

// GLL points on [-1, 1] (ascending), weights, and D[i * (p + 1) + j] = l_j'(xi_i), the derivative
// of the j-th Lagrange polynomial on these points, evaluated at point i.
struct GllRule {
  int order = 1;
  std::vector<double> points;
  std::vector<double> weights;
  std::vector<double> derivative;
};

// Orders 1..8 (Newton iteration on the roots of (1 - x^2) P_p'(x); exact to round-off). The rules
// are computed once and cached; the reference stays valid for the life of the program. Throws
// std::invalid_argument for other orders.
const GllRule& gll_rule(int order);

// Orders the element kernels below are compiled for (the GLL rule itself goes to 8).
constexpr int kMaxLagrangeHexOrder = 3;

// For blocks with order 2 or 3: reference Jacobians and weights at every GLL point, reference
// volumes, stress/force storage, the characteristic length (smallest distance between adjacent
// GLL nodes along grid lines) and the critical step 2 / omega_max at the reference configuration
// (see estimate_max_eigenvalue). Throws rf::SolverError naming the element's user ID when
// det(dX/dxi) <= 0 at a GLL point, or when the block is not a supported order.
void initialize_lagrange_hex_block(HexBlock& block, const NodalView& nodes);

// Internal forces at the current coordinates (total-Lagrangian, neo-Hookean) into block.force,
// Cauchy stress at every GLL point into block.stress, current volumes, and the smallest critical
// step: the reference step scaled by the ratio of the current to the reference smallest GLL node
// spacing. `dt` is unused (the material is hyperelastic) and kept for the common kernel signature.
// Reports failed (with the first such element) when J <= 0 at a point or a result is not finite.
// OpenMP-parallel over elements, static schedule, deterministic for a given thread count.
KernelResult compute_lagrange_hex_forces(HexBlock& block, const NodalView& nodes, double dt);

// Smallest critical step over the block at the current coordinates, no force evaluation (failed
// when J <= 0 at a point).
KernelResult lagrange_hex_critical_timestep(const HexBlock& block, const NodalView& nodes);

// rho * w_q * det J0 to the node at GLL point q (nodal_mass indexed by dense node index).
void add_lagrange_hex_lumped_mass(const HexBlock& block, std::vector<double>& nodal_mass);

// Largest eigenvalue omega^2 of K_e phi = omega^2 M_e phi for element e of an initialized block
// (linear elastic stiffness at the reference configuration, GLL-lumped mass), raised to an upper
// bound: Lanczos on M^-1/2 K M^-1/2 (matrix-free), Ritz value plus its residual norm (see the
// definition for why). Exposed for tests; initialize_lagrange_hex_block uses it for reference_dt.
double estimate_max_eigenvalue(const HexBlock& block, std::size_t element);

// Diagnostics of the estimate above: the largest Ritz value (a lower bound of omega^2_max), the
// norm of its residual, the number of Lanczos steps taken, and the returned estimate.
struct EigenEstimate {
  double ritz = 0.0;
  double residual = 0.0;
  int steps = 0;
  double estimate = 0.0;
};
EigenEstimate estimate_max_eigenvalue_detail(const HexBlock& block, std::size_t element);

// The element's small-strain stiffness applied to a displacement vector u (3 per node,
// node-major): f = K_e u, linear elasticity at the reference configuration, through the same
// sum-factorised gradient and divergence operators as the force kernel. Exposed for tests.
void apply_linear_stiffness(const HexBlock& block, std::size_t element, const double* u, double* f);

}  // namespace rf::element
