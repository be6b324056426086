#include "modal/mode_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "modal/stiffness_assembly.hpp"
#include "output/writers.hpp"
#include "solver/build_state.hpp"

namespace rf::modal {

void write_eigout_csv(const std::filesystem::path& file, const ModeSet& modes) {
  std::FILE* out = std::fopen(file.c_str(), "w");
  if (!out) throw std::runtime_error(fmt::format("cannot open '{}' for writing", file.string()));
  std::fputs("mode,eigenvalue,frequency_hz,generalized_mass,residual\n", out);
  for (std::size_t k = 0; k < modes.mode_count(); ++k) {
    const double lambda = modes.eigenvalues[k];
    const double f = std::sqrt(std::max(lambda, 0.0)) / (2.0 * M_PI);
    fmt::print(out, "{},{:.17g},{:.17g},{:.17g},{:.6e}\n", k + 1, lambda, f,
               modes.generalized_mass[k], modes.residual[k]);
  }
  if (std::fclose(out) != 0) {
    throw std::runtime_error(fmt::format("cannot write '{}'", file.string()));
  }
}

void write_mode_fields(const std::filesystem::path& directory, const model::Model& model,
                       const std::vector<model::Id>& parts, const ModeSet& modes) {
  const model::Model sub = extract_parts(model, parts);
  solver::State state = solver::build_state(sub, solver::NodeIndex(sub));
  const std::size_t n = state.nodes.size();
  if (n != modes.node_count() || state.nodes.id != modes.node_ids) {
    throw std::runtime_error("modes.vtu: the mode set does not belong to this model and parts");
  }
  output::FieldWriter writer(directory, "modes");
  // Drawn size: the largest nodal displacement of every mode is 10 % of the bounding-box
  // diagonal of the reference mesh (mass-normalised shapes have arbitrary, often huge or tiny,
  // lengths). `displacement` keeps the true shape; the factor is field data `mode_scale`.
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < n; ++i) {
    const double p[3] = {state.nodes.x0.x[i], state.nodes.x0.y[i], state.nodes.x0.z[i]};
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  }
  const double diagonal = n == 0 ? 0.0 : std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  for (std::size_t k = 0; k < modes.mode_count(); ++k) {
    const double* phi = modes.shape(k);
    double largest = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      largest = std::max(largest, std::hypot(phi[3 * i], phi[3 * i + 1], phi[3 * i + 2]));
    }
    output::FrameOptions options;
    options.scale_name = "mode_scale";
    options.point_displacement_scale =
        largest > 0.0 && diagonal > 0.0 ? mode_display_fraction * diagonal / largest : 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      state.nodes.x.x[i] = state.nodes.x0.x[i] + phi[3 * i];
      state.nodes.x.y[i] = state.nodes.x0.y[i] + phi[3 * i + 1];
      state.nodes.x.z[i] = state.nodes.x0.z[i] + phi[3 * i + 2];
    }
    state.time = static_cast<double>(k + 1);
    writer.write_frame(state, options);
  }
}

void write_eigen_outputs(const std::filesystem::path& directory, const model::Model& model,
                         const EigenRequest& request, const ModeSet& modes) {
  std::filesystem::create_directories(directory);
  write_mode_database(directory / "modes.h5", modes);
  write_eigout_csv(directory / "eigout.csv", modes);
  write_mode_fields(directory, model, request.parts, modes);
}

}  // namespace rf::modal
