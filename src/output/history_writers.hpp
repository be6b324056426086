// matsum.csv, spcforc.csv and elout.csv (docs/output.md): per-part energies and momenta,
// reaction forces of constrained nodes, stresses of selected solid elements.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "output/writers.hpp"
#include "solver/cross_sections.hpp"
#include "solver/part_histories.hpp"

namespace rf::output {

inline constexpr std::string_view kMatsumHeader =
    "time,part,internal_energy,kinetic_energy,hourglass_energy,momentum_x,momentum_y,momentum_z,"
    "rigid_velocity_x,rigid_velocity_y,rigid_velocity_z,added_mass,bulk_viscosity_energy";
inline constexpr std::string_view kSpcforcHeader =
    "time,node,force_x,force_y,force_z,moment_x,moment_y,moment_z";
inline constexpr std::string_view kEloutHeader =
    "time,element,part,sxx,syy,szz,sxy,syz,szx,effective_stress,pressure,"
    "effective_plastic_strain";
inline constexpr std::string_view kSecforcHeader =
    "time,section,force_x,force_y,force_z,force_resultant,normal_force,moment_x,moment_y,"
    "moment_z,moment_resultant,centroid_x,centroid_y,centroid_z";

// One output time of matsum.csv: a row per part.
std::string matsum_text(double time, const std::vector<solver::PartSummary>& parts);
// One output time of spcforc.csv: a row per constrained node (user IDs from `node_ids`).
std::string spcforc_text(double time, const std::vector<solver::NodeReaction>& reactions,
                         const std::vector<model::Id>& node_ids);

// An element of *DATABASE_HISTORY_SOLID or _SHELL: its block (in State::hex_blocks or
// State::shell_blocks) and its index there.
struct HistoryElement {
  std::size_t block = 0;
  std::size_t element = 0;
};
// One output time of elout.csv: a row per history solid (mean stress over its points).
std::string elout_text(double time, const solver::State& state,
                       const std::vector<HistoryElement>& solids);

inline constexpr std::string_view kEloutShellHeader =
    "time,element,part,point,zeta,sxx,syy,szz,sxy,syz,szx,effective_stress,"
    "effective_plastic_strain";
// One output time of elout_shell.csv: a row per through-thickness point of each history shell
// (bottom to top, zeta in [-1, 1]), stresses in global axes.
std::string elout_shell_text(double time, const solver::State& state,
                             const std::vector<HistoryElement>& shells);

// One output time of secforc.csv: a row per cross section.
std::string secforc_text(double time, const std::vector<solver::SectionForce>& sections);

}  // namespace rf::output
