// Per-thread results of an element kernel pass and their deterministic combination, shared by
// every element family. With a static OpenMP schedule thread t owns a contiguous, increasing
// range of elements, so combining the partials in thread order makes the result independent of
// timing: "first failure" is the lowest element index and the sums add in a fixed order.
#pragma once

#include <omp.h>

#include <array>
#include <cstdint>
#include <vector>

#include "element/hex_block.hpp"  // KernelResult

namespace rf::element {

struct alignas(64) KernelPartial {
  double hourglass_work = 0.0;
  double bulk_viscosity_work = 0.0;
  double min_dt = 1e300;
  std::int64_t min_dt_element = -1;
  std::int64_t failed_element = -1;
  double failed_measure = 0.0;  // volume, area or length of the failed element

  void record_dt(double dt, std::int64_t e) {
    if (dt < min_dt) {
      min_dt = dt;
      min_dt_element = e;
    }
  }
  void record_failure(std::int64_t e, double measure) {
    if (failed_element < 0) {
      failed_element = e;
      failed_measure = measure;
    }
  }
};

// Mass scaling (solver/mass_scaling.hpp) multiplies an element's mass by s_e and so its critical
// step by sqrt(s_e): a block keeps sqrt(s_e) per element in `step_scale`, empty without scaling.
inline double scaled_step(const std::vector<double>& step_scale, std::int64_t e, double dt) {
  return step_scale.empty() ? dt : dt * step_scale[static_cast<std::size_t>(e)];
}

inline constexpr int kMaxKernelThreads = 256;
using KernelPartials = std::array<KernelPartial, kMaxKernelThreads>;

inline KernelResult combine_partials(const KernelPartials& partials, int threads) {
  KernelResult r;
  for (int t = 0; t < threads; ++t) {
    const KernelPartial& p = partials[t];
    r.hourglass_work += p.hourglass_work;
    r.bulk_viscosity_work += p.bulk_viscosity_work;
    if (p.min_dt < r.min_dt) {
      r.min_dt = p.min_dt;
      r.min_dt_element = p.min_dt_element;
    }
    if (!r.failed && p.failed_element >= 0) {
      r.failed = true;
      r.failed_element = p.failed_element;
      r.failed_volume = p.failed_measure;
    }
  }
  return r;
}

// Threads of a kernel pass (at most kMaxKernelThreads partials are kept).
inline int kernel_thread_count() {
  const int n = omp_get_max_threads();
  return n < kMaxKernelThreads ? n : kMaxKernelThreads;
}

}  // namespace rf::element
