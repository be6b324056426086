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
    text.push_back('\n');
  }
  return fmt::to_string(text);
}

std::string spcforc_text(double time, const std::vector<solver::NodeReaction>& reactions,
                         const std::vector<model::Id>& node_ids) {
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  for (const solver::NodeReaction& r : reactions) {
    fmt::format_to(out, "{:.17g},{},{:.17g},{:.17g},{:.17g}\n", time, node_ids[r.node], r.force[0],
                   r.force[1], r.force[2]);
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
                       const std::vector<HistorySolid>& solids) {
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  for (const HistorySolid& h : solids) {
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

}  // namespace rf::output
