#include "app/run_log.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "app/model_summary.hpp"
#include "solver/simulation.hpp"

namespace rf::app {

RunLog::RunLog(const std::filesystem::path& path, bool append) : path_(path) {
  file_ = std::fopen(path.c_str(), append ? "ab" : "wb");
}

RunLog::~RunLog() {
  if (file_ != nullptr) std::fclose(file_);
}

void RunLog::write(std::string_view text) {
  if (file_ == nullptr) return;
  std::fwrite(text.data(), 1, text.size(), file_);
  std::fflush(file_);
}

void RunLog::model_summary(const model::Model& model, const solver::Simulation& sim) {
  if (file_ == nullptr) return;
  write("\n== model (as `rigidflex check` prints it) ==\n");
  print_model_summary(model, sim, file_);
  // The phase ran when the simulation was constructed: what it did (docs/theory.md).
  if (const auto& relaxation = sim.dynamic_relaxation(); relaxation.cycles > 0) {
    fmt::print(file_,
               "dynamic relaxation {} after {} cycles, pseudo-time {:.6g}: distortional kinetic "
               "energy {:.3g} of its peak; the transient starts from the relaxed state\n",
               relaxation.converged ? "converged" : "stopped before converging", relaxation.cycles,
               relaxation.pseudo_time, relaxation.kinetic_energy_ratio);
  }
  std::fflush(file_);
}

std::string format_phase_times(const solver::Simulation& sim, double loop_seconds) {
  const solver::PhaseTimes& times = sim.phase_times();
  const double measured = std::accumulate(std::begin(times.seconds), std::end(times.seconds), 0.0);
  const double total = std::max(loop_seconds, measured);
  auto line = [&](std::string_view name, double s) {
    return fmt::format("  {:<24} {:>10.3f} s {:>6.1f} %\n", name, s,
                       total > 0.0 ? 100.0 * s / total : 0.0);
  };
  std::string text = "time per phase (wall time of the time loop):\n";
  for (int p = 0; p < solver::PhaseTimes::kCount; ++p) {
    text += line(solver::PhaseTimes::kNames[p], std::max(0.0, times.seconds[p]));
  }
  text += line("other (progress, loop)", std::max(0.0, total - measured));
  text += line("time loop", total);
  return text;
}

void RunLog::finish(const solver::Simulation& sim, const std::string& status,
                    const std::string& message, const std::vector<std::string>& run_warnings,
                    double loop_seconds) {
  if (file_ == nullptr) return;
  std::string text = "\n== end ==\n";
  text += fmt::format("warnings during the run: {}\n", run_warnings.size());
  for (const auto& w : run_warnings) text += fmt::format("  {}\n", w);
  text += fmt::format("{}{}{}: t = {:.9g}, cycle {}\n", status, message.empty() ? "" : ": ",
                      message, sim.state().time, sim.state().cycle);
  text += format_phase_times(sim, loop_seconds);
  write(text);
}

}  // namespace rf::app
