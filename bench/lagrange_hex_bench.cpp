// Throughput of compute_lagrange_hex_forces on a structured N^3 block of 8-node hexahedra raised
// to order p (mesh/p_order). Run with OMP_NUM_THREADS=1 for the per-core figure;
// "ns_per_element" is one element evaluation, "ns_per_node_slot" the same divided by (p+1)^3.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <vector>

#include "element/lagrange_hex.hpp"
#include "mesh/p_order.hpp"

namespace {

struct Block {
  std::vector<double> x, y, z, vx, vy, vz;
  rf::element::HexBlock block;
  rf::element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
};

Block make_block(int n, int order) {
  const int m = n + 1;
  std::vector<std::array<double, 3>> corners;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        corners.push_back({i + 0.1 * std::sin(0.7 * j + 0.3 * k),
                           j + 0.1 * std::sin(0.5 * k + 0.2 * i),
                           k + 0.1 * std::sin(0.4 * i + 0.6 * j)});
  auto id = [m](int i, int j, int k) { return static_cast<std::int32_t>(i + m * (j + m * k)); };
  std::vector<std::array<std::int32_t, 8>> hexes;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                         id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                         id(i, j + 1, k + 1)});
  Block b;
  rf::mesh::HexElevator elevator(order, corners);
  b.block.conn = elevator.add_block(hexes);
  for (const auto& c : corners) {
    b.x.push_back(c[0]);
    b.y.push_back(c[1]);
    b.z.push_back(c[2]);
  }
  b.vx.assign(b.x.size(), 0.0);
  b.vy.assign(b.x.size(), 0.0);
  b.vz.assign(b.x.size(), 0.0);
  b.block.order = order;
  b.block.material = rf::material::make_elastic(7800.0, 2.0e11, 0.3);
  for (std::size_t e = 0; e < hexes.size(); ++e)
    b.block.element_id.push_back(static_cast<rf::model::Id>(e + 1));
  rf::element::initialize_lagrange_hex_block(b.block, b.view());
  // A smooth deformation so that every point has a non-trivial F.
  for (std::size_t a = 0; a < b.x.size(); ++a) {
    const double X = b.x[a], Y = b.y[a], Z = b.z[a];
    b.x[a] += 1e-3 * std::sin(0.1 * Y + 0.2 * Z);
    b.y[a] += 1e-3 * std::cos(0.3 * Z) * X * 0.1;
    b.z[a] += 1e-3 * std::sin(0.2 * X * Y * 0.1);
  }
  return b;
}

void run(benchmark::State& state, int order) {
  Block b = make_block(static_cast<int>(state.range(0)), order);
  for (auto _ : state) {
    auto r = rf::element::compute_lagrange_hex_forces(b.block, b.view(), 1e-7);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  const double elements = static_cast<double>(b.block.size());
  const double slots = elements * b.block.nodes_per_element();
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(elements));
  state.counters["ns_per_element"] = benchmark::Counter(
      elements * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["ns_per_node_slot"] = benchmark::Counter(
      slots * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_LagrangeHexP2(benchmark::State& s) {
  run(s, 2);
}
void BM_LagrangeHexP3(benchmark::State& s) {
  run(s, 3);
}

// Set-up cost per element (reference Jacobians and the Lanczos eigenvalue estimate).
void BM_LagrangeHexInit(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  Block b = make_block(8, order);
  for (auto _ : state) {
    rf::element::initialize_lagrange_hex_block(b.block, b.view());
    benchmark::ClobberMemory();
  }
  const double elements = static_cast<double>(b.block.size());
  state.counters["us_per_element"] = benchmark::Counter(
      elements * 1e-6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_LagrangeHexP2)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LagrangeHexP3)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LagrangeHexInit)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

}  // namespace
