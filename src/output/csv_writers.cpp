// glstat.csv and nodout.csv: plain CSV through a large stdio buffer. Numbers are written with
// 17 significant digits so that a value read back with strtod is bit-identical to the one the
// solver held; conservation checks downstream can then work at round-off level.
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "output/writers.hpp"

namespace rf::output {

namespace {

// Large enough that a typical run touches the disk a handful of times per output file.
constexpr std::size_t kCsvBufferBytes = 1 << 20;

void append_number(fmt::memory_buffer& out, double value) {
  fmt::format_to(std::back_inserter(out), "{:.17g}", value);
}

}  // namespace

CsvFile::CsvFile(const std::filesystem::path& path, const std::string& header,
                 std::int64_t continue_at)
    : path_(path) {
  if (continue_at >= 0) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec || size < static_cast<std::uintmax_t>(continue_at)) {
      throw std::runtime_error(
          fmt::format("cannot continue output file '{}': it is missing or shorter than {} bytes",
                      path.string(), continue_at));
    }
    std::filesystem::resize_file(path, static_cast<std::uintmax_t>(continue_at), ec);
    if (ec) {
      throw std::runtime_error(
          fmt::format("cannot cut output file '{}': {}", path.string(), ec.message()));
    }
  }
  file_ = std::fopen(path.c_str(), continue_at >= 0 ? "ab" : "wb");
  if (file_ == nullptr) {
    throw std::runtime_error(fmt::format("cannot open output file '{}' for writing: {}",
                                         path.string(), std::strerror(errno)));
  }
  // Full buffering with a big buffer: rows are small and many.
  std::setvbuf(file_, nullptr, _IOFBF, kCsvBufferBytes);
  if (continue_at < 0) write_line(header);
}

CsvFile::CsvFile(CsvFile&& other) noexcept
    : file_(std::exchange(other.file_, nullptr)), path_(std::move(other.path_)) {}

CsvFile& CsvFile::operator=(CsvFile&& other) noexcept {
  if (this != &other) {
    close();
    file_ = std::exchange(other.file_, nullptr);
    path_ = std::move(other.path_);
  }
  return *this;
}

CsvFile::~CsvFile() {
  close();
}

void CsvFile::close() noexcept {
  if (file_ != nullptr) {
    std::fclose(file_);
    file_ = nullptr;
  }
}

void CsvFile::write_text(std::string_view text) {
  if (file_ == nullptr) {
    throw std::runtime_error("write to a CSV file that is not open");
  }
  if (!text.empty() && std::fwrite(text.data(), 1, text.size(), file_) != text.size()) {
    throw std::runtime_error(
        fmt::format("cannot write to output file '{}': {}", path_.string(), std::strerror(errno)));
  }
}

void CsvFile::write_line(const std::string& line) {
  write_text(line);
  write_text("\n");
}

void CsvFile::flush() {
  if (file_ != nullptr && std::fflush(file_) != 0) {
    throw std::runtime_error(
        fmt::format("cannot write to output file '{}': {}", path_.string(), std::strerror(errno)));
  }
}

std::int64_t CsvFile::flushed_size() {
  flush();
  return file_ != nullptr ? static_cast<std::int64_t>(std::ftell(file_)) : 0;
}

GlstatWriter::GlstatWriter(const std::filesystem::path& path, std::int64_t continue_at)
    : csv_(path, std::string(kGlstatHeader), continue_at) {}

void GlstatWriter::write(const GlstatRow& row) {
  fmt::memory_buffer line;
  append_number(line, row.time);
  line.push_back(',');
  append_number(line, row.dt);
  fmt::format_to(std::back_inserter(line), ",{},", row.cycle);
  const double rest[] = {row.kinetic_energy,      row.internal_energy,     row.hourglass_energy,
                         row.external_work,       row.total_energy,        row.energy_ratio,
                         row.momentum[0],         row.momentum[1],         row.momentum[2],
                         row.angular_momentum[0], row.angular_momentum[1], row.angular_momentum[2],
                         row.switch_energy,       row.frozen_energy,       row.rigidwall_work,
                         row.contact_energy,      row.modal_energy};
  bool first = true;
  for (double value : rest) {
    if (!first) line.push_back(',');
    first = false;
    append_number(line, value);
  }
  line.push_back('\n');
  csv_.write_text(std::string_view(line.data(), line.size()));
}

