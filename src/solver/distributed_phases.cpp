// The phases of a cycle that exist only in a distributed run (docs/parallel.md, stage 1:
// replicated state, partitioned elements). Simulation calls them where the ranks must agree;
// in one process none of them runs and the cycle is unchanged.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "model/error.hpp"
#include "model/error_context.hpp"
#include "parallel/communicator.hpp"
#include "parallel/distribution.hpp"
#include "solver/interrupt.hpp"
#include "solver/simulation.hpp"

namespace rf::solver {

// The start of a distributed run. Nothing of the model is refused here any more: flexible
// bodies, erosion, element sensors, section forces, switching with the bulk viscosity and restart
// dumps all run on ranks (docs/parallel.md).
void Simulation::start_distributed_run() {
  const model::Model& model = model_;
  distribution_ = std::make_unique<parallel::ElementDistribution>(parallel::world(), state_);
  // A deleted element leaves its rank's list of elements (solver/erosion.hpp); the ranks agree
  // on the deletions every cycle (Simulation::erode_failed_elements).
  erosion_.set_distributed(true);
  // Hourglass work per block (hexahedra, shells, beams), then the bulk viscosity's per block.
  rank_block_work_.assign(
      2 * (state_.hex_blocks.size() + state_.shell_blocks.size() + state_.beam_blocks.size()), 0.0);
  // matsum's part work is summed over the ranks at output times, so every rank keeps its share.
  if (model.output.matsum && !part_histories_)
    part_histories_ = std::make_unique<PartHistories>(state_, rigid_);
}

void Simulation::sum_partial_forces_across_ranks() {
  const parallel::Communicator& comm = distribution_->communicator();
  distribution_->sum_partial_forces(state_, &rank_block_work_);
  // The hourglass and bulk viscosity work in block order, as one process adds them.
  const std::size_t blocks = rank_block_work_.size() / 2;
  for (std::size_t b = 0; b < blocks; ++b) {
    const bool hex = b < state_.hex_blocks.size();
    if (hex ? state_.hex_blocks[b].rigid
            : (b < state_.hex_blocks.size() + state_.shell_blocks.size()
                   ? state_.shell_blocks[b - state_.hex_blocks.size()].rigid
                   : state_.beam_blocks[b - state_.hex_blocks.size() - state_.shell_blocks.size()]
                         .rigid))
      continue;
    energy_.hourglass += rank_block_work_[b];
    energy_.bulk_viscosity += rank_block_work_[blocks + b];
    if (part_histories_)
      part_histories_->add_hourglass(b, rank_block_work_[b], rank_block_work_[blocks + b]);
  }
  parallel::StepAgreement a;
  if (std::isfinite(element_dt_)) {
    a.dt = element_dt_;
    a.element = static_cast<double>(controlling_element_);
  }
  if (!breakdown_message_.empty()) a.failed_rank = comm.rank();
  a.interrupt = interrupt::requested();
  a.output_due = element_output_due() ? 1.0 : 0.0;
  const auto start = std::chrono::steady_clock::now();
  comm.agree(a);
  distribution_->add_reduction_seconds(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  // No rank computed an element (every part rigid): no element step anywhere, as in one process.
  element_dt_ = a.dt < 1e300 ? a.dt : std::numeric_limits<double>::infinity();
  if (a.dt < 1e300) controlling_element_ = static_cast<model::Id>(a.element);
  if (a.failed_rank < 1e9) {  // the failing rank's message on every rank
    comm.broadcast(breakdown_message_, static_cast<int>(a.failed_rank));
  }
  agreed_interrupt_ = static_cast<int>(a.interrupt);
  agreed_output_due_ = a.output_due > 0.0;
}

bool Simulation::element_output_due() const {
  const double t = state_.time;
  return (elout_csv_ && elout_schedule_.due(t)) ||
         (elout_shell_csv_ && elout_shell_schedule_.due(t)) ||
         (matsum_csv_ && matsum_schedule_.due(t)) || (fields_ && d3plot_schedule_.due(t)) ||
         (secforc_csv_ && secforc_schedule_.due(t));
}

void Simulation::gather_element_state_for_output(bool force) {
  if (!(force || agreed_output_due_)) return;
  if (gathered_cycle_ != state_.cycle) {
    gathered_cycle_ = state_.cycle;
    distribution_->gather_element_state(state_);
    // The replicated state must be the same everywhere; its energy is a cheap fingerprint.
    distribution_->check_replicated(energy_.total(), "the total energy");
  }
  // Section forces (secforc.csv) from each rank's element force slots, summed: a section's
  // force and moment about the (replicated) centroid are linear in the slots.
  if (!cross_sections_.empty()) {
    section_rows_.clear();
    for (const CrossSectionCut& cut : cross_sections_)
      section_rows_.push_back(cut.evaluate(state_));
    std::vector<double> sums;
    sums.reserve(7 * section_rows_.size());
    for (const SectionForce& row : section_rows_) {
      sums.insert(sums.end(), row.force.begin(), row.force.end());
      sums.insert(sums.end(), row.moment.begin(), row.moment.end());
      sums.push_back(row.normal_force);
    }
    distribution_->communicator().sum(sums.data(), sums.size());
    for (std::size_t k = 0; k < section_rows_.size(); ++k) {
      SectionForce& row = section_rows_[k];
      std::copy_n(sums.begin() + static_cast<std::ptrdiff_t>(7 * k), 3, row.force.begin());
      std::copy_n(sums.begin() + static_cast<std::ptrdiff_t>(7 * k + 3), 3, row.moment.begin());
      row.normal_force = sums[7 * k + 6];
    }
  }
  if (part_histories_) {  // the ranks' shares of the part work, summed for the output only
    rank_part_work_ = part_histories_->internal_work();
    distribution_->communicator().sum(part_histories_->internal_work().data(),
                                      part_histories_->internal_work().size());
  }
}

// A restart dump of a distributed run is one file, written by rank 0 (restart/dumper.cpp): the
// replicated state is the same everywhere, the element state is made complete as for output,
// plus what only the owners keep current (force slots, which the first output after a restart
// sums for secforc; shell strains and erosion work, which later failures read). matsum's part
// work is a per-rank share that the ranks sum only for output: each share is dumped, so that a
// restart on as many ranks gives every rank its own back and continues bit for bit.
void Simulation::prepare_restart_dump_on_ranks() {
  distribution_->gather_restart_state(state_);
  dump_rank_part_work_.clear();
  if (part_histories_) {
    const std::vector<double>& work = part_histories_->internal_work();
    const std::string mine(reinterpret_cast<const char*>(work.data()),
                           work.size() * sizeof(double));
    const std::string all = distribution_->communicator().all_gather(mine);
    dump_rank_part_work_.resize(all.size() / sizeof(double));
    std::memcpy(dump_rank_part_work_.data(), all.data(), all.size());
  }
}

void Simulation::finish_restart_dump_on_ranks() {
  distribution_->keep_own_force_slots(state_);
  dump_rank_part_work_.clear();
}

void Simulation::finish_output_on_ranks() {
  if (part_histories_ && !rank_part_work_.empty()) {
    part_histories_->internal_work() = rank_part_work_;
    rank_part_work_.clear();
  }
}

}  // namespace rf::solver
