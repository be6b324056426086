// The model summary printed by `rigidflex check`.
#pragma once

#include <cstdio>
#include <string>

#include "model/model.hpp"

namespace rf::solver {
class Simulation;
}

namespace rf::app {

// Nodes, elements by shape, parts with section and material, sets, curves, controls and
// every warning. Also validates what only the solver set-up checks (cross references).
void print_model_summary(const model::Model& model, std::FILE* out);
// The same for a simulation already built from `model` (run: d3hsp.txt, no second set-up).
void print_model_summary(const model::Model& model, const solver::Simulation& sim, std::FILE* out);

// "file:line: *KEYWORD: message", leaving out the parts a warning does not have.
std::string format_warning(const model::Warning& warning);

}  // namespace rf::app
