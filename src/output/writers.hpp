// Result files. Names and columns are an interface (docs/output.md): change them only
// by adding columns at the end.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/state.hpp"

namespace rf::output {

// One row of glstat.csv.
struct GlstatRow {
  double time = 0.0;
  double dt = 0.0;
  std::int64_t cycle = 0;
  double kinetic_energy = 0.0;
  double internal_energy = 0.0;   // elastic strain energy (excludes hourglass)
  double hourglass_energy = 0.0;
  double external_work = 0.0;     // loads + prescribed motion + SPC reactions
  double total_energy = 0.0;      // kinetic + internal + hourglass
  double energy_ratio = 1.0;      // total / (initial total + external work)
  double momentum[3] = {0, 0, 0};
  double angular_momentum[3] = {0, 0, 0};  // about the global origin
};

// Plain CSV file with a fixed header; rows are flushed at close. Numbers use %.9g or
// better so that histories can be differentiated downstream.
class CsvFile {
 public:
  CsvFile() = default;
  CsvFile(const std::filesystem::path& path, const std::string& header);
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;
  CsvFile(CsvFile&& other) noexcept;
  CsvFile& operator=(CsvFile&& other) noexcept;
  ~CsvFile();
  void write_line(const std::string& line);
  void flush();
  bool is_open() const { return file_ != nullptr; }

 private:
  std::FILE* file_ = nullptr;
};

class GlstatWriter {
 public:
  explicit GlstatWriter(const std::filesystem::path& path);
  void write(const GlstatRow& row);
  void flush() { csv_.flush(); }

 private:
  CsvFile csv_;
};

// nodout.csv: time,node,x,y,z,vx,vy,vz,ax,ay,az for every history node at each output time.
class NodoutWriter {
 public:
  NodoutWriter(const std::filesystem::path& path, std::vector<std::int32_t> dense_nodes);
  void write(const solver::State& state);
  void flush() { csv_.flush(); }

 private:
  CsvFile csv_;
  std::vector<std::int32_t> nodes_;
};

// d3plot.pvd + d3plot_NNNN.vtu (VTK XML UnstructuredGrid, ASCII or appended raw binary) per frame:
// point data displacement, velocity; cell data stress (6 components, Voigt xx,yy,zz,xy,yz,zx),
// effective_stress (von Mises), part_id, element_id.
class FieldWriter {
 public:
  explicit FieldWriter(const std::filesystem::path& directory, std::string stem = "d3plot");
  void write_frame(const solver::State& state);
  // Writes/refreshes the .pvd collection; called after every frame so a crashed run is readable.
  void write_collection() const;
  int frames() const { return static_cast<int>(times_.size()); }

 private:
  std::filesystem::path directory_;
  std::string stem_;
  std::vector<double> times_;
  std::vector<std::string> files_;
};

struct RunSummary {
  std::string status;   // "normal termination" or "error termination"
  std::string message;  // reason when not normal
  double final_time = 0.0;
  std::int64_t cycles = 0;
  std::int64_t nodes = 0;
  std::int64_t elements = 0;
  double wall_seconds = 0.0;
  double ns_per_element_cycle = 0.0;
  int threads = 1;
  std::vector<std::string> warnings;
};

void write_run_json(const std::filesystem::path& path, const RunSummary& summary);

}  // namespace rf::output
