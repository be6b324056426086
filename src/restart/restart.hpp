// `rigidflex restart`: rebuilds a run from a restart dump and continues it. The model is read
// again from the deck texts the dump carries (so the original files are not needed), every
// dynamic quantity is then overwritten from the dump, an optional restart deck changes the
// termination or switches parts, and the output files are continued so that they end up equal to
// those of an uninterrupted run (docs/restart.md).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "model/model.hpp"
#include "restart/dump.hpp"
#include "solver/simulation.hpp"

namespace rf::restart {

struct RestartOptions {
  std::filesystem::path dump;
  std::filesystem::path restart_deck;      // empty: a simple restart (nothing changed)
  std::filesystem::path output_directory;  // empty: the directory the dump is in
  std::optional<double> dump_interval;     // --dump-every; unset: as in the dumped run
  int threads = 0;                         // 0: as many as the dumped run used
  bool write_fields = true;
  // False on the ranks > 0 of a distributed restart: they rebuild the same state from the dump
  // and take part in the run, but have no output directory and touch no file (rank 0 writes).
  bool writes_files = true;
};

struct Restarted {
  std::unique_ptr<solver::Simulation> simulation;
  DumpHeader header;
  std::filesystem::path output_directory;
  int threads = 0;
  // Notices for the user: another RigidFlex version, another thread count, output files that
  // could not be continued.
  std::vector<model::Warning> warnings;
};

// Throws rf::InputError for a missing, damaged or foreign dump, a dump of another version, and
// errors in the restart deck, each naming the file (and card and field for the deck).
Restarted restart_from_dump(const RestartOptions& options);

}  // namespace rf::restart
