// Contiguous batch of 8-node hexahedra that share part, section, material and hourglass
// settings. Kernels loop over a block with no per-element dispatch.
#pragma once

#include <cstdint>
#include <vector>

#include "element/element_ownership.hpp"
#include "element/erosion_state.hpp"
#include "element/nodal_averaging.hpp"
#include "material/elastic.hpp"
#include "material/history.hpp"
#include "material/hyperelastic.hpp"
#include "material/johnson_cook.hpp"
#include "material/plastic_parameters.hpp"
#include "model/model.hpp"

namespace rf::element {

// SIGN CONVENTION. block.force holds INTERNAL nodal forces f_int = integral B^T sigma dV (plus
// hourglass resisting forces), and the solver forms a = (f_ext - f_int) / m. A stretched element
// (sigma_xx > 0) therefore has f_int pointing OUTWARD at its nodes, and -f_int pulls the nodes
// inward; hourglass forces likewise have the sign of the hourglass velocity they resist.
//
// Degenerate hexahedra use LS-DYNA's connectivity conventions: tetrahedron n1 n2 n3 n4 n4 n4 n4
// n4, pyramid n1 n2 n3 n4 n5 n5 n5 n5, pentahedron/wedge n1 n2 n3 n4 n5 n5 n6 n6. See
// hex_block.cpp for how each is treated.

// Shape of an element as detected from its connectivity by initialize_hex_block.
enum class HexShape : std::uint8_t {
  kHexahedron = 0,
  kWedge = 1,        // 6 distinct nodes
  kPyramid = 2,      // 5 distinct nodes
  kTetrahedron = 3,  // 4 distinct nodes
  kOtherDegenerate = 4,
};

// Read-only view of the nodal arrays a kernel needs (struct-of-arrays, dense indices).
struct NodalView {
  const double* x;  // current coordinates x^{n+1}
  const double* y;
  const double* z;
  const double* vx;  // velocity v^{n+1/2}
  const double* vy;
  const double* vz;
};

// Hourglass settings resolved for a block (part HGID, else *CONTROL_HOURGLASS).
struct HourglassSettings {
  int ihq = 1;      // 1-3 viscous (Flanagan-Belytschko), 4-5 stiffness, 6 Belytschko-Bindeman
  double qm = 0.1;  // coefficient
};

// Artificial bulk viscosity of a block (part *HOURGLASS Q1/Q2, else *CONTROL_BULK_VISCOSITY;
// docs/theory.md): q = rho l (q1 l e_kk^2 - q2 c e_kk) while the volume shrinks (e_kk < 0).
// Both zero: off (IMPETUS decks, Lagrange hexahedra).
struct BulkViscositySettings {
  double q1 = 0.0;  // quadratic coefficient
  double q2 = 0.0;  // linear coefficient
  bool on() const { return q1 > 0.0 || q2 > 0.0; }
};

struct HexBlock {
  model::Id part_id = 0;
  int part_index = 0;
  // 1: one-point + hourglass (also ELFORM 10 tetrahedra); 2: selective-reduced (2x2x2
  // deviatoric, 1pt volumetric); 13: nodal-pressure tetrahedron (element/tet13_block.hpp);
  // 16: 10-node quadratic tetrahedron, 4-point rule (element/tet10_block.hpp)
  int elform = 1;
  HourglassSettings hourglass;
  BulkViscositySettings bulk_viscosity;
  // Elastic constants of every material (wave speed, hourglass, contact stiffness), then the
  // material's own: index in material::SolidMaterials (material/registry.hpp) selects the stress
  // update once per block; plasticity parameters for the J2 materials.
  material::ElasticConstants material;
  int material_index = 0;
  material::PlasticParameters plastic;
  material::HyperelasticParameters hyperelastic;  // *MAT_027, *MAT_077_O
  material::JohnsonCookParameters johnson_cook;   // *MAT_015 (+ *EOS_)
  // Elements of a *MAT_RIGID part: they give mass and appear in the output, but have no kernel
  // and no force slots in the assembly (the body moves their nodes).
  bool rigid = false;
  // Whether the block has force slots in the assembly (State::incidence, AssemblyPlan): set
  // when the state is built (not for *MAT_RIGID parts) and kept when part switching makes the
  // block rigid for a while (its slots then hold zeros).
  bool has_force_slots = true;
  // The elements this process computes (element_ownership.hpp; all of them in one process).
  ElementOwnership owned;
  // Failed elements (element/erosion_state.hpp); disabled for blocks without a failure criterion.
  ErosionState erosion;
  // Polynomial order of the element's interpolation. 1: the 8-node hexahedron (elform applies);
  // 2 or 3: tensor-product Lagrange hexahedron on Gauss-Lobatto-Legendre points with (p+1)^3
  // nodes and GLL quadrature, total-Lagrangian (element/lagrange_hex.hpp; elform is ignored).
  int order = 1;

  std::vector<model::Id> element_id;  // user IDs, size n
  std::vector<std::int32_t> conn;     // dense node indices, 8 per element

