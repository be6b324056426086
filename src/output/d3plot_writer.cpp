// LS-DYNA binary d3plot database (see d3plot_writer.hpp and docs/output.md#d3plot).
//
// Word numbers of the control section follow the LS-DYNA manual's "d3plot" description
// (Appendix "LS-DYNA Database Binary Output Files"); the reader that has to agree is ParaView's
// vtkLSDynaReader, which checks the version word 14 to lie in (900, 1000) to detect the word size
// and byte order, and LS-PrePost.
#include "output/d3plot_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <system_error>

#include "output/writers.hpp"

namespace rf::output {

namespace {

namespace fs = std::filesystem;

constexpr int kGlobalCount = 6;  // NGLBV: KE, IE, TE, vx, vy, vz
constexpr int kSolidValues = 7;  // NV3D: 6 stresses + effective plastic strain
constexpr int kBeamValues = 6;   // NV1D: N, Qs, Qt, Ms, Mt, T (resultants only, BEAMIP 0)
// MAXINT: shell points written per element. LS-DYNA's default of 3 writes, whatever NIP, the
// mid-surface, inner (bottom) and outer (top) points in this order (*DATABASE_EXTENT_BINARY
// MAXINT; ParaView's reader names them Stress, StressInnerSurf, StressOuterSurf).
constexpr int kShellPoints = 3;
constexpr int kShellPointValues = 7;  // 6 global stresses + effective plastic strain
// Per shell after the points (IOSHL(4) = 1000): thickness, two element-dependent variables and
// the internal energy. No resultants (IOSHL(3) = 0).
constexpr int kShellElementValues = 4;
constexpr int kShellValues = kShellPoints * kShellPointValues + kShellElementValues;  // NV2D

// One 4-byte word as the database stores it: integers as int32, reals as float32.
float int_word(std::int64_t value) {
  if (value > INT32_MAX || value < INT32_MIN) {
    throw std::runtime_error(
        fmt::format("d3plot: the value {} does not fit a 4-byte integer word", value));
  }
  return std::bit_cast<float>(static_cast<std::int32_t>(value));
}

void write_words(const fs::path& path, const char* mode, std::int64_t offset,
                 const std::vector<float>& words) {
  std::FILE* file = std::fopen(path.c_str(), mode);
  if (file == nullptr) {
    throw std::runtime_error(
        fmt::format("cannot open output file '{}' for writing", path.string()));
  }
  bool ok = std::fseek(file, static_cast<long>(offset), SEEK_SET) == 0;
  ok = ok && std::fwrite(words.data(), sizeof(float), words.size(), file) == words.size();
  ok = (std::fclose(file) == 0) && ok;
  if (!ok) throw std::runtime_error(fmt::format("cannot write to output file '{}'", path.string()));
}

// The solids as written: 8 dense node indices and the block they come from. Elements of order
// p > 1 become their p^3 sub-hexahedra between neighbouring tensor nodes; 10-node tetrahedra
// their corner tetrahedron.
template <class Visit>
void for_each_written_solid(const solver::State& state, const Visit& visit) {
  for (const element::HexBlock& block : state.hex_blocks) {
    const int p = block.order;
    const std::size_t npe = static_cast<std::size_t>(block.nodes_per_element());
    for (std::size_t e = 0; e < block.size(); ++e) {
      const std::int32_t* c = &block.conn[npe * e];
      if (block.quadratic_tetrahedra()) {
        // 10-node tetrahedra: the corner tetrahedron in LS-DYNA's degenerate form n1 n2 n3 n4 n4
        // n4 n4 n4 (the 8-node solid record; the mid-side nodes are in the node list with their
        // motion, but no 10-node connectivity record is written).
        const std::int32_t corners[8] = {c[0], c[1], c[2], c[3], c[3], c[3], c[3], c[3]};
        visit(block, e, corners);
        continue;
      }
      if (p <= 1) {
        visit(block, e, c);
        continue;
      }
      auto at = [&](int i, int j, int k) { return c[i + (p + 1) * (j + (p + 1) * k)]; };
      for (int k = 0; k < p; ++k)
        for (int j = 0; j < p; ++j)
          for (int i = 0; i < p; ++i) {
            const std::int32_t sub[8] = {
                at(i, j, k),     at(i + 1, j, k),     at(i + 1, j + 1, k),     at(i, j + 1, k),
                at(i, j, k + 1), at(i + 1, j, k + 1), at(i + 1, j + 1, k + 1), at(i, j + 1, k + 1)};
            visit(block, e, sub);
          }
    }
  }
}

}  // namespace

double d3plot_effective_plastic_strain(const element::HexBlock& block, std::size_t e) {
  // The material's history field (docs/materials.md), mean over the element's stress points as
  // in the VTU cell array; 0 for materials without plastic strain.
  const material::HistoryArray* h = element::find_history(block, "effective_plastic_strain");
  if (!h || h->field.components != 1) return 0.0;
  const std::size_t points = static_cast<std::size_t>(block.points_per_element());
  if (h->values.size() < (e + 1) * points) return 0.0;
  double sum = 0.0;
  for (std::size_t q = 0; q < points; ++q) sum += h->values[e * points + q];
  return sum / static_cast<double>(points);
}

// Beam resultants in the order of the format: N, Qs, Qt, Ms, Mt, T (the block stores
// N, Qs, Qt, T, Ms, Mt), in the beam's local axes.
void D3plotWriter::write_beam_values(const element::BeamBlock& block, std::size_t e) {
  double r[6] = {0, 0, 0, 0, 0, 0};
  if (block.resultant.size() >= 6 * (e + 1)) std::copy_n(&block.resultant[6 * e], 6, r);
  for (int k : {0, 1, 2, 4, 5, 3}) buffer_.push_back(static_cast<float>(r[k]));
}

// Shell values: the mid-surface, inner (bottom) and outer (top) points, each 6 stresses in global
// axes (turned from the co-rotational frame at the current configuration, as the VTU frames)
// and the effective plastic strain; then thickness, two element-dependent variables (0) and the
// internal energy (0: no per-element energy is kept). Per through-thickness index the value is
// the mean over the in-plane points (ELFORM 16: 4); the mid-surface value is the middle point
// for odd NIP and the mean of the two central points for even NIP, as LS-DYNA writes it.
void D3plotWriter::write_shell_values(const solver::NodalState& nodes,
                                      const element::ShellBlock& block, std::size_t e) {
  const std::size_t nip = static_cast<std::size_t>(std::max(block.nip, 1));
  const std::size_t points = static_cast<std::size_t>(block.points_per_element());
  const std::size_t planar = points / nip;
  const std::int32_t* c = &block.conn[4 * e];
  const std::array<std::array<double, 3>, 3> frame = shell_frame(nodes, c);
  const material::HistoryArray* plastic = element::find_history(block, "effective_plastic_strain");
  if (plastic && (plastic->field.components != 1 || plastic->values.size() < (e + 1) * points)) {
    plastic = nullptr;
  }
  const bool has_stress = block.stress.size() >= (e + 1) * points * element::kShellStress;
  // Mean over the in-plane points of through-thickness index i: 6 stresses + plastic strain.
  auto layer = [&](std::size_t i, double out[7]) {
    std::fill(out, out + 7, 0.0);
    for (std::size_t a = 0; a < planar; ++a) {
      const std::size_t q = a * nip + i;
      if (has_stress) {
        double g[6];
        shell_stress_to_global(&block.stress[(e * points + q) * element::kShellStress], frame, g);
        for (int k = 0; k < 6; ++k) out[k] += g[k] / static_cast<double>(planar);
      }
      if (plastic) out[6] += plastic->values[e * points + q] / static_cast<double>(planar);
    }
  };
  double mid[7], low[7], high[7];
  layer(nip / 2, mid);
  if (nip % 2 == 0) {
    double other[7];
    layer(nip / 2 - 1, other);
    for (int k = 0; k < 7; ++k) mid[k] = 0.5 * (mid[k] + other[k]);
  }
  layer(0, low);
  layer(nip - 1, high);
  for (const double* values : {mid, low, high}) {
    for (int k = 0; k < 7; ++k) buffer_.push_back(static_cast<float>(values[k]));
  }
  // The current thickness (changed by *CONTROL_SHELL ISTUPD 1/4; else the mean of T1..T4).
  buffer_.push_back(static_cast<float>(block.element_thickness[e]));
  for (int k = 0; k < 3; ++k) buffer_.push_back(0.0f);
}

std::string D3plotWriter::member_name(int k) {
  return k == 0 ? std::string("d3plot") : fmt::format("d3plot{:02d}", k);
}

D3plotWriter::D3plotWriter(fs::path directory, std::string title, std::int64_t family_bytes)
    : directory_(std::move(directory)), title_(std::move(title)), family_bytes_(family_bytes) {}

// d3plot holds the control words and the geometry only; the states follow in d3plot01,
// d3plot02, ... ParaView 5.11's reader loses its place in the geometry when the root file also
// holds states (it reads the control words as element materials and crashes).
std::pair<int, std::int64_t> D3plotWriter::position_of(std::int64_t index) const {
  return {static_cast<int>(1 + index / layout_.states_per_member),
          4 * (index % layout_.states_per_member) * layout_.state_words};
}

void D3plotWriter::write_header(const solver::State& state) {
  const solver::NodalState& nodes = state.nodes;
  const std::int64_t node_count = static_cast<std::int64_t>(nodes.size());

  // Materials: the part IDs in ascending order; a solid's material number is its position + 1.
  // Materials of all families (solids, beams, shells) share one numbering.
  std::map<model::Id, bool> rigid_of_part;
  std::map<model::Id, int> solid_parts, beam_parts, shell_parts;
  for (const element::HexBlock& block : state.hex_blocks) {
    rigid_of_part[block.part_id] = rigid_of_part[block.part_id] || block.rigid;
    solid_parts[block.part_id] = 1;
  }
  for (const element::BeamBlock& block : state.beam_blocks) {
    rigid_of_part[block.part_id] = rigid_of_part[block.part_id] || block.rigid;
    beam_parts[block.part_id] = 1;
  }
  for (const element::ShellBlock& block : state.shell_blocks) {
    rigid_of_part[block.part_id] = rigid_of_part[block.part_id] || block.rigid;
    shell_parts[block.part_id] = 1;
  }
  std::map<model::Id, std::int64_t> material_number;
  for (const auto& [pid, rigid] : rigid_of_part) {
    const auto next = static_cast<std::int64_t>(material_number.size()) + 1;
    material_number[pid] = next;
  }
  const std::int64_t materials = static_cast<std::int64_t>(material_number.size());

  std::vector<float> connectivity;
  std::vector<float> solid_ids;
  element_count_ = 0;
  for_each_written_solid(state,
                         [&](const element::HexBlock& block, std::size_t e, const std::int32_t* n) {
                           for (int k = 0; k < 8; ++k) connectivity.push_back(int_word(n[k] + 1));
                           connectivity.push_back(int_word(material_number.at(block.part_id)));
                           solid_ids.push_back(int_word(block.element_id[e]));
                           ++element_count_;
                         });
  // Beams: N1 N2, orientation node N3 (0: the beam's axes are not part of this format; the
  // orientation comes from a vector as often as from a node), two unused words, material.
  std::vector<float> beam_words, beam_ids;
  beam_count_ = 0;
  for (const element::BeamBlock& block : state.beam_blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      beam_words.push_back(int_word(block.conn[2 * e] + 1));
      beam_words.push_back(int_word(block.conn[2 * e + 1] + 1));
      for (int k = 0; k < 3; ++k) beam_words.push_back(int_word(0));
      beam_words.push_back(int_word(material_number.at(block.part_id)));
      beam_ids.push_back(int_word(block.element_id[e]));
      ++beam_count_;
    }
  }
  // Shells: N1..N4 (triangles N3 = N4, as in *ELEMENT_SHELL), material.
  std::vector<float> shell_words, shell_ids;
  shell_count_ = 0;
  for (const element::ShellBlock& block : state.shell_blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      for (int k = 0; k < 4; ++k) shell_words.push_back(int_word(block.conn[4 * e + k] + 1));
      shell_words.push_back(int_word(material_number.at(block.part_id)));
      shell_ids.push_back(int_word(block.element_id[e]));
      ++shell_count_;
    }
  }

  const std::int64_t narbs =
      16 + node_count + element_count_ + beam_count_ + shell_count_ + 3 * materials;
  std::vector<float> words(64, int_word(0));
  {
    char title[40];
    std::memset(title, ' ', sizeof title);
    std::memcpy(title, title_.data(), std::min<std::size_t>(title_.size(), sizeof title));
    std::memcpy(words.data(), title, sizeof title);
    std::memcpy(&words[13], "RFLX", 4);  // release
  }
  auto set = [&](int word, std::int64_t value) { words[word] = int_word(value); };
  set(10, 0);          // RUNTIME: 0, so that a run's files are the same byte for byte every time
  set(11, 1);          // FILETYPE: d3plot
  words[14] = 960.0f;  // VERSION
  // NDIM 4: 3-D with unpacked connectivity and no material-type section. (NDIM 5 adds a list
  // of material types that only matters for rigid shells, which have no state data; ParaView's
  // reader would list those materials once more, as empty rigid-body parts.)
  set(15, 4);
  set(16, node_count);
  set(17, 6);  // ICODE: finite-element code
  set(18, kGlobalCount);
  set(19, 0);                                              // IT: no temperatures
  set(20, 1);                                              // IU: coordinates
  set(21, 1);                                              // IV: velocities
  set(22, 1);                                              // IA: accelerations
  set(23, element_count_);                                 // NEL8
  set(24, static_cast<std::int64_t>(solid_parts.size()));  // NUMMAT8
  set(27, kSolidValues);                                   // NV3D
  set(28, beam_count_);                                    // NEL2
  set(29, static_cast<std::int64_t>(beam_parts.size()));   // NUMMAT2
  set(30, kBeamValues);                                    // NV1D
  set(31, shell_count_);                                   // NEL4
  set(32, static_cast<std::int64_t>(shell_parts.size()));  // NUMMAT4
  set(33, kShellValues);                                   // NV2D
  set(34, 0);                                              // NEIPH: no extra solid values
  set(35, 0);                                              // NEIPS: no extra shell values per point
  set(36, -(10000 + kShellPoints));  // MAXINT < -10000: one deletion flag per element
  set(39, narbs);
  set(43, 1000);       // IOSHL(1): 6 stresses per shell point
  set(44, 1000);       // IOSHL(2): effective plastic strain per shell point
  set(45, 0);          // IOSHL(3): no shell resultants
  set(46, 1000);       // IOSHL(4): thickness, 2 element variables, internal energy
  set(51, materials);  // NMMAT

  // Geometry: reference coordinates, then the solids.
  for (std::int64_t i = 0; i < node_count; ++i) {
    words.push_back(static_cast<float>(nodes.x0.x[i]));
    words.push_back(static_cast<float>(nodes.x0.y[i]));
    words.push_back(static_cast<float>(nodes.x0.z[i]));
  }
  words.insert(words.end(), connectivity.begin(), connectivity.end());
  // (No thick shells.) Beams, then shells: the manual's order of the geometry section.
  words.insert(words.end(), beam_words.begin(), beam_words.end());
  words.insert(words.end(), shell_words.begin(), shell_words.end());
  // User IDs. Pointers are word addresses in the file; NSORT < 0 says that the material lists
  // follow the element IDs.
  const std::int64_t node_ids_at = static_cast<std::int64_t>(words.size()) + 16;
  const std::int64_t solid_ids_at = node_ids_at + node_count;
  // Element IDs in the order solids (NSRH), beams (NSRB), shells (NSRS), thick shells (NSRT).
  const std::int64_t beam_ids_at = solid_ids_at + element_count_;
  const std::int64_t shell_ids_at = beam_ids_at + beam_count_;
  const std::int64_t materials_at = shell_ids_at + shell_count_;
  const std::int64_t header_ids[16] = {-node_ids_at,
                                       solid_ids_at,
                                       beam_ids_at,
                                       shell_ids_at,
                                       materials_at,
                                       node_count,
                                       element_count_,
                                       beam_count_,
                                       shell_count_,
                                       0,
                                       materials_at,
                                       materials_at + materials,
                                       materials_at + 2 * materials,
                                       materials,
                                       0,
                                       materials};
  std::int64_t rigid_materials = 0;
  for (const auto& [pid, rigid] : rigid_of_part) rigid_materials += rigid ? 1 : 0;
  for (int k = 0; k < 16; ++k) words.push_back(int_word(k == 14 ? rigid_materials : header_ids[k]));
  for (std::int64_t i = 0; i < node_count; ++i) words.push_back(int_word(nodes.id[i]));
  words.insert(words.end(), solid_ids.begin(), solid_ids.end());
  words.insert(words.end(), beam_ids.begin(), beam_ids.end());
  words.insert(words.end(), shell_ids.begin(), shell_ids.end());
  for (int list = 0; list < 3; ++list) {
    // Ordered IDs, unordered IDs (the same: we number in ascending order), and the
    // cross-reference from the unordered to the ordered list.
    for (const auto& [pid, number] : material_number) {
      words.push_back(int_word(list == 2 ? number : pid));
    }
  }

  // Part titles (NTYPE 90001 of the manual's title section), after an end-of-file marker that
  // closes the geometry: NUMPROP, then per part its user ID and 72 characters of title, in the
  // material order above. ParaView's reader names its blocks from them. The root file then ends
  // with the usual end-of-file marker (the states are in d3plot01, ...).
  words.push_back(kEndOfFile);
  words.push_back(int_word(90001));
  words.push_back(int_word(materials));
  for (const auto& [pid, number] : material_number) {
    std::string title;
    for (const solver::PartInfo& part : state.parts) {
      if (part.id == pid) title = part.title;
    }
    char text[72];
    std::memset(text, ' ', sizeof text);
    std::memcpy(text, title.data(), std::min<std::size_t>(title.size(), sizeof text));
    words.push_back(int_word(pid));
    const std::size_t at = words.size();
    words.resize(at + sizeof text / 4);
    std::memcpy(&words[at], text, sizeof text);
  }

  layout_.header_words = static_cast<std::int64_t>(words.size());
  layout_.state_words = 1 + kGlobalCount + 9 * node_count + (kSolidValues + 1) * element_count_ +
                        (kBeamValues + 1) * beam_count_ + (kShellValues + 1) * shell_count_;
  const std::int64_t family_words = family_bytes_ / 4;
  layout_.states_per_member = std::max<std::int64_t>(1, (family_words - 1) / layout_.state_words);

  if (resume_states_ >= 0 && cut_back_to(resume_states_)) {
    states_ = resume_states_;
  } else {
    // A new family: first remove members an earlier run left here (a reader would take them
    // for states of this run).
    for (int k = 0; k < 100; ++k) {
      std::error_code ec;
      fs::remove(directory_ / member_name(k), ec);
    }
    words.push_back(kEndOfFile);
    write_words(directory_ / member_name(0), "wb", 0, words);
    states_ = 0;
  }
  resume_states_ = -1;
  header_written_ = true;
}

