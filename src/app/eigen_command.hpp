// `rigidflex eigen DECK` and the eigen branch of `rigidflex run` (docs/eigen.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace rf::app {

struct EigenCommandOptions {
  std::filesystem::path output;              // output directory
  std::optional<int> modes;                  // --modes (else NEIG of the deck, else 20)
  std::vector<model::Id> parts;              // --parts (empty: all)
  std::optional<double> shift;               // --shift (eigenvalue units, negative)
  std::optional<double> remove_rigid_below;  // --remove-rigid F: LFLAG 1, LFTEND F
  std::string solver = "cholmod";            // cholmod | simplicial
  bool explicit_rotary_inertia = false;      // --rotary-inertia explicit
  std::optional<double> drilling_factor;     // --drilling-factor
  bool quiet = false;
};

// Runs the analysis on a model read from a deck and writes modes.h5, eigout.csv and
// modes.pvd/modes_NNNN.vtu into options.output. Returns the process exit status (0).
int run_eigen_command(const model::Model& model, const EigenCommandOptions& options);

// "1,2,5" -> {1, 2, 5}; throws std::invalid_argument with a message on bad text.
std::vector<model::Id> parse_part_list(const std::string& text);

}  // namespace rf::app
