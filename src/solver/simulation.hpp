// The explicit transient analysis: central-difference time integration with lumped mass and
// a variable, stability-limited time step (Belytschko, Liu & Moran, Nonlinear Finite Elements,
// section 6.2). One Simulation owns the state of one run.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "contact/contact.hpp"
#include "contact/rigid_wall.hpp"
#include "model/model.hpp"
#include "model/restart_switch.hpp"
#include "output/d3plot_writer.hpp"
#include "output/history_writers.hpp"
#include "output/modal_writer.hpp"
#include "output/writers.hpp"
#include "solver/boundary.hpp"
#include "solver/build_state.hpp"
#include "solver/erosion.hpp"
#include "solver/flexible_bodies.hpp"
#include "solver/joint_stiffness.hpp"
#include "solver/joints.hpp"
#include "solver/mass_scaling.hpp"
#include "solver/nodal_constraints.hpp"
#include "solver/part_histories.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"
#include "switching/part_switching.hpp"

namespace rf::sensor {
struct SensorSystem;
class SensorCsv;
}  // namespace rf::sensor

namespace rf::parallel {
class ElementDistribution;
}  // namespace rf::parallel

namespace rf::restart {
class Dumper;
struct SimulationAccess;
}  // namespace rf::restart

namespace rf::solver {

// Energy bookkeeping. Kinetic energy and the work terms are evaluated at half steps so that
// the discrete balance of the central-difference scheme holds to round-off:
//   KE^{n+1/2} - KE^{n-1/2} = sum (f_ext^n - f_int^n + r^n) . d^n,
//   d^n = dt_avg^n (v^{n-1/2} + v^{n+1/2}) / 2,
// with r the reactions of fixed and prescribed DOFs (see docs/theory.md).
struct EnergyAccount {
  double kinetic = 0.0;
  double internal_work = 0.0;  // work of internal forces, hourglass included
  double hourglass = 0.0;      // hourglass part of internal_work
  // Bulk viscosity part of internal_work (energy the artificial viscosity has dissipated).
  double bulk_viscosity = 0.0;
  double external_work = 0.0;  // loads, body forces and reactions
  // The part of external_work done by rigid walls (their forces are in f_ext).
  double rigidwall_work = 0.0;
  // Kinetic energy of non-rigid motion removed by deformable-to-rigid switches (cumulative).
  double switch_energy = 0.0;
  // Strain energy held by elements frozen in parts that are rigid by switching (part of
  // internal_work; reported, not added again).
  double frozen_energy = 0.0;
  // Minus the work of the contact forces (penalty energy stored plus friction and damping
  // dissipation); kept out of external_work and counted in the total (docs/contact.md).
  double contact_energy = 0.0;
  // The part of external_work done by mass-proportional damping (*DAMPING_GLOBAL,
  // *DAMPING_PART_MASS); negative: the energy damping has removed.
  double damping_work = 0.0;
  double initial_total = 0.0;
  // Elastic energy 1/2 w^2 q^2 of the modes of flexible bodies now (their kinetic energy is in
  // `kinetic`, modal damping losses in internal_work).
  double modal_elastic = 0.0;
  // Element erosion (solver/erosion.hpp): the work of the deleted elements' forces (part of
  // internal_work, reported apart) and the kinetic energy of the removed nodes (no longer in
  // `kinetic`, so added to the total).
  double eroded_internal = 0.0;
  double eroded_kinetic = 0.0;
  double momentum[3] = {0, 0, 0};
  double angular_momentum[3] = {0, 0, 0};

  double internal() const {
    return internal_work - hourglass - bulk_viscosity + modal_elastic - eroded_internal;
  }
  double total() const {
    return kinetic + internal_work + modal_elastic + switch_energy + contact_energy +
           eroded_kinetic;
  }
  double ratio() const {
    const double reference = initial_total + external_work;
    return reference != 0.0 ? total() / reference : 1.0;
  }
};

// What the dynamic relaxation phase did (*CONTROL_DYNAMIC_RELAXATION); zero cycles: none ran.
struct DynamicRelaxationSummary {
  std::int64_t cycles = 0;
  double pseudo_time = 0.0;
  double kinetic_energy_ratio = 0.0;  // distortional kinetic energy / its peak at the end
  bool converged = false;
};

// Whether the deck asks for dynamic relaxation: IDRFLG 1 or -1, or IDRFLG 0 with a curve flagged
// SIDR 1 or 2 (LS-DYNA); never IDRFLG -999.
inline bool dynamic_relaxation_requested(const model::Model& model) {
  const int flag = model.dynamic_relaxation.idrflg;
  if (flag == 1 || flag == -1) return true;
  if (flag != 0) return false;
  for (const auto& [id, curve] : model.curves)
    if (curve.sidr != 0) return true;
  return false;
}

// Wall time spent in each phase of the cycle (d3hsp.txt), summed over the run. A steady_clock
// reading costs tens of nanoseconds; a cycle takes about a dozen, negligible against the work.
struct PhaseTimes {
  enum Phase {
    kSwitching,    // part switches due between cycles
    kVelocities,   // accelerations, velocity update, constraints, energy sums
    kRigidBodies,  // rigid walls and rigid/flexible bodies
    kOutput,       // CSV rows and frames
    kPositions,    // position update
    kElements,     // element kernels and force assembly
    kContact,      // contact search and forces
    kLoads,        // external loads
    kSensors,      // sensors and controls (their CSV rows included)
    kTimeStep,     // step selection
    kDumps,        // restart dumps
    kCount
  };
  static constexpr const char* kNames[kCount] = {
      "part switching", "velocity update", "rigid bodies and walls",
      "output",         "positions",       "elements",
      "contact",        "loads",           "sensors",
      "time step",      "restart dumps"};
  double seconds[kCount] = {};
};

struct SimulationOptions {
  std::filesystem::path output_directory;  // empty: no files written
  bool write_fields = true;                // VTU frames (frames.pvd) and the binary d3plot
  // Restart (restart/restart.hpp): the state is read from a dump afterwards, so the constructor
  // does not initialise it, and the CSV files are continued from the sizes they had at the dump
  // (negative: start the file anew).
  bool from_dump = false;
  output::CsvContinuation continuation;
  // Reads the mode databases of *PART_MODES (empty: modal::read_mode_database).
  ModeLoader mode_loader;
  // false: the dynamic relaxation phase a deck asks for is not run (`check` only reports it).
  bool relax = true;
};

class Simulation {
 public:
  // The simulation keeps its own copy of the model: boundary conditions refer to its curves.
  Simulation(model::Model model, SimulationOptions options);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // One explicit cycle (see the definition: the whole cycle on one screen).
  void cycle();
  bool finished() const { return finished_; }

  // Runs to termination. `on_progress` is called every cycle with this object; it decides
  // itself how often to print. Throws rf::SolverError on breakdown after writing the state.
  // A SIGINT/SIGTERM (solver/interrupt.hpp) ends the run as termination does, at the next
  // cycle boundary, with a restart dump if dumps are enabled: see interrupt_signal().
  void run(const std::function<void(const Simulation&)>& on_progress = {});
  // What the dynamic relaxation phase did before the transient (none: zero cycles).
  const DynamicRelaxationSummary& dynamic_relaxation() const { return relaxation_; }
  // The signal that ended run() early, or 0.
  int interrupt_signal() const { return interrupt_signal_; }
  // Wall time per phase so far (this process: a restarted run counts from the restart).
  const PhaseTimes& phase_times() const { return phase_times_; }

  const State& state() const { return state_; }
  // Element erosion: criteria, ledger, the last cycle's deletions (solver/erosion.hpp).
  const Erosion& erosion() const { return erosion_; }
  State& mutable_state() { return state_; }
  const EnergyAccount& energy() const { return energy_; }
  double end_time() const { return end_time_; }
  std::int64_t element_count() const { return element_count_; }
  const RigidSystem& rigid_bodies() const { return rigid_; }
  const JointSystem& joints() const { return joints_; }
  const JointStiffnessSystem& joint_stiffnesses() const { return joint_stiffnesses_; }
  const NodalConstraints& nodal_constraints() const { return nodal_constraints_; }
  const MassScaling& mass_scaling() const { return mass_scaling_; }
  const contact::RigidWallSystem& rigid_walls() const { return walls_; }
  contact::RigidWallSystem& mutable_rigid_walls() { return walls_; }
  const contact::ContactSystem& contacts() const { return contacts_; }
  contact::ContactSystem& mutable_contacts() { return contacts_; }
  // Notices found while turning the model into a state (ignored constraints, regularised
  // inertia); the reader's warnings are in the model.
  const std::vector<model::Warning>& warnings() const { return warnings_; }
  // Every part switch so far (switch.csv rows).
  const std::vector<switching::SwitchEvent>& switch_events() const { return switch_events_; }
  // User ID and part of the element that controls the step (for messages and progress).
  model::Id controlling_element() const { return controlling_element_; }
  // Sensors, switches and controls as of the last evaluation (DEF2RIG events included).
  const sensor::SensorSystem& sensors() const { return *sensors_; }
  // The element partition of a distributed run (docs/parallel.md); nullptr in one process.
  const parallel::ElementDistribution* distribution() const { return distribution_.get(); }

  // Restart dumps (restart/dumper.hpp), written by run() between cycles when due.
  void enable_restart_dumps(std::unique_ptr<restart::Dumper> dumper);
  const restart::Dumper* restart_dumper() const { return dumper_.get(); }
  // Part switching requested by a restart deck, applied to the state read from the dump.
  void apply_restart_switches(const std::vector<model::RestartSwitch>& switches);

 private:
  // The phases of a cycle, in order.
  void update_velocities();  // a^n -> v^{n+1/2}, constraints, rigid bodies, energy
  // omega^{n-1/2} -> omega^{n+1/2} of the nodes with rotations; their energy and spin sums.
  std::array<double, 7> update_rotations(double dt_avg);
  template <class Describe>
  void record_kernel_result(const element::KernelResult& r,
                            const std::vector<model::Id>& element_id, Describe&& describe);
  void gather_internal_forces(bool book_work);
  void compute_structural_forces();  // shells and beams (part of compute_internal_forces)
  void compute_discrete_forces();    // springs and dampers (part of compute_internal_forces)
  void apply_rigid_walls();          // (inside update_velocities) walls stop nodes and bodies
  void write_output_if_due(bool force);
  void update_positions();         // x^{n+1} = x^n + dt v^{n+1/2}
  void compute_internal_forces();  // element kernels at n+1, assembly, element time step
  // Deletes the elements that failed in this cycle's kernels (before their forces are gathered).
  void erode_failed_elements();
  // Smallest critical step of the deformable blocks of every family at the current geometry
  // (no TSSFAC), and the element that sets it: after a switch or a deletion, when the kernels'
  // minimum of the cycle no longer describes the model.
  std::pair<double, model::Id> critical_step_of_blocks() const;
  void compute_contact_forces();   // contact at x^{n+1} (contact/contact.hpp)
  void compute_external_forces();  // loads at t^{n+1}, plus the contact forces
  void scale_masses_if_needed();   // *CONTROL_TIMESTEP DT2MS (solver/mass_scaling.hpp)
  void select_time_step();         // dt^{n+3/2}
  void update_sensors();           // sensors, switches, controls at t^{n+1} (sensor/sensor.hpp)

  void switch_parts_if_due();  // *DEFORMABLE_TO_RIGID_AUTOMATIC, between cycles

  // Distributed runs (solver/distributed_phases.cpp, docs/parallel.md); none is called in one
  // process. Partitions the elements and refuses what stage 1 does not distribute.
  void start_distributed_run();
  // After the element kernels and the assembly: nodal forces and hourglass work summed over the
  // ranks; the element step, failures, interrupts and the output schedule agreed.
  void sum_partial_forces_across_ranks();
  // Before the output of a cycle that writes element data (or any output when `force`): the
  // element state complete on every rank, matsum's part work summed; undone by
  // finish_output_on_ranks() after the output.
  void gather_element_state_for_output(bool force);
  void finish_output_on_ranks();
  bool element_output_due() const;  // rank 0: some element output is due at state_.time
  // Around a restart dump (restart/dumper.cpp), on every rank: the state rank 0 writes made
  // complete (the owners' element state, force slots included) and the ranks' shares of matsum's
  // part work gathered (dump_rank_part_work_); afterwards each rank's force slots are its own
  // again.
  void prepare_restart_dump_on_ranks();
  void finish_restart_dump_on_ranks();

  void relax_dynamically();
  void initialize();
  // Applies one switch (both directions of a set) and repairs forces and the step.
  void apply_switch(model::Id swset, const std::vector<model::PartSwitch>& to_rigid,
                    const std::vector<model::PartSwitch>& to_deformable, double dtmax);
  void check_breakdown();
  // options_.mode_loader, else the modes.h5 reader (*PART_MODES).
  ModeLoader mode_loader() const;
  // Mass without mass scaling's added mass (body loads act on it); nullptr without scaling.
  const std::vector<double>* physical_mass() const {
    return mass_scaling_.active() ? &mass_scaling_.physical_mass : nullptr;
  }
  void write_output_now();
  output::D3plotGlobals d3plot_globals() const;  // the 6 global values of a d3plot state
  bool end_reached() const;
  // Dumps read and write every member below (restart/simulation_access.hpp).
  friend struct restart::SimulationAccess;

  const model::Model model_;
  SimulationOptions options_;
  NodeIndex node_index_;
  State state_;
  RigidSystem rigid_;
  JointSystem joints_;  // *CONSTRAINED_JOINT_... (penalty springs between node pairs)
  JointStiffnessSystem joint_stiffnesses_;  // *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED
  NodalConstraints nodal_constraints_;      // *CONSTRAINED_SPOTWELD, *CONSTRAINED_NODE_SET
  MassScaling mass_scaling_;                // *CONTROL_TIMESTEP DT2MS; inactive without it
  Erosion erosion_;  // failure criteria and deleted elements; inert without them
  std::unique_ptr<output::CsvFile> erosion_csv_;  // erosion.csv: one row per deleted element
  std::vector<model::Warning> warnings_;
  Boundary boundary_;
  contact::RigidWallSystem walls_;
  contact::ContactSystem contacts_;
  EnergyAccount energy_;
  Vec3Array v_previous_;  // v^{n-1/2}, kept for the energy balance and full-step velocities

  double end_time_ = 0.0;
  std::int64_t end_cycle_ = 0;
  double element_dt_ = 0.0;  // min critical element step (without TSSFAC) at the last evaluation
  // The springs' and dampers' share of it (mass scaling recomputes the continuum elements').
  double discrete_dt_ = std::numeric_limits<double>::infinity();
  model::Id discrete_controlling_element_ = 0;
  double initial_dt_ = 0.0;
  double dt_average_ = 0.0;  // (dt^{n-1/2} + dt^{n+1/2}) / 2
  std::int64_t element_count_ = 0;
  std::vector<double> reduction_scratch_rotations_;
  model::Id controlling_element_ = 0;
  bool finished_ = false;
  DynamicRelaxationSummary relaxation_;  // the phase before the transient, if any
  int interrupt_signal_ = 0;  // SIGINT/SIGTERM seen between cycles: the run ends as at ENDTIM
  PhaseTimes phase_times_;

  // Breakdown detected by a kernel or the velocity update (reported by check_breakdown()).
  std::string breakdown_message_;

  struct OutputSchedule {
    double interval = 0.0;
    double next = 0.0;
    bool due(double t) const { return interval > 0.0 && t >= next * (1.0 - 1e-12); }
    std::int64_t last_cycle = -1;
    void mark_written(double t, std::int64_t cycle) {
      last_cycle = cycle;
      if (interval > 0.0) {
        while (next <= t * (1.0 + 1e-12)) next += interval;
      }
    }
  };
  OutputSchedule glstat_schedule_, nodout_schedule_, d3plot_schedule_;
  std::unique_ptr<output::GlstatWriter> glstat_;
  std::unique_ptr<output::NodoutWriter> nodout_;
  std::unique_ptr<output::RbdoutWriter> rbdout_;
  OutputSchedule rbdout_schedule_;
  std::vector<output::RbdoutRow> rbdout_rows_;
  std::unique_ptr<output::ModalWriter> modal_csv_;  // flexible bodies, at the rbdout times
  std::unique_ptr<output::RwforcWriter> rwforc_;
  OutputSchedule rwforc_schedule_;
  std::vector<output::RwforcRow> rwforc_rows_;
  std::unique_ptr<output::RcforcWriter> rcforc_;
  OutputSchedule rcforc_schedule_;
  std::vector<output::RcforcRow> rcforc_rows_;
  std::unique_ptr<output::FieldWriter> fields_;
  std::unique_ptr<output::D3plotWriter> d3plot_;  // LS-DYNA binary states, at the frame times
  // *DATABASE_MATSUM, *DATABASE_SPCFORC, *DATABASE_HISTORY_SOLID (+ *DATABASE_ELOUT).
  std::unique_ptr<PartHistories> part_histories_;
  std::unique_ptr<output::CsvFile> matsum_csv_, spcforc_csv_, elout_csv_;
  OutputSchedule matsum_schedule_, spcforc_schedule_, elout_schedule_;
  void flush_csv_files();
  std::vector<output::HistoryElement> elout_solids_;
  std::unique_ptr<output::CsvFile> elout_shell_csv_;
  OutputSchedule elout_shell_schedule_;
  std::vector<output::HistoryElement> elout_shells_;
  // *DATABASE_CROSS_SECTION_PLANE (+ *DATABASE_SECFORC): secforc.csv.
  std::vector<CrossSectionCut> cross_sections_;
  std::unique_ptr<output::CsvFile> secforc_csv_;
  OutputSchedule secforc_schedule_;
  // *DATABASE_JNTFORC: jntforc.csv (only when the card is present and the model has joints).
  std::unique_ptr<output::CsvFile> jntforc_csv_;
  OutputSchedule jntforc_schedule_;
  std::vector<output::JntforcRow> jntforc_rows_;
  // Spot welds: swforc.csv (*DATABASE_SWFORC DT, or about 1000 rows per run).
  std::unique_ptr<output::CsvFile> swforc_csv_;
  OutputSchedule swforc_schedule_;
  std::vector<SectionForce> section_rows_;
  std::vector<double> reduction_scratch_;

  // Part switching (empty unless the deck has *DEFORMABLE_TO_RIGID*).
  std::unique_ptr<switching::PartSwitcher> switcher_;
  std::unique_ptr<switching::AutomaticSwitching> automatic_switching_;
  std::vector<switching::SwitchEvent> switch_events_;
  switching::SwitchQueries switch_queries_;  // wall and sensor conditions (set once)
  std::vector<int> switch_due_;              // scratch: sets due this cycle
  std::unique_ptr<output::SwitchWriter> switch_csv_;
  double switch_dt_cap_ = 0.0;  // DTMAX of the last switch set that fired (0: none)
  std::unique_ptr<sensor::SensorSystem> sensors_;
  std::unique_ptr<sensor::SensorCsv> sensor_csv_;
  std::unique_ptr<restart::Dumper> dumper_;
  // Distributed runs only (null in one process).
  std::unique_ptr<parallel::ElementDistribution> distribution_;
  std::vector<double> rank_block_work_;  // hourglass work per block, this rank's elements
  std::vector<double> rank_part_work_;   // matsum's part work of this rank during output
  bool agreed_output_due_ = false;       // rank 0 writes element output at the next pass
  int agreed_interrupt_ = 0;             // an interrupt seen by any rank
  std::int64_t gathered_cycle_ = -1;     // the cycle whose element state was gathered
  std::vector<double> dump_rank_part_work_;  // during a dump: every rank's part work, by rank
};

}  // namespace rf::solver
