// jntforc.csv: forces and moments of the joints (docs/output.md).
#include <fmt/format.h>

#include <cmath>

#include "output/writers.hpp"

namespace rf::output {

std::string jntforc_text(const std::vector<JntforcRow>& rows) {
  fmt::memory_buffer text;
  for (const JntforcRow& row : rows) {
    // 17 significant digits, as every CSV file: values read back bit-identical.
    fmt::format_to(std::back_inserter(text), "{:.17g},{}", row.time, row.joint);
    for (const auto* v : {&row.force, &row.moment}) {
      for (const double value : *v) fmt::format_to(std::back_inserter(text), ",{:.17g}", value);
      const double resultant = std::sqrt((*v)[0] * (*v)[0] + (*v)[1] * (*v)[1] + (*v)[2] * (*v)[2]);
      fmt::format_to(std::back_inserter(text), ",{:.17g}", resultant);
    }
    fmt::format_to(std::back_inserter(text), ",{}", row.stiffness);
    for (const auto* v : {&row.angle, &row.stiffness_moment}) {
      for (const double value : *v) fmt::format_to(std::back_inserter(text), ",{:.17g}", value);
    }
    fmt::format_to(std::back_inserter(text), ",{:.17g},{:.17g}", row.elastic_energy,
                   row.dissipated_energy);
    text.push_back('\n');
  }
  return std::string(text.data(), text.size());
}

}  // namespace rf::output
