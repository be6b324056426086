// rcforc.csv: resultant forces of the contact interfaces (docs/output.md).
#include <fmt/format.h>

#include "output/writers.hpp"

namespace rf::output {

RcforcWriter::RcforcWriter(const std::filesystem::path& path, std::int64_t continue_at)
    : csv_(path, std::string(kRcforcHeader), continue_at) {}

void RcforcWriter::write(const std::vector<RcforcRow>& rows) {
  fmt::memory_buffer text;
  for (const RcforcRow& row : rows) {
    // 17 significant digits, as every CSV file: values read back bit-identical.
    fmt::format_to(std::back_inserter(text), "{:.17g},{}", row.time, row.contact);
    for (const double value : row.slave_force)
      fmt::format_to(std::back_inserter(text), ",{:.17g}", value);
    for (const double value : row.slave_force)
      fmt::format_to(std::back_inserter(text), ",{:.17g}", value == 0.0 ? 0.0 : -value);
    fmt::format_to(std::back_inserter(text), ",{}\n", row.active_nodes);
  }
  csv_.write_text(std::string_view(text.data(), text.size()));
}

}  // namespace rf::output
