// modal.csv: the modal state of every flexible body (*PART_MODES) at each output time,
// time,body,mode,amplitude,velocity (docs/output.md). `mode` is the mode's number in the mode
// database.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>

#include "output/writers.hpp"
#include "solver/rigid_bodies.hpp"

namespace rf::output {

inline constexpr std::string_view kModalHeader = "time,body,mode,amplitude,velocity";

class ModalWriter {
 public:
  explicit ModalWriter(const std::filesystem::path& path, std::int64_t continue_at = -1);
  // Rows at t^n, written between the velocity and the position update: amplitude q^n (the
  // modes already advanced to t^{n+1}) and the modal velocity at t^n.
  void write(double time, const solver::RigidSystem& rigid);
  void flush() { csv_.flush(); }
  std::int64_t flushed_size() { return csv_.flushed_size(); }

 private:
  CsvFile csv_;
};

}  // namespace rf::output
