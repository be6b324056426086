// sensor.csv: sensor values, switch outputs and control statuses over time (docs/output.md).
#pragma once

#include <fmt/format.h>

#include <filesystem>
#include <limits>
#include <string_view>

#include "output/writers.hpp"
#include "sensor/sensor.hpp"

namespace rf::sensor {

inline constexpr std::string_view kSensorHeader = "time,kind,id,value";

class SensorCsv {
 public:
  // `interval`: regular output interval (> 0).
  // `continue_at` >= 0: continue the file from that size (restart, see output::CsvFile).
  SensorCsv(const std::filesystem::path& path, double interval, std::int64_t continue_at = -1);
  std::int64_t flushed_size() { return csv_.flushed_size(); }
  // Called after every evaluation. Writes one row per sensor, switch and control when the
  // interval is due, when a switch output or control status changed in this evaluation (so
  // that the cycle of every change is on file), or when `force` is set (end of the run).
  void write(const SensorSystem& system, bool force);
  void flush() { csv_.flush(); }

 private:
  output::CsvFile csv_;
  double interval_ = 0.0;
  double next_ = 0.0;
  double last_time_ = -std::numeric_limits<double>::infinity();
  fmt::memory_buffer rows_;  // reused: no allocation once it has grown
};

}  // namespace rf::sensor
