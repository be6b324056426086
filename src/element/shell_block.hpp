// Contiguous batch of 4-node shells (N3 = N4: triangles) that share part, section, material and
// hourglass settings: the shell element family (issue 16). Nodes of shells carry rotations; the
// rotational degrees of freedom live in solver::RotationalState, indexed by a rotational index
// that the block stores next to the nodal connectivity (`rotation_conn`).
//
// SIGN CONVENTION as for solids (hex_block.hpp): block.force holds INTERNAL nodal forces and
// moments; the solver forms a = (f_ext - f_int) / m and alpha = (m_ext - m_int) / I.
//
// Stresses are stored in the element's co-rotational frame (Belytschko, Lin and Tsay 1984): the
// frame turns with the element, so a rigid rotation leaves them unchanged (objectivity) and a
// switch to rigid and back needs no rotation of the shell stresses.
#pragma once

#include <cstdint>
#include <vector>

#include "element/element_ownership.hpp"
#include "element/erosion_state.hpp"
#include "element/hex_block.hpp"  // NodalView, HourglassSettings, KernelResult
#include "material/barlat.hpp"
#include "material/elastic.hpp"
#include "material/history.hpp"
#include "material/plastic_parameters.hpp"
#include "model/model.hpp"

namespace rf::element {

// Angular velocities omega^{n+1/2} by rotational index (struct-of-arrays).
struct RotationalView {
  const double* wx;
  const double* wy;
  const double* wz;
};

// Through-thickness integration rule of *SECTION_SHELL (QR/IRID < 0 user rules: not supported).
enum class ThroughThicknessRule : std::uint8_t { kGauss = 0, kLobatto = 1 };

// Force and moment entries per element: 4 nodes x (fx, fy, fz, mx, my, mz), node-major, global.
inline constexpr int kShellSlot = 24;
// Stress components stored per integration point, co-rotational frame: xx, yy, xy, yz, zx
// (plane stress: sigma_zz = 0).
inline constexpr int kShellStress = 5;

struct ShellBlock {
  model::Id part_id = 0;
  int part_index = 0;
  int elform = 2;  // 2: Belytschko-Lin-Tsay (one point in the plane); 16: fully integrated
  HourglassSettings hourglass;
  // *CONTROL_BULK_VISCOSITY TYPE -1/-2 (with the part's *HOURGLASS Q1/Q2): the membrane bulk
  // viscosity of shell_block.cpp, section 10. Off (both zero) with TYPE 1, as in LS-DYNA.
  BulkViscositySettings bulk_viscosity;
  material::ElasticConstants material;
  int material_index = 0;  // index in material::SolidMaterials (registry.hpp)
  material::PlasticParameters plastic;
  material::BarlatParameters barlat;  // *MAT_036 (material/barlat.hpp)
  bool rigid = false;
  // The elements this process computes (element_ownership.hpp; all of them in one process).
  ElementOwnership owned;
  // Failed elements (element/erosion_state.hpp); disabled for blocks without a failure criterion.
  ErosionState erosion;
  bool has_force_slots = true;

  // Section (*SECTION_SHELL): transverse shear factor SHRF, NIP points through the thickness
  // (1..10) of rule `rule`. zeta in [-1, 1] from bottom to top, weights summing to 2.
  double shear_factor = 5.0 / 6.0;
  int nip = 2;
  ThroughThicknessRule rule = ThroughThicknessRule::kGauss;
  std::vector<double> zeta;    // nip
  std::vector<double> weight;  // nip
  // Belytschko-Wong-Chiang warping correction (*CONTROL_SHELL BWC = 1 turns it on for ELFORM 2;
  // LS-DYNA's default BWC = 2 leaves it off).
  bool warping_correction = false;
  // *CONTROL_SHELL ISTUPD: 0 constant thickness; 1 the membrane straining changes the thickness
  // (elastic and plastic through-thickness strain); 4 the same with the elastic strains
  // neglected (shell_block.cpp, section 12).
  int thickness_update = 0;

  std::vector<model::Id> element_id;  // user IDs, size n
  std::vector<std::int32_t> conn;     // dense node indices, 4 per element (N3 == N4: triangle)
  std::vector<std::int32_t> rotation_conn;  // rotational indices of the same nodes, 4 per element
  std::vector<double> thickness;            // nodal thicknesses T1..T4, 4 per element
  std::vector<std::uint8_t> triangle;       // 1 where N3 == N4

