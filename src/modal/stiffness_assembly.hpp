// Linear stiffness and lumped mass of a sub-model, consistent with the explicit solver.
//
// The state (nodes, blocks, lumped mass, *CHANGE_P-ORDER elevation) is built by the explicit
// solver's own solver::build_state, so the mass is exactly the one the time loop uses. Each
// element stiffness matrix is obtained from the explicit element kernel itself by central
// differences of its internal force: column j of K_e = (f(+h e_j) - f(-h e_j)) / 2h, where
// f(u) is one kernel pass from the stress-free reference with displacement u = v dt (v = e_j,
// dt = h). All elements of a block are probed at once on a copy of the mesh in which every
// element has its own nodes, so one probe is one vectorised, OpenMP-parallel kernel pass over
// the block: 2 x 24 passes for a linear hexahedron, 2 x 3 (p+1)^3 for order p. The kernels are
// linear in u up to O(u^2) geometric terms, which the central difference cancels; the result is
// the tangent stiffness at the reference state, i.e. the stiffness the explicit solver has for
// small motions (checked in tests against kernel forces of a whole mesh).
//
// Viscous hourglass control (IHQ 1-3) has no stiffness: the hourglass modes of ELFORM 1 would
// be zero-energy modes. Those blocks are probed with the Belytschko-Bindeman stiffness (IHQ 6,
// same QM) and a warning says so (docs/eigen.md).
#pragma once

#include <Eigen/Sparse>
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "solver/state.hpp"

namespace rf::modal {

// DOF numbering: translations first, DOF 3 i + d of dense node i (d = x, y, z), then the
// rotations of the nodes of shells and beams (solver::RotationalState), DOF 3 n + 3 r + d of
// rotational index r. A solid-only model has 3 n DOFs, as before shells and beams.
struct StructuralMatrices {
  solver::State state;                    // the explicit solver's state of the sub-model
  std::vector<model::Id> node_parts;      // per node: the part of the first element using it
  Eigen::SparseMatrix<double> stiffness;  // (3n + 3r)^2
  // 3n + 3r: lumped node mass repeated for x, y, z, then the lumped rotational inertia of the
  // explicit solver (the scaled rotary inertia of shells and beams, docs/eigen.md) repeated.
  Eigen::VectorXd mass;
  // 3n + 3r: 1 where *BOUNDARY_SPC / *NODE TC / RC fixes the DOF.
  std::vector<std::uint8_t> fixed;
  std::size_t translation_dofs() const { return 3 * state.nodes.size(); }
  std::size_t rotation_count() const { return state.rotations.size(); }
  // User ID of the node of a DOF.
  model::Id node_of_dof(std::size_t dof) const;
  // Largest |K_e - K_e^T| / max |K_e| over the element matrices before symmetrisation.
  double element_asymmetry = 0.0;
  std::vector<std::string> warnings;
};

// A copy of `model` holding only the elements of `parts` (empty: all), the nodes they use and
// the SPCs on those nodes (node sets are restricted to them). Loads, prescribed motion, initial
// velocities, rigid-body constraints, walls, sensors and switching are dropped. *MAT_RIGID parts
// among `parts` become elastic with the card's RO, E, PR (the usual *PART_MODES workflow keeps
// the transient deck, where the part is rigid). Throws rf::InputError for unknown parts.
model::Model extract_parts(const model::Model& model, const std::vector<model::Id>& parts,
                           std::vector<std::string>* warnings = nullptr);

// Stiffness matrices of the elements [first, first + count) of `block` (reference
// configuration), (3 npe)^2 each, row-major, DOF 3 a + d of local node a. Exposed for tests.
std::vector<double> element_stiffness_matrices(const element::HexBlock& block,
                                               const solver::NodalState& nodes, std::size_t first,
                                               std::size_t count);

// Drilling stiffness factor: k = kDrillingFactor G t A per shell element (docs/eigen.md).
inline constexpr double kDrillingFactor = 1e-3;

// Stiffness matrices of the elements [first, first + count) of a shell or beam block
// (reference configuration), (6 npe)^2 each (npe 4 shells, 2 beams), row-major, DOF 6 a + d of
// local node a (d 0-2 translations, 3-5 rotations; zero rows and columns for a truss's rotations
// and a triangle's repeated node). Shell blocks get the drilling stiffness of docs/eigen.md with
// `drilling_factor` (0: the kernel's stiffness alone, for tests).
// Exposed for tests.
std::vector<double> element_stiffness_matrices(const element::ShellBlock& block,
                                               const solver::NodalState& nodes, std::size_t first,
                                               std::size_t count,
                                               double drilling_factor = kDrillingFactor);
std::vector<double> element_stiffness_matrices(const element::BeamBlock& block,
                                               const solver::NodalState& nodes, std::size_t first,
                                               std::size_t count);

// Rotational inertia of the nodes of shells and beams in M (docs/eigen.md). kPhysical: the
// rotary inertia of the continuum, lumped: rho t^3 / 12 per unit area of shell (Mindlin), and
// rho (Iss + Itt) L / 2 per beam node (the polar moment, so that torsion is exact; bending of a
// slender beam hardly depends on it). kExplicit: the explicit solver's scaled rotary inertia
// (add_shell_lumped_mass, add_beam_lumped_mass), much larger, which lowers bending frequencies
// by O(element size) but is the mass the time loop integrates with.
enum class RotaryInertia { kPhysical, kExplicit };

// Builds the state of the sub-model of `parts` and assembles K (OpenMP over elements) and M.
StructuralMatrices assemble_structural_matrices(const model::Model& model,
                                                const std::vector<model::Id>& parts,
                                                RotaryInertia inertia = RotaryInertia::kPhysical,
                                                double drilling_factor = kDrillingFactor);

}  // namespace rf::modal
