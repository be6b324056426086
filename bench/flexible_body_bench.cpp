// Cost of one explicit cycle with a die-like solid part that is fully deformable, rigid, or a
// flexible rigid body (*PART_MODES) with 10/20/40/70 modes (FORM 0 and 1), bonded to a
// deformable plate and pushed by a load on its top face. The seed's forming example compares the
// same variants (docs/performance.md, "Flexible bodies"). The die's modes come from the eigen
// analysis of the die alone, computed once.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <string>

#include "io/keyword/reader.hpp"
#include "modal/eigen_analysis.hpp"
#include "solver/simulation.hpp"

namespace {

constexpr int kPlate = 24, kPlateLayers = 2, kDie = 16, kDieLayers = 8;
constexpr double kPlateSize = 0.24, kPlateThickness = 0.02, kDieHeight = 0.08;

// Node IDs: plate (i, j, k) -> 1 + i + (n+1)(j + (n+1) k); die nodes above the plate's top face
// start at 100000. The die's bottom face is the plate's top face over the middle 16 x 16 cells.
int plate_node(int i, int j, int k) {
  return 1 + i + (kPlate + 1) * (j + (kPlate + 1) * k);
}
int die_node(int i, int j, int k) {  // k >= 0 in die layers, k = 0 on the plate
  const int offset = (kPlate - kDie) / 2;
  if (k == 0) return plate_node(i + offset, j + offset, kPlateLayers);
  return 100000 + i + (kDie + 1) * (j + (kDie + 1) * k);
}

std::string deck(const std::string& die_material, const std::string& extra, bool with_plate) {
  const double h = kPlateSize / kPlate, t = kPlateThickness / kPlateLayers;
  const double hd = kDieHeight / kDieLayers;
  const int offset = (kPlate - kDie) / 2;
  std::string s = "*KEYWORD\n*NODE\n";
  for (int k = 0; k <= kPlateLayers; ++k)
    for (int j = 0; j <= kPlate; ++j)
      for (int i = 0; i <= kPlate; ++i) {
        const bool die_face = k == kPlateLayers && i >= offset && i <= offset + kDie &&
                              j >= offset && j <= offset + kDie;
        if (!with_plate && !die_face) continue;
        s += fmt::format("{},{:.9g},{:.9g},{:.9g}\n", plate_node(i, j, k), i * h, j * h, k * t);
      }
  for (int k = 1; k <= kDieLayers; ++k)
    for (int j = 0; j <= kDie; ++j)
      for (int i = 0; i <= kDie; ++i) {
        s += fmt::format("{},{:.9g},{:.9g},{:.9g}\n", die_node(i, j, k), (i + offset) * h,
                         (j + offset) * h, kPlateThickness + k * hd);
      }
  s += "*ELEMENT_SOLID\n";
  int eid = 0;
  if (with_plate) {
    for (int k = 0; k < kPlateLayers; ++k)
      for (int j = 0; j < kPlate; ++j)
        for (int i = 0; i < kPlate; ++i) {
          s += fmt::format("{},2,{},{},{},{},{},{},{},{}\n", ++eid, plate_node(i, j, k),
                           plate_node(i + 1, j, k), plate_node(i + 1, j + 1, k),
                           plate_node(i, j + 1, k), plate_node(i, j, k + 1),
                           plate_node(i + 1, j, k + 1), plate_node(i + 1, j + 1, k + 1),
                           plate_node(i, j + 1, k + 1));
        }
  }
  eid = 10000;
  for (int k = 0; k < kDieLayers; ++k)
    for (int j = 0; j < kDie; ++j)
      for (int i = 0; i < kDie; ++i) {
        s += fmt::format("{},1,{},{},{},{},{},{},{},{}\n", ++eid, die_node(i, j, k),
                         die_node(i + 1, j, k), die_node(i + 1, j + 1, k), die_node(i, j + 1, k),
                         die_node(i, j, k + 1), die_node(i + 1, j, k + 1),
                         die_node(i + 1, j + 1, k + 1), die_node(i, j + 1, k + 1));
      }
  s += "*PART\ndie\n1,1,1\n*SECTION_SOLID\n1,2\n" + die_material;
  if (with_plate) {
    s += "*PART\nplate\n2,2,2,0,2\n*SECTION_SOLID\n2,1\n*MAT_ELASTIC\n2,7850,2e11,0.3\n"
         "*HOURGLASS\n2,6,0.1\n";
    // Top face of the die pushed down.
    s += "*SET_NODE_LIST\n1\n";
    int count = 0;
    for (int j = 0; j <= kDie; ++j)
      for (int i = 0; i <= kDie; ++i) {
        s += fmt::format("{}{}", count % 8 == 0 ? "" : ",", die_node(i, j, kDieLayers));
        if (++count % 8 == 0) s += "\n";
      }
    if (count % 8 != 0) s += "\n";
    s += "*LOAD_NODE_SET\n1,3,1,-100.0\n*DEFINE_CURVE\n1\n0,0\n1e-3,1\n1,1\n";
  }
  return s + extra + "*CONTROL_TERMINATION\n1,0\n*END\n";
}

const std::string kElasticDie = "*MAT_ELASTIC\n1,7850,2e11,0.3\n";
const std::string kRigidDie = "*MAT_RIGID\n1,7850,2e11,0.3\n0,0,0\n";

const rf::modal::ModeSet& die_modes() {
  static const rf::modal::ModeSet modes = [] {
    rf::modal::EigenRequest request;
    request.mode_count = 70;
    request.remove_rigid_below = true;
    request.left_frequency = 1.0;
    return rf::modal::compute_modes(rf::io::read_deck_text(deck(kElasticDie, "", false), "die.k"),
                                    request);
  }();
  return modes;
}

void run_cycles(benchmark::State& bench, const std::string& text) {
  rf::solver::SimulationOptions options;
  options.write_fields = false;
  options.mode_loader = [](const std::filesystem::path&) { return die_modes(); };
  rf::solver::Simulation sim(rf::io::read_deck_text(text, "bench.k"), options);
  for (int k = 0; k < 20; ++k) sim.cycle();  // warm caches
  for (auto _ : bench) sim.cycle();
  bench.counters["dt_us"] = sim.state().dt * 1e6;
}

void BM_DieDeformable(benchmark::State& bench) {
  run_cycles(bench, deck(kElasticDie, "", true));
}
void BM_DieRigid(benchmark::State& bench) {
  run_cycles(bench, deck(kRigidDie, "", true));
}
void BM_DieFlexible(benchmark::State& bench) {
  const int modes = static_cast<int>(bench.range(0));
  const int form = static_cast<int>(bench.range(1));
  run_cycles(
      bench,
      deck(kRigidDie, fmt::format("*PART_MODES\n1,{},{},0,3\ndie_modes.h5\n", modes, form), true));
}

BENCHMARK(BM_DieDeformable)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DieRigid)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DieFlexible)->ArgsProduct({{10, 20, 40, 70}, {0, 1}})->Unit(benchmark::kMicrosecond);

}  // namespace
