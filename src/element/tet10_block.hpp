// The 10-node quadratic tetrahedron (*SECTION_SOLID ELFORM 16): a HexBlock whose elements have
// 10 nodes in LS-DYNA's order (corners N1..N4, then the mid-side nodes of edges 1-2, 2-3, 3-1,
// 1-4, 2-4, 3-4; the VTK_QUADRATIC_TETRA order), integrated with the 4-point rule. The equations
// are in tet10_block.cpp and docs/theory.md ("Tetrahedra (ELFORM 16)").
#pragma once

#include <string>

#include "element/hex_block.hpp"

namespace rf::element {

inline constexpr int kTet10Nodes = 10;
inline constexpr int kTet10Points = 4;
// Corner pairs of the six edges, in the order of the mid-side nodes N5..N10.
inline constexpr int kTet10Edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
// Lumped mass fractions of the element mass rho V (HRZ diagonal scaling, tet10_block.cpp).
inline constexpr double kTet10CornerMass = 1.0 / 36.0;
inline constexpr double kTet10MidsideMass = 4.0 / 27.0;
// Mid-side nodes farther than this fraction of the edge length from the edge's midpoint are
// refused (a swapped node order, not a curved edge).
inline constexpr double kTet10MidsideTolerance = 0.25;

// What is wrong with a 10-node tetrahedron at coordinates x (LS-DYNA order), or "" if nothing:
// a mid-side node too far from its edge midpoint (kTet10MidsideTolerance), or a Jacobian
// determinant that is not positive at a node or an integration point (inverted, degenerate, or
// too curved). The text names the node (N1..N10) or point.
std::string tet10_geometry_problem(const double x[kTet10Nodes][3]);

// Allocates the per-element state (6 stresses and the material history at each of the 4
// points, 30 force slots) and computes the reference volumes. Throws rf::SolverError naming the
// element if tet10_geometry_problem finds a problem.
void initialize_tet10_block(HexBlock& block, const NodalView& nodes);

// Internal forces of every owned element at x^{n+1}, with the velocity gradient of v^{n+1/2}
// at the mid-step configuration at each point, the material update at each point, the forces
// f_a = sum_q w_q det J_q (sigma_q - q_q I) grad N_a(xi_q) into block.force, current volumes and
// the smallest critical step. OpenMP-parallel over elements, no shared writes, no allocation.
KernelResult compute_tet10_forces(HexBlock& block, const NodalView& nodes, double dt);

// Smallest critical step over the block at the current coordinates (no force evaluation).
// `raw_steps` (optional) receives every element's step without mass scaling.
KernelResult tet10_critical_timestep(const HexBlock& block, const NodalView& nodes,
                                     std::vector<double>* raw_steps = nullptr);

// Characteristic length of one element at coordinates x: (1/4) min over the integration points
// of det J / max_a |c_a(J)|, the smallest altitude of the affine tetrahedron spanned by the
// columns of J (for a straight-sided element, the smallest altitude of its corner tetrahedron).
// Returns a non-positive value when det J <= 0 at a point. The step is this length over the
// dilatational wave speed (tet10_block.cpp explains the factor 1/4).
double tet10_characteristic_length(const double x[kTet10Nodes][3]);

// Lumped mass: rho V0 / 36 to each corner, 4 rho V0 / 27 to each mid-side node (HRZ).
// `element_factor` (optional): each element's share multiplied by it.
void add_tet10_lumped_mass(const HexBlock& block, std::vector<double>& nodal_mass,
                           const std::vector<double>* element_factor = nullptr);

}  // namespace rf::element
