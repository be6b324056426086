// Contiguous batch of discrete elements (*ELEMENT_DISCRETE) of one part: translational springs
// and dampers between two nodes, the discrete element family (issue 21). Massless: their nodes
// take mass from *ELEMENT_MASS or from the elements they share, and the step they allow comes
// from those nodal masses (prepare_discrete_time_steps).
//
// The force acts along the current line N1 -> N2 (VID 0): with l the current length, l0 the
// initial one and n = (x2 - x1) / l,
//   elongation  d = l - l0 + OFFSET          (OFFSET > 0: tension at time zero)
//   spring      N = S K d                    (*MAT_SPRING_ELASTIC)
//   nonlinear   N = S f(d)                   (*MAT_SPRING_NONLINEAR_ELASTIC, f the LCD curve)
//   damper      N = S DC n . (v2 - v1)       (*MAT_DAMPER_VISCOUS)
// N > 0 is tension. SIGN CONVENTION as for solids (hex_block.hpp): block.force holds INTERNAL
// nodal forces, -N n on N1 and +N n on N2.
#pragma once

#include <cstdint>
#include <vector>

#include "element/hex_block.hpp"  // NodalView, KernelResult
#include "model/model.hpp"

namespace rf::element {

// Force entries per element: 2 nodes x (fx, fy, fz), node-major, global.
inline constexpr int kDiscreteSlot = 6;

enum class DiscreteLaw : std::uint8_t {
  kLinearSpring = 0,     // *MAT_SPRING_ELASTIC (S01)
  kViscousDamper = 1,    // *MAT_DAMPER_VISCOUS (S02)
  kNonlinearSpring = 2,  // *MAT_SPRING_NONLINEAR_ELASTIC (S04)
};

struct DiscreteBlock {
  model::Id part_id = 0;
  int part_index = 0;
  model::Id material_id = 0;
  DiscreteLaw law = DiscreteLaw::kLinearSpring;
  double stiffness = 0.0;  // K (S01)
  double damping = 0.0;    // DC (S02)
  // S04: force vs elongation, strictly increasing abscissae (the LCD curve with its scale
  // factors applied), extrapolated linearly beyond the ends.
  std::vector<double> curve_elongation, curve_force;

  std::vector<model::Id> element_id;  // user IDs, size n
  std::vector<std::int32_t> conn;     // dense node indices, 2 per element
  std::vector<double> scale;          // S per element
  std::vector<double> offset;         // OFFSET per element
  std::vector<double> length0;        // initial length
  // Inverse masses (1/m1 + 1/m2) the element's step is based on; set once the rigid bodies are
  // known (prepare_discrete_time_steps). 0: both nodes immovable, no step limit.
  std::vector<double> inverse_mass;
  std::vector<double> axial_force;  // N at the last evaluation (tension positive)
  std::vector<double> force;        // kDiscreteSlot per element

  // Work done on the block's elements since time zero (a restart dump carries it), summed like
  // the internal work of every element, f_slot . dt_avg (v^{n-1/2} + v^{n+1/2}) / 2 at the
  // element's nodes (solver::add_discrete_work): for springs the energy they hold relative to
  // time zero (to O(dt^2) the integral of N dd), for dampers the energy they have dissipated.
  // The same sum as the internal energy, so kinetic + spring + damper energy balances exactly.
  double spring_energy = 0.0;
  double damper_energy = 0.0;
  // Energy the springs hold at time zero from their OFFSET (not part of the energy sums, which
  // start at zero: the springs' work may fall by as much below zero).
  double preload_energy = 0.0;

  std::size_t size() const { return element_id.size(); }
};

// Checks the block (law, connectivity, curve), allocates per-element state and computes the
// initial lengths. Throws rf::InputError naming the element for coincident nodes (the line of
// action would be undefined; orientation vectors are not supported).
void initialize_discrete_block(DiscreteBlock& block, const NodalView& nodes,
                               const model::SourceLocation& where);

// Forces at the current positions (springs) and velocities v^{n+1/2} (dampers) into the slots.
// The result's min_dt is the block's critical step; failed marks an element whose nodes have
// come together (no line of action).
KernelResult compute_discrete_forces(DiscreteBlock& block, const NodalView& nodes);

// Critical step of each element from the nodal masses, the stability limits of the central
// difference for a two-mass system (docs/elements.md, "Discrete elements"):
//   spring  dt <= 2 / omega,  omega^2 = S k (1/m1 + 1/m2)  (k = K, or the curve's largest slope)
//   damper  dt <= 2 / (S DC (1/m1 + 1/m2))
KernelResult discrete_critical_timestep(const DiscreteBlock& block);

}  // namespace rf::element
