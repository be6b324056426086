// Output of an eigen analysis (docs/eigen.md, docs/output.md): modes.h5 (mode database),
// eigout.csv (one row per mode) and modes.pvd + modes_NNNN.vtu (ParaView: one file per mode,
// "displacement" = the mass-normalised mode shape, the points X0 + s * shape with s in field data
// `mode_scale`, the collection's time = mode number).
#pragma once

#include <filesystem>
#include <vector>

#include "modal/eigen_analysis.hpp"
#include "modal/mode_set.hpp"
#include "model/model.hpp"

namespace rf::modal {

// eigout.csv: mode,eigenvalue,frequency_hz,generalized_mass,residual
void write_eigout_csv(const std::filesystem::path& file, const ModeSet& modes);

// Largest drawn displacement of a mode shape in modes_NNNN.vtu, as a fraction of the bounding-box
// diagonal of the reference mesh.
inline constexpr double mode_display_fraction = 0.1;

// modes.pvd and modes_NNNN.vtu for the sub-model of `parts` (the mesh is rebuilt with the
// explicit solver's build_state, so nodes are in the order of the ModeSet). Points are
// X0 + s * phi with s = mode_display_fraction * diagonal / max |phi_i| (field data
// `mode_scale`); point data `displacement` is phi itself.
void write_mode_fields(const std::filesystem::path& directory, const model::Model& model,
                       const std::vector<model::Id>& parts, const ModeSet& modes);

// All three into `directory` (created when missing).
void write_eigen_outputs(const std::filesystem::path& directory, const model::Model& model,
                         const EigenRequest& request, const ModeSet& modes);

}  // namespace rf::modal
