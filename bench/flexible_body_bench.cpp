// Cost of one explicit cycle with a die-like solid part that is fully deformable, rigid, or a
// flexible rigid body (*PART_MODES) with 10/20/40/70 modes (FORM 0 and 1) on a deformable plate.
// Two setups: bonded (BM_Die*: the die shares the plate's nodes over its bottom face and is pushed
// by a load on its top face) and contact (BM_ContactDie*: the die starts 0.1 mm above the plate,
// moving at 5 m/s, and strikes it through *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE; the timed cycles
// lie within the impact). The seed's forming example compares the same variants
// (docs/performance.md, "Flexible bodies"). The die's modes come from the eigen analysis of the
// die alone, computed once per setup.
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
// With contact the die has its own bottom nodes (k = 0), 0.1 mm above the plate and shifted by
// half a plate cell so that no die node lies on a plate node.
constexpr double kContactGap = 1e-4, kContactSpeed = 5.0;
int die_node(int i, int j, int k, bool contact = false) {  // k = 0: the die's bottom face
  const int offset = (kPlate - kDie) / 2;
  if (k == 0 && !contact) return plate_node(i + offset, j + offset, kPlateLayers);
  return 100000 + i + (kDie + 1) * (j + (kDie + 1) * k);
}

std::string deck(const std::string& die_material, const std::string& extra, bool with_plate,
                 bool contact = false) {
  const double h = kPlateSize / kPlate, t = kPlateThickness / kPlateLayers;
  const double hd = kDieHeight / kDieLayers;
  const int offset = (kPlate - kDie) / 2;
  std::string s = "*KEYWORD\n*NODE\n";
  for (int k = 0; k <= kPlateLayers; ++k)
    for (int j = 0; j <= kPlate; ++j)
      for (int i = 0; i <= kPlate; ++i) {
        const bool die_face = k == kPlateLayers && i >= offset && i <= offset + kDie &&
                              j >= offset && j <= offset + kDie;
        if (!with_plate && (contact || !die_face)) continue;
        s += fmt::format("{},{:.9g},{:.9g},{:.9g}\n", plate_node(i, j, k), i * h, j * h, k * t);
      }
  const double shift = contact ? 0.5 : 0.0, gap = contact ? kContactGap : 0.0;
  for (int k = contact ? 0 : 1; k <= kDieLayers; ++k)
    for (int j = 0; j <= kDie; ++j)
      for (int i = 0; i <= kDie; ++i) {
        s += fmt::format("{},{:.9g},{:.9g},{:.9g}\n", die_node(i, j, k, contact),
                         (i + offset + shift) * h, (j + offset + shift) * h,
                         kPlateThickness + gap + k * hd);
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
        const auto n = [&](int a, int b, int c) { return die_node(i + a, j + b, k + c, contact); };
        s += fmt::format("{},1,{},{},{},{},{},{},{},{}\n", ++eid, n(0, 0, 0), n(1, 0, 0),
                         n(1, 1, 0), n(0, 1, 0), n(0, 0, 1), n(1, 0, 1), n(1, 1, 1), n(0, 1, 1));
      }
  s += "*PART\ndie\n1,1,1\n*SECTION_SOLID\n1,2\n" + die_material;
  if (with_plate && contact) {
    s += "*PART\nplate\n2,2,2,0,2\n*SECTION_SOLID\n2,1\n*MAT_ELASTIC\n2,7850,2e11,0.3\n"
         "*HOURGLASS\n2,6,0.1\n";
    // Plate pinned along the edges of its bottom face; the die strikes it.
    s += "*SET_NODE_LIST\n1\n";
    int count = 0;
    for (int j = 0; j <= kPlate; ++j)
      for (int i = 0; i <= kPlate; ++i) {
        if (i != 0 && i != kPlate && j != 0 && j != kPlate) continue;
        s += fmt::format("{}{}", count % 8 == 0 ? "" : ",", plate_node(i, j, 0));
        if (++count % 8 == 0) s += "\n";
      }
    if (count % 8 != 0) s += "\n";
    s += fmt::format(
        "*BOUNDARY_SPC_SET\n1,0,1,1,1\n*INITIAL_VELOCITY_GENERATION\n1,2,0,0,0,{}\n0,0,0,0,0,0\n"
        "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n1,die\n1,2,3,3\n0,0,0,0,0\n1,1\n",
        -kContactSpeed);
  } else if (with_plate) {
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

rf::modal::ModeSet compute_die_modes(bool contact) {
  rf::modal::EigenRequest request;
  request.mode_count = 70;
  request.remove_rigid_below = true;
  request.left_frequency = 1.0;
  return rf::modal::compute_modes(
      rf::io::read_deck_text(deck(kElasticDie, "", false, contact), "die.k"), request);
}

const rf::modal::ModeSet& die_modes(bool contact) {
  static const rf::modal::ModeSet bonded = compute_die_modes(false);
  if (!contact) return bonded;
  static const rf::modal::ModeSet separate = compute_die_modes(true);
  return separate;
}

void run_cycles(benchmark::State& bench, const std::string& text, bool contact = false) {
  rf::solver::SimulationOptions options;
  options.write_fields = false;
  options.mode_loader = [contact](const std::filesystem::path&) { return die_modes(contact); };
  rf::solver::Simulation sim(rf::io::read_deck_text(text, "bench.k"), options);
  for (int k = 0; k < 20; ++k) sim.cycle();  // warm caches
  if (!contact) {
    for (auto _ : bench) sim.cycle();
  } else {  // the share of the timed cycles with nodes in contact (1: all within the impact)
    std::int64_t cycles = 0, in_contact = 0;
    for (auto _ : bench) {
      sim.cycle();
      ++cycles;
      in_contact += sim.contacts().interfaces[0].active_nodes > 0 ? 1 : 0;
    }
    bench.counters["in_contact"] = static_cast<double>(in_contact) / static_cast<double>(cycles);
  }
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

void BM_ContactDieDeformable(benchmark::State& bench) {
  run_cycles(bench, deck(kElasticDie, "", true, true), true);
}
void BM_ContactDieRigid(benchmark::State& bench) {
  run_cycles(bench, deck(kRigidDie, "", true, true), true);
}
void BM_ContactDieFlexible(benchmark::State& bench) {
  const int modes = static_cast<int>(bench.range(0));
  const int form = static_cast<int>(bench.range(1));
  run_cycles(bench,
             deck(kRigidDie, fmt::format("*PART_MODES\n1,{},{},0,3\ndie_modes.h5\n", modes, form),
                  true, true),
             true);
}

BENCHMARK(BM_DieDeformable)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DieRigid)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DieFlexible)->ArgsProduct({{10, 20, 40, 70}, {0, 1}})->Unit(benchmark::kMicrosecond);
// A fixed number of cycles (after 20 warm-up cycles), all within the impact (counter
// in_contact: the share of them with nodes in contact).
BENCHMARK(BM_ContactDieDeformable)->Iterations(150)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ContactDieRigid)->Iterations(150)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ContactDieFlexible)
    ->ArgsProduct({{10, 20, 40, 70}, {0, 1}})
    ->Iterations(150)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
