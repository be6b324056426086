// rigidflex: command-line entry point.
//   rigidflex run DECK [-o DIR] [--threads N] [--quiet] [--set name=value]... [--dump-every T]
//   rigidflex restart DUMP [RESTART_DECK] [-o DIR] [--threads N] [--quiet] [--dump-every T]
//   rigidflex check DECK
//   rigidflex eigen DECK [-o DIR] [--modes N] [--parts LIST] ...
//   rigidflex plot DIR [-o OUTDIR]
#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>
#include <CLI/CLI.hpp>
#include <Eigen/Core>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/eigen_command.hpp"
#include "app/model_summary.hpp"
#include "app/result_files.hpp"
#include "app/run_log.hpp"
#include "io/keyword/reader.hpp"
#include "modal/eigen_analysis.hpp"
#include "model/error.hpp"
#include "output/output_directory.hpp"
#include "output/writers.hpp"
#include "parallel/communicator.hpp"
#include "parallel/distribution.hpp"
#include "parallel/partition.hpp"
#include "restart/dumper.hpp"
#include "restart/restart.hpp"
#include "solver/build_state.hpp"
#include "solver/interrupt.hpp"
#include "solver/simulation.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Exit codes: documented in docs/cli.md. An interrupted run exits with 128 + the signal
// (solver/interrupt.hpp): 130 for SIGINT, 143 for SIGTERM.
constexpr int kExitUsageError = 1;
constexpr int kExitInputError = 2;
constexpr int kExitSolverError = 3;
constexpr int kExitOtherError = 4;

// Warnings the reader found before an input error ended the read (ReadOptions::
// warnings_on_error): printed before the error, which they often explain.
std::vector<rf::model::Warning> g_warnings_before_error;

std::map<std::string, double> parse_overrides(const std::vector<std::string>& assignments) {
  std::map<std::string, double> out;
  for (const auto& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw rf::InputError({}, fmt::format("--set expects name=value, got '{}'", a));
    }
    std::string name = a.substr(0, eq);
    if (!name.empty() && (name[0] == '%' || name[0] == '&')) name.erase(0, 1);
    const std::string value = a.substr(eq + 1);
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (end == value.c_str() || *end != '\0') {
      throw rf::InputError({}, fmt::format("--set {}: '{}' is not a number", name, value));
    }
    // strtod reads "nan" and "inf" (and overflows to inf): a parameter reaches the physics.
    if (!std::isfinite(v)) {
      throw rf::InputError({}, fmt::format("--set {}: '{}' is not a finite number", name, value));
    }
    out[name] = v;
  }
  return out;
}

rf::io::Dialect parse_dialect(const std::string& s) {
  if (s == "impetus") return rf::io::Dialect::Impetus;
  if (s == "lsdyna") return rf::io::Dialect::LsDyna;
  return rf::io::Dialect::Auto;
}

std::string format_seconds(double s) {
  if (s < 120.0) return fmt::format("{:.1f} s", s);
  if (s < 7200.0) return fmt::format("{:.1f} min", s / 60.0);
  return fmt::format("{:.1f} h", s / 3600.0);
}

// Progress: a rewritten line on a terminal, plain lines every 10% otherwise.
class ProgressPrinter {
 public:
  // `start_fraction`: the part of the run already done (a restart), for the time left.
  explicit ProgressPrinter(bool quiet, double start_fraction = 0.0)
      : quiet_(quiet), tty_(isatty(fileno(stdout)) != 0), start_fraction_(start_fraction) {}

  void operator()(const rf::solver::Simulation& sim) {
    if (quiet_) return;
    const auto now = Clock::now();
    const double end = sim.end_time();
    const double t = sim.state().time;
    const double fraction = end > 0.0 ? std::min(1.0, t / end) : 0.0;
    if (printed_final_) return;
    if (tty_) {
      if (now - last_ < std::chrono::milliseconds(250) && !sim.finished()) return;
    } else {
      if (fraction < next_fraction_ && !sim.finished()) return;
      while (next_fraction_ <= fraction + 1e-12) next_fraction_ += 0.1;
      // The 100% line is printed once, when the run has finished.
      if (fraction >= 1.0 - 1e-12 && !sim.finished()) return;
    }
    printed_final_ = sim.finished();
    last_ = now;
    const double wall = std::chrono::duration<double>(now - start_).count();
    const double done = fraction - start_fraction_;
    const double left = done > 0.0 ? wall * (1.0 - fraction) / done : 0.0;
    const std::string line = fmt::format(
        "t = {:.5e} ({:5.1f}%)  cycle {:>9}  dt = {:.3e}  wall {}  left {}", t, 100.0 * fraction,
        sim.state().cycle, sim.state().dt, format_seconds(wall), format_seconds(left));
    if (tty_) {
      std::fprintf(stdout, "\r%s   ", line.c_str());
      if (sim.finished()) std::fputc('\n', stdout);
    } else {
      std::fprintf(stdout, "%s\n", line.c_str());
    }
    std::fflush(stdout);
  }

 private:
  bool quiet_;
  bool tty_;
  double start_fraction_ = 0.0;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_{};
  double next_fraction_ = 0.0;
  bool printed_final_ = false;
};

int command_check(const std::string& deck, const rf::io::ReadOptions& read_options, int ranks) {
  const rf::model::Model model = rf::io::read_deck(deck, read_options);
  try {
    rf::app::print_model_summary(model, stdout);
  } catch (const rf::InputError&) {
    // The set-up failed: the summary (with its warnings) was not printed; the reader's
    // warnings may explain the error, so they come first.
    g_warnings_before_error = model.warnings;
    throw;
  }
  if (ranks > 0) {  // --ranks N: the partition a distributed run on N ranks would use
    const rf::solver::NodeIndex index(model);
    const rf::solver::State state = rf::solver::build_state(model, index);
    std::fputs(
        rf::parallel::describe_partition(rf::parallel::partition_elements(state, ranks)).c_str(),
        stdout);
  }
  return 0;
}

// Ranks 1.. of a distributed run (docs/parallel.md): the same model and cycle as rank 0, which
// alone prints and writes files; these only compute their elements and take part in the
// reductions.
int command_run_follower(const std::string& deck, const rf::io::ReadOptions& read_options,
                         int threads, double dump_every) {
  if (threads > 0) omp_set_num_threads(threads);
  const rf::model::Model model = rf::io::read_deck(deck, read_options);
  rf::solver::SimulationOptions options;  // no output directory: rank 0 writes the files
  options.write_fields = false;
  rf::solver::Simulation sim(model, options);
  // The same dump schedule as rank 0: every rank takes part in a dump (restart/dumper.cpp).
  rf::restart::DumpSchedule schedule = rf::restart::Dumper::every(dump_every);
  schedule.at_termination = dump_every > 0.0;
  sim.enable_restart_dumps(
      std::make_unique<rf::restart::Dumper>(rf::restart::ModelInput{}, schedule));
  sim.run();
  return 0;
}

// A rank > 0 of a distributed restart: the same state from the same dump, no files.
int command_restart_follower(rf::restart::RestartOptions options) {
  options.writes_files = false;
  options.output_directory.clear();
  rf::restart::Restarted restarted = rf::restart::restart_from_dump(options);
  restarted.simulation->run();
  return 0;
}

// The frame collection to open in ParaView: the new name first, the old one otherwise.
std::string frames_collection(const fs::path& out) {
  for (const char* name : {"frames.pvd", "d3plot.pvd"}) {
    if (fs::exists(out / name)) return name;
  }
  return {};
}

// Runs a constructed simulation to termination with progress output, writes run.json and the
// closing lines. `summary` arrives with status-independent fields (threads, warnings) filled.
int run_to_termination(rf::solver::Simulation& sim, const fs::path& out,
                       rf::output::RunSummary& summary, bool quiet, rf::app::RunLog& log) {
  const auto start = Clock::now();
  const std::int64_t first_cycle = sim.state().cycle;  // > 0 on restart
  const std::size_t warnings_at_start = sim.warnings().size();
  auto finish = [&] {
    // Warnings that came up during the run (switches): reported now, kept in run.json.
    std::vector<std::string> run_warnings;
    for (std::size_t k = warnings_at_start; k < sim.warnings().size(); ++k) {
      run_warnings.push_back(rf::app::format_warning(sim.warnings()[k]));
      std::fprintf(stderr, "warning: %s\n", run_warnings.back().c_str());
      summary.warnings.push_back(run_warnings.back());
    }
    summary.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    summary.final_time = sim.state().time;
    summary.cycles = sim.state().cycle;
    summary.nodes = static_cast<std::int64_t>(sim.state().nodes.size());
    summary.elements = sim.element_count();
    const double element_cycles =
        static_cast<double>(summary.elements) *
        static_cast<double>(std::max<std::int64_t>(1, summary.cycles - first_cycle));
    summary.ns_per_element_cycle = 1e9 * summary.wall_seconds / element_cycles;
    log.finish(sim, summary.status, summary.message, run_warnings, summary.wall_seconds);
    rf::output::write_run_json(out / "run.json", summary);
  };
  try {
    const double end = sim.end_time();
    ProgressPrinter progress(quiet, end > 0.0 ? std::min(1.0, sim.state().time / end) : 0.0);
    sim.run(std::ref(progress));
  } catch (const std::exception& e) {
    summary.status = "error termination";
    summary.message = e.what();
    try {
      finish();
    } catch (const std::exception& also) {
      // The run's own error is the one to report; run.json is left absent.
      std::fprintf(stderr, "error: %s\n", also.what());
    }
    throw;
  }
  if (const int signal = sim.interrupt_signal(); signal != 0) {
    // Sense switch: the run stopped between cycles with its last rows, frame and a dump.
    const rf::restart::Dumper* dumper = sim.restart_dumper();
    const fs::path dump = dumper && !dumper->written().empty() ? dumper->written().back() : "";
    summary.status = "interrupted";
    summary.message = fmt::format(
        "stopped by {} at t = {:.9g} (cycle {}){}", rf::solver::interrupt::signal_name(signal),
        sim.state().time, sim.state().cycle,
        dump.empty() ? "" : fmt::format("; continue with: rigidflex restart {}", dump.string()));
    finish();
    if (!quiet && isatty(fileno(stdout))) std::fputc('\n', stdout);  // end the progress line
    std::fprintf(stderr, "interrupted: %s\n", summary.message.c_str());
    std::fprintf(stderr, "results in %s/: %s\n",
                 fs::absolute(out).lexically_normal().string().c_str(),
                 rf::app::list_results(out, rf::app::ResultKind::kTransient).c_str());
    return rf::solver::interrupt::exit_status(signal);
  }
  summary.status = "normal termination";
  finish();
  if (!quiet) {
    std::printf(
        "normal termination: t = %g after %lld cycles, %.2f s wall, %.1f ns per "
        "element-cycle\n",
        summary.final_time, static_cast<long long>(summary.cycles), summary.wall_seconds,
        summary.ns_per_element_cycle);
    if (const rf::restart::Dumper* dumper = sim.restart_dumper();
        dumper && !dumper->written().empty()) {
      std::printf("restart dumps: %zu written (last %s), %.2f s\n", dumper->written().size(),
                  dumper->written().back().filename().string().c_str(), dumper->seconds());
    }
    const std::string frames = frames_collection(out);
    std::printf("results in %s/: %s%s\n", fs::absolute(out).lexically_normal().string().c_str(),
                rf::app::list_results(out, rf::app::ResultKind::kTransient).c_str(),
                frames.empty() ? "" : fmt::format("; open {} in ParaView", frames).c_str());
  }
  return 0;
}

// run.json for a run that failed: a failure to write it (the disk that made the run fail, say)
// is reported but does not hide the run's own error.
void write_run_json_after_error(const fs::path& path, const rf::output::RunSummary& summary) {
  try {
    rf::output::write_run_json(path, summary);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
}

// Warnings are printed whatever --quiet says (it hides progress only).
void report_warning(rf::output::RunSummary& summary, const rf::model::Warning& w) {
  summary.warnings.push_back(rf::app::format_warning(w));
  std::fprintf(stderr, "warning: %s\n", summary.warnings.back().c_str());
}

// A reused output directory: the result files of an earlier run are removed first, so that
// nothing of it is mistaken for this run's (only RigidFlex's own names: app/result_files.hpp).
void clear_output_directory(const fs::path& out, rf::app::ResultKind kind, bool quiet,
                            std::string* log_line = nullptr) {
  const std::vector<std::string> removed = rf::app::clear_earlier_results(out, kind);
  if (removed.empty()) return;
  const std::string line =
      fmt::format("output directory {} held {} result file(s) of an earlier run; removed: {}",
                  out.string(), removed.size(), rf::app::short_list(removed));
  if (!quiet) std::printf("%s\n", line.c_str());
  if (log_line) *log_line = line;
}

std::string command_line_of(int argc, char** argv) {
  std::string text;
  for (int k = 0; k < argc; ++k) text += fmt::format("{}{}", k ? " " : "", argv[k]);
  return text;
}

std::string log_header(const std::string& command_line) {
  const std::time_t now = std::time(nullptr);
  char when[64] = {};
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S %Z", std::localtime(&now));
  return fmt::format("RigidFlex {}\nstarted {}\ncommand: {}\nthreads: {}\n", RIGIDFLEX_VERSION,
                     when, command_line, omp_get_max_threads());
}

int command_run(const std::string& deck, std::string output_dir, int threads, bool quiet,
                rf::io::ReadOptions read_options, const std::string& dialect, double dump_every,
                const std::string& command_line) {
  const rf::parallel::Communicator& world = rf::parallel::world();
  if (world.rank() != 0) return command_run_follower(deck, read_options, threads, dump_every);
  if (threads > 0) omp_set_num_threads(threads);
  if (output_dir.empty()) output_dir = fs::path(deck).stem().string() + "_out";
  const fs::path out = output_dir;
  rf::output::prepare_output_directory(out);

  rf::output::RunSummary summary;
  summary.threads = omp_get_max_threads();
  summary.ranks = world.size();

  // The deck texts are kept: a dump carries them (restart/model_input.hpp), and an interrupted
  // run writes one even without --dump-every.
  rf::restart::ModelInput input;
  read_options.record_files = &input.files;
  rf::model::Model model;
  try {
    model = rf::io::read_deck(deck, read_options);
  } catch (const rf::InputError& e) {
    summary.status = "error termination";
    summary.message = e.what();
    write_run_json_after_error(out / "run.json", summary);
    throw;
  }
  for (const auto& w : model.warnings) report_warning(summary, w);
  if (read_options.ignore_unsupported) {
    summary.ignore_unsupported = true;
    for (const auto& w : model.ignored_physics) {
      summary.ignored_unsupported.push_back(rf::app::format_warning(w));
    }
  }
  // *CONTROL_IMPLICIT_EIGENVALUE with IMFLAG 1: an eigen analysis instead of a transient run.
  if (rf::modal::deck_requests_eigen_analysis(model)) {
    if (world.distributed()) {
      throw rf::InputError({model.files.empty() ? deck : model.files.front(), 0,
                            "*CONTROL_IMPLICIT_EIGENVALUE", 1, "NEIG"},
                           "an eigen analysis runs in one process: start it without mpirun");
    }
    clear_output_directory(out, rf::app::ResultKind::kEigen, quiet);
    rf::model::Model quiet_model = model;
    quiet_model.warnings.clear();  // reported above
    rf::app::EigenCommandOptions eigen;
    eigen.output = out;
    eigen.quiet = quiet;
    return rf::app::run_eigen_command(quiet_model, eigen);
  }
  if (model.implicit.imflag == 1) {
    throw rf::InputError({model.files.empty() ? deck : model.files.front(), 0,
                          "*CONTROL_IMPLICIT_GENERAL", 1, "IMFLAG"},
                         "IMFLAG 1 (implicit) is supported only for an eigen analysis: add "
                         "*CONTROL_IMPLICIT_EIGENVALUE with NEIG > 0");
  }

  std::string cleared;
  clear_output_directory(out, rf::app::ResultKind::kTransient, quiet, &cleared);
  std::unique_ptr<rf::solver::Simulation> sim;
  try {
    sim = std::make_unique<rf::solver::Simulation>(model, rf::solver::SimulationOptions{out, true});
  } catch (const std::exception& e) {
    summary.status = "error termination";
    summary.message = e.what();
    write_run_json_after_error(out / "run.json", summary);
    throw;
  }
  for (const auto& w : sim->warnings()) report_warning(summary, w);
  input.main_deck = deck;
  input.dialect = dialect;
  input.overrides = read_options.parameter_overrides;
  // Without --dump-every no dump is scheduled, not even at termination; an interrupt still
  // writes one (Dumper::write_if_due).
  rf::restart::DumpSchedule schedule = rf::restart::Dumper::every(dump_every);
  schedule.at_termination = dump_every > 0.0;
  sim->enable_restart_dumps(std::make_unique<rf::restart::Dumper>(std::move(input), schedule));
  rf::app::RunLog log(out / "d3hsp.txt", false);
  log.write(log_header(command_line));
  if (!cleared.empty()) log.write(cleared + "\n");
  log.model_summary(model, *sim);
  if (world.distributed()) log.write(fmt::format("ranks: {}\n", world.size()));
  if (!quiet) {
    std::printf("rigidflex %s: %zu nodes, %lld elements, end time %g, %d thread(s)%s\n",
                RIGIDFLEX_VERSION, sim->state().nodes.size(),
                static_cast<long long>(sim->element_count()), sim->end_time(), summary.threads,
                world.distributed() ? fmt::format(" x {} ranks", world.size()).c_str() : "");
  }
  const int status = run_to_termination(*sim, out, summary, quiet, log);
  if (const rf::parallel::ElementDistribution* d = sim->distribution()) {
    const rf::parallel::Partition& p = d->partition();
    const std::string line = fmt::format(
        "ranks: {}, load imbalance {:.3f}, {} interface nodes; rank 0 spent {:.3f} s in the "
        "per-cycle reductions (force sum, step agreement)\n",
        world.size(), p.imbalance(), p.interface_nodes, d->reduction_seconds());
    log.write(line);
    if (!quiet) std::fputs(line.c_str(), stdout);
  }
  return status;
}

int command_restart(const rf::restart::RestartOptions& options, bool quiet,
                    const std::string& command_line) {
  const std::string dump = options.dump.string();
  rf::restart::Restarted restarted = rf::restart::restart_from_dump(options);
  rf::output::RunSummary summary;
  summary.threads = restarted.threads;
  summary.ranks = rf::parallel::world().size();
  for (const auto& w : restarted.warnings) report_warning(summary, w);
  rf::solver::Simulation& sim = *restarted.simulation;
  rf::app::RunLog log(restarted.output_directory / "d3hsp.txt", true);
  log.write("\n== restart ==\n" + log_header(command_line));
  log.write(fmt::format("from {} at t = {:.9g} (cycle {})\n", dump, restarted.header.time,
                        restarted.header.cycle));
  for (const auto& w : summary.warnings) log.write(fmt::format("warning: {}\n", w));
  if (!quiet) {
    std::printf(
        "rigidflex %s: restart from %s at t = %g (cycle %lld), end time %g, %d "
        "thread(s)\n",
        RIGIDFLEX_VERSION, dump.c_str(), restarted.header.time,
        static_cast<long long>(restarted.header.cycle), sim.end_time(), summary.threads);
  }
  return run_to_termination(sim, restarted.output_directory, summary, quiet, log);
}

// `rigidflex plot DIR`: runs the plot script (scripts/rigidflex-plot.py, installed beside the
// executable as rigidflex-plot) with Debian's python3; its exit status is the command's.
int command_plot(const std::string& directory, const std::string& output_dir) {
  std::error_code ec;
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  std::string script;
  for (const fs::path& candidate :
       {exe_dir / "rigidflex-plot",
        fs::path(RIGIDFLEX_SOURCE_DIR) / "scripts" / "rigidflex-plot.py"}) {
    if (!ec && fs::exists(candidate)) {
      script = candidate.string();
      break;
    }
  }
  if (script.empty()) {
    throw std::runtime_error(
        "the plot script rigidflex-plot is neither beside the executable "
        "nor in the source tree");
  }
  std::vector<std::string> args = {"python3", script, directory};
  if (!output_dir.empty()) {
    args.push_back("-o");
    args.push_back(output_dir);
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  // Debian's interpreter first: matplotlib is a Debian package (scripts/install-deps.sh).
  execv("/usr/bin/python3", argv.data());
  execvp("python3", argv.data());
  throw std::runtime_error("cannot start python3 for the plot script");
}

// libgomp's default lets a thread that waits at a barrier spin (up to ~300000 iterations)
// before it sleeps. On a machine that also runs other jobs, spinning threads take the cores the
// working threads need: with --threads equal to the cores a run was measured 12-26x slower than
// on one thread (issue 22, docs/performance.md), while with waiting threads asleep at once
// (OMP_WAIT_POLICY=passive) it was faster than one thread. libgomp reads OMP_WAIT_POLICY and
// GOMP_SPINCOUNT once, when it is loaded, before main, so the program sets the passive policy
// and re-executes itself, unless the user chose a policy (either variable set) or set
// RIGIDFLEX_OMP_DEFAULTS=0. docs/cli.md.
void use_robust_openmp_wait_policy(char** argv) {
  const auto set = [](const char* name) {
    const char* v = std::getenv(name);
    return v != nullptr && *v != '\0';
  };
  if (set("OMP_WAIT_POLICY") || set("GOMP_SPINCOUNT")) return;
  if (const char* v = std::getenv("RIGIDFLEX_OMP_DEFAULTS");
      v != nullptr && std::strcmp(v, "0") == 0) {
    return;
  }
  // Once only: the re-executed program finds OMP_WAIT_POLICY set.
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // No /proc (or exec refused): carry on with libgomp's default policy.
  unsetenv("OMP_WAIT_POLICY");
}

}  // namespace

// A distributed run that fails: rank 0 reports the error (every rank holds the same model and
// state, so the others would repeat it; a follower's own kind of failure is printed with its
// rank), then every rank is ended, so that none waits forever in a collective operation.
[[noreturn]] void end_distributed_run(int status, const char* kind, const char* message,
                                      bool replicated) {
  const rf::parallel::Communicator& world = rf::parallel::world();
  if (world.rank() == 0) {
    std::fprintf(stderr, "%s: %s\n", kind, message);
  } else if (!replicated) {
    std::fprintf(stderr, "rank %d: %s: %s\n", world.rank(), kind, message);
  } else {
    // Rank 0 meets the same error and reports it; its MPI_Abort ends this rank too. Waiting
    // first keeps this rank's abort from killing rank 0 before its message is out.
    std::this_thread::sleep_for(std::chrono::seconds(10));
  }
  std::fflush(stderr);
  world.abort(status);
}

int main(int argc, char** argv) {
  use_robust_openmp_wait_policy(argv);
  // Eigen would split its larger matrix products over the OpenMP threads with blockings that
  // depend on the thread count (a flexible body's per-cycle products among them), so results
  // changed in the last bits with --threads. Our kernels parallelise over elements and nodes
  // themselves; Eigen's products run on one thread and results are the same for any thread
  // count (docs/cli.md).
  Eigen::setNbThreads(1);
  // MPI_Init only under an MPI launcher (mpirun -np N rigidflex run ...): docs/parallel.md.
  rf::parallel::Session mpi_session(&argc, &argv);
  CLI::App app{"RigidFlex: explicit finite-element dynamics with rigid/deformable switching"};
  app.set_version_flag("--version", std::string(RIGIDFLEX_VERSION));
  app.require_subcommand(1);

  std::string deck, output_dir, dialect = "auto", dump, restart_deck;
  int threads = 0;
  bool quiet = false;
  bool ignore_unsupported = false;
  std::vector<std::string> assignments;
  double dump_every = 0.0;

  auto* run = app.add_subcommand("run", "Run the analysis a deck describes");
  run->add_option("deck", deck, "Keyword deck")->required();
  run->add_option("-o,--output", output_dir, "Output directory (default: <deck stem>_out)");
  run->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--quiet", quiet, "No progress or summary (warnings and errors still printed)");
  run->add_option("--set", assignments, "Override a *PARAMETER: name=value (repeatable)");
  run->add_option("--dialect", dialect, "Input dialect")
      ->check(CLI::IsMember({"auto", "lsdyna", "impetus"}));
  run->add_flag("--ignore-unsupported", ignore_unsupported,
                "Run without the unsupported keywords that change the physics (listed in the log "
                "and run.json) instead of refusing the deck");
  run->add_option("--dump-every", dump_every,
                  "Write a restart dump DIR/d3dump_NNNN.h5 every T of simulated time and at the "
                  "end")
      ->check(CLI::PositiveNumber);

  auto* restart = app.add_subcommand("restart", "Continue a run from a restart dump");
  restart->add_option("dump", dump, "Restart dump (d3dump_NNNN.h5)")->required();
  restart->add_option("restart_deck", restart_deck,
                      "Restart deck: *CONTROL_TERMINATION, *DEFORMABLE_TO_RIGID, "
                      "*RIGID_TO_DEFORMABLE");
  restart->add_option("-o,--output", output_dir, "Output directory (default: the dump's)");
  restart->add_option("--threads", threads, "OpenMP threads (default: as the dumped run)")
      ->check(CLI::NonNegativeNumber);
  restart->add_flag("--quiet", quiet, "No progress or summary (warnings and errors still printed)");
  auto* restart_dump_every = restart
                                 ->add_option("--dump-every", dump_every,
                                              "Restart dump interval (default: as the dumped run)")
                                 ->check(CLI::PositiveNumber);

  auto* check = app.add_subcommand("check", "Read and validate a deck, print a model summary");
  check->add_option("deck", deck, "Keyword deck")->required();
  check->add_option("--set", assignments, "Override a *PARAMETER: name=value (repeatable)");
  check->add_option("--dialect", dialect, "Input dialect")
      ->check(CLI::IsMember({"auto", "lsdyna", "impetus"}));
  check->add_flag("--ignore-unsupported", ignore_unsupported,
                  "Accept the deck without the unsupported keywords that change the physics");
  int check_ranks = 0;
  check
      ->add_option("--ranks", check_ranks,
                   "Also print the element partition for N MPI ranks (elements and weight per "
                   "rank, load imbalance, interface nodes)")
      ->check(CLI::PositiveNumber);

  std::optional<int> eigen_modes;
  std::string eigen_parts, eigen_solver = "cholmod", eigen_rotary_inertia = "physical";
  std::optional<double> eigen_shift, eigen_remove_rigid, eigen_drilling_factor;
  auto* eigen = app.add_subcommand(
      "eigen", "Eigen analysis (modes of free-free or constrained parts) of any deck");
  eigen->add_option("deck", deck, "Keyword deck")->required();
  eigen->add_option("-o,--output", output_dir, "Output directory (default: <deck stem>_eigen)");
  eigen
      ->add_option("--modes", eigen_modes,
                   "Number of modes (default: NEIG of *CONTROL_IMPLICIT_EIGENVALUE, else 20)")
      ->check(CLI::PositiveNumber);
  eigen->add_option("--parts", eigen_parts, "Analyse only these parts, e.g. 1,2 (default: all)");
  eigen->add_option("--shift", eigen_shift,
                    "Negative shift sigma of the shift-invert operator, eigenvalue units "
                    "(default: automatic)");
  eigen->add_option("--remove-rigid", eigen_remove_rigid,
                    "Drop modes at or below this frequency (LFLAG 1, LFTEND)");
  eigen->add_option("--solver", eigen_solver, "Sparse Cholesky: cholmod or simplicial (Eigen)")
      ->check(CLI::IsMember({"cholmod", "simplicial"}));
  eigen
      ->add_option("--rotary-inertia", eigen_rotary_inertia,
                   "Rotational inertia of shell and beam nodes: physical (default) or explicit "
                   "(the explicit solver's scaled rotary inertia, docs/eigen.md)")
      ->check(CLI::IsMember({"physical", "explicit"}));
  eigen
      ->add_option("--drilling-factor", eigen_drilling_factor,
                   "Drilling penalty of shells, k = F G t A (default 1e-3, docs/eigen.md); "
                   "larger F moves the drilling modes up the spectrum")
      ->check(CLI::PositiveNumber);
  eigen->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  eigen->add_flag("--quiet", quiet, "No progress or summary (warnings and errors still printed)");
  eigen->add_option("--set", assignments, "Override a *PARAMETER: name=value (repeatable)");
  eigen->add_option("--dialect", dialect, "Input dialect")
      ->check(CLI::IsMember({"auto", "lsdyna", "impetus"}));
  eigen->add_flag("--ignore-unsupported", ignore_unsupported,
                  "Analyse the deck without the unsupported keywords that change the physics");

  std::string plot_dir;
  auto* plot = app.add_subcommand(
      "plot", "PNG plots of a run's histories (energies, nodes, rigid bodies, forces) into DIR");
  plot->add_option("dir", plot_dir, "Output directory of a run")->required();
  plot->add_option("-o,--output", output_dir, "Where the PNGs go (default: DIR)");

  // Usage errors (unknown option, missing or invalid argument) exit with 1, not CLI11's own
  // codes (105-109...), so that the documented set stays small (docs/cli.md).
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);  // prints the message (or --help, --version)
    return status == 0 ? 0 : kExitUsageError;
  }
  // Ctrl-C and SIGTERM end a run or restart between cycles, with its files whole.
  if (*run || *restart) rf::solver::interrupt::install_handlers();
  const std::string command_line = command_line_of(argc, argv);

  try {
    rf::io::ReadOptions read_options;
    read_options.warnings_on_error = &g_warnings_before_error;
    read_options.dialect = parse_dialect(dialect);
    read_options.parameter_overrides = parse_overrides(assignments);
    read_options.ignore_unsupported = ignore_unsupported;
    read_options.check_runnable = *check || *run;
    if (*check) return command_check(deck, read_options, check_ranks);
    if (*plot) return command_plot(plot_dir, output_dir);
    if (*eigen) {
      if (threads > 0) omp_set_num_threads(threads);
      if (eigen_shift && !(*eigen_shift < 0.0)) {
        throw std::invalid_argument(
            "--shift must be negative (K - sigma M must be positive "
            "definite)");
      }
      rf::app::EigenCommandOptions options;
      options.output = output_dir.empty() ? fs::path(deck).stem().string() + "_eigen" : output_dir;
      options.modes = eigen_modes;
      options.parts = rf::app::parse_part_list(eigen_parts);
      options.shift = eigen_shift;
      options.remove_rigid_below = eigen_remove_rigid;
      options.solver = eigen_solver;
      options.explicit_rotary_inertia = eigen_rotary_inertia == "explicit";
      options.drilling_factor = eigen_drilling_factor;
      options.quiet = quiet;
      rf::model::Model model = rf::io::read_deck(deck, read_options);
      clear_output_directory(options.output, rf::app::ResultKind::kEigen, quiet);
      return rf::app::run_eigen_command(std::move(model), options);
    }
    if (*restart) {
      rf::restart::RestartOptions options;
      options.dump = dump;
      options.restart_deck = restart_deck;
      options.output_directory = output_dir;
      options.threads = threads;
      if (restart_dump_every->count() > 0) options.dump_interval = dump_every;
      if (rf::parallel::world().rank() != 0) return command_restart_follower(options);
      return command_restart(options, quiet, command_line);
    }
    return command_run(deck, output_dir, threads, quiet, read_options, dialect, dump_every,
                       command_line);
  } catch (const rf::InputError& e) {
    if (rf::parallel::world().distributed()) {
      end_distributed_run(kExitInputError, "input error", e.what(), true);
    }
    for (const auto& w : g_warnings_before_error) {
      std::fprintf(stderr, "warning: %s\n", rf::app::format_warning(w).c_str());
    }
    std::fprintf(stderr, "input error: %s\n", e.what());
    return kExitInputError;
  } catch (const rf::SolverError& e) {
    if (rf::parallel::world().distributed()) {
      end_distributed_run(kExitSolverError, "error termination", e.what(), true);
    }
    std::fprintf(stderr, "error termination: %s\n", e.what());
    return kExitSolverError;
  } catch (const std::exception& e) {
    if (rf::parallel::world().distributed()) {
      end_distributed_run(kExitOtherError, "error", e.what(), false);
    }
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitOtherError;
  }
}
