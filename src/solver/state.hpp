// Solver state: dense indices and contiguous arrays, built once from a Model.
// Nodal quantities are struct-of-arrays (one vector per component) so kernels stream them.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "element/beam_block.hpp"
#include "element/discrete_block.hpp"
#include "element/hex_block.hpp"
#include "element/shell_block.hpp"
#include "model/model.hpp"

namespace rf::solver {

struct Vec3Array {
  std::vector<double> x, y, z;
  void resize(std::size_t n, double value = 0.0) {
    x.assign(n, value);
    y.assign(n, value);
    z.assign(n, value);
  }
  std::size_t size() const { return x.size(); }
};

struct NodalState {
  std::vector<model::Id> id;  // dense index -> user node ID
  Vec3Array x0;               // reference coordinates
  Vec3Array x;                // current coordinates x^n
  Vec3Array v;                // velocity v^{n-1/2} before the update, v^{n+1/2} after
  Vec3Array a;                // acceleration a^n
  Vec3Array f_int;            // assembled internal force (elements, incl. hourglass)
  Vec3Array f_ext;            // assembled external force (loads, body forces)
  std::vector<double> mass;   // lumped mass
  // Per node, 1 once erosion has deleted every element of the node (LS-DYNA's ENMASS 0): its
  // mass, velocity and (rotational) inertia are zero from then on, its kinetic energy and
  // momentum went to the eroded ledger, and contact ignores it. Empty when nothing can erode.
  std::vector<std::uint8_t> removed;
  bool is_removed(std::size_t i) const { return !removed.empty() && removed[i] != 0; }
  std::size_t size() const { return id.size(); }
};

// The element kernels' read-only view of the nodal positions and velocities.
inline element::NodalView view_of(const NodalState& nodes) {
  return {nodes.x.x.data(), nodes.x.y.data(), nodes.x.z.data(),
          nodes.v.x.data(), nodes.v.y.data(), nodes.v.z.data()};
}

// Rotational degrees of freedom, only for the nodes that need them (shell and beam nodes):
// struct-of-arrays by rotational index. Solid-only models leave every array empty and pay
// nothing. The lumped rotational inertia is isotropic (one value per node), as for shells and
// beams in LS-DYNA, so the angular velocity update needs no gyroscopic term.
struct RotationalState {
  std::vector<std::int32_t> of_node;  // dense node -> rotational index, -1 none (empty: none)
  std::vector<std::int32_t> node;     // rotational index -> dense node
  Vec3Array w;                        // angular velocity omega^{n-1/2}, then omega^{n+1/2}
  Vec3Array w_previous;               // omega^{n-1/2} during the energy sums
  Vec3Array m_int;                    // assembled internal moment
  Vec3Array m_ext;                    // external moment (*LOAD_NODE DOF 5-7)
  std::vector<double> inertia;        // lumped rotational inertia
  std::size_t size() const { return node.size(); }
  bool empty() const { return node.empty(); }
  std::int32_t index(std::int32_t dense_node) const {
    return of_node.empty() ? -1 : of_node[static_cast<std::size_t>(dense_node)];
  }
};

// Assembly of the families whose force slots carry moments (shells, beams): for each node its
// slots, in ascending (family, block, element, local node) order, so the gather is race-free and
// the same for any thread count. A slot is the offset of (fx, fy, fz, mx, my, mz) in a block's
// force array.
struct StructuralIncidence {
  std::vector<std::int64_t> offset;  // size nodes + 1 (empty: no shells or beams)
  std::vector<std::int64_t> slot;
  std::vector<std::int32_t> block;   // index into `forces` (shell blocks first, then beams)
  std::vector<const double*> forces;
};

// Node -> element-slot incidence (CSR). Element kernels write each element's nodal forces
// into their own 24-entry slot; assembly sums the slots of a node in a fixed order, so the
// result is race-free and identical for any thread count.
struct NodeIncidence {
  std::vector<std::int64_t> offset;  // size nodes + 1
  std::vector<std::int64_t> slot;    // flattened (block, element, local node) → force index
  std::vector<std::int32_t> block;   // which block each slot belongs to
};

// Element-order assembly schedule for a given thread count (built on first use). Thread t owns
// the nodes [node_begin[t], node_begin[t+1]) and walks, block by block, the element range
// element_range[t * blocks + b] = {first, last + 1} of elements that touch one of its nodes,
// adding only the slots of its own nodes. Every node therefore receives its slots in ascending
// (block, element, local node) order, the same order as the CSR incidence, so both paths give
// bit-identical sums. `use_csr` is set when the node numbering makes the ranges overlap so much
// that the walk would be slower than the CSR gather.
struct AssemblyPlan {
  int threads = 0;
  bool use_csr = false;
  std::vector<std::int64_t> node_begin;                              // threads + 1
  std::vector<std::pair<std::int64_t, std::int64_t>> element_range;  // threads x blocks
};

struct PartInfo {
  model::Id id = 0;
  std::string title;
  int elform = 1;
  std::int64_t element_count = 0;
};

struct State {
  NodalState nodes;
  std::vector<element::HexBlock> hex_blocks;  // one block per part (contiguous elements)
  std::vector<element::ShellBlock> shell_blocks;  // one block per shell part
  std::vector<element::BeamBlock> beam_blocks;    // one block per beam part
  std::vector<element::DiscreteBlock> discrete_blocks;  // springs and dampers, one per part
  RotationalState rotations;
  StructuralIncidence structural_incidence;
  NodeIncidence incidence;
  std::vector<PartInfo> parts;
  double time = 0.0;
  double dt = 0.0;       // dt^{n+1/2}, the step about to be taken
  double dt_prev = 0.0;  // dt^{n-1/2}
  std::int64_t cycle = 0;
  std::vector<const double*> block_force_pointers;  // scratch for assembly, sized once
  // Nodes added by *CHANGE_P-ORDER (dense indices after the model's nodes; IDs above them).
  std::int64_t generated_node_count = 0;
  // Mass added by *ELEMENT_MASS and *ELEMENT_MASS_PART (already in nodes.mass).
  double added_mass = 0.0;
  AssemblyPlan assembly_plan;
};

}  // namespace rf::solver