NodoutWriter::NodoutWriter(const std::filesystem::path& path, std::vector<std::int32_t> dense_nodes,
                           std::int64_t continue_at)
    : csv_(path, std::string(kNodoutHeader), continue_at), nodes_(std::move(dense_nodes)) {}

void NodoutWriter::write(const solver::State& state) {
  write_rows(state, nullptr);
}

void NodoutWriter::write(const solver::State& state, const solver::Vec3Array& v_previous) {
  write_rows(state, &v_previous);
}

void NodoutWriter::write_rows(const solver::State& state, const solver::Vec3Array* v_previous) {
  const solver::NodalState& n = state.nodes;
  fmt::memory_buffer rows;
  for (std::int32_t i : nodes_) {
    if (i < 0 || static_cast<std::size_t>(i) >= n.size()) {
      throw std::runtime_error(
          fmt::format("nodout: history node index {} outside 0..{}", i, n.size()));
    }
    append_number(rows, state.time);
    fmt::format_to(std::back_inserter(rows), ",{}", n.id[i]);
    double vx = n.v.x[i], vy = n.v.y[i], vz = n.v.z[i];
    if (v_previous) {
      vx = 0.5 * (vx + v_previous->x[i]);
      vy = 0.5 * (vy + v_previous->y[i]);
      vz = 0.5 * (vz + v_previous->z[i]);
    }
    const double values[] = {n.x.x[i], n.x.y[i], n.x.z[i], vx,      vy,
                             vz,       n.a.x[i], n.a.y[i], n.a.z[i]};
    for (double value : values) {
      rows.push_back(',');
      append_number(rows, value);
    }
    rows.push_back('\n');
  }
  csv_.write_text(std::string_view(rows.data(), rows.size()));
}

SwitchWriter::SwitchWriter(const std::filesystem::path& path, std::int64_t continue_at)
    : csv_(path, std::string(kSwitchHeader), continue_at) {}

void SwitchWriter::write(const SwitchRow& row) {
  fmt::memory_buffer line;
  append_number(line, row.time);
  fmt::format_to(std::back_inserter(line), ",{},{},", row.swset,
                 row.to_rigid ? "to_rigid" : "to_deformable");
  for (std::size_t k = 0; k < row.parts.size(); ++k) {
    fmt::format_to(std::back_inserter(line), "{}{}", k ? " " : "", row.parts[k]);
  }
  for (const double value : {row.kinetic_energy_before, row.kinetic_energy_after, row.momentum[0],
                             row.momentum[1], row.momentum[2]}) {
    line.push_back(',');
    append_number(line, value);
  }
  line.push_back('\n');
  csv_.write_text(std::string_view(line.data(), line.size()));
}

RbdoutWriter::RbdoutWriter(const std::filesystem::path& path, std::int64_t continue_at)
    : csv_(path, std::string(kRbdoutHeader), continue_at) {}

void RbdoutWriter::write(const std::vector<RbdoutRow>& rows) {
  fmt::memory_buffer text;
  for (const RbdoutRow& row : rows) {
    append_number(text, row.time);
    fmt::format_to(std::back_inserter(text), ",{},", row.body);
    append_number(text, row.mass);
    for (const auto* group : {&row.x, &row.v, &row.a, &row.w}) {
      for (double value : *group) {
        text.push_back(',');
        append_number(text, value);
      }
    }
    for (double value : row.r) {
      text.push_back(',');
      append_number(text, value);
    }
    text.push_back('\n');
  }
  csv_.write_text(std::string_view(text.data(), text.size()));
}

}  // namespace rf::output
