#include "parallel/distribution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "model/error.hpp"

namespace rf::parallel {

ElementDistribution::ElementDistribution(const Communicator& comm, solver::State& state)
    : comm_(comm) {
  // One partition for all: computed on rank 0 (METIS is deterministic for a fixed seed, but a
  // broadcast does not depend on that), sent to the others.
  std::string error;
  std::vector<std::int32_t> owners;
  if (comm_.rank() == 0) {
    try {
      partition_ = partition_elements(state, comm_.size());
      owners = flatten_owners(partition_);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  comm_.broadcast(error, 0);
  if (!error.empty()) throw std::invalid_argument(error);
  comm_.broadcast(owners, 0);
  if (comm_.rank() != 0) {
    partition_.ranks = comm_.size();
    unflatten_owners(owners, state, partition_);
  }
  apply_partition(partition_, comm_.rank(), state);
}

void ElementDistribution::sum_partial_forces(solver::State& state, std::vector<double>* extra_in,
                                             bool moments) {
  const auto start = std::chrono::steady_clock::now();
  static std::vector<double> none;
  std::vector<double>& extra = extra_in ? *extra_in : none;
  solver::NodalState& nodes = state.nodes;
  solver::RotationalState& rot = state.rotations;
  const std::size_t n = nodes.size(), nr = moments ? rot.size() : 0;
  buffer_.resize(3 * n + 3 * nr + extra.size());
  double* b = buffer_.data();
  std::copy(nodes.f_int.x.begin(), nodes.f_int.x.end(), b);
  std::copy(nodes.f_int.y.begin(), nodes.f_int.y.end(), b + n);
  std::copy(nodes.f_int.z.begin(), nodes.f_int.z.end(), b + 2 * n);
  double* m = b + 3 * n;
  if (nr > 0) {
    std::copy(rot.m_int.x.begin(), rot.m_int.x.end(), m);
    std::copy(rot.m_int.y.begin(), rot.m_int.y.end(), m + nr);
    std::copy(rot.m_int.z.begin(), rot.m_int.z.end(), m + 2 * nr);
  }
  std::copy(extra.begin(), extra.end(), m + 3 * nr);
  comm_.sum(b, buffer_.size());
  std::copy(b, b + n, nodes.f_int.x.begin());
  std::copy(b + n, b + 2 * n, nodes.f_int.y.begin());
  std::copy(b + 2 * n, b + 3 * n, nodes.f_int.z.begin());
  if (nr > 0) {
    std::copy(m, m + nr, rot.m_int.x.begin());
    std::copy(m + nr, m + 2 * nr, rot.m_int.y.begin());
    std::copy(m + 2 * nr, m + 3 * nr, rot.m_int.z.begin());
  }
  std::copy(m + 3 * nr, m + 3 * nr + extra.size(), extra.begin());
  reduction_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

namespace {

// The owner rank of every element of a block by the partition (empty: not partitioned). The
// partition, not the block's current ElementOwnership: an eroded element leaves the latter, and
// its last state (plastic strain, damage) must still come from its owner.
struct Owners {
  const std::vector<std::int32_t>* owner = nullptr;
  int rank = 0;
};

Owners owners_of(const std::vector<std::vector<std::int32_t>>& family, std::size_t b, int rank) {
  return {b < family.size() && !family[b].empty() ? &family[b] : nullptr, rank};
}

// Zeros the values of the elements of other ranks (stride values per element), then sums over
// the ranks.
void gather_array(const Communicator& comm, const Owners& owners, std::size_t elements,
                  std::vector<double>& values) {
  if (!owners.owner || elements == 0 || values.empty()) return;
  const std::size_t stride = values.size() / elements;
  for (std::size_t e = 0; e < elements; ++e) {
    if ((*owners.owner)[e] == owners.rank) continue;
    std::fill_n(values.begin() + static_cast<std::ptrdiff_t>(stride * e), stride, 0.0);
  }
  comm.sum(values.data(), values.size());
}

template <class Block>
void gather_common(const Communicator& comm, const Owners& owners, Block& block) {
  gather_array(comm, owners, block.size(), block.stress);
  for (auto& h : block.history) gather_array(comm, owners, block.size(), h.values);
}

}  // namespace

void ElementDistribution::gather_element_state(solver::State& state) {
  // The arrays a kernel changes (element/*.cpp). A new per-element array that changes during a
  // run belongs here too, or output on more than one rank shows other ranks' elements stale.
  // Each family: stresses and history, then the arrays of its own kernel.
  auto family = [&](auto& blocks, const std::vector<std::vector<std::int32_t>>& owners,
                    auto&& own_arrays) {
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const Owners o = owners_of(owners, b, comm_.rank());
      gather_common(comm_, o, blocks[b]);
      for (std::vector<double>* values : own_arrays(blocks[b]))
        gather_array(comm_, o, blocks[b].size(), *values);
    }
  };
  family(state.hex_blocks, partition_.hex, [](element::HexBlock& block) {
    return std::array<std::vector<double>*, 2>{&block.hourglass_state, &block.volume};
  });
  family(state.shell_blocks, partition_.shell, [](element::ShellBlock& block) {
    // element_thickness: changed by the kernel with *CONTROL_SHELL ISTUPD 1/4 (constant, and
    // then the same on every rank, without).
    return std::array<std::vector<double>*, 3>{&block.hourglass_state, &block.area,
                                               &block.element_thickness};
  });
  family(state.beam_blocks, partition_.beam, [](element::BeamBlock& block) {
    return std::array<std::vector<double>*, 3>{&block.frame, &block.resultant, &block.length};
  });
}

void ElementDistribution::gather_restart_state(solver::State& state) {
  gather_element_state(state);
  auto family = [&](auto& blocks, const std::vector<std::vector<std::int32_t>>& owners) {
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const Owners o = owners_of(owners, b, comm_.rank());
      auto& block = blocks[b];
      gather_array(comm_, o, block.size(), block.force);
      if (block.erosion.enabled) {
        gather_array(comm_, o, block.size(), block.erosion.work);
        gather_array(comm_, o, block.size(), block.erosion.artificial_work);
        gather_array(comm_, o, block.size(), block.erosion.impulse);
      }
      if constexpr (requires { block.strain; }) gather_array(comm_, o, block.size(), block.strain);
    }
  };
  family(state.hex_blocks, partition_.hex);
  family(state.shell_blocks, partition_.shell);
  family(state.beam_blocks, partition_.beam);
}

void ElementDistribution::keep_own_force_slots(solver::State& state) const {
  zero_other_ranks_force_slots(partition_, comm_.rank(), state);
}

void ElementDistribution::check_replicated(double value, const char* what) const {
  const double lo = comm_.min(value), hi = comm_.max(value);
  if (!(lo == hi) && !(std::isnan(lo) && std::isnan(hi))) {
    throw SolverError(fmt::format(
        "the ranks of this distributed run no longer agree on {} ({:.17g} to {:.17g}): the "
        "replicated state diverged (please report this with the deck)",
        what, lo, hi));
  }
}

}  // namespace rf::parallel