bool D3plotWriter::cut_back_to(std::int64_t states) {
  const auto [member, offset] = position_of(states);
  std::error_code ec;
  // The member that ends before state `states`: it must hold everything up to there.
  const int last = offset > 0 ? member : member - 1;
  const std::int64_t needed = offset > 0  ? offset
                              : last == 0 ? 4 * layout_.header_words
                                          : 4 * layout_.states_per_member * layout_.state_words;
  const fs::path path = directory_ / member_name(last);
  const auto size = fs::file_size(path, ec);
  if (ec || static_cast<std::int64_t>(size) < needed) return false;
  fs::resize_file(path, static_cast<std::uintmax_t>(needed), ec);
  if (ec) return false;
  write_words(path, "r+b", needed, {kEndOfFile});
  for (int k = last + 1; k < 100; ++k) fs::remove(directory_ / member_name(k), ec);
  return true;
}

void D3plotWriter::write_state(const solver::State& state, const D3plotGlobals& globals) {
  if (!header_written_) write_header(state);
  const solver::NodalState& nodes = state.nodes;
  const std::size_t node_count = nodes.size();
  buffer_.clear();
  buffer_.reserve(static_cast<std::size_t>(layout_.state_words) + 1);
  buffer_.push_back(static_cast<float>(state.time));
  buffer_.push_back(static_cast<float>(globals.kinetic_energy));
  buffer_.push_back(static_cast<float>(globals.internal_energy));
  buffer_.push_back(static_cast<float>(globals.total_energy));
  for (double v : globals.velocity) buffer_.push_back(static_cast<float>(v));
  for (const solver::Vec3Array* field : {&nodes.x, &nodes.v, &nodes.a}) {
    for (std::size_t i = 0; i < node_count; ++i) {
      buffer_.push_back(static_cast<float>(field->x[i]));
      buffer_.push_back(static_cast<float>(field->y[i]));
      buffer_.push_back(static_cast<float>(field->z[i]));
    }
  }
  std::int64_t written = 0;
  for_each_written_solid(
      state, [&](const element::HexBlock& block, std::size_t e, const std::int32_t*) {
        double mean[6];
        element_mean_stress(block, e, mean);
        for (double s : mean) buffer_.push_back(static_cast<float>(s));
        buffer_.push_back(static_cast<float>(d3plot_effective_plastic_strain(block, e)));
        ++written;
      });
  if (written != element_count_) {
    throw std::runtime_error("d3plot: the number of solids changed during the run");
  }
  std::int64_t beams = 0, shells = 0;
  for (const element::BeamBlock& block : state.beam_blocks) {
    for (std::size_t e = 0; e < block.size(); ++e, ++beams) write_beam_values(block, e);
  }
  for (const element::ShellBlock& block : state.shell_blocks) {
    for (std::size_t e = 0; e < block.size(); ++e, ++shells) write_shell_values(nodes, block, e);
  }
  if (beams != beam_count_ || shells != shell_count_) {
    throw std::runtime_error("d3plot: the number of beams or shells changed during the run");
  }
  // Deletion flags (MDLOPT 2), 1 = active, 0 = eroded (solver/erosion.hpp), in the manual's
  // order: solids, (thick shells), shells, beams.
  for_each_written_solid(state,
                         [&](const element::HexBlock& block, std::size_t e, const std::int32_t*) {
                           buffer_.push_back(block.erosion.is_eroded(e) ? 0.0f : 1.0f);
                         });
  for (const element::ShellBlock& block : state.shell_blocks)
    for (std::size_t e = 0; e < block.size(); ++e)
      buffer_.push_back(block.erosion.is_eroded(e) ? 0.0f : 1.0f);
  for (const element::BeamBlock& block : state.beam_blocks)
    for (std::size_t e = 0; e < block.size(); ++e)
      buffer_.push_back(block.erosion.is_eroded(e) ? 0.0f : 1.0f);
  if (static_cast<std::int64_t>(buffer_.size()) != layout_.state_words) {
    throw std::logic_error("d3plot: state size differs from the layout");
  }
  buffer_.push_back(kEndOfFile);

  const auto [member, offset] = position_of(states_);
  write_words(directory_ / member_name(member), offset == 0 ? "wb" : "r+b", offset, buffer_);
  ++states_;
}

}  // namespace rf::output
