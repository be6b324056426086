// The model summary printed by `rigidflex check`.
#pragma once

#include <cstdio>
#include <string>

#include "model/model.hpp"

namespace rf::app {

// Nodes, elements by shape, parts with section and material, sets, curves, controls and
// every warning. Also validates what only the solver set-up checks (cross references).
void print_model_summary(const model::Model& model, std::FILE* out);

// "file:line: *KEYWORD: message", leaving out the parts a warning does not have.
std::string format_warning(const model::Warning& warning);

}  // namespace rf::app
