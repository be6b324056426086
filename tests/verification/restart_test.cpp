// Restart: a run stopped after a dump and continued with `restart` must write the same files,
// byte for byte, as the same run left alone (same thread count). The reference is the
// uninterrupted run, which depends on none of the restart code: a state member the dump forgot,
// a value rounded on its way through the file, a CSV row written twice or missed, a frame
// renumbered, all show up as a differing byte. The later dumps are compared too, so the restored
// state is checked as a whole, not only through the output.
#include <gtest/gtest.h>

#include <hdf5.h>
#include <omp.h>
#include <unistd.h>
#include <cstdio>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "io/keyword/reader.hpp"
#include "modal/eigen_analysis.hpp"
#include "model/error.hpp"
#include "restart/dumper.hpp"
#include "restart/restart.hpp"
#include "restart_decks.hpp"

namespace rf::test {
namespace {

namespace fs = std::filesystem;

// ctest runs every test in its own process, side by side: directories carry the process ID.
fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("rigidflex_restart_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Interrupted {};

// What `rigidflex run DECK -o dir --dump-every interval` does. With `stop_after` the run is
// abandoned at the first cycle past that time, as if killed: the files keep the rows, frames and
// dumps written until then.
void run_with_dumps(const fs::path& deck, const fs::path& dir, double interval,
                    std::optional<double> stop_after = std::nullopt,
                    const std::map<std::string, double>& overrides = {}) {
  restart::ModelInput input;
  io::ReadOptions read_options;
  read_options.parameter_overrides = overrides;
  read_options.record_files = &input.files;
  model::Model model = io::read_deck(deck, read_options);
  input.main_deck = deck.string();
  input.overrides = overrides;
  solver::Simulation sim(std::move(model), {dir, true});
  sim.enable_restart_dumps(
      std::make_unique<restart::Dumper>(std::move(input), restart::Dumper::every(interval)));
  try {
    sim.run([&](const solver::Simulation& s) {
      if (stop_after && s.state().time > *stop_after) throw Interrupted{};
    });
  } catch (const Interrupted&) {
  }
}

restart::Restarted restart_and_run(const fs::path& dump, const fs::path& restart_deck = {},
                                   const fs::path& output = {}) {
  restart::RestartOptions options;
  options.dump = dump;
  options.restart_deck = restart_deck;
  options.output_directory = output;
  restart::Restarted r = restart::restart_from_dump(options);
  r.simulation->run();
  return r;
}

// The files of `reference` that `keep` accepts must exist in `other` with the same bytes.
template <class Keep>
int expect_same_files(const fs::path& reference, const fs::path& other, Keep keep) {
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(reference)) {
    const std::string name = entry.path().filename().string();
    if (!keep(name)) continue;
    ++compared;
    const std::string a = read_file(entry.path());
    const std::string b = read_file(other / name);
    if (a == b) continue;
    std::size_t first = 0;
    while (first < std::min(a.size(), b.size()) && a[first] == b[first]) ++first;
    ADD_FAILURE() << name << " differs from the uninterrupted run's at byte " << first << " ("
                  << a.size() << " vs " << b.size() << " bytes)";
  }
  return compared;
}

int expect_same_files(const fs::path& reference, const fs::path& other) {
  return expect_same_files(reference, other, [](const std::string&) { return true; });
}

bool is_result(const std::string& name) {
  return name.ends_with(".csv") || name.ends_with(".vtu") || name.ends_with(".pvd");
}

struct Case {
  std::string name;
  std::string deck;  // deck text, or empty to use `file`
  std::string file;
  std::map<std::string, double> overrides;
  double dump_interval = 0.0;
  int threads = 1;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name << ", " << c.threads << " thread(s)";
}

std::string case_name(const testing::TestParamInfo<Case>& info) {
  return info.param.name + "_" + std::to_string(info.param.threads) + "_threads";
}

class RestartBitwise : public testing::TestWithParam<Case> {};

TEST_P(RestartBitwise, StoppedAfterADumpAndRestartedEqualsUninterrupted) {
  const Case& c = GetParam();
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(c.threads);
  const std::string tag = c.name + "_" + std::to_string(c.threads);
  const fs::path base = scratch(tag);
  fs::path deck = c.file;
  if (!c.deck.empty()) {
    deck = base / "deck.k";
    write_file(deck, c.deck);
  }
  const fs::path reference = base / "reference";
  const fs::path interrupted = base / "interrupted";
  run_with_dumps(deck, reference, c.dump_interval, std::nullopt, c.overrides);
  ASSERT_TRUE(fs::exists(reference / "d3dump_0004.h5")) << "the case must dump at least 4 times";

  // Stopped a while after the third dump; restarted from the second, so the restart has rows,
  // frames and a dump of the interrupted run to replace.
  run_with_dumps(deck, interrupted, c.dump_interval, 3.5 * c.dump_interval, c.overrides);
  ASSERT_TRUE(fs::exists(interrupted / "d3dump_0003.h5"));
  ASSERT_FALSE(fs::exists(interrupted / "d3dump_0004.h5"));
  omp_set_num_threads(1);  // the restart must take the thread count from the dump
  const restart::Restarted r = restart_and_run(interrupted / "d3dump_0002.h5");
  omp_set_num_threads(saved_threads);
  EXPECT_EQ(r.threads, c.threads);
  EXPECT_GT(r.header.cycle, 0);
  EXPECT_TRUE(r.warnings.empty());

  const int compared = expect_same_files(reference, interrupted);
  EXPECT_GE(compared, 10);  // CSV files, frames, collection and dumps
  for (const char* name : {"glstat.csv", "frames.pvd"}) EXPECT_TRUE(fs::exists(interrupted / name));
  if (!HasFailure()) fs::remove_all(base);  // kept for inspection otherwise
}

// The spinning deck with mass-proportional damping: global on the shaft, a curve on the rigid
// hub (the damping forces in f_ext and the damping work cross the dump).
std::string damped_spinning_rigid() {
  std::string deck = restart_decks::spinning_rigid(4e-5, 0);
  deck.insert(deck.rfind("*END"),
              "*DAMPING_GLOBAL\n0,2.0e4\n*DEFINE_CURVE\n90\n0.0,1.0e4\n1.0,1.0e4\n"
              "*DAMPING_PART_MASS\n1,90\n");
  return deck;
}

// The deformable deck with a cross section through its middle (secforc.csv) and history solids
// by set (elout.csv): both CSV files continue across the dump.
std::string deformable_with_sections() {
  std::string deck = restart_decks::deformable(4e-5);
  deck.insert(deck.rfind("*END"),
              "*DATABASE_CROSS_SECTION_PLANE\n0,2.0,0.0,0.0,3.0,0.0,0.0\n*DATABASE_SECFORC\n2e-7\n"
              "*SET_SOLID\n5\n1,2\n*DATABASE_HISTORY_SOLID_SET\n5\n*DATABASE_ELOUT\n2e-7\n");
  return deck;
}

// The deformable deck with mass scaling (DT2MS just above its elements' steps): mass is added
// at the start and again while it deforms, before and after the dump; the body load acts on
// the physical mass.
std::string deformable_mass_scaled() {
  std::string deck = restart_decks::deformable(4e-5);
  const std::string control = "*CONTROL_TIMESTEP\n0,0.5\n";
  deck.replace(deck.find(control), control.size(), "*CONTROL_TIMESTEP\n0,0.5,0,0.0,-1.75e-7\n");
  return deck;
}

// The deformable deck with discrete elements: a mass hung on a spring and a damper from the
// block's corner (the damper's dissipated energy and the spring energy cross the dump, glstat's
// last columns).
std::string deformable_with_springs() {
  std::string deck = restart_decks::deformable(4e-5);
  deck.insert(deck.rfind("*END"),
              "*NODE\n900,6.0,2.0,2.0\n*ELEMENT_MASS\n900,900,1.0e-7\n"
              "*SECTION_DISCRETE\n10,0\n0.0,0.0\n*PART\nspring\n10,10,10\n*PART\ndamper\n11,10,11\n"
              "*MAT_SPRING_ELASTIC\n10,100.0\n*MAT_DAMPER_VISCOUS\n11,1.0e-3\n"
              "*ELEMENT_DISCRETE\n900,10,25,900,0,1.0,0,0.05\n901,11,900,25\n");
  return deck;
}

// Joint stiffness between a fixed rigid cube and a tumbling one: curves on phi and theta,
// damping on phi, friction on theta and stops on psi, with the angles, moments and energies of
// jntforc.csv (through a spherical joint at the centre of the tumbling cube) continued across
// the dump. The friction spring slips between 0.07 and 0.1 s and sticks from 0.1 to 0.155 s:
// the restart from the dump at 0.1 s must carry its slip angle (measured: restoring it as 0
// changes d3plot01 and the later dumps).
std::string joint_stiffness() {
  std::string s = "*KEYWORD\n*TITLE\nrestart: joint stiffness\n";
  s += "*CONTROL_TERMINATION\n0.2,0\n*CONTROL_TIMESTEP\n1.0e-4\n";
  s += restart_decks::output_cards(2e-3, 2e-2) + "*DATABASE_JNTFORC\n2.0e-3\n";
  s += "*NODE\n1,0.0,0.0,0.0\n2,1.0,0.0,0.0\n3,1.0,1.0,0.0\n4,0.0,1.0,0.0\n5,0.0,0.0,1.0\n"
       "6,1.0,0.0,1.0\n7,1.0,1.0,1.0\n8,0.0,1.0,1.0\n11,2.0,0.0,0.0\n12,3.0,0.0,0.0\n"
       "13,3.0,1.0,0.0\n14,2.0,1.0,0.0\n15,2.0,0.0,1.0\n16,3.0,0.0,1.0\n17,3.0,1.0,1.0\n"
       "18,2.0,1.0,1.0\n101,2.5,0.5,0.5\n102,2.5,0.5,0.5\n";
  s += "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n2,2,11,12,13,14,15,16,17,18\n";
  s += "*PART\nground\n1,1,1\n*PART_INERTIA\ntumbler\n2,1,2\n2.5,0.5,0.5,3.0,0,0\n"
       "2.0,0.0,0.0,1.5,0.0,2.5\n0.0,0.0,0.0,6.0,-5.0,9.0\n";
  s += "*SECTION_SOLID\n1,1\n*MAT_RIGID\n1,7850.0,2.1e11,0.3\n1.0,7,7\n"
       "*MAT_RIGID\n2,7850.0,2.1e11,0.3\n";
  s += "*CONSTRAINED_EXTRA_NODES_NODE\n1,101\n2,102\n";
  s += "*CONSTRAINED_JOINT_SPHERICAL_ID\n4,centre\n101,102\n";
  s += "*DEFINE_COORDINATE_VECTOR\n1,1.0,1.0,0.0,-1.0,2.0,1.0\n";
  s += "*DEFINE_CURVE\n5\n-10.0,-30000.0\n0.0,0.0\n0.3,400.0\n10.0,10000.0\n";
  s += "*DEFINE_CURVE\n6\n-100.0,-20.0\n100.0,20.0\n";
  s += "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n10,1,2,1,0,4\n5,5,0,6,0,0\n"
       "0.0,0.0,2000.0,150.0,3000.0,0.0\n0.0,0.0,0.0,0.0,10.0,10.0\n";
  s += "*END\n";
  return s;
}

const Case kCases[] = {
    {"deformable", restart_decks::deformable(4e-5), "", {}, 6e-6, 1},
    {"deformable", restart_decks::deformable(4e-5), "", {}, 6e-6, 2},
    {"rigid_linear", restart_decks::spinning_rigid(4e-5, 0), "", {}, 6e-6, 1},
    {"rigid_linear", restart_decks::spinning_rigid(4e-5, 0), "", {}, 6e-6, 2},
    {"rigid_curvilinear", restart_decks::spinning_rigid(4e-5, 2), "", {}, 6e-6, 1},
    {"rigid_curvilinear", restart_decks::spinning_rigid(4e-5, 2), "", {}, 6e-6, 2},
    {"plastic", restart_decks::plastic(4e-5), "", {}, 6e-6, 1},
    {"plastic", restart_decks::plastic(4e-5), "", {}, 6e-6, 2},
    // Erosion: elements deleted before and after the dump (erosion.csv continued).
    {"erosion", restart_decks::eroding(4e-5), "", {}, 6e-6, 1},
    {"erosion", restart_decks::eroding(4e-5), "", {}, 6e-6, 2},
    // Nodal-pressure tetrahedra (ELFORM 13), J2 plasticity.
    {"tetrahedra13", restart_decks::tetrahedra(4e-5), "", {}, 6e-6, 1},
    {"tetrahedra13", restart_decks::tetrahedra(4e-5), "", {}, 6e-6, 2},
    // 10-node tetrahedra (ELFORM 16), J2 plasticity at 4 points.
    {"tetrahedra16", restart_decks::tetrahedra16(4e-5), "", {}, 6e-6, 1},
    {"tetrahedra16", restart_decks::tetrahedra16(4e-5), "", {}, 6e-6, 2},
    {"rubber", restart_decks::rubber(4e-5), "", {}, 6e-6, 1},
    {"rubber", restart_decks::rubber(4e-5), "", {}, 6e-6, 2},
    {"johnson_cook", restart_decks::johnson_cook(4e-5), "", {}, 6e-6, 1},
    {"johnson_cook", restart_decks::johnson_cook(4e-5), "", {}, 6e-6, 2},
    {"quadratic", restart_decks::quadratic(4e-5), "", {}, 6e-6, 1},
    {"quadratic", restart_decks::quadratic(4e-5), "", {}, 6e-6, 2},
    // The *RIGID_BODY_UPDATE example: prescribed rotation (accumulated travel), both updates.
    {"torsion_update0", "", RIGIDFLEX_EXAMPLES "/torsion_rigid_update.k", {{"type", 0}}, 1.5e-3, 2},
    {"torsion_update2", "", RIGIDFLEX_EXAMPLES "/torsion_rigid_update.k", {{"type", 2}}, 1.5e-3, 1},
    // Part switching: dumped while rigid (paired CODE 0 sets), restarted through the release.
    {"switching", "", RIGIDFLEX_EXAMPLES "/switching_spinning_block.k", {}, 0.04, 1},
    {"switching", "", RIGIDFLEX_EXAMPLES "/switching_spinning_block.k", {}, 0.04, 2},
    // Sensors: timers and control statuses carried across the dump; the DEF2RIG switch after it.
    {"sensor_def2rig", "", RIGIDFLEX_EXAMPLES "/sensor_def2rig.k", {}, 4e-5, 1},
    // Rigid walls: forces, impulses, work and a moving wall's motion across the dump.
    {"rigid_walls", "", RIGIDFLEX_TEST_DECKS "/rigidwall_switching_block.k", {}, 0.04, 1},
    // Contact: friction springs, nodal contact forces and contact energy across the dump.
    {"contact", "", RIGIDFLEX_TEST_DECKS "/contact_sliding_block.k", {}, 0.004, 1},
    {"contact", "", RIGIDFLEX_TEST_DECKS "/contact_sliding_block.k", {}, 0.004, 2},
    // Contact with shells: a block and a thin plate on a plate (two-sided segments; the side
    // memory, contact normal and segment per slave node, across the dumps, taken in contact).
    {"contact_shells", "", RIGIDFLEX_TEST_DECKS "/contact_shell_plate.k", {}, 0.0004, 1},
    {"contact_shells", "", RIGIDFLEX_TEST_DECKS "/contact_shell_plate.k", {}, 0.0004, 2},
    // Spot welds: deleted (NCSF 1) before the dump restarted from, activated (NCSF 2) and
    // failed (TF) after it; swforc.csv continued.
    {"spot_welds", "", RIGIDFLEX_TEST_DECKS "/spot_weld_switching.k", {}, 0.2, 1},
    // Mass-proportional damping of nodes and of a rigid body.
    {"damping", damped_spinning_rigid(), "", {}, 6e-6, 1},
    {"damping", damped_spinning_rigid(), "", {}, 6e-6, 2},
    {"sections", deformable_with_sections(), "", {}, 6e-6, 1},
    {"sections", deformable_with_sections(), "", {}, 6e-6, 2},
    {"mass_scaling", deformable_mass_scaled(), "", {}, 6e-6, 1},
    {"mass_scaling", deformable_mass_scaled(), "", {}, 6e-6, 2},
    {"springs", deformable_with_springs(), "", {}, 6e-6, 1},
    {"springs", deformable_with_springs(), "", {}, 6e-6, 2},
    // Joint stiffness: friction slip, angles and moments across the dump.
    {"joint_stiffness", joint_stiffness(), "", {}, 0.05, 1},
    // Shells (ELFORM 2: *MAT_024 with IHQ 4, *MAT_003 NIP 5 with IHQ 5) and beams (integrated
    // *MAT_003, resultant), spinning and bent: stresses, history, hourglass forces, beam frames and
    // resultants, nodal angular velocities and moments across the dump.
    {"shells_beams", restart_decks::shells_and_beams(4e-5), "", {}, 6e-6, 1},
    {"shells_beams", restart_decks::shells_and_beams(4e-5), "", {}, 6e-6, 2},
    // The same with mass scaling (DT2MS just above the elements' steps): shell and beam factors
    // and the scaled rotational inertias.
    {"shells_beams_mass_scaled", restart_decks::shells_and_beams(4e-5, -2.0e-7), "", {}, 6e-6, 1},
    {"shells_beams_mass_scaled", restart_decks::shells_and_beams(4e-5, -2.0e-7), "", {}, 6e-6, 2},
    // Shell and beam parts switched rigid at 8 us and back at 26 us: restarted from the dump in
    // the rigid phase (12 us), through the release.
    {"shells_beams_switching", restart_decks::shells_and_beams_switching(4e-5), "", {}, 6e-6, 1},
    {"shells_beams_switching", restart_decks::shells_and_beams_switching(4e-5), "", {}, 6e-6, 2},
    // Shells with a strain criterion (EFFEPS with FAILTM, NCS 2): the integrated shell strain
    // across the dump decides which elements erode after it.
    {"shell_strain_erosion", restart_decks::shells_eroding_by_strain(4e-5, 0.1), "", {}, 6e-6, 1},
    {"shell_strain_erosion", restart_decks::shells_eroding_by_strain(4e-5, 0.1), "", {}, 6e-6, 2},
    // The same decks with fully integrated shells (ELFORM 16: 4 x NIP points per element,
    // plastic history per point) and with the ELFORM 16 part switched rigid and back.
    {"shells16_beams", fully_integrated(restart_decks::shells_and_beams(4e-5)), "", {}, 6e-6, 1},
    {"shells16_beams", fully_integrated(restart_decks::shells_and_beams(4e-5)), "", {}, 6e-6, 2},
    {"shells16_beams_switching",
     fully_integrated(restart_decks::shells_and_beams_switching(4e-5)),
     "",
     {},
     6e-6,
     2},
};

INSTANTIATE_TEST_SUITE_P(Restart, RestartBitwise, testing::ValuesIn(kCases), case_name);

// The mass-scaled case adds mass at the start, before the dump it restarts from (12 us) and
// after it: the dump carries the element factors and the running sums.
TEST(Restart, MassScaledDeckAddsMassBeforeAndAfterTheDump) {
  solver::Simulation sim(read(deformable_mass_scaled()), {});
  const double at_start = sim.mass_scaling().added_mass;
  EXPECT_GT(at_start, 0.0);
  while (sim.state().time < 1.2e-5) sim.cycle();
  const double at_dump = sim.mass_scaling().added_mass;
  const auto cycles_at_dump = sim.mass_scaling().rescaled_cycles;
  while (!sim.finished()) sim.cycle();
  std::printf(
      "mass-scaled restart deck: added mass %.6g at the start, %.6g at the dump, %.6g at "
      "the end; cycles with mass added %lld before the dump, %lld in all\n",
      at_start, at_dump, sim.mass_scaling().added_mass, static_cast<long long>(cycles_at_dump),
      static_cast<long long>(sim.mass_scaling().rescaled_cycles));
  EXPECT_GT(cycles_at_dump, 0);
  EXPECT_GT(sim.mass_scaling().rescaled_cycles, cycles_at_dump);
  EXPECT_GT(sim.mass_scaling().added_mass, at_dump);
}

// The erosion case deletes elements before the dump it restarts from (12 us) and after it.
TEST(Restart, ErodingDeckDeletesElementsBeforeAndAfterTheDump) {
  solver::Simulation sim(read(restart_decks::eroding(4e-5)), {});
  while (sim.state().time < 1.2e-5) sim.cycle();
  const auto at_dump = sim.erosion().ledger();
  while (!sim.finished()) sim.cycle();
  const auto& at_end = sim.erosion().ledger();
  std::printf(
      "eroding restart deck: %lld elements (%lld nodes) eroded by the dump, %lld (%lld) "
      "at the end; energy ratio %.9f\n",
      static_cast<long long>(at_dump.elements), static_cast<long long>(at_dump.nodes),
      static_cast<long long>(at_end.elements), static_cast<long long>(at_end.nodes),
      sim.energy().ratio());
  EXPECT_GT(at_dump.elements, 0);
  EXPECT_GT(at_end.elements, at_dump.elements);
  EXPECT_NEAR(sim.energy().ratio(), 1.0, 1e-2);
}

// The shell strain case: the *MAT_024 shells (part 1) integrate their strain (EFFEPS) from the
// start, and elements erode by it only after the dump (12 us), at FAILTM (20 us): the strain the
// dump carries decides which.
TEST(Restart, ShellStrainDeckErodesOnlyAfterTheDump) {
  solver::Simulation sim(read(restart_decks::shells_eroding_by_strain(4e-5, 0.1)), {});
  auto largest_strain = [&] {
    const auto& strain = sim.state().shell_blocks[0].strain;
    double m = 0.0;
    for (const double v : strain) m = std::max(m, std::abs(v));
    return m;
  };
  while (sim.state().time < 1.2e-5) sim.cycle();
  const auto at_dump = sim.erosion().ledger();
  const double strain_at_dump = largest_strain();
  while (!sim.finished()) sim.cycle();
  std::printf(
      "shell strain restart deck: largest strain component %.4g at the dump, %lld "
      "elements eroded by then, %lld at the end\n",
      strain_at_dump, static_cast<long long>(at_dump.elements),
      static_cast<long long>(sim.erosion().ledger().elements));
  EXPECT_GT(strain_at_dump, 0.0);
  EXPECT_EQ(at_dump.elements, 0);
  EXPECT_GT(sim.erosion().ledger().elements, 0);
}

// The plastic case flows plastically before the dump it restarts from (12 us) and after it,
// in both parts, and its back stress is not zero: the dump carries real history.
TEST(Restart, PlasticDeckFlowsPlasticallyAcrossTheDump) {
  solver::Simulation sim(read(restart_decks::plastic(4e-5)), {});
  auto max_of = [&](std::size_t b, const char* name) {
    const auto* h = element::find_history(sim.state().hex_blocks[b], name);
    double m = 0.0;
    if (h)
      for (double v : h->values) m = std::max(m, std::abs(v));
    return m;
  };
  while (sim.state().time < 1.0e-5) sim.cycle();
  const double early[2] = {max_of(0, "effective_plastic_strain"),
                           max_of(1, "effective_plastic_strain")};
  EXPECT_GT(early[0], 1e-3);
  EXPECT_GT(early[1], 1e-3);
  EXPECT_GT(max_of(0, "back_stress"), 1.0);
  while (!sim.finished()) sim.cycle();
  EXPECT_GT(max_of(0, "effective_plastic_strain"), early[0]);
  EXPECT_GT(max_of(1, "effective_plastic_strain"), early[1]);
}

// A 6 x 1 x 1 bar of ELFORM 2 hexahedra: elements 1-2 part 1 (elastic), 3-6 part 2 with
// `part2_cards` (its material and whatever goes with it), spinning and stretching, 40 us.
std::string bonded_bar_deck(const std::string& part2_cards) {
  BoxMesh mesh;
  mesh.nx = 6;
  mesh.lx = 6.0;
  std::string s = "*KEYWORD\n";
  s += mesh.keyword_text([](int i, int, int) { return i < 2 ? 1 : 2; });
  s += "*PART\nblock\n1,1,1\n*PART\nflexible\n2,2,2\n*SECTION_SOLID\n1,2\n"
       "*SECTION_SOLID\n2,2\n*MAT_ELASTIC\n1,7.85e-9,210000.0,0.3\n";
  s += part2_cards;
  s += "*INITIAL_VELOCITY_GENERATION\n0,2,300,0,0,1000\n0.5,0.5,0.5,0,1,0\n"
       "*CONTROL_TERMINATION\n4e-5,0\n*CONTROL_TIMESTEP\n0,0.5\n";
  return s + restart_decks::output_cards(2e-7, 2e-6) + "*END\n";
}

constexpr const char* kElasticPart2 = "*MAT_ELASTIC\n2,7.85e-9,210000.0,0.3\n";

// The 8 lowest elastic modes of part 2 of the bar (eigen analysis of the all-elastic deck).
void write_part2_modes(const fs::path& file) {
  modal::EigenRequest request;
  request.mode_count = 8;
  request.parts = {2};
  request.remove_rigid_below = true;
  request.left_frequency = 1.0;
  modal::write_mode_database(
      file,
      modal::compute_modes(io::read_deck_text(bonded_bar_deck(kElasticPart2), "eigen.k"), request));
}

// A flexible body (*PART_MODES, modes from the eigen analysis written to modes.h5 next to the
// deck) sharing its end face with a deformable block, spinning: the modal state (q, s) crosses
// the dump and modal.csv continues; the restart equals the uninterrupted run byte for byte.
TEST(Restart, FlexibleBodyBitwise) {
  const fs::path base = scratch("flexible");
  write_part2_modes(base / "modes.h5");
  write_file(base / "deck.k",
             bonded_bar_deck("*MAT_RIGID\n2,7.85e-9,210000.0,0.3\n0,0,0\n*PART_MODES\n2,8,0,0,3\n"
                             "modes.h5\n1,8,0.01\n"));
  const double interval = 6e-6;
  const fs::path reference = base / "reference";
  const fs::path interrupted = base / "interrupted";
  run_with_dumps(base / "deck.k", reference, interval, std::nullopt, {});
  ASSERT_TRUE(fs::exists(reference / "d3dump_0004.h5"));
  ASSERT_TRUE(fs::exists(reference / "modal.csv"));
  run_with_dumps(base / "deck.k", interrupted, interval, 3.5 * interval, {});
  const restart::Restarted r = restart_and_run(interrupted / "d3dump_0002.h5");
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_GE(expect_same_files(reference, interrupted), 10);
  if (!HasFailure()) fs::remove_all(base);
}

// The deck of FlexibleBodyBitwise with part 2 elastic: *PART_MODES on it, switched rigid at
// 10 us (a flexible body, docs/flexible_bodies.md section 6) and back to deformable at 30 us.
// Restarted from a dump in the flexible phase, the run equals the uninterrupted one byte for
// byte (the flexible body is made again from the dumped mode frame).
TEST(Restart, SwitchedFlexibleBodyBitwise) {
  const fs::path base = scratch("switched_flexible");
  write_part2_modes(base / "modes.h5");
  write_file(base / "deck.k",
             bonded_bar_deck(std::string(kElasticPart2) +
                             "*PART_MODES\n2,8,0,0,3\nmodes.h5\n1,8,0.01\n"
                             "*DEFORMABLE_TO_RIGID_AUTOMATIC\n10,0,1e-5\n0,0,0,0,1,0\n2\n"
                             "*DEFORMABLE_TO_RIGID_AUTOMATIC\n20,0,3e-5\n0,0,0,0,0,1\n2\n"));
  const double interval = 6e-6;
  const fs::path reference = base / "reference";
  const fs::path interrupted = base / "interrupted";
  run_with_dumps(base / "deck.k", reference, interval, std::nullopt, {});
  ASSERT_TRUE(fs::exists(reference / "d3dump_0004.h5"));
  // Rigid (a flexible body) at 10 us, before the dump restarted from (12 us), deformable at 30 us.
  std::ifstream switches(reference / "switch.csv");
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(switches, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 3u);
  std::ifstream modal_csv(reference / "modal.csv");
  int modal_rows = 0;
  while (std::getline(modal_csv, line)) ++modal_rows;
  EXPECT_GT(modal_rows, 8 * 10);  // 8 modes, every rbdout row of the flexible phase
  run_with_dumps(base / "deck.k", interrupted, interval, 3.5 * interval, {});
  (void)restart_and_run(interrupted / "d3dump_0002.h5");
  EXPECT_GE(expect_same_files(reference, interrupted), 10);
  if (!HasFailure()) fs::remove_all(base);
}

// Restarting into another directory (-o): the new directory receives the earlier rows and
// frames and ends up with the same results as the uninterrupted run.
TEST(Restart, IntoAnotherDirectoryGivesTheSameResults) {
  omp_set_num_threads(1);
  const fs::path base = scratch("other_directory");
  const fs::path deck = base / "deck.k";
  write_file(deck, restart_decks::deformable(4e-5));
  run_with_dumps(deck, base / "reference", 6e-6);
  run_with_dumps(deck, base / "interrupted", 6e-6, 3.5 * 6e-6);
  restart_and_run(base / "interrupted" / "d3dump_0002.h5", {}, base / "continued");
  EXPECT_GE(expect_same_files(base / "reference", base / "continued", is_result), 5);
  if (!HasFailure()) fs::remove_all(base);
}

// A restart deck with a later *CONTROL_TERMINATION extends the run: from a dump taken before
// the original end, the extended run equals a run made to the later time from the start.
TEST(Restart, LaterTerminationEqualsARunToTheLaterTime) {
  omp_set_num_threads(1);
  const fs::path base = scratch("extend");
  const fs::path short_deck = base / "short.k";
  const fs::path long_deck = base / "long.k";
  write_file(short_deck, restart_decks::spinning_rigid(3e-5, 2));
  write_file(long_deck, restart_decks::spinning_rigid(5e-5, 2));
  const fs::path restart_deck = base / "extend.k";
  write_file(restart_deck, "*KEYWORD\n*CONTROL_TERMINATION\n5.0e-5\n*END\n");
  run_with_dumps(long_deck, base / "long", 6e-6);
  run_with_dumps(short_deck, base / "short", 6e-6);
  const restart::Restarted r = restart_and_run(base / "short" / "d3dump_0003.h5", restart_deck);
  EXPECT_DOUBLE_EQ(r.simulation->end_time(), 5e-5);
  EXPECT_DOUBLE_EQ(r.simulation->state().time, 5e-5);
  // The dumps differ in the deck text they carry; every result file must be equal.
  EXPECT_GE(expect_same_files(base / "long", base / "short", is_result), 10);
  if (!HasFailure()) fs::remove_all(base);
}

// From the dump written at termination, a later *CONTROL_TERMINATION continues the run to the
// new end. The original run shortened its last step to land on the old end, so the extension
// is not bit-identical to a longer run, but must agree to the accuracy of the time integration.
TEST(Restart, FromTheFinalDumpTheRunContinues) {
  omp_set_num_threads(1);
  const fs::path base = scratch("final_dump");
  write_file(base / "short.k", restart_decks::deformable(2.1e-5));
  write_file(base / "long.k", restart_decks::deformable(4e-5));
  write_file(base / "extend.k", "*KEYWORD\n*CONTROL_TERMINATION\n4.0e-5\n*END\n");
  run_with_dumps(base / "short.k", base / "short", 1e-5);
  run_with_dumps(base / "long.k", base / "long", 1e-5);
  // Dumps at 1e-5, 2e-5 and the end (2.1e-5).
  ASSERT_TRUE(fs::exists(base / "short" / "d3dump_0003.h5"));
  ASSERT_FALSE(fs::exists(base / "short" / "d3dump_0004.h5"));
  const restart::Restarted r =
      restart_and_run(base / "short" / "d3dump_0003.h5", base / "extend.k");
  EXPECT_NEAR(r.header.time, 2.1e-5, 1e-15);
  EXPECT_DOUBLE_EQ(r.simulation->state().time, 4e-5);
  // Last glstat rows: same time, kinetic energy within 0.1 % (the runs differ by one shortened
  // step out of ~200).
  auto last_row = [](const fs::path& file) {
    std::istringstream in(read_file(file));
    std::string line, last;
    while (std::getline(in, line)) last = line;
    std::vector<double> values;
    std::istringstream fields(last);
    for (std::string f; std::getline(fields, f, ',');) values.push_back(std::stod(f));
    return values;
  };
  const auto extended = last_row(base / "short" / "glstat.csv");
  const auto reference = last_row(base / "long" / "glstat.csv");
  ASSERT_EQ(extended.size(), reference.size());
  EXPECT_DOUBLE_EQ(extended[0], reference[0]);
  EXPECT_NEAR(extended[3], reference[3], 1e-3 * reference[3]);
  // The restarted part of the run continued the dump numbering.
  EXPECT_TRUE(fs::exists(base / "short" / "d3dump_0005.h5"));
  if (!HasFailure()) fs::remove_all(base);
}

// ---- Bad input: clear errors, no crash -------------------------------------------------------

// The message of the InputError that restarting `dump` (with `deck`, into `output`) throws ("" if
// none).
std::string restart_error_of(const fs::path& dump, const fs::path& deck, const fs::path& output) {
  restart::RestartOptions options;
  options.dump = dump;
  options.restart_deck = deck;
  options.output_directory = output;
  try {
    restart::restart_from_dump(options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class RestartInput : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    omp_set_num_threads(1);
    base_ = scratch("bad_input");
    write_file(base_ / "deck.k", restart_decks::deformable(2e-5));
    run_with_dumps(base_ / "deck.k", base_ / "run", 1e-5);
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
  static fs::path dump() { return base_ / "run" / "d3dump_0001.h5"; }
  static fs::path copy_of_dump(const std::string& name) {
    const fs::path path = base_ / name;
    fs::copy_file(dump(), path, fs::copy_options::overwrite_existing);
    return path;
  }
  static std::string restart_error(const fs::path& dump, const fs::path& deck = {}) {
    return restart_error_of(dump, deck, base_ / "out");
  }
  static fs::path base_;
};
fs::path RestartInput::base_;

TEST_F(RestartInput, MissingDump) {
  const std::string message = restart_error(base_ / "no_such_dump.h5");
  EXPECT_NE(message.find("no_such_dump.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

TEST_F(RestartInput, FileThatIsNotHdf5) {
  write_file(base_ / "text.h5", "*KEYWORD\nthis is a deck, not a dump\n");
  const std::string message = restart_error(base_ / "text.h5");
  EXPECT_NE(message.find("not a restart dump"), std::string::npos) << message;
}

TEST_F(RestartInput, TruncatedDump) {
  const fs::path path = copy_of_dump("truncated.h5");
  fs::resize_file(path, fs::file_size(path) / 2);
  const std::string message = restart_error(path);
  EXPECT_NE(message.find("truncated.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("damaged"), std::string::npos) << message;
}

TEST_F(RestartInput, FlippedByteInTheDataIsCaughtByTheChecksum) {
  const fs::path path = copy_of_dump("flipped.h5");
  // Where the first chunk of the nodal x coordinates lies in the file.
  haddr_t address = 0;
  hsize_t size = 0;
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t set = H5Dopen2(file, "/nodes/x_x", H5P_DEFAULT);
    const hid_t space = H5Dget_space(set);
    hsize_t offset[1] = {0};
    unsigned mask = 0;
    const herr_t found = H5Dget_chunk_info(set, space, 0, offset, &mask, &address, &size);
    H5Sclose(space);
    H5Dclose(set);
    H5Fclose(file);
    ASSERT_GE(found, 0);
  }
  ASSERT_GT(size, 16u);
  {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekg(static_cast<std::streamoff>(address + size / 2));
    char byte = 0;
    f.read(&byte, 1);
    byte = static_cast<char>(byte ^ 0x10);
    f.seekp(static_cast<std::streamoff>(address + size / 2));
    f.write(&byte, 1);
  }
  const std::string message = restart_error(path);
  EXPECT_NE(message.find("/nodes/x_x"), std::string::npos) << message;
  EXPECT_NE(message.find("checksum"), std::string::npos) << message;
}

TEST_F(RestartInput, DumpOfAnotherVersion) {
  const fs::path path = copy_of_dump("version.h5");
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t root = H5Gopen2(file, "/", H5P_DEFAULT);
    const hid_t attribute = H5Aopen(root, "dump_version", H5P_DEFAULT);
    const std::int64_t version = 999;
    H5Awrite(attribute, H5T_NATIVE_INT64, &version);
    H5Aclose(attribute);
    H5Gclose(root);
    H5Fclose(file);
  }
  const std::string message = restart_error(path);
  EXPECT_NE(message.find("restart dump version 999"), std::string::npos) << message;
  EXPECT_NE(message.find("reads dump version 1 only"), std::string::npos) << message;
}

TEST_F(RestartInput, HdfFileWithoutTheDumpMarker) {
  const fs::path path = base_ / "foreign.h5";
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(file);
  const std::string message = restart_error(path);
  EXPECT_NE(message.find("not a RigidFlex restart dump"), std::string::npos) << message;
}

TEST_F(RestartInput, UnknownKeywordInTheRestartDeck) {
  write_file(base_ / "bad.k",
             "*KEYWORD\n*CONTROL_TERMINATION\n3.0e-5\n*BOUNDARY_SPC_NODE\n1,0,1\n*END\n");
  const std::string message = restart_error(dump(), base_ / "bad.k");
  EXPECT_NE(message.find("bad.k:4"), std::string::npos) << message;
  EXPECT_NE(message.find("*BOUNDARY_SPC_NODE cannot be used in a restart deck"), std::string::npos)
      << message;
  EXPECT_NE(message.find("*CONTROL_TERMINATION, *DEFORMABLE_TO_RIGID, *RIGID_TO_DEFORMABLE"),
            std::string::npos)
      << message;
}

TEST_F(RestartInput, TerminationBeforeTheDump) {
  write_file(base_ / "early.k", "*KEYWORD\n*CONTROL_TERMINATION\n1.0e-6\n*END\n");
  const std::string message = restart_error(dump(), base_ / "early.k");
  EXPECT_NE(message.find("field ENDTIM"), std::string::npos) << message;
  EXPECT_NE(message.find("does not lie after the dump's time"), std::string::npos) << message;
}

TEST_F(RestartInput, SwitchingAPartWithoutElementsIsAnError) {
  write_file(base_ / "switch.k", "*KEYWORD\n*DEFORMABLE_TO_RIGID\n77\n*END\n");
  const std::string message = restart_error(dump(), base_ / "switch.k");
  EXPECT_NE(message.find("switch.k:3"), std::string::npos) << message;
  EXPECT_NE(message.find("77"), std::string::npos) << message;
}

// A dump of the shell-and-beam deck (at 6 us), for the refusals below.
class ShellRestartInput : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    omp_set_num_threads(1);
    base_ = scratch("shell_input");
    deck_ = restart_decks::shells_and_beams(4e-5);
    write_file(base_ / "deck.k", deck_);
    run_with_dumps(base_ / "deck.k", base_ / "run", 6e-6, 7e-6);
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
  static fs::path dump() { return base_ / "run" / "d3dump_0001.h5"; }
  static fs::path base_;
  static std::string deck_;
};
fs::path ShellRestartInput::base_;
std::string ShellRestartInput::deck_;

// The dump with its deck text replaced by one with a shell element less (element 15, part 2):
// the rebuilt model no longer matches the dumped shell block, and the restart says which part
// and how many elements each side has.
TEST_F(ShellRestartInput, DumpRefusesAModelWithAnotherShellCount) {
  const fs::path path = base_ / "fewer_shells.h5";
  fs::copy_file(dump(), path, fs::copy_options::overwrite_existing);
  std::string fewer = deck_;
  const std::size_t at = fewer.find("\n15,2,");
  ASSERT_NE(at, std::string::npos);
  fewer.erase(at + 1, fewer.find('\n', at + 1) - at);
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t model = H5Gopen2(file, "/model", H5P_DEFAULT);
    ASSERT_GE(H5Ldelete(model, "file_0000", H5P_DEFAULT), 0);
    const hsize_t size[1] = {fewer.size()};
    const hid_t space = H5Screate_simple(1, size, nullptr);
    const hid_t set = H5Dcreate2(model, "file_0000", H5T_NATIVE_UINT8, space, H5P_DEFAULT,
                                 H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(set, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, fewer.data());
    H5Dclose(set);
    H5Sclose(space);
    H5Gclose(model);
    H5Fclose(file);
  }
  const std::string message = restart_error_of(path, {}, base_ / "out");
  EXPECT_NE(message.find("/shells"), std::string::npos) << message;
  EXPECT_NE(message.find("describes shell part 2 (ELFORM 2, 8 elements), the model rebuilt "
                         "from the dump's deck has shell part 2 (ELFORM 2, 7 elements)"),
            std::string::npos)
      << message;
}

// A restart deck's *DEFORMABLE_TO_RIGID switches a shell part (any element family,
// docs/switching.md "Shells and beams"): part 1 (shells) becomes one rigid body at the restart
// time and the run goes on to the end with it rigid.
TEST_F(ShellRestartInput, SwitchingOnRestartMakesAShellPartRigid) {
  write_file(base_ / "switch.k", "*KEYWORD\n*DEFORMABLE_TO_RIGID\n1\n*END\n");
  const restart::Restarted r = restart_and_run(dump(), base_ / "switch.k", base_ / "switch_out");
  const solver::State& state = r.simulation->state();
  EXPECT_DOUBLE_EQ(state.time, 4e-5);
  ASSERT_EQ(state.shell_blocks.size(), 2u);
  EXPECT_TRUE(state.shell_blocks[0].rigid);
  EXPECT_FALSE(state.shell_blocks[1].rigid);
  ASSERT_EQ(r.simulation->rigid_bodies().bodies.size(), 1u);
  EXPECT_EQ(r.simulation->rigid_bodies().bodies[0].parts, std::vector<model::Id>{1});
  ASSERT_EQ(r.simulation->switch_events().size(), 1u);
  EXPECT_NEAR(r.simulation->energy().ratio(), 1.0, 1e-3);
}

// A small restart that switches part 2 (ELFORM 2) of the deformable block to rigid half way and
// runs on: the part must then move rigidly (no further strain) while part 1 keeps deforming.
TEST(Restart, DeformableToRigidOnRestart) {
  omp_set_num_threads(1);
  const fs::path base = scratch("switch");
  write_file(base / "deck.k", restart_decks::deformable(4e-5));
  write_file(base / "switch.k",
             "*KEYWORD\n*CONTROL_TERMINATION\n4.0e-5\n*DEFORMABLE_TO_RIGID\n2,0,PART\n*END\n");
  run_with_dumps(base / "deck.k", base / "run", 1e-5, 1.5e-5);
  const restart::Restarted r = restart_and_run(base / "run" / "d3dump_0001.h5", base / "switch.k");
  const solver::State& state = r.simulation->state();
  EXPECT_DOUBLE_EQ(state.time, 4e-5);
  ASSERT_EQ(state.hex_blocks.size(), 2u);
  EXPECT_TRUE(state.hex_blocks[1].rigid);
  EXPECT_FALSE(state.hex_blocks[0].rigid);
  EXPECT_EQ(r.simulation->rigid_bodies().bodies.size(), 1u);
  EXPECT_EQ(r.simulation->rigid_bodies().bodies[0].parts, std::vector<model::Id>{2});
}

}  // namespace
}  // namespace rf::test
