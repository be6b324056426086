// Throughput of compute_hex_forces on a structured N^3 block. Run with OMP_NUM_THREADS=1 for the
// per-core figure; the "ns_per_element" counter is the time of one element-cycle.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "element/hex_block.hpp"

namespace {

struct Block {
  std::vector<double> x, y, z, vx, vy, vz;
  rf::element::HexBlock block;
  rf::element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
};

Block make_block(int n, int elform, int ihq, bool bulk) {
  Block b;
  const int m = n + 1;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        // Mildly distorted grid with a smooth velocity field.
        b.x.push_back(i + 0.1 * std::sin(0.7 * j + 0.3 * k));
        b.y.push_back(j + 0.1 * std::sin(0.5 * k + 0.2 * i));
        b.z.push_back(k + 0.1 * std::sin(0.4 * i + 0.6 * j));
        b.vx.push_back(1e-3 * std::sin(0.1 * i + 0.2 * j));
        b.vy.push_back(1e-3 * std::cos(0.3 * k));
        b.vz.push_back(1e-3 * std::sin(0.2 * i * j));
      }
  auto id = [m](int i, int j, int k) { return static_cast<std::int32_t>(i + m * (j + m * k)); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        b.block.element_id.push_back(static_cast<rf::model::Id>(b.block.element_id.size() + 1));
        for (auto c :
             {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
              id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)})
          b.block.conn.push_back(c);
      }
  b.block.material = rf::material::make_elastic(7800.0, 2.0e11, 0.3);
  b.block.elform = elform;
  b.block.hourglass.ihq = ihq;
  b.block.hourglass.qm = ihq == 6 ? 1.0 : 0.1;
  if (bulk) b.block.bulk_viscosity = {1.5, 0.06};  // LS-DYNA's defaults
  rf::element::initialize_hex_block(b.block, b.view());
  return b;
}

// `bulk`: with the bulk viscosity of LS-DYNA decks (the field compresses some elements).
void run(benchmark::State& state, int elform, int ihq, bool bulk = false) {
  Block b = make_block(static_cast<int>(state.range(0)), elform, ihq, bulk);
  for (auto _ : state) {
    auto r = rf::element::compute_hex_forces(b.block, b.view(), 1e-7);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  const double elements = static_cast<double>(b.block.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(elements));
  state.counters["ns_per_element"] = benchmark::Counter(
      elements * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_HexElform1Ihq1(benchmark::State& s) {
  run(s, 1, 1);
}
void BM_HexElform1Ihq2(benchmark::State& s) {
  run(s, 1, 2);
}
void BM_HexElform1Ihq6(benchmark::State& s) {
  run(s, 1, 6);
}
void BM_HexElform2(benchmark::State& s) {
  run(s, 2, 0);
}
void BM_HexElform1Ihq1Bulk(benchmark::State& s) {
  run(s, 1, 1, true);
}
void BM_HexElform1Ihq6Bulk(benchmark::State& s) {
  run(s, 1, 6, true);
}
void BM_HexElform2Bulk(benchmark::State& s) {
  run(s, 2, 0, true);
}

BENCHMARK(BM_HexElform1Ihq1)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexElform1Ihq2)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexElform1Ihq6)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexElform2)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexElform1Ihq1Bulk)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexElform1Ihq6Bulk)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexElform2Bulk)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

}  // namespace
