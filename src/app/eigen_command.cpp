#include "app/eigen_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "app/model_summary.hpp"
#include "app/result_files.hpp"
#include "modal/eigen_analysis.hpp"
#include "modal/mode_output.hpp"

namespace rf::app {

std::vector<model::Id> parse_part_list(const std::string& text) {
  std::vector<model::Id> parts;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty()) continue;
    std::size_t used = 0;
    long long value = 0;
    try {
      value = std::stoll(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || value <= 0) {
      throw std::invalid_argument(
          fmt::format("--parts: '{}' is not a positive part ID (expected e.g. 1,2,5)", item));
    }
    parts.push_back(value);
  }
  return parts;
}

int run_eigen_command(const model::Model& model, const EigenCommandOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  modal::EigenRequest request =
      model.implicit.eigenvalue ? modal::request_from_deck(model) : modal::EigenRequest{};
  if (options.modes) request.mode_count = *options.modes;
  request.parts = options.parts;
  if (options.shift) request.shift = *options.shift;
  if (options.remove_rigid_below) {
    request.remove_rigid_below = true;
    request.left_frequency = *options.remove_rigid_below;
  }
  request.backend = options.solver == "simplicial" ? modal::FactorizationBackend::EigenSimplicial
                                                   : modal::FactorizationBackend::Cholmod;
  if (options.explicit_rotary_inertia) request.rotary_inertia = modal::RotaryInertia::kExplicit;
  if (options.drilling_factor) request.drilling_factor = *options.drilling_factor;
  std::vector<std::string> log;
  request.log = &log;
  // Warnings always (--quiet hides progress and summaries only).
  for (const auto& w : model.warnings) {
    std::fprintf(stderr, "warning: %s\n", format_warning(w).c_str());
  }
  modal::EigenReport report;
  const modal::ModeSet modes = modal::compute_modes(model, request, report);
  for (const auto& line : log) {
    if (line.rfind("warning: ", 0) == 0)
      std::fprintf(stderr, "%s\n", line.c_str());
    else if (!options.quiet)
      std::printf("%s\n", line.c_str());
  }
  modal::write_eigen_outputs(options.output, model, request, modes);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.quiet) {
    std::printf("%5s %14s %14s %10s %6s\n", "mode", "eigenvalue", "frequency_hz", "residual",
                "rigid");
    for (std::size_t k = 0; k < modes.mode_count(); ++k) {
      const double f = std::sqrt(std::max(modes.eigenvalues[k], 0.0)) / (2.0 * M_PI);
      std::printf("%5zu %14.6e %14.6g %10.2e %6s\n", k + 1, modes.eigenvalues[k], f,
                  modes.residual[k], modes.rigid[k] ? "yes" : "");
    }
    std::printf(
        "normal termination: eigen analysis, %zu modes (%d rigid found, %d removed by LFLAG), "
        "%zu DOFs, %.2f s wall (assembly %.2f s, factorization %.2f s, Lanczos %.2f s)\n",
        modes.mode_count(), report.rigid_found, report.removed_by_lflag, report.dof_count, seconds,
        report.seconds_assembly, report.seconds_factorization, report.seconds_lanczos);
    std::printf("results in %s/: %s\n",
                std::filesystem::absolute(options.output).lexically_normal().string().c_str(),
                list_results(options.output, ResultKind::kEigen).c_str());
  }
  return 0;
}

}  // namespace rf::app
