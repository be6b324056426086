// Contact search and forces per cycle against the number of segments (docs/contact.md,
// docs/performance.md): two N x N x 1 plates of hexahedra, the upper one pressed 1 % of an
// element into the lower one over its whole face, SURFACE_TO_SURFACE between them (both passes).
// "Cycle" times compute_contact_forces with the grids valid (the steady state); "Rebuild" forces
// both grids to be rebuilt every call (the worst case). "ShellCycle", "ThinShellCycle": the same
// with two N x N shell plates of thickness 1 and 0.1 (two-sided segments, contact surfaces at
// t/2: the same 1 % penetration). Counters: segments (both sides), ns per segment and ns per slave
// node (the slave nodes of both passes). Run with OMP_NUM_THREADS=1 for the per-core figure:
//   OMP_NUM_THREADS=1 build/bench/rigidflex_bench --benchmark_filter=Contact
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "contact/contact.hpp"
#include "material/elastic.hpp"
#include "solver/build_state.hpp"

namespace {

struct Plates {
  rf::model::Model model;
  std::unique_ptr<rf::solver::NodeIndex> index;
  rf::solver::State state;
  rf::contact::ContactSystem contacts;
};

// Plate `part` of n x n x 1 unit elements at height z0, nodes appended to the state.
void add_plate(rf::solver::State& state, int n, double z0, double shift, rf::model::Id part) {
  auto& nodes = state.nodes;
  const auto first = static_cast<std::int32_t>(nodes.size());
  const int m = n + 1;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        nodes.id.push_back(static_cast<rf::model::Id>(nodes.id.size() + 1));
        nodes.x.x.push_back(i + shift);
        nodes.x.y.push_back(j + shift);
        nodes.x.z.push_back(z0 + k);
        nodes.mass.push_back(1.0);
      }
  rf::element::HexBlock block;
  block.part_id = part;
  block.material = rf::material::make_elastic(1000.0, 1e7, 0.3);
  auto id = [&](int i, int j, int k) { return first + i + m * (j + m * k); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      block.element_id.push_back(static_cast<rf::model::Id>(block.element_id.size() + 1));
      for (auto c : {id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0), id(i, j + 1, 0),
                     id(i, j, 1), id(i + 1, j, 1), id(i + 1, j + 1, 1), id(i, j + 1, 1)}) {
        block.conn.push_back(c);
      }
      block.volume0.push_back(1.0);
    }
  state.hex_blocks.push_back(std::move(block));
}

// Shell plate `part` of n x n unit quadrilaterals of thickness `t` at height z0.
void add_shell_plate(rf::solver::State& state, int n, double z0, double shift, rf::model::Id part,
                     double t) {
  auto& nodes = state.nodes;
  const auto first = static_cast<std::int32_t>(nodes.size());
  const int m = n + 1;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      nodes.id.push_back(static_cast<rf::model::Id>(nodes.id.size() + 1));
      nodes.x.x.push_back(i + shift);
      nodes.x.y.push_back(j + shift);
      nodes.x.z.push_back(z0);
      nodes.mass.push_back(1.0);
    }
  rf::element::ShellBlock block;
  block.part_id = part;
  block.material = rf::material::make_elastic(1000.0, 1e7, 0.3);
  auto id = [&](int i, int j) { return first + i + m * j; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      block.element_id.push_back(static_cast<rf::model::Id>(block.element_id.size() + 1));
      for (auto c : {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}) {
        block.conn.push_back(c);
        block.thickness.push_back(t);
      }
      block.triangle.push_back(0);
    }
  state.shell_blocks.push_back(std::move(block));
}

