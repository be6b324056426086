// Which elements of a block this process computes. One process computes them all; in a
// distributed run (src/parallel, docs/parallel.md) every rank holds every block but computes the
// forces of only the elements the partition gave it, and the partial nodal forces are summed
// across ranks. Kernels take their loop from here: the one-process path is the plain loop over
// [0, n), unchanged.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace rf::element {

struct ElementOwnership {
  // False: every element of the block (one process). True: only `elements`.
  bool partitioned = false;
  std::vector<std::int64_t> elements;  // ascending element indices owned by this rank

  // Runs of consecutive owned elements cut into batches of at most `lanes` (SIMD kernels).
  struct Batch {
    std::int64_t first = 0;
    std::int32_t count = 0;
  };
  // Batches for a lane width, built by prepare_batches() once, outside any parallel region.
  std::vector<Batch> batches;
  int batch_lanes = 0;

  void prepare_batches(int lanes) {
    if (batch_lanes == lanes) return;
    batches.clear();
    std::size_t k = 0;
    while (k < elements.size()) {
      const std::int64_t first = elements[k];
      std::int32_t count = 1;
      while (k + count < elements.size() && count < lanes && elements[k + count] == first + count)
        ++count;
      batches.push_back({first, count});
      k += static_cast<std::size_t>(count);
    }
    batch_lanes = lanes;
  }
  // Number of loop items of a per-element loop over a block of n elements, and the element of
  // item i.
  std::int64_t count(std::int64_t n) const {
    return partitioned ? static_cast<std::int64_t>(elements.size()) : n;
  }
  std::int64_t element(std::int64_t i) const {
    return partitioned ? elements[static_cast<std::size_t>(i)] : i;
  }
};

}  // namespace rf::element
