// rwforc.csv: forces and motion of the rigid walls (docs/output.md).
#include <fmt/format.h>

#include "output/writers.hpp"

namespace rf::output {

RwforcWriter::RwforcWriter(const std::filesystem::path& path, std::int64_t continue_at)
    : csv_(path, std::string(kRwforcHeader), continue_at) {}

void RwforcWriter::write(const std::vector<RwforcRow>& rows) {
  fmt::memory_buffer text;
  for (const RwforcRow& row : rows) {
    // 17 significant digits, as every CSV file: values read back bit-identical.
    fmt::format_to(std::back_inserter(text), "{:.17g},{},{:.17g}", row.time, row.wall,
                   row.normal_force);
    for (const double value : row.force)
      fmt::format_to(std::back_inserter(text), ",{:.17g}", value);
    for (const double value : {row.displacement, row.velocity, row.normal_impulse, row.work}) {
      fmt::format_to(std::back_inserter(text), ",{:.17g}", value);
    }
    for (const double value : row.segment_force)
      fmt::format_to(std::back_inserter(text), ",{:.17g}", value);
    text.push_back('\n');
  }
  csv_.write_text(std::string_view(text.data(), text.size()));
}

}  // namespace rf::output
