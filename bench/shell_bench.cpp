// Throughput of compute_shell_forces (Belytschko-Lin-Tsay ELFORM 2, fully integrated ELFORM 16)
// on an N x N plate, mildly
// warped, with smooth velocity and angular velocity fields. Run with OMP_NUM_THREADS=1 for the
// per-core figure; "ns_per_element" is the time of one element-cycle (kernel only: no gather
// of the assembly, no time integration).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "element/shell_block.hpp"
#include "material/registry.hpp"

namespace {

struct Plate {
  std::vector<double> x, y, z, vx, vy, vz, wx, wy, wz;
  rf::element::ShellBlock block;
  rf::element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
  rf::element::RotationalView rotations() const { return {wx.data(), wy.data(), wz.data()}; }
};

Plate make_plate(int n, int nip, int ihq, int material_index, int elform, int istupd) {
  Plate p;
  p.block.elform = elform;
  p.block.thickness_update = istupd;  // *CONTROL_SHELL ISTUPD
  const int m = n + 1;
  const double h = 0.01;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      p.x.push_back(h * (i + 0.1 * std::sin(0.7 * j)));
      p.y.push_back(h * (j + 0.1 * std::sin(0.5 * i)));
      p.z.push_back(1e-4 * std::sin(0.3 * i + 0.2 * j));
      p.vx.push_back(1e-2 * std::sin(0.1 * i + 0.2 * j));
      p.vy.push_back(1e-2 * std::cos(0.3 * j));
      p.vz.push_back(1e-1 * std::sin(0.05 * i * j));
      p.wx.push_back(0.5 * std::cos(0.2 * i));
      p.wy.push_back(0.5 * std::sin(0.1 * j));
      p.wz.push_back(0.1);
    }
  auto id = [m](int i, int j) { return static_cast<std::int32_t>(i + m * j); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      p.block.element_id.push_back(static_cast<rf::model::Id>(p.block.element_id.size() + 1));
      for (auto c : {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}) {
        p.block.conn.push_back(c);
        p.block.rotation_conn.push_back(c);
        p.block.thickness.push_back(1e-3);
      }
    }
  p.block.material = rf::material::make_elastic(7800.0, 2.0e11, 0.3);
  p.block.material_index = material_index;
  if (material_index != 0) {
    p.block.plastic.sigy = 2.5e8;
    p.block.plastic.isotropic_modulus = 1e9;
    p.block.plastic.strain = {0.0, 1.0};
    p.block.plastic.stress = {2.5e8, 2.5e8 + 1e9};
  }
  p.block.nip = nip;
  p.block.hourglass.ihq = ihq;
  p.block.hourglass.qm = 0.1;
  rf::element::initialize_shell_block(p.block, p.view());
  return p;
}

void run(benchmark::State& state, int nip, int ihq, int material_index, int elform = 2,
         int istupd = 0) {
  Plate p = make_plate(static_cast<int>(state.range(0)), nip, ihq, material_index, elform, istupd);
  for (auto _ : state) {
    auto r = rf::element::compute_shell_forces(p.block, p.view(), p.rotations(), 1e-7);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  const double elements = static_cast<double>(p.block.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(elements));
  state.counters["ns_per_element"] = benchmark::Counter(
      elements * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_ShellBltNip2Ihq1(benchmark::State& s) {
  run(s, 2, 1, 0);
}
void BM_ShellBltNip2Ihq4(benchmark::State& s) {
  run(s, 2, 4, 0);
}
void BM_ShellBltNip5Ihq1(benchmark::State& s) {
  run(s, 5, 1, 0);
}
void BM_ShellBltNip5Mat024(benchmark::State& s) {
  run(s, 5, 1, 2);
}
// ELFORM 16: four in-plane points, no hourglass control (IHQ ignored).
void BM_ShellFullNip2(benchmark::State& s) {
  run(s, 2, 1, 0, 16);
}
void BM_ShellFullNip5Mat024(benchmark::State& s) {
  run(s, 5, 1, 2, 16);
}
// The thickness update (*CONTROL_SHELL ISTUPD 1): what it adds to the kernels above.
void BM_ShellBltNip2Ihq1Istupd1(benchmark::State& s) {
  run(s, 2, 1, 0, 2, 1);
}
void BM_ShellBltNip5Mat024Istupd1(benchmark::State& s) {
  run(s, 5, 1, 2, 2, 1);
}
void BM_ShellFullNip2Istupd1(benchmark::State& s) {
  run(s, 2, 1, 0, 16, 1);
}

BENCHMARK(BM_ShellBltNip2Ihq1)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShellBltNip2Ihq4)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShellBltNip5Ihq1)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShellBltNip5Mat024)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShellFullNip2)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShellFullNip5Mat024)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShellBltNip2Ihq1Istupd1)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShellBltNip5Mat024Istupd1)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShellFullNip2Istupd1)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace
