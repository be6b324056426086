// rigidflex: command-line entry point.
//   rigidflex run DECK [-o DIR] [--threads N] [--quiet] [--set name=value]...
//   rigidflex check DECK
#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/model_summary.hpp"
#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "output/writers.hpp"
#include "solver/simulation.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Exit codes: documented in docs/cli.md.
constexpr int kExitInputError = 2;
constexpr int kExitSolverError = 3;
constexpr int kExitOtherError = 4;

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
  explicit ProgressPrinter(bool quiet) : quiet_(quiet), tty_(isatty(fileno(stdout)) != 0) {}

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
    const double left = fraction > 0.0 ? wall * (1.0 - fraction) / fraction : 0.0;
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
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_{};
  double next_fraction_ = 0.0;
  bool printed_final_ = false;
};

int command_check(const std::string& deck, const rf::io::ReadOptions& read_options) {
  const rf::model::Model model = rf::io::read_deck(deck, read_options);
  rf::app::print_model_summary(model, stdout);
  return 0;
}

int command_run(const std::string& deck, std::string output_dir, int threads, bool quiet,
                const rf::io::ReadOptions& read_options) {
  if (threads > 0) omp_set_num_threads(threads);
  if (output_dir.empty()) output_dir = fs::path(deck).stem().string() + "_out";
  const fs::path out = output_dir;
  fs::create_directories(out);

  rf::output::RunSummary summary;
  summary.threads = omp_get_max_threads();
  const auto start = Clock::now();
  auto finish = [&](const rf::solver::Simulation* sim) {
    summary.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (sim) {
      summary.final_time = sim->state().time;
      summary.cycles = sim->state().cycle;
      summary.nodes = static_cast<std::int64_t>(sim->state().nodes.size());
      summary.elements = sim->element_count();
      const double element_cycles = static_cast<double>(summary.elements) *
                                    static_cast<double>(std::max<std::int64_t>(1, summary.cycles));
      summary.ns_per_element_cycle = 1e9 * summary.wall_seconds / element_cycles;
    }
    rf::output::write_run_json(out / "run.json", summary);
  };

  rf::model::Model model;
  try {
    model = rf::io::read_deck(deck, read_options);
  } catch (const rf::InputError& e) {
    summary.status = "error termination";
    summary.message = e.what();
    finish(nullptr);
    throw;
  }
  for (const auto& w : model.warnings) {
    summary.warnings.push_back(rf::app::format_warning(w));
    if (!quiet) std::fprintf(stderr, "warning: %s\n", summary.warnings.back().c_str());
  }

  std::unique_ptr<rf::solver::Simulation> sim;
  try {
    sim = std::make_unique<rf::solver::Simulation>(model, rf::solver::SimulationOptions{out, true});
    for (const auto& w : sim->warnings()) {
      summary.warnings.push_back(rf::app::format_warning(w));
      if (!quiet) std::fprintf(stderr, "warning: %s\n", summary.warnings.back().c_str());
    }
    if (!quiet) {
      std::printf("rigidflex %s: %zu nodes, %lld elements, end time %g, %d thread(s)\n",
                  RIGIDFLEX_VERSION, sim->state().nodes.size(),
                  static_cast<long long>(sim->element_count()), sim->end_time(), summary.threads);
    }
    ProgressPrinter progress(quiet);
    sim->run(std::ref(progress));
  } catch (const std::exception& e) {
    summary.status = "error termination";
    summary.message = e.what();
    finish(sim.get());
    throw;
  }
  summary.status = "normal termination";
  finish(sim.get());
  if (!quiet) {
    std::printf(
        "normal termination: t = %g after %lld cycles, %.2f s wall, %.1f ns per "
        "element-cycle\n",
        summary.final_time, static_cast<long long>(summary.cycles), summary.wall_seconds,
        summary.ns_per_element_cycle);
    std::printf(
        "results in %s/ (glstat.csv, d3plot.pvd, run.json); open d3plot.pvd in "
        "ParaView\n",
        fs::absolute(out).lexically_normal().string().c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"RigidFlex: explicit finite-element dynamics with rigid/deformable switching"};
  app.set_version_flag("--version", std::string(RIGIDFLEX_VERSION));
  app.require_subcommand(1);

  std::string deck, output_dir, dialect = "auto";
  int threads = 0;
  bool quiet = false;
  std::vector<std::string> assignments;

  auto* run = app.add_subcommand("run", "Run the analysis a deck describes");
  run->add_option("deck", deck, "Keyword deck")->required();
  run->add_option("-o,--output", output_dir, "Output directory (default: <deck stem>_out)");
  run->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--quiet", quiet, "Print nothing but errors");
  run->add_option("--set", assignments, "Override a *PARAMETER: name=value (repeatable)");
  run->add_option("--dialect", dialect, "Input dialect")
      ->check(CLI::IsMember({"auto", "lsdyna", "impetus"}));

  auto* check = app.add_subcommand("check", "Read and validate a deck, print a model summary");
  check->add_option("deck", deck, "Keyword deck")->required();
  check->add_option("--set", assignments, "Override a *PARAMETER: name=value (repeatable)");
  check->add_option("--dialect", dialect, "Input dialect")
      ->check(CLI::IsMember({"auto", "lsdyna", "impetus"}));

  CLI11_PARSE(app, argc, argv);

  try {
    rf::io::ReadOptions read_options;
    read_options.dialect = parse_dialect(dialect);
    read_options.parameter_overrides = parse_overrides(assignments);
    if (*check) return command_check(deck, read_options);
    return command_run(deck, output_dir, threads, quiet, read_options);
  } catch (const rf::InputError& e) {
    std::fprintf(stderr, "input error: %s\n", e.what());
    return kExitInputError;
  } catch (const rf::SolverError& e) {
    std::fprintf(stderr, "error termination: %s\n", e.what());
    return kExitSolverError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitOtherError;
  }
}
