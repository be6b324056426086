// Throughput of compute_beam_forces on a long zig-zag chain of 2-node beams (ELFORM 1 rectangle
// elastic and J2, ELFORM 2 elastic, ELFORM 3 truss). Run with OMP_NUM_THREADS=1 for the
// per-core figure; the "ns_per_element" counter is the time of one element-cycle.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "element/beam_block.hpp"
#include "material/registry.hpp"

namespace {

struct Chain {
  std::vector<double> x, y, z, vx, vy, vz, wx, wy, wz;
  rf::element::BeamBlock block;
  rf::element::NodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
  rf::element::RotationalView rview() const { return {wx.data(), wy.data(), wz.data()}; }
};

Chain make_chain(int n, int elform, bool plastic) {
  Chain c;
  for (int i = 0; i <= n; ++i) {
    c.x.push_back(0.1 * i);
    c.y.push_back(0.01 * std::sin(0.7 * i));
    c.z.push_back(0.01 * std::cos(0.3 * i));
    c.vx.push_back(1e-3 * std::sin(0.1 * i));
    c.vy.push_back(1e-3 * std::cos(0.2 * i));
    c.vz.push_back(1e-3 * std::sin(0.3 * i));
    c.wx.push_back(1e-2 * std::sin(0.4 * i));
    c.wy.push_back(1e-2 * std::cos(0.5 * i));
    c.wz.push_back(1e-2 * std::sin(0.6 * i));
  }
  rf::element::BeamBlock& b = c.block;
  b.elform = elform;
  b.material = rf::material::make_elastic(7800.0, 2.0e11, 0.3);
  b.material_index = rf::material::material_index(
      plastic ? rf::model::MaterialKind::PlasticKinematic : rf::model::MaterialKind::Elastic);
  b.plastic.sigy = 1e3;  // yields at once: every point takes the plastic return
  b.plastic.isotropic_modulus = 1e9;
  b.plastic.strain = {0.0, 1.0};
  b.plastic.stress = {1e3, 1e3 + 1e9};
  b.area = 6e-4;
  b.iss = 4.5e-8;
  b.itt = 2e-8;
  b.torsion = 4e-8;
  b.ts1 = 0.02;
  b.tt1 = 0.03;
  for (int e = 0; e < n; ++e) {
    b.element_id.push_back(e + 1);
    b.conn.insert(b.conn.end(), {e, e + 1});
    b.rotation_conn.insert(b.rotation_conn.end(), {elform == 3 ? -1 : e, elform == 3 ? -1 : e + 1});
  }
  rf::element::initialize_beam_block(b, c.view());
  return c;
}

void run(benchmark::State& state, int elform, bool plastic) {
  Chain c = make_chain(static_cast<int>(state.range(0)), elform, plastic);
  for (auto _ : state) {
    auto r = rf::element::compute_beam_forces(c.block, c.view(), c.rview(), 1e-7);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  const double elements = static_cast<double>(c.block.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(elements));
  state.counters["ns_per_element"] = benchmark::Counter(
      elements * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_BeamElform2(benchmark::State& s) {
  run(s, 2, false);
}
void BM_BeamElform1Elastic(benchmark::State& s) {
  run(s, 1, false);
}
void BM_BeamElform1Plastic(benchmark::State& s) {
  run(s, 1, true);
}
void BM_Truss(benchmark::State& s) {
  run(s, 3, false);
}

BENCHMARK(BM_BeamElform2)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BeamElform1Elastic)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BeamElform1Plastic)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Truss)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
