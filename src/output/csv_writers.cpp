// glstat.csv and nodout.csv: plain CSV through a large buffer of whole rows. Numbers are written
// with 17 significant digits so that a value read back with strtod is bit-identical to the one
// the solver held; conservation checks downstream can then work at round-off level.
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "output/writers.hpp"
#include "solver/interrupt.hpp"

namespace rf::output {

namespace {

// Rows go to the file once this much is pending: the block size glibc's stdio used here before
// (setvbuf with a null buffer ignores the size asked for), so files fill as a run goes on and
// can be followed (tail -f, tests reading while the simulation lives), at one write per 4 KiB.
constexpr std::size_t kCsvBufferBytes = 1 << 12;

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
  // Our own buffer instead of stdio's: stdio writes whenever its buffer is full, in the middle of
  // a row, and a process killed then leaves a cut row. Ours holds whole rows only and goes to
  // the file in one write (flush_pending), which a second Ctrl-C lets finish.
  std::setvbuf(file_, nullptr, _IONBF, 0);
  pending_.reserve(2 * kCsvBufferBytes);
  if (continue_at < 0) write_line(header);
}

CsvFile::CsvFile(CsvFile&& other) noexcept
    : file_(std::exchange(other.file_, nullptr)),
      path_(std::move(other.path_)),
      pending_(std::move(other.pending_)) {}

CsvFile& CsvFile::operator=(CsvFile&& other) noexcept {
  if (this != &other) {
    close();
    file_ = std::exchange(other.file_, nullptr);
    path_ = std::move(other.path_);
    pending_ = std::move(other.pending_);
  }
  return *this;
}

CsvFile::~CsvFile() {
  close();
}

void CsvFile::close() noexcept {
  if (file_ != nullptr) {
    try {
      flush_pending();
    } catch (...) {  // a destructor cannot report it; flush() before closing does
    }
    std::fclose(file_);
    file_ = nullptr;
  }
}

void CsvFile::write_text(std::string_view text) {
  if (file_ == nullptr) {
    throw std::runtime_error("write to a CSV file that is not open");
  }
  pending_.append(text);
  if (pending_.size() >= kCsvBufferBytes) flush_pending();
}

void CsvFile::write_line(const std::string& line) {
  pending_.append(line);
  pending_.push_back('\n');
  if (pending_.size() >= kCsvBufferBytes) flush_pending();
}

// The pending rows in one write (a loop only if the kernel takes less), inside a WholeWrite so
// that a second Ctrl-C cannot end the process in the middle of them.
void CsvFile::flush_pending() {
  if (file_ == nullptr || pending_.empty()) return;
  const solver::interrupt::WholeWrite whole;
  const int fd = fileno(file_);
  std::size_t done = 0;
  while (done < pending_.size()) {
    const ssize_t n = ::write(fd, pending_.data() + done, pending_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      throw std::runtime_error(fmt::format("cannot write to output file '{}': {}", path_.string(),
                                           n < 0 ? std::strerror(errno) : "nothing was written"));
    }
    done += static_cast<std::size_t>(n);
  }
  pending_.clear();
}

void CsvFile::flush() {
  flush_pending();
}

std::int64_t CsvFile::flushed_size() {
  flush();
  return file_ != nullptr ? static_cast<std::int64_t>(::lseek(fileno(file_), 0, SEEK_END)) : 0;
}

GlstatWriter::GlstatWriter(const std::filesystem::path& path, std::int64_t continue_at)
    : csv_(path, std::string(kGlstatHeader), continue_at) {}

void GlstatWriter::write(const GlstatRow& row) {
  fmt::memory_buffer line;
  append_number(line, row.time);
  line.push_back(',');
  append_number(line, row.dt);
  fmt::format_to(std::back_inserter(line), ",{},", row.cycle);
  const double rest[] = {row.kinetic_energy,
                         row.internal_energy,
                         row.hourglass_energy,
                         row.external_work,
                         row.total_energy,
                         row.energy_ratio,
                         row.momentum[0],
                         row.momentum[1],
                         row.momentum[2],
                         row.angular_momentum[0],
                         row.angular_momentum[1],
                         row.angular_momentum[2],
                         row.switch_energy,
                         row.frozen_energy,
                         row.rigidwall_work,
                         row.contact_energy,
                         row.modal_energy,
                         row.damping_work,
                         row.added_mass,
                         row.mass_scaling_work,
                         row.bulk_viscosity_energy,
                         row.spring_energy,
                         row.damper_energy,
                         row.eroded_internal_energy,
                         row.eroded_kinetic_energy,
                         row.eroded_elements};
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
