#include "sensor/sensor_output.hpp"

#include <iterator>
#include <string>

namespace rf::sensor {

SensorCsv::SensorCsv(const std::filesystem::path& path, double interval, std::int64_t continue_at)
    : csv_(path, std::string(kSensorHeader), continue_at), interval_(interval) {}

void SensorCsv::write(const SensorSystem& system, bool force) {
  const double t = system.time;
  const bool due = t >= next_ * (1.0 - 1e-12);
  if (!(due || system.changed || force) || t == last_time_) return;
  rows_.clear();
  auto out = std::back_inserter(rows_);
  for (std::size_t k = 0; k < system.sensor_ids.size(); ++k) {
    fmt::format_to(out, "{:.17g},sensor,{},{:.17g}\n", t, system.sensor_ids[k], system.values[k]);
  }
  for (const auto& sw : system.switches) {
    fmt::format_to(out, "{:.17g},switch,{},{}\n", t, sw.id, sw.output ? 1 : 0);
  }
  for (const auto& c : system.controls) {
    fmt::format_to(out, "{:.17g},control,{},{}\n", t, c.id, c.on ? 1 : 0);
  }
  csv_.write_text(std::string_view(rows_.data(), rows_.size()));
  last_time_ = t;
  if (due && interval_ > 0.0) {
    while (next_ <= t * (1.0 + 1e-12)) next_ += interval_;
  }
}

}  // namespace rf::sensor