// shell_thickness > 0: shell plates of that thickness, mid-surfaces 0.99 t apart.
std::unique_ptr<Plates> make_plates(int n, double shell_thickness = 0.0) {
  auto p = std::make_unique<Plates>();
  rf::model::Part part;
  part.id = 1;
  p->model.parts[1] = part;
  part.id = 2;
  p->model.parts[2] = part;
  rf::model::Contact contact;
  contact.number = 1;
  contact.id = 1;
  contact.ssid = 1;
  contact.msid = 2;
  contact.sstyp = 3;
  contact.mstyp = 3;
  p->model.contacts.push_back(contact);
  if (shell_thickness > 0.0) {  // contact distance (t + t) / 2: 1 % penetration
    add_shell_plate(p->state, n, 0.99 * shell_thickness, 0.3, 1, shell_thickness);
    add_shell_plate(p->state, n, 0.0, 0.0, 2, shell_thickness);
  } else {
    add_plate(p->state, n, 0.99, 0.3, 1);  // upper plate, 1 % into the lower one, offset in x y
    add_plate(p->state, n, 0.0, 0.0, 2);
  }
  const std::size_t count = p->state.nodes.size();
  p->state.nodes.v.resize(count);
  p->state.nodes.f_ext.resize(count);
  p->index = std::make_unique<rf::solver::NodeIndex>(p->model);
  p->contacts = rf::contact::build_contacts(p->model, *p->index, p->state);
  return p;
}

std::int64_t segment_count(const rf::contact::ContactSystem& contacts) {
  std::int64_t n = 0;
  for (const auto& side : contacts.interfaces[0].sides) {
    n += static_cast<std::int64_t>(side.segments.size());
  }
  return n;
}

void run(benchmark::State& bench, bool rebuild, double shell_thickness = 0.0) {
  const auto plates = make_plates(static_cast<int>(bench.range(0)), shell_thickness);
  rf::contact::compute_contact_forces(plates->contacts, plates->state, 1e-6);
  for (auto _ : bench) {
    if (rebuild) {
      for (auto& pass : plates->contacts.interfaces[0].passes) pass.grid.built = false;
    }
    rf::contact::compute_contact_forces(plates->contacts, plates->state, 1e-6);
    benchmark::DoNotOptimize(plates->contacts.force.z.data());
  }
  const auto segments = segment_count(plates->contacts);
  bench.counters["segments"] = static_cast<double>(segments);
  bench.counters["in_contact"] = static_cast<double>(plates->contacts.interfaces[0].active_nodes);
  bench.counters["ns_per_segment"] = benchmark::Counter(
      static_cast<double>(segments) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  std::int64_t slave_nodes = 0;
  for (const auto& pass : plates->contacts.interfaces[0].passes) {
    slave_nodes += static_cast<std::int64_t>(pass.results.size());
  }
  bench.counters["ns_per_slave_node"] = benchmark::Counter(
      static_cast<double>(slave_nodes) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void ContactCycle(benchmark::State& bench) {
  run(bench, false);
}
void ContactRebuild(benchmark::State& bench) {
  run(bench, true);
}
// Shells as thick as the elements are long (the reach of the search grows with the thickness)
// and a typical t = h / 10.
void ContactShellCycle(benchmark::State& bench) {
  run(bench, false, 1.0);
}
void ContactThinShellCycle(benchmark::State& bench) {
  run(bench, false, 0.1);
}

// N = 50, 158, 500: about 1e4, 1e5, 1e6 segments over both plates (2 N^2 + 4 N each).
BENCHMARK(ContactCycle)->Arg(50)->Arg(158)->Arg(500)->Unit(benchmark::kMillisecond);
BENCHMARK(ContactRebuild)->Arg(50)->Arg(158)->Arg(500)->Unit(benchmark::kMillisecond);
// Shells: N = 70, 224: about 1e4, 1e5 segments (2 N^2).
BENCHMARK(ContactShellCycle)->Arg(70)->Arg(224)->Unit(benchmark::kMillisecond);
BENCHMARK(ContactThinShellCycle)->Arg(70)->Arg(224)->Unit(benchmark::kMillisecond);

}  // namespace
