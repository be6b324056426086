// Restart dumps during a run: when they are due and what they are called. A dump is written
// between cycles, at the top of the loop, where the state is complete at t^n (positions, forces
// and dt^{n+1/2} known, velocities at n-1/2), exactly the state after Simulation::initialize at
// t = 0; resuming from it repeats the remaining cycles bit for bit (docs/restart.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "restart/model_input.hpp"

namespace rf::solver {
class Simulation;
}

namespace rf::restart {

// The dump schedule; a dump stores it (after counting itself), so a restarted run neither
// rewrites the dump it started from nor renumbers later ones.
struct DumpSchedule {
  double interval = 0.0;         // simulated time between dumps (0: none on a schedule)
  double next = 0.0;             // time of the next scheduled dump
  bool at_termination = true;    // one more at the end of the run (like LS-DYNA's d3dump)
  std::int64_t last_cycle = -1;  // cycle of the last dump
  std::int64_t count = 0;        // dumps written so far: the last one is d3dump_<count>.h5
};

// d3dump_0001.h5, d3dump_0002.h5, ... (more digits past 9999).
std::string dump_file_name(std::int64_t number);

class Dumper {
 public:
  Dumper(ModelInput input, DumpSchedule schedule) : input_(std::move(input)), schedule_(schedule) {}

  // A dump every `interval` of simulated time from t = 0 (first at t = interval) and one at
  // termination.
  static DumpSchedule every(double interval);

  // Writes a dump into the simulation's output directory when one is due at this cycle.
  void write_if_due(solver::Simulation& sim);

  const ModelInput& input() const { return input_; }
  const DumpSchedule& schedule() const { return schedule_; }
  // Paths written by this run, and the wall time spent writing them.
  const std::vector<std::filesystem::path>& written() const { return written_; }
  double seconds() const { return seconds_; }

 private:
  ModelInput input_;
  DumpSchedule schedule_;
  std::vector<std::filesystem::path> written_;
  double seconds_ = 0.0;
};

}  // namespace rf::restart
