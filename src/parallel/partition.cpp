#include "parallel/partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

#ifdef RIGIDFLEX_HAVE_MPI
#include <metis.h>
#endif

namespace rf::parallel {

int element_weight(const element::HexBlock& block) {
  // ELFORM 16: four points, each with two 10-node Jacobians and a material update; measured 3.6
  // times ELFORM 10 (the ELFORM 1 kernel, weight 10) per element in bench/tet_bench.cpp.
  if (block.quadratic_tetrahedra()) return 36;
  if (block.order == 2) return 105;
  if (block.order >= 3) return 250;
  return block.elform == 2 ? 85 : 10;
}

int element_weight(const element::ShellBlock& block) {
  // ELFORM 16 (four in-plane points, no hourglass): measured 2.4 (elastic NIP 2) to 3.2
  // (*MAT_024 NIP 5) times ELFORM 2 per element in bench/shell_bench.cpp.
  if (block.elform == 16) return std::max(1, 12 * block.nip);
  return std::max(1, 5 * block.nip);
}

int element_weight(const element::BeamBlock& block) {
  return block.elform == 3 ? 2 : 12;
}

namespace {

// The blocks whose elements have kernels: every block with assembly slots (a part rigid by
// switching keeps them and is partitioned, so ownership never changes during a run).
bool partitioned(const element::HexBlock& b) {
  return b.has_force_slots;
}
bool partitioned(const element::ShellBlock& b) {
  return b.has_force_slots && !b.rigid;
}
bool partitioned(const element::BeamBlock& b) {
  return b.has_force_slots && !b.rigid;
}

// Calls visit(family owner vector, block, nodes per element) for every block in flattening
// order: hex, shell, beam.
template <class State, class P, class Visit>
void for_each_block(State& state, P& p, Visit&& visit) {
  p.hex.resize(state.hex_blocks.size());
  p.shell.resize(state.shell_blocks.size());
  p.beam.resize(state.beam_blocks.size());
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b)
    visit(p.hex[b], state.hex_blocks[b], state.hex_blocks[b].nodes_per_element());
  for (std::size_t b = 0; b < state.shell_blocks.size(); ++b)
    visit(p.shell[b], state.shell_blocks[b], 4);
  for (std::size_t b = 0; b < state.beam_blocks.size(); ++b)
    visit(p.beam[b], state.beam_blocks[b], 2);
}

}  // namespace

std::int64_t Partition::total_elements() const {
  return std::accumulate(elements.begin(), elements.end(), std::int64_t{0});
}

double Partition::imbalance() const {
  if (weight.empty()) return 1.0;
  const double total = static_cast<double>(std::accumulate(weight.begin(), weight.end(), 0LL));
  const double mean = total / static_cast<double>(weight.size());
  const double top = static_cast<double>(*std::max_element(weight.begin(), weight.end()));
  return mean > 0.0 ? top / mean : 1.0;
}

std::int64_t partitionable_element_count(const solver::State& state) {
  std::int64_t n = 0;
  for (const auto& b : state.hex_blocks)
    if (partitioned(b)) n += static_cast<std::int64_t>(b.size());
  for (const auto& b : state.shell_blocks)
    if (partitioned(b)) n += static_cast<std::int64_t>(b.size());
  for (const auto& b : state.beam_blocks)
    if (partitioned(b)) n += static_cast<std::int64_t>(b.size());
  return n;
}

namespace {

// Quality figures of an owner assignment.
void measure(const solver::State& state, Partition& p) {
  p.elements.assign(static_cast<std::size_t>(p.ranks), 0);
  p.weight.assign(static_cast<std::size_t>(p.ranks), 0);
  // Per node: the first rank seen, and whether a second one touches it.
  std::vector<std::int32_t> first(state.nodes.size(), -1);
  std::vector<std::uint8_t> shared(state.nodes.size(), 0);
  for_each_block(state, p, [&](const std::vector<std::int32_t>& owner, const auto& block, int npe) {
    if (owner.empty()) return;
    const int w = element_weight(block);
    for (std::size_t e = 0; e < block.size(); ++e) {
      const std::int32_t r = owner[e];
      ++p.elements[static_cast<std::size_t>(r)];
      p.weight[static_cast<std::size_t>(r)] += w;
      for (int k = 0; k < npe; ++k) {
        const auto node = static_cast<std::size_t>(block.conn[npe * e + k]);
        if (first[node] < 0)
          first[node] = r;
        else if (first[node] != r)
          shared[node] = 1;
      }
    }
  });
  p.interface_nodes = std::count(shared.begin(), shared.end(), std::uint8_t{1});
}

}  // namespace

