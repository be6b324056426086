// The files RigidFlex writes into an output directory, by name pattern (docs/output.md): a
// reused directory is cleared of an earlier run's results (never of anything else), and the
// closing line lists what is there after the run.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rf::app {

enum class ResultKind {
  kTransient,  // run / restart: CSV histories, frames, dumps, run.json, d3hsp.txt, plots
  kEigen,      // eigen analyses: modes.h5, eigout.csv, modes.pvd, modes_NNNN.vtu
};

// True when `name` (a file name, no directory) is one RigidFlex writes for results of `kind`.
bool is_result_file(const std::string& name, ResultKind kind);

// Removes the result files of `kind` an earlier run left in `directory` (files only, by the
// patterns of is_result_file; nothing else is touched) and returns their names, sorted.
std::vector<std::string> clear_earlier_results(const std::filesystem::path& directory,
                                               ResultKind kind);

// The result files of `kind` in `directory`, sorted, a numbered series shown once with its
// count: "glstat.csv, d3plot.pvd, d3plot_NNNN.vtu (21 files), run.json".
std::string list_results(const std::filesystem::path& directory, ResultKind kind);

// "a, b, c and 4 more": a short form of a long list of names for messages.
std::string short_list(const std::vector<std::string>& names, std::size_t shown = 6);

}  // namespace rf::app
