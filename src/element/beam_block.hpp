// Contiguous batch of 2-node beams and trusses that share part, section and material: the beam
// element family (issue 16). Beam nodes carry rotations (solver::RotationalState); a truss
// (ELFORM 3) has none and its rotation_conn entries are -1.
//
// SIGN CONVENTION as for solids (hex_block.hpp): block.force holds INTERNAL nodal forces and
// moments; the solver forms a = (f_ext - f_int) / m and alpha = (m_ext - m_int) / I.
#pragma once

#include <cstdint>
#include <vector>

#include "element/element_ownership.hpp"
#include "element/erosion_state.hpp"
#include "element/hex_block.hpp"    // NodalView, KernelResult
#include "element/shell_block.hpp"  // RotationalView
#include "material/elastic.hpp"
#include "material/history.hpp"
#include "material/plastic_parameters.hpp"
#include "model/model.hpp"

namespace rf::element {

// Force and moment entries per element: 2 nodes x (fx, fy, fz, mx, my, mz), node-major, global.
inline constexpr int kBeamSlot = 12;

enum class BeamCrossSection : std::uint8_t {
  kRectangular = 0,  // *SECTION_BEAM CST 0: TS1/TS2 (s), TT1/TT2 (t) at the two nodes
  kTubular = 1,      // CST 1: outer diameters TS1/TS2, inner TT1/TT2
};

struct BeamBlock {
  model::Id part_id = 0;
  int part_index = 0;
  // 1: Hughes-Liu with cross-section integration; 2: Belytschko-Schwer resultant (A, I, J);
  // 3: truss (axial only).
  int elform = 2;
  material::ElasticConstants material;
  int material_index = 0;
  material::PlasticParameters plastic;
  bool rigid = false;
  // The elements this process computes (element_ownership.hpp; all of them in one process).
  ElementOwnership owned;
  // Failed elements (element/erosion_state.hpp); disabled for blocks without a failure criterion.
  ErosionState erosion;
  bool has_force_slots = true;

  // Section (*SECTION_BEAM). Resultant and truss: A, ISS, ITT, J (IRR), SA (shear area).
  double area = 0.0;
  double iss = 0.0;      // second moment about the local s axis
  double itt = 0.0;      // second moment about the local t axis
  double torsion = 0.0;  // J
  double shear_area = 0.0;
  double shear_factor = 1.0;  // SHRF
  // Hughes-Liu: cross-section shape and dimensions at node 1 (s, t) and node 2.
  BeamCrossSection cross_section = BeamCrossSection::kRectangular;
  double ts1 = 0.0, ts2 = 0.0, tt1 = 0.0, tt2 = 0.0;
  // ELFORM 1: stress points of the mid-length cross-section (filled by initialize_beam_block
  // from the shape and the mean of the nodal dimensions): coordinates along s and t and
  // weights (areas). ELFORM 1 also gets area, iss, itt and torsion computed from the section.
  std::vector<double> section_s, section_t, section_weight;

  std::vector<model::Id> element_id;        // user IDs, size n
  std::vector<std::int32_t> conn;           // dense node indices, 2 per element
  std::vector<std::int32_t> rotation_conn;  // rotational indices, 2 per element (-1 truss)
  // Orientation of the local s axis at the reference configuration, 3 per element: from the
  // third node (N3) or the orientation vector of *ELEMENT_BEAM_ORIENTATION; a default
  // perpendicular to the axis otherwise.
  std::vector<double> orientation;

  // Per-element state: the co-rotational local frame (9 per element, rows e1 e2 e3, e1 along
  // the axis), resultants (6 per element: N, Qs, Qt, Mtorsion, Ms, Mt; every formulation, the
  // truss only N) and the axial stress per point (truss: 1 per element; ELFORM 1: one per
  // section point; ELFORM 2: none). History of the J2 materials (truss and ELFORM 1), per
  // point: "effective_plastic_strain" and "uniaxial_back_stress" (1 component each).
  std::vector<double> frame;
  std::vector<double> resultant;
  std::vector<double> stress;
  std::vector<material::HistoryArray> history;
  std::vector<double> length0;  // reference length
  // sqrt(s_e) of mass scaling (solver/mass_scaling.hpp): the element's mass is s_e times its
  // physical mass, so its step is sqrt(s_e) times longer. Empty without mass scaling.
  std::vector<double> step_scale;
  std::vector<double> length;   // current length
  std::vector<double> force;    // kBeamSlot per element

  std::size_t size() const { return element_id.size(); }
  // Axial stress points per element (truss 1, ELFORM 1 the section points, ELFORM 2 none).
  int points_per_element() const {
    return elform == 3 ? 1 : (elform == 1 ? static_cast<int>(section_weight.size()) : 0);
  }
};

// Checks the block (formulation, material, section, connectivity), fills ELFORM 1 section
// points and properties, allocates per-element state and computes reference lengths and the
// initial local frames. Throws rf::SolverError naming the part (or the element for a zero
// length or an orientation along the axis).
void initialize_beam_block(BeamBlock& block, const NodalView& nodes);
KernelResult compute_beam_forces(BeamBlock& block, const NodalView& nodes,
                                 const RotationalView& rotations, double dt);
// `raw_steps` (optional) receives every element's step without mass scaling (0 where failed).
KernelResult beam_critical_timestep(const BeamBlock& block, const NodalView& nodes,
                                    std::vector<double>* raw_steps = nullptr);
// `element_factor` (optional): each element's shares multiplied by it (mass scaling).
void add_beam_lumped_mass(const BeamBlock& block, std::vector<double>& nodal_mass,
                          std::vector<double>& rotational_inertia,
                          const std::vector<double>* element_factor = nullptr);

}  // namespace rf::element
