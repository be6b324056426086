// Throughput of the tetrahedron kernels on an N^3 grid of cells split into six tetrahedra each
// (LS-DYNA's connectivity n1 n2 n3 n4 n4 n4 n4 n4): ELFORM 10 (the ELFORM 1 kernel with the
// hourglass control off, as build_state sets it up) against ELFORM 13 (the nodal-pressure
// tetrahedron: three passes, one of them over the nodes) and ELFORM 16 (the 10-node quadratic
// tetrahedron, 4 points; the same tetrahedra with a mid-side node on each edge). Run with
// OMP_NUM_THREADS=1 for the per-core figure; "ns_per_element" is the time of one element-cycle.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "element/hex_block.hpp"
#include "element/kernels.hpp"
#include "material/registry.hpp"

namespace {

struct Block {
  std::vector<double> x, y, z, vx, vy, vz;
  rf::element::HexBlock block;
  rf::element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
};

Block make_block(int n, int elform, bool bulk, bool plastic) {
  Block b;
  const int m = n + 1;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        b.x.push_back(i + 0.1 * std::sin(0.7 * j + 0.3 * k));
        b.y.push_back(j + 0.1 * std::sin(0.5 * k + 0.2 * i));
        b.z.push_back(k + 0.1 * std::sin(0.4 * i + 0.6 * j));
        b.vx.push_back(1e-3 * std::sin(0.1 * i + 0.2 * j));
        b.vy.push_back(1e-3 * std::cos(0.3 * k));
        b.vz.push_back(1e-3 * std::sin(0.2 * i * j));
      }
  auto id = [m](std::array<int, 3> v) {
    return static_cast<std::int32_t>(v[0] + m * (v[1] + m * v[2]));
  };
  static constexpr std::array<std::array<int, 3>, 6> kOrders{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& order : kOrders) {
          std::array<std::array<int, 3>, 4> v{};
          v[0] = {i, j, k};
          for (int s = 1; s < 4; ++s) {
            v[s] = v[s - 1];
            v[s][static_cast<std::size_t>(order[static_cast<std::size_t>(s - 1)])] += 1;
          }
          auto p = [&](int s) {
            const std::int32_t c = id(v[s]);
            return std::array<double, 3>{b.x[c], b.y[c], b.z[c]};
          };
          const auto a = p(0), e1 = p(1), e2 = p(2), e3 = p(3);
          const double u[3] = {e1[0] - a[0], e1[1] - a[1], e1[2] - a[2]};
          const double w[3] = {e2[0] - a[0], e2[1] - a[1], e2[2] - a[2]};
          const double t[3] = {e3[0] - a[0], e3[1] - a[1], e3[2] - a[2]};
          const double det = u[0] * (w[1] * t[2] - w[2] * t[1]) -
                             u[1] * (w[0] * t[2] - w[2] * t[0]) +
                             u[2] * (w[0] * t[1] - w[1] * t[0]);
          if (det < 0.0) std::swap(v[1], v[2]);
          b.block.element_id.push_back(static_cast<rf::model::Id>(b.block.element_id.size() + 1));
          for (int s = 0; s < 8; ++s)
            b.block.conn.push_back(id(v[static_cast<std::size_t>(std::min(s, 3))]));
        }
  if (elform == 16) {
    // One mid-side node per edge (shared), at the edge's midpoint with the mean velocity.
    std::vector<std::int32_t> conn;
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> midside;
    static constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for (std::size_t e = 0; e < b.block.element_id.size(); ++e) {
      const std::int32_t* c = &b.block.conn[8 * e];
      conn.insert(conn.end(), c, c + 4);
      for (const auto& edge : kEdge) {
        const std::int32_t p = c[edge[0]], q = c[edge[1]];
        const auto [it, inserted] = midside.try_emplace({std::min(p, q), std::max(p, q)},
                                                        static_cast<std::int32_t>(b.x.size()));
        if (inserted) {
          for (auto* a : {&b.x, &b.y, &b.z, &b.vx, &b.vy, &b.vz})
            a->push_back(0.5 *
                         ((*a)[static_cast<std::size_t>(p)] + (*a)[static_cast<std::size_t>(q)]));
        }
        conn.push_back(it->second);
      }
    }
    b.block.conn = std::move(conn);
  }
  b.block.material = rf::material::make_elastic(7800.0, 2.0e11, 0.3);
  if (plastic) {
    b.block.material_index =
        rf::material::material_index(rf::model::MaterialKind::PiecewiseLinearPlasticity);
    b.block.plastic.strain = {0.0, 1.0};
    b.block.plastic.stress = {2.0e8, 1.2e9};
    b.block.plastic.sigy = 2.0e8;
    b.block.plastic.isotropic_modulus = 1.0e9;
  }
  b.block.elform = elform == 10 ? 1 : elform;
  b.block.hourglass.qm = 0.0;                      // ELFORM 10: no hourglass modes (build_state)
  if (bulk) b.block.bulk_viscosity = {1.5, 0.06};  // LS-DYNA's defaults
  rf::element::initialize_block(b.block, b.view());
  return b;
}

void run(benchmark::State& state, int elform, bool bulk, bool plastic = false) {
  Block b = make_block(static_cast<int>(state.range(0)), elform, bulk, plastic);
  for (auto _ : state) {
    auto r = rf::element::compute_block_forces(b.block, b.view(), 1e-7);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  const double elements = static_cast<double>(b.block.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(elements));
  state.counters["ns_per_element"] = benchmark::Counter(
      elements * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_TetElform10(benchmark::State& s) {
  run(s, 10, false);
}
void BM_TetElform13(benchmark::State& s) {
  run(s, 13, false);
}
void BM_TetElform10Bulk(benchmark::State& s) {
  run(s, 10, true);
}
void BM_TetElform13Bulk(benchmark::State& s) {
  run(s, 13, true);
}
void BM_TetElform10Mat024(benchmark::State& s) {
  run(s, 10, true, true);
}
void BM_TetElform13Mat024(benchmark::State& s) {
  run(s, 13, true, true);
}

void BM_TetElform16(benchmark::State& s) {
  run(s, 16, false);
}
void BM_TetElform16Bulk(benchmark::State& s) {
  run(s, 16, true);
}
void BM_TetElform16Mat024(benchmark::State& s) {
  run(s, 16, true, true);
}

BENCHMARK(BM_TetElform10)->Arg(24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetElform13)->Arg(24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetElform10Bulk)->Arg(24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetElform13Bulk)->Arg(24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetElform10Mat024)->Arg(24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetElform13Mat024)->Arg(24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetElform16)->Arg(24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetElform16Bulk)->Arg(24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetElform16Mat024)->Arg(24)->Unit(benchmark::kMillisecond);

}  // namespace