  // Per-element state, struct-of-arrays where it is streamed.
  // Cauchy stress, Voigt order xx,yy,zz,xy,yz,zx; 6 * points_per_element() per element.
  std::vector<double> stress;
  // History variables of the material, one array per registered field, each with
  // field.components values per stress point (material/history.hpp). Empty for elastic blocks.
  std::vector<material::HistoryArray> history;
  // Accumulated hourglass generalized forces for the stiffness forms (IHQ 4,5,6): 12 per element.
  std::vector<double> hourglass_state;
  std::vector<double> volume0;  // reference volume
  // sqrt(s_e) of mass scaling (solver/mass_scaling.hpp): the element's mass is s_e times its
  // physical mass, so its step is sqrt(s_e) times longer. Empty without mass scaling.
  std::vector<double> step_scale;
  std::vector<double> volume0_cbrt;  // V0^{1/3}, scales the viscous hourglass coefficient
  std::vector<double> volume;        // current volume
  // Element nodal forces of the last evaluation, 3 * nodes_per_element() per element (node-major:
  // f0x,f0y,f0z,...).
  std::vector<double> force;
  // Shape detected from the connectivity (initialize_hex_block), one per element.
  std::vector<HexShape> shape;
  // ELFORM 13 only: corners, node -> element lists and scratch of the nodal averaging.
  NodalAveraging nodal_averaging;

  // Order > 1 only (see lagrange_hex.hpp). Per quadrature point: the inverse reference Jacobian
  // dxi/dX (9, row-major) and the weight w_q det(dX/dxi); per element: the critical step and the
  // characteristic length at the reference configuration, which scale the step during the run.
  std::vector<double> reference_inverse_jacobian;
  std::vector<double> reference_weight;
  std::vector<double> reference_dt;
  std::vector<double> reference_length;

  std::size_t size() const { return element_id.size(); }
  // Nodes of one element in conn: 8 for order 1 (degenerate shapes repeat IDs), (p+1)^3 above,
  // numbered in tensor order i + (p+1) (j + (p+1) k) along the reference axes xi, eta, zeta
  // (xi from hex node 1 to 2, eta from 1 to 4, zeta from 1 to 5).
  // ELFORM 16: 10, corners N1..N4 then the mid-side nodes of edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
  int nodes_per_element() const {
    if (elform == 16) return 10;
    return order == 1 ? 8 : (order + 1) * (order + 1) * (order + 1);
  }
  // Stress points: 1 (ELFORM 1), 8 (ELFORM 2), 4 (ELFORM 16), (p+1)^3 GLL points (order > 1).
  int points_per_element() const {
    if (elform == 16) return 4;
    if (order > 1) return nodes_per_element();
    return elform == 2 ? 8 : 1;
  }
  // Whether the block holds 10-node quadratic tetrahedra (ELFORM 16, element/tet10_block.hpp).
  bool quadratic_tetrahedra() const { return elform == 16; }
};

// What one pass of a kernel over a block reports back to the solver.
struct KernelResult {
  double hourglass_work = 0.0;       // work done by hourglass forces this step (energy units)
  double bulk_viscosity_work = 0.0;  // work done by the bulk viscosity pressure this step
  double min_dt = 1e300;             // smallest critical step over the block (no TSSFAC)
  std::int64_t min_dt_element = -1;  // index within the block
  bool failed = false;               // negative/zero volume or non-finite result
  std::int64_t failed_element = -1;
  double failed_volume = 0.0;
};

// Finds a history array by name (nullptr if the block's material has none).
const material::HistoryArray* find_history(const HexBlock& block, std::string_view name);

// Sizes block.history for the block's material (zeros), points_per_element() points each.
void allocate_history(HexBlock& block);

// Allocates per-element state and computes reference volumes. Throws rf::SolverError naming
// the element if a volume is not positive.
void initialize_hex_block(HexBlock& block, const NodalView& nodes);

// Internal forces of every element of the block at x^{n+1} with strain rate from v^{n+1/2},
// updating stresses and hourglass state over a step dt. Element forces go to block.force.
// OpenMP-parallel over elements; no shared writes.
KernelResult compute_hex_forces(HexBlock& block, const NodalView& nodes, double dt);

// Critical time step of each element at the current configuration (L_e / c), minimum reported.
// `raw_steps` (optional) receives every element's step without mass scaling (0 where failed).
KernelResult hex_critical_timestep(const HexBlock& block, const NodalView& nodes,
                                   std::vector<double>* raw_steps = nullptr);

// Lumped mass: rho * V0 / 8 to each node (degenerate hexes: per distinct node, see docs).
// `element_factor` (optional): each element's share multiplied by it (mass scaling's added mass).
void add_hex_lumped_mass(const HexBlock& block, std::vector<double>& nodal_mass,
                         const std::vector<double>* element_factor = nullptr);

// Number of distinct nodes of an 8-entry connectivity (8 for a proper hexahedron).
int distinct_node_count(const std::int32_t* conn8);

}  // namespace rf::element
