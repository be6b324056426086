// Stage 1 of distributed runs (docs/parallel.md): replicated state, partitioned elements. Every
// rank holds the whole model and state; each computes the element forces of its own elements
// (partition.hpp), and the named phases below make the ranks agree again: the partial nodal
// forces are summed, the step and the failures reduced, the element state brought together
// before output and switching. Everything else in the cycle runs on every rank identically.
#pragma once

#include <string>
#include <vector>

#include "parallel/communicator.hpp"
#include "parallel/partition.hpp"
#include "solver/state.hpp"

namespace rf::parallel {

class ElementDistribution {
 public:
  // Partitions the elements (rank 0 runs METIS and broadcasts the owners) and restricts the
  // kernels to this rank's elements. Collective.
  ElementDistribution(const Communicator& comm, solver::State& state);

  const Communicator& communicator() const { return comm_; }
  const Partition& partition() const { return partition_; }
  // Only rank 0 writes files.
  bool writes_files() const { return comm_.rank() == 0; }

  // After the element kernels and the assembly: f_int and the internal moments, each rank's
  // part so far, become their sums over the ranks; `extra` (per-block values such as the
  // hourglass work of this evaluation) is summed in the same reduction, and the internal moments
  // only when `moments` (a re-assembly of the hexahedra alone leaves them summed). Collective.
  void sum_partial_forces(solver::State& state, std::vector<double>* extra, bool moments = true);

  // Every block's element state (stresses, history, hourglass state, current volume, area or
  // length, beam frames and resultants) complete on every rank: each rank contributes its own
  // elements, zeros elsewhere, and a sum brings them together, exactly (x + 0 = x). Force slots
  // are left alone (the others' stay zero for the assembly). Collective; output times and
  // switches only.
  void gather_element_state(solver::State& state);

  // Before a restart dump (rank 0 writes the whole state): gather_element_state() and, beyond
  // what output needs, the element force slots, the integrated shell strains, the erosion work
  // sums and stress impulses, which only the owner keeps up to date. Collective. The force slots
  // must be made this rank's own again afterwards (keep_own_force_slots).
  void gather_restart_state(solver::State& state);
  // Zeros the force slots of the elements other ranks own (by the partition), so that the
  // assembly sums each element once: after a dump, and after a restart has read the dump's
  // complete slots.
  void keep_own_force_slots(solver::State& state) const;

  // The same `value` on every rank, else throws rf::SolverError naming `what` (a safety net
  // for the replicated state, checked at output times). Collective.
  void check_replicated(double value, const char* what) const;

  // Wall time this rank spent in the per-cycle force sum (packing included) and the step
  // agreement: the communication share of a cycle (d3hsp.txt, docs/parallel.md).
  double reduction_seconds() const { return reduction_seconds_; }
  void add_reduction_seconds(double s) { reduction_seconds_ += s; }

 private:
  double reduction_seconds_ = 0.0;
  const Communicator& comm_;
  Partition partition_;
  std::vector<double> buffer_;  // the packed sum of sum_partial_forces
};

}  // namespace rf::parallel
