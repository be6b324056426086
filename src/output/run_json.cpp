// run.json: machine-readable summary of a run for scripts and CI (docs/output.md).
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "output/output_directory.hpp"
#include "output/writers.hpp"

namespace rf::output {

namespace {

// JSON string literal. Bytes >= 0x80 pass through: messages are UTF-8 and JSON allows them raw.
void append_json_string(fmt::memory_buffer& out, std::string_view text) {
  out.push_back('"');
  for (char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"':
        fmt::format_to(std::back_inserter(out), "\\\"");
        break;
      case '\\':
        fmt::format_to(std::back_inserter(out), "\\\\");
        break;
      case '\n':
        fmt::format_to(std::back_inserter(out), "\\n");
        break;
      case '\r':
        fmt::format_to(std::back_inserter(out), "\\r");
        break;
      case '\t':
        fmt::format_to(std::back_inserter(out), "\\t");
        break;
      case '\b':
        fmt::format_to(std::back_inserter(out), "\\b");
        break;
      case '\f':
        fmt::format_to(std::back_inserter(out), "\\f");
        break;
      default:
        if (c < 0x20) {
          fmt::format_to(std::back_inserter(out), "\\u{:04x}", static_cast<unsigned>(c));
        } else {
          out.push_back(ch);
        }
    }
  }
  out.push_back('"');
}

// JSON has no NaN or infinity; a failed run may well have produced them, so write null.
void append_json_number(fmt::memory_buffer& out, double value) {
  if (std::isfinite(value)) {
    fmt::format_to(std::back_inserter(out), "{:.17g}", value);
  } else {
    fmt::format_to(std::back_inserter(out), "null");
  }
}

}  // namespace

void write_run_json(const std::filesystem::path& path, const RunSummary& summary) {
  fmt::memory_buffer json;
  auto out = std::back_inserter(json);
  fmt::format_to(out, "{{\n  \"status\": ");
  append_json_string(json, summary.status);
  fmt::format_to(out, ",\n  \"message\": ");
  append_json_string(json, summary.message);
  fmt::format_to(out, ",\n  \"final_time\": ");
  append_json_number(json, summary.final_time);
  fmt::format_to(out, ",\n  \"cycles\": {},\n  \"nodes\": {},\n  \"elements\": {}", summary.cycles,
                 summary.nodes, summary.elements);
  fmt::format_to(out, ",\n  \"wall_seconds\": ");
  append_json_number(json, summary.wall_seconds);
  fmt::format_to(out, ",\n  \"ns_per_element_cycle\": ");
  append_json_number(json, summary.ns_per_element_cycle);
  fmt::format_to(out, ",\n  \"threads\": {},\n  \"ranks\": {},\n  \"warnings\": [", summary.threads,
                 summary.ranks);
  for (std::size_t i = 0; i < summary.warnings.size(); ++i) {
    fmt::format_to(out, "{}\n    ", i == 0 ? "" : ",");
    append_json_string(json, summary.warnings[i]);
  }
  fmt::format_to(out, "{}]", summary.warnings.empty() ? "" : "\n  ");
  if (summary.ignore_unsupported) {
    fmt::format_to(out,
                   ",\n  \"ignore_unsupported\": true,\n  \"ignored_unsupported_keywords\": [");
    for (std::size_t i = 0; i < summary.ignored_unsupported.size(); ++i) {
      fmt::format_to(out, "{}\n    ", i == 0 ? "" : ",");
      append_json_string(json, summary.ignored_unsupported[i]);
    }
    fmt::format_to(out, "{}]", summary.ignored_unsupported.empty() ? "" : "\n  ");
  }
  fmt::format_to(out, "\n}}\n");

  // Atomically and, in the CLI, last: a run.json that exists is complete and says how the run
  // ended (docs/output.md).
  write_file_atomically(path, std::string_view(json.data(), json.size()));
}

}  // namespace rf::output
