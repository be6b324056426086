// Element partition of a distributed run (docs/parallel.md): the elements of the deformable
// blocks of every family (8-node and Lagrange hexahedra, shells, beams) split into one part per
// rank by METIS (METIS_PartGraphKway) on the element dual graph, in which two elements are
// neighbours when they share a node, each element weighted by the measured cost of its family.
// Elements of *MAT_RIGID parts have no kernel and are not partitioned.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/state.hpp"

namespace rf::parallel {

// Relative cost of one element evaluation per family, in units of about 16 ns (the 8-node
// ELFORM 1 hexahedron = 10): the one-thread kernel timings of docs/performance.md (hexahedra
// ELFORM 1 ~160 ns, ELFORM 2 ~1350 ns, Lagrange p = 2 ~1700 ns, p = 3 ~4000 ns; shells ELFORM 2
// with 2 points through the thickness ~155 ns, scaling with the points; beams ~190 ns, trusses
// ~30 ns).
int element_weight(const element::HexBlock& block);
int element_weight(const element::ShellBlock& block);
int element_weight(const element::BeamBlock& block);

struct Partition {
  int ranks = 1;
  // Owner rank of every element, per family and block (empty for blocks not partitioned:
  // *MAT_RIGID parts).
  std::vector<std::vector<std::int32_t>> hex, shell, beam;
  // Quality: elements and summed weight per rank, nodes touched by elements of two or more
  // ranks (the interface a halo exchange would send).
  std::vector<std::int64_t> elements;
  std::vector<std::int64_t> weight;
  std::int64_t interface_nodes = 0;
  std::int64_t total_elements() const;
  // max / mean of the weights (1: perfect balance).
  double imbalance() const;
};

// The partitioned elements of a state (deformable-capable blocks of every family).
std::int64_t partitionable_element_count(const solver::State& state);

// Splits the elements into `ranks` parts. Throws std::invalid_argument when ranks exceeds the
// number of partitioned elements (naming both) or ranks < 1, and std::runtime_error when METIS
// is missing from the build or fails.
Partition partition_elements(const solver::State& state, int ranks);

// Every owner array in one vector (hex blocks, then shells, then beams), for a broadcast, and
// back into a partition of the same state.
std::vector<std::int32_t> flatten_owners(const Partition& p);
void unflatten_owners(const std::vector<std::int32_t>& owners, const solver::State& state,
                      Partition& p);

// Restricts every partitioned block's kernel loop to the elements `rank` owns
// (element::ElementOwnership) and zeroes the force slots of the others, so that the nodal
// assembly on this rank sums only its own elements.
void apply_partition(const Partition& p, int rank, solver::State& state);

// Zeroes the force slots of the elements other ranks own, leaving this rank's: what
// apply_partition does to the slots, again after a restart dump made them complete.
void zero_other_ranks_force_slots(const Partition& p, int rank, solver::State& state);

// Lines for `rigidflex check --ranks N`.
std::string describe_partition(const Partition& p);

}  // namespace rf::parallel