Partition partition_elements(const solver::State& state, int ranks) {
  if (ranks < 1)
    throw std::invalid_argument(fmt::format("the rank count {} is not positive", ranks));
  const std::int64_t count = partitionable_element_count(state);
  if (ranks > 1 && ranks > count) {
    throw std::invalid_argument(fmt::format(
        "{} ranks for {} deformable elements: a distributed run needs at least one element per "
        "rank (run on at most {} ranks)",
        ranks, count, count));
  }
  Partition p;
  p.ranks = ranks;
  for_each_block(state, p, [&](std::vector<std::int32_t>& owner, const auto& block, int) {
    if (partitioned(block)) owner.assign(block.size(), 0);
  });
  if (ranks > 1) {
#ifdef RIGIDFLEX_HAVE_MPI
    // The mesh of the partitioned elements in METIS's CSR form, with their weights.
    std::vector<idx_t> eptr{0}, eind, vwgt;
    for_each_block(state, p, [&](std::vector<std::int32_t>& owner, const auto& block, int npe) {
      if (owner.empty()) return;
      const int w = element_weight(block);
      for (std::size_t e = 0; e < block.size(); ++e) {
        // Repeated nodes of degenerate elements appear once (METIS counts shared nodes).
        const auto* c = &block.conn[static_cast<std::size_t>(npe) * e];
        const std::size_t start = eind.size();
        for (int k = 0; k < npe; ++k) {
          if (std::find(eind.begin() + static_cast<std::ptrdiff_t>(start), eind.end(),
                        static_cast<idx_t>(c[k])) == eind.end())
            eind.push_back(static_cast<idx_t>(c[k]));
        }
        eptr.push_back(static_cast<idx_t>(eind.size()));
        vwgt.push_back(w);
      }
    });
    idx_t ne = static_cast<idx_t>(vwgt.size());
    idx_t nn = static_cast<idx_t>(state.nodes.size());
    idx_t ncommon = 1;  // neighbours share at least one node
    idx_t numflag = 0;
    idx_t* xadj = nullptr;
    idx_t* adjncy = nullptr;
    if (METIS_MeshToDual(&ne, &nn, eptr.data(), eind.data(), &ncommon, &numflag, &xadj, &adjncy) !=
        METIS_OK) {
      throw std::runtime_error("METIS could not build the element graph (METIS_MeshToDual)");
    }
    idx_t ncon = 1, nparts = ranks, objval = 0;
    std::vector<idx_t> part(static_cast<std::size_t>(ne), 0);
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 1;  // fixed: the same partition on every run
    options[METIS_OPTION_CONTIG] = 0;
    const int status =
        METIS_PartGraphKway(&ne, &ncon, xadj, adjncy, vwgt.data(), nullptr, nullptr, &nparts,
                            nullptr, nullptr, options, &objval, part.data());
    METIS_Free(xadj);
    METIS_Free(adjncy);
    if (status != METIS_OK) {
      throw std::runtime_error(
          fmt::format("METIS could not partition {} elements into {} parts", ne, ranks));
    }
    std::size_t k = 0;
    for_each_block(state, p, [&](std::vector<std::int32_t>& owner, const auto&, int) {
      for (auto& o : owner) o = static_cast<std::int32_t>(part[k++]);
    });
    // METIS may leave a part empty on tiny graphs: that rank then computes no element, which
    // is still correct (its partial forces are zero).
#else
    throw std::runtime_error(
        "this build has no METIS: element partitioning needs libmetis-dev and libopenmpi-dev "
        "(scripts/install-deps.sh) and RIGIDFLEX_MPI=ON");
#endif
  }
  measure(state, p);
  return p;
}

