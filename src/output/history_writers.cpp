#include "output/history_writers.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

#include "output/d3plot_writer.hpp"

namespace rf::output {

std::string matsum_text(double time, const std::vector<solver::PartSummary>& parts) {
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  for (const solver::PartSummary& p : parts) {
    // 17 significant digits, as every CSV file: values read back bit-identical.
    fmt::format_to(out, "{:.17g},{},{:.17g},{:.17g},{:.17g}", time, p.part, p.internal_energy,
                   p.kinetic_energy, p.hourglass_energy);
    for (double v : p.momentum) fmt::format_to(out, ",{:.17g}", v);
    for (double v : p.rigid_velocity) fmt::format_to(out, ",{:.17g}", v);
    fmt::format_to(out, ",{:.17g}", p.added_mass);
    fmt::format_to(out, ",{:.17g}", p.bulk_viscosity_energy);
    text.push_back('\n');
  }
  return fmt::to_string(text);
}

std::string spcforc_text(double time, const std::vector<solver::NodeReaction>& reactions,
                         const std::vector<model::Id>& node_ids) {
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  for (const solver::NodeReaction& r : reactions) {
    fmt::format_to(out, "{:.17g},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", time,
                   node_ids[r.node], r.force[0], r.force[1], r.force[2], r.moment[0], r.moment[1],
                   r.moment[2]);
  }
  return fmt::to_string(text);
}

std::string secforc_text(double time, const std::vector<solver::SectionForce>& sections) {
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  auto norm = [](const std::array<double, 3>& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  };
  for (const solver::SectionForce& s : sections) {
    fmt::format_to(out, "{:.17g},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},", time, s.section,
                   s.force[0], s.force[1], s.force[2], norm(s.force), s.normal_force);
    fmt::format_to(out, "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", s.moment[0],
                   s.moment[1], s.moment[2], norm(s.moment), s.centroid[0], s.centroid[1],
                   s.centroid[2]);
  }
  return fmt::to_string(text);
}

std::string elout_text(double time, const solver::State& state,
                       const std::vector<HistoryElement>& solids) {
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  for (const HistoryElement& h : solids) {
    const element::HexBlock& block = state.hex_blocks[h.block];
    double s[6];
    element_mean_stress(block, h.element, s);
    fmt::format_to(out, "{:.17g},{},{}", time, block.element_id[h.element], block.part_id);
    for (double v : s) fmt::format_to(out, ",{:.17g}", v);
    fmt::format_to(out, ",{:.17g},{:.17g},{:.17g}\n", von_mises(s), pressure_of(s),
                   d3plot_effective_plastic_strain(block, h.element));
  }
  return fmt::to_string(text);
}

std::string elout_shell_text(double time, const solver::State& state,
                             const std::vector<HistoryElement>& shells) {
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  for (const HistoryElement& h : shells) {
    const element::ShellBlock& block = state.shell_blocks[h.block];
    const std::size_t nip = static_cast<std::size_t>(block.nip);
    const std::size_t points = static_cast<std::size_t>(block.points_per_element());
    const std::size_t in_plane = points / nip;
    const auto frame = shell_frame(state.nodes, &block.conn[4 * h.element]);
    const material::HistoryArray* plastic =
        element::find_history(block, "effective_plastic_strain");
    for (std::size_t k = 0; k < nip; ++k) {
      // Mean over the in-plane points at this height (one point for ELFORM 2).
      double s[6] = {0, 0, 0, 0, 0, 0};
      double strain = 0.0;
      for (std::size_t p = 0; p < in_plane; ++p) {
        const std::size_t q = h.element * points + p * nip + k;
        double g[6] = {0, 0, 0, 0, 0, 0};
        if (!block.stress.empty()) {
          shell_stress_to_global(&block.stress[q * element::kShellStress], frame, g);
        }
        for (int c = 0; c < 6; ++c) s[c] += g[c] / static_cast<double>(in_plane);
        if (plastic && plastic->field.components == 1 && q < plastic->values.size()) {
          strain += plastic->values[q] / static_cast<double>(in_plane);
        }
      }
      fmt::format_to(out, "{:.17g},{},{},{},{:.17g}", time, block.element_id[h.element],
                     block.part_id, k + 1, block.zeta[k]);
      for (double v : s) fmt::format_to(out, ",{:.17g}", v);
      fmt::format_to(out, ",{:.17g},{:.17g}\n", von_mises(s), strain);
    }
  }
  return fmt::to_string(text);
}

}  // namespace rf::output
