#include "restart/dumper.hpp"

#include <fmt/format.h>

#include <chrono>

#include "restart/dump.hpp"
#include "restart/simulation_access.hpp"

namespace rf::restart {

std::string dump_file_name(std::int64_t number) {
  return fmt::format("d3dump_{:04d}.h5", number);
}

DumpSchedule Dumper::every(double interval) {
  DumpSchedule s;
  s.interval = interval > 0.0 ? interval : 0.0;
  s.next = s.interval;
  return s;
}

void Dumper::write_if_due(solver::Simulation& sim) {
  const solver::State& state = SimulationAccess::state(sim);
  const std::filesystem::path& directory = SimulationAccess::output_directory(sim);
  // On ranks every process keeps the schedule and takes part (the state rank 0 writes is
  // gathered from all); rank 0 alone has an output directory and writes.
  const bool distributed = SimulationAccess::distributed(sim);
  if ((directory.empty() && !distributed) || schedule_.last_cycle == state.cycle) return;
  // Same tolerance as the output schedules (Simulation::OutputSchedule::due).
  const bool scheduled = schedule_.interval > 0.0 && state.time >= schedule_.next * (1.0 - 1e-12);
  // An interrupted run (Ctrl-C, SIGTERM) always leaves a dump to continue from.
  const bool at_end = (schedule_.at_termination || sim.interrupt_signal() != 0) &&
                      SimulationAccess::end_reached(sim);
  if (!scheduled && !at_end) return;

  const auto start = std::chrono::steady_clock::now();
  // Count the dump and move the schedule before writing, so the dump holds the schedule as it
  // is after itself: a restart from it neither rewrites it nor reuses its number.
  ++schedule_.count;
  schedule_.last_cycle = state.cycle;
  if (schedule_.interval > 0.0) {
    while (schedule_.next <= state.time * (1.0 + 1e-12)) schedule_.next += schedule_.interval;
  }
  const std::filesystem::path path = directory / dump_file_name(schedule_.count);
  if (distributed) SimulationAccess::prepare_dump_on_ranks(sim);
  if (SimulationAccess::writes_files(sim)) {
    write_restart_dump(sim, path);
    written_.push_back(path);
  }
  if (distributed) SimulationAccess::finish_dump_on_ranks(sim);
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rf::restart