  // Per-element state.
  // Stress: kShellStress per point, nip points per element (ELFORM 16: 4 x nip), co-rotational.
  std::vector<double> stress;
  std::vector<material::HistoryArray> history;  // per point, as for solids (material/history.hpp)
  // Hourglass generalized forces, 5 per element (in-plane x, y; out-of-plane w; two
  // rotational), co-rotational frame: the accumulated forces of the stiffness forms (IHQ 4, 5),
  // the last step's forces of the viscous forms (IHQ 1-3, for the trapezoidal work).
  std::vector<double> hourglass_state;
  std::vector<double> area0;  // reference mid-surface area
  // sqrt(s_e) of mass scaling (solver/mass_scaling.hpp): the element's mass is s_e times its
  // physical mass, so its step is sqrt(s_e) times longer. Empty without mass scaling.
  std::vector<double> step_scale;
  // Current element thickness: at initialisation the mean of the nodal thicknesses of the
  // distinct nodes, then changed by the kernel with a thickness update (thickness_update != 0).
  // Everything that needs the shell's present thickness reads this one (forces, hourglass,
  // frozen energy of a switch, output).
  std::vector<double> element_thickness;
  // The initial element thickness (the same mean, never changed): the element's mass
  // rho t0 A0 and rotary inertia, which a thickness change leaves alone (mass is conserved).
  std::vector<double> element_thickness0;
  std::vector<double> area;  // current area
  // Anisotropic materials (*MAT_036): cosine and sine of the angle from the element's side 1-2
  // (co-rotational e1) to the material's rolling direction, 2 per element, fixed at
  // initialisation from the reference geometry and AOPT (the axes turn with the element).
  // Empty for isotropic materials.
  std::vector<double> material_axes;
  // Element forces and moments of the last evaluation, kShellSlot per element.
  std::vector<double> force;
  // Strain integrated from the rate of deformation at every point (xx, yy and the tensor
  // component xy, co-rotational like the stress), 3 per point; allocated only when an erosion
  // criterion needs it (solver/erosion.cpp), empty otherwise and then never touched.
  std::vector<double> strain;

  std::size_t size() const { return element_id.size(); }
  int in_plane_points() const { return elform == 16 ? 4 : 1; }
  int points_per_element() const { return in_plane_points() * nip; }
};

// Fills zeta/weight for the block's rule and nip, allocates per-element state and computes
// reference areas. Throws rf::InputError-free rf::SolverError naming the element when an
// element is degenerate (zero area) or a thickness is not positive.
void initialize_shell_block(ShellBlock& block, const NodalView& nodes);

// Internal forces and moments at x^{n+1} with rates from v^{n+1/2}, omega^{n+1/2}, over a step
// dt; stresses and hourglass state updated. Results to block.force. OpenMP-parallel over
// elements, no shared writes.
KernelResult compute_shell_forces(ShellBlock& block, const NodalView& nodes,
                                  const RotationalView& rotations, double dt);

// Critical step of each element at the current configuration (no TSSFAC), minimum reported:
// dt = L_s / c, L_s = (1 + beta) A / max(side), beta = 0 quads, 1 triangles (LS-DYNA ISDO 0),
// c = sqrt(E / (rho (1 - nu^2))). (At rest: the bulk viscosity, which compute_shell_forces
// includes, acts only while an element's area shrinks.)
// `raw_steps` (optional) receives every element's step without mass scaling (0 where failed).
KernelResult shell_critical_timestep(const ShellBlock& block, const NodalView& nodes,
                                     std::vector<double>* raw_steps = nullptr);

// Lumped translational mass (to nodal_mass by dense node index) and rotational inertia (to
// rotational_inertia by rotational index). Per distinct node of an element with mass
// m = rho t0 A0 / (number of distinct nodes): rotational inertia m (A0 / 4 + t0^2 / 12) about
// every axis (scaled rotary inertia, see shell_block.cpp), so that rotations never govern the
// step. t0 the initial thickness: a thickness update changes neither (section 12).
// `element_factor` (optional): each element's shares multiplied by it (mass scaling).
void add_shell_lumped_mass(const ShellBlock& block, std::vector<double>& nodal_mass,
                           std::vector<double>& rotational_inertia,
                           const std::vector<double>* element_factor = nullptr);

// Through-thickness rule: nip points zeta (ascending, in [-1, 1]) and weights (sum 2). Gauss
// 1..10, Lobatto 2..10 (nip 1 is the mid-surface point whatever the rule). Returns false for an
// unsupported (rule, nip).
bool through_thickness_points(ThroughThicknessRule rule, int nip, std::vector<double>& zeta,
                              std::vector<double>& weight);

// Finds a history array of a shell block by name (nullptr if the block's material has none).
const material::HistoryArray* find_history(const ShellBlock& block, std::string_view name);

}  // namespace rf::element
