// Restart dumps in HDF5: one function pair per subsystem, so that a field added to a subsystem
// is added to its writer and reader and nowhere else. Layout of a dump (docs/restart.md):
//
//   /            attributes format, dump_version, rigidflex_version, time, cycle, threads
//   /model       the deck texts, dialect and --set overrides (write_model_input)
//   /nodes       nodal arrays (write_nodes)
//   /blocks/NNNN per-element state of each HexBlock (write_hex_blocks)
//   /discrete    energies and forces of the discrete blocks (only when the model has any)
//   /shells/NNNN per-element state of each ShellBlock (element::visit_shell_state; with shells)
//   /beams/NNNN  per-element state of each BeamBlock (element::visit_beam_state; with beams)
//   /rotations   the nodal rotational state (solver::visit_rotational_state; with shells/beams)
//   /rigid       the rigid system, wholesale: bodies, body_of_node, motions, loads
//   /boundary    resolved constraints and loads, wholesale (write_boundary)
//   /simulation  Simulation's own members (SimulationAccess::write_members)
//   /output      CSV sizes, VTU frames, output schedules (SimulationAccess::write_output)
//   /dumps       the dump schedule (write_dump_schedule)
//   /features    part switching, rigid walls, sensors (SimulationAccess::write_features)
//
// Time functions (load curves, *FUNCTION) are stored by ID and found again in the model that
// the restart rebuilds from the dump's deck text.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "element/hex_block.hpp"
#include "io/restart/hdf5_file.hpp"
#include "restart/dumper.hpp"
#include "restart/model_input.hpp"
#include "solver/boundary.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"

namespace rf::restart {
// Rigid bodies, wholesale (also the nodal rigid bodies part switching deleted).
void write_bodies(const io::h5::Group& g, const std::vector<solver::RigidBody>& bodies);
std::vector<solver::RigidBody> read_bodies(const io::h5::Group& g, std::size_t node_count);
}  // namespace rf::restart

namespace rf::solver {
class Simulation;
}

namespace rf::restart {

// Increment when the layout changes in a way an older reader cannot follow (a renamed or
// re-typed object, a changed meaning). A dump of another version is refused with a message.
inline constexpr std::int64_t kDumpVersion = 1;
inline constexpr const char* kDumpFormat = "RigidFlex restart dump";

void write_model_input(const io::h5::Group& g, const ModelInput& input);
ModelInput read_model_input(const io::h5::Group& g);

void write_nodes(const io::h5::Group& g, const solver::NodalState& nodes,
                 const solver::Vec3Array& v_previous);
void read_nodes(const io::h5::Group& g, solver::NodalState& nodes, solver::Vec3Array& v_previous);

void write_hex_blocks(const io::h5::Group& g, const std::vector<element::HexBlock>& blocks);
void read_hex_blocks(const io::h5::Group& g, std::vector<element::HexBlock>& blocks);

// Discrete elements (springs, dampers): the work sums (spring and damper energy), the last axial
// forces and force slots (the next step's work uses them), per block.
void write_discrete_blocks(const io::h5::Group& g,
                           const std::vector<element::DiscreteBlock>& blocks);
void read_discrete_blocks(const io::h5::Group& g, std::vector<element::DiscreteBlock>& blocks);

// Shells and beams: per block its identity (part, ELFORM, rigid flag, element IDs, checked
// against the rebuilt model on reading) and the arrays the family's visitor names
// (element::visit_shell_state, element::visit_beam_state), material history included.
void write_shell_blocks(const io::h5::Group& g, const std::vector<element::ShellBlock>& blocks);
void read_shell_blocks(const io::h5::Group& g, std::vector<element::ShellBlock>& blocks);
void write_beam_blocks(const io::h5::Group& g, const std::vector<element::BeamBlock>& blocks);
void read_beam_blocks(const io::h5::Group& g, std::vector<element::BeamBlock>& blocks);

// Angular velocities, moments and rotational inertias of the nodes with rotations
// (solver::visit_rotational_state); the rotational node list is checked against the rebuilt one.
void write_rotations(const io::h5::Group& g, const solver::RotationalState& rotations);
void read_rotations(const io::h5::Group& g, solver::RotationalState& rotations);

// `model` resolves time functions to IDs (write) and back (read). Read replaces the whole
// system (bodies may have been created or removed during the run); node_count checks indices.
void write_rigid_system(const io::h5::Group& g, const solver::RigidSystem& rigid,
                        const model::Model& model);
void read_rigid_system(const io::h5::Group& g, solver::RigidSystem& rigid,
                       const model::Model& model, std::size_t node_count);

void write_boundary(const io::h5::Group& g, const solver::Boundary& boundary,
                    const model::Model& model);
void read_boundary(const io::h5::Group& g, solver::Boundary& boundary, const model::Model& model);

void write_dump_schedule(const io::h5::Group& g, const DumpSchedule& schedule);
DumpSchedule read_dump_schedule(const io::h5::Group& g);

// The whole dump of `sim` (which must have restart dumps enabled: the model input and schedule
// come from its Dumper), written to a temporary name and renamed, so a crash while writing
// never leaves a damaged file under the dump's name. Flushes the CSV files.
void write_restart_dump(solver::Simulation& sim, const std::filesystem::path& path);

// What a dump says about itself, read without rebuilding the model. Throws rf::InputError for
// a missing, damaged or foreign file and for a dump of another version.
struct DumpHeader {
  std::int64_t version = 0;
  std::string rigidflex_version;
  double time = 0.0;
  std::int64_t cycle = 0;
  int threads = 0;
  int ranks = 1;  // MPI ranks of the dumped run (dumps without the attribute: one process)
};
DumpHeader read_dump_header(const io::h5::File& file, const std::filesystem::path& path);

}  // namespace rf::restart