std::vector<std::int32_t> flatten_owners(const Partition& p) {
  std::vector<std::int32_t> all;
  for (const auto* family : {&p.hex, &p.shell, &p.beam})
    for (const auto& owner : *family) all.insert(all.end(), owner.begin(), owner.end());
  return all;
}

void unflatten_owners(const std::vector<std::int32_t>& owners, const solver::State& state,
                      Partition& p) {
  std::size_t k = 0;
  for_each_block(state, p, [&](std::vector<std::int32_t>& owner, const auto& block, int) {
    if (!partitioned(block)) {
      owner.clear();
      return;
    }
    if (k + block.size() > owners.size())
      throw std::runtime_error("the broadcast partition does not match the model");
    owner.assign(owners.begin() + static_cast<std::ptrdiff_t>(k),
                 owners.begin() + static_cast<std::ptrdiff_t>(k + block.size()));
    k += block.size();
  });
  measure(state, p);
}

namespace {

// The rank's elements of one block.
template <class Block>
void restrict_block(const std::vector<std::vector<std::int32_t>>& owners, std::size_t b, int rank,
                    Block& block) {
  if (b >= owners.size() || owners[b].empty()) return;  // not partitioned (*MAT_RIGID)
  const std::vector<std::int32_t>& owner = owners[b];
  block.owned.partitioned = true;
  block.owned.elements.clear();
  block.owned.batches.clear();
  block.owned.batch_lanes = 0;
  for (std::size_t e = 0; e < block.size(); ++e)
    if (owner[e] == rank) block.owned.elements.push_back(static_cast<std::int64_t>(e));
}

// The force slots of one block's elements that other ranks own, zeroed.
template <class Block>
void zero_other_slots(const std::vector<std::vector<std::int32_t>>& owners, std::size_t b, int rank,
                      Block& block) {
  if (b >= owners.size() || owners[b].empty() || block.size() == 0) return;
  const std::vector<std::int32_t>& owner = owners[b];
  const std::size_t slot = block.force.size() / block.size();
  for (std::size_t e = 0; e < block.size(); ++e)
    if (owner[e] != rank)
      std::fill_n(block.force.begin() + static_cast<std::ptrdiff_t>(slot * e), slot, 0.0);
}

}  // namespace

void apply_partition(const Partition& p, int rank, solver::State& state) {
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b)
    restrict_block(p.hex, b, rank, state.hex_blocks[b]);
  for (std::size_t b = 0; b < state.shell_blocks.size(); ++b)
    restrict_block(p.shell, b, rank, state.shell_blocks[b]);
  for (std::size_t b = 0; b < state.beam_blocks.size(); ++b)
    restrict_block(p.beam, b, rank, state.beam_blocks[b]);
  zero_other_ranks_force_slots(p, rank, state);
}

void zero_other_ranks_force_slots(const Partition& p, int rank, solver::State& state) {
  for (std::size_t b = 0; b < state.hex_blocks.size(); ++b)
    zero_other_slots(p.hex, b, rank, state.hex_blocks[b]);
  for (std::size_t b = 0; b < state.shell_blocks.size(); ++b)
    zero_other_slots(p.shell, b, rank, state.shell_blocks[b]);
  for (std::size_t b = 0; b < state.beam_blocks.size(); ++b)
    zero_other_slots(p.beam, b, rank, state.beam_blocks[b]);
}

std::string describe_partition(const Partition& p) {
  std::string text = fmt::format(
      "partition into {} ranks (METIS k-way on the element graph, weights per family): {} "
      "elements, load imbalance {:.3f} (max/mean weight), {} interface nodes\n",
      p.ranks, p.total_elements(), p.imbalance(), p.interface_nodes);
  for (int r = 0; r < p.ranks; ++r) {
    text +=
        fmt::format("  rank {}: {} elements, weight {}\n", r,
                    p.elements[static_cast<std::size_t>(r)], p.weight[static_cast<std::size_t>(r)]);
  }
  return text;
}

}  // namespace rf::parallel
