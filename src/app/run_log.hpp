// d3hsp.txt: the log a run leaves beside its results (named after LS-DYNA's d3hsp, docs/output.md):
// how it was started, the model summary `check` prints (every warning included), warnings that
// came up during the run, how it ended and the wall time per phase of the cycle.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "model/model.hpp"

namespace rf::solver {
class Simulation;
}

namespace rf::app {

class RunLog {
 public:
  // `append`: a restart adds to the log of the run it continues (a new file if there is none).
  // A log that cannot be opened is not an error of the run: the log is then skipped, and
  // ok() says so.
  RunLog(const std::filesystem::path& path, bool append);
  ~RunLog();
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;
  bool ok() const { return file_ != nullptr; }
  const std::filesystem::path& path() const { return path_; }

  // Text as given; flushed, so the log is readable while the run goes on.
  void write(std::string_view text);
  void model_summary(const model::Model& model, const solver::Simulation& sim);
  // The end: status line, run-time warnings, time per phase against `loop_seconds`, the wall
  // time of the whole time loop.
  void finish(const solver::Simulation& sim, const std::string& status, const std::string& message,
              const std::vector<std::string>& run_warnings, double loop_seconds);

 private:
  std::FILE* file_ = nullptr;
  std::filesystem::path path_;
};

// The phase table of RunLog::finish, also usable on its own (tests).
std::string format_phase_times(const solver::Simulation& sim, double loop_seconds);

}  // namespace rf::app
