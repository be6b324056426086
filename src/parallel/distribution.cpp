#include "parallel/distribution.hpp"

#include <fmt/format.h>

#include <algorithm>
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

// Zeros the values of the elements `owned` does not list (stride values per element), then sums
// over the ranks.
void gather_array(const Communicator& comm, const element::ElementOwnership& owned,
                  std::size_t elements, std::vector<double>& values) {
  if (!owned.partitioned || elements == 0 || values.empty()) return;
  const std::size_t stride = values.size() / elements;
  std::size_t k = 0;
  for (std::size_t e = 0; e < elements; ++e) {
    if (k < owned.elements.size() && static_cast<std::size_t>(owned.elements[k]) == e) {
      ++k;
      continue;
    }
    std::fill_n(values.begin() + static_cast<std::ptrdiff_t>(stride * e), stride, 0.0);
  }
  comm.sum(values.data(), values.size());
}

template <class Block>
void gather_common(const Communicator& comm, Block& block) {
  gather_array(comm, block.owned, block.size(), block.stress);
  for (auto& h : block.history) gather_array(comm, block.owned, block.size(), h.values);
}

}  // namespace

void ElementDistribution::gather_element_state(solver::State& state) {
  // The arrays a kernel changes (element/*.cpp). A new per-element array that changes during a
  // run belongs here too, or output on more than one rank shows other ranks' elements stale.
  for (auto& block : state.hex_blocks) {
    gather_common(comm_, block);
    gather_array(comm_, block.owned, block.size(), block.hourglass_state);
    gather_array(comm_, block.owned, block.size(), block.volume);
  }
  for (auto& block : state.shell_blocks) {
    gather_common(comm_, block);
    gather_array(comm_, block.owned, block.size(), block.hourglass_state);
    gather_array(comm_, block.owned, block.size(), block.area);
  }
  for (auto& block : state.beam_blocks) {
    gather_common(comm_, block);
    gather_array(comm_, block.owned, block.size(), block.frame);
    gather_array(comm_, block.owned, block.size(), block.resultant);
    gather_array(comm_, block.owned, block.size(), block.length);
  }
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
