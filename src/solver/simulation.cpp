#include "solver/simulation.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "contact/wall_drawing.hpp"
#include "element/kernels.hpp"
#include "model/curve.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"
#include "parallel/communicator.hpp"
#include "parallel/distribution.hpp"
#include "restart/dumper.hpp"
#include "sensor/sensor.hpp"
#include "sensor/sensor_output.hpp"
#include "solver/interrupt.hpp"
#include "solver/step_rotation.hpp"

namespace rf::solver {

namespace {

// Sums of nodal quantities over fixed-size chunks, combined in chunk order: the result is
// the same for any number of threads (floating-point addition is not associative).
constexpr std::int64_t kReductionChunk = 2048;

template <std::size_t N, class Body>
std::array<double, N> deterministic_sum(std::int64_t n, std::vector<double>& scratch,
                                        const Body& body) {
  const std::int64_t chunks = (n + kReductionChunk - 1) / kReductionChunk;
  scratch.assign(static_cast<std::size_t>(chunks) * N, 0.0);
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < chunks; ++c) {
    std::array<double, N> acc{};
    const std::int64_t end = std::min(n, (c + 1) * kReductionChunk);
    for (std::int64_t i = c * kReductionChunk; i < end; ++i) body(i, acc);
    for (std::size_t k = 0; k < N; ++k) scratch[c * N + k] = acc[k];
  }
  std::array<double, N> total{};
  for (std::int64_t c = 0; c < chunks; ++c) {
    for (std::size_t k = 0; k < N; ++k) total[k] += scratch[c * N + k];
  }
  return total;
}

using PhaseClock = std::chrono::steady_clock;

double default_interval(double configured, double end_time, double rows) {
  return configured > 0.0 ? configured : end_time / rows;
}

}  // namespace

Simulation::Simulation(model::Model model_in, SimulationOptions options)
    : model_(std::move(model_in)),
      options_(std::move(options)),
      node_index_(model_),
      state_(build_state(model_, node_index_)),
      rigid_(build_rigid_system(model_, node_index_, state_)),
      warnings_(rigid_.warnings),
      boundary_(resolve_boundary(model_, node_index_, state_, rigid_.body_of_node, warnings_)) {
  const model::Model& model = model_;
  for (const auto& block : state_.hex_blocks) element_count_ += block.size();
  for (const auto& block : state_.shell_blocks) element_count_ += block.size();
  for (const auto& block : state_.beam_blocks) element_count_ += block.size();
  for (const auto& block : state_.discrete_blocks) element_count_ += block.size();
  check_structural_support(model_, state_);
  erosion_.setup(model_, state_);  // before the contacts: erodible solids expose inner faces
  end_time_ = model.termination.endtim;
  end_cycle_ = model.termination.endcyc;
  if (end_time_ <= 0.0 && end_cycle_ <= 0) {
    throw InputError({model.files.empty() ? std::string() : model.files.front(), 1, "", 0, ""},
                     "*CONTROL_TERMINATION is missing or ENDTIM is not positive: nothing "
                     "says when the analysis ends");
  }
  if (element_count_ == 0 && rigid_.empty()) {
    throw InputError({model.files.empty() ? std::string() : model.files.front(), 1, "", 0, ""},
                     "the model has no elements or rigid bodies to simulate");
  }
  for (std::size_t i = 0; i < state_.nodes.size(); ++i) {
    if (rigid_.is_rigid(static_cast<std::int32_t>(i))) continue;  // moved by its body
    if (state_.nodes.mass[i] <= 0.0 && !(boundary_.fixed[i] == 7)) {
      // A node without mass cannot be integrated; it is held where it is.
      boundary_.fixed[i] = 7;
      boundary_.constrained_nodes.push_back(static_cast<std::int32_t>(i));
    }
  }
  std::sort(boundary_.constrained_nodes.begin(), boundary_.constrained_nodes.end());
  boundary_.constrained_nodes.erase(
      std::unique(boundary_.constrained_nodes.begin(), boundary_.constrained_nodes.end()),
      boundary_.constrained_nodes.end());
  joints_ = build_joints(model_, node_index_, state_);
  if (!model_.joint_stiffnesses.empty() && model_.switching.flagged) {
    throw InputError(model::context_of(model_.joint_stiffnesses.front().where, "PIDA"),
                     "*CONSTRAINED_JOINT_STIFFNESS together with part switching "
                     "(*DEFORMABLE_TO_RIGID...) is not supported: a switched part would leave "
                     "the joint without its rigid body");
  }
  joint_stiffnesses_ = build_joint_stiffnesses(model_, rigid_);
  nodal_constraints_ = build_nodal_constraints(model_, node_index_, state_, rigid_);
  mass_scaling_ = setup_mass_scaling(model_, state_);
  contacts_ = contact::build_contacts(model_, node_index_, state_);
  // Contact surfaces are known before flexible bodies are attached: a flexible body reconstructs
  // its contact nodes every cycle because the search reads their positions.
  attach_flexible_bodies(model_, node_index_, state_, boundary_, contacts_.nodes, rigid_,
                         mode_loader());
  walls_ = contact::build_rigid_walls(model_, node_index_, state_, boundary_, warnings_);
  // CODE 1/3 of automatic switching ask the walls (ENTNO is the wall's deck number).
  switch_queries_.wall_force = [this](model::Id number) {
    return contact::wall_normal_force(walls_, static_cast<int>(number));
  };
  switch_queries_.wall_within_offset = [this](model::Id number, double offset,
                                              const std::vector<model::Id>& parts) {
    return contact::wall_within_offset(walls_, static_cast<int>(number), offset, parts, state_);
  };
  // CODE 2/4 of automatic switching ask the contacts (ENTNO is the contact ID).
  switch_queries_.contact_force = [this](model::Id id) {
    return contact::resultant_force(contacts_, id);
  };
  switch_queries_.contact_within_offset = [this](model::Id id, double offset,
                                                 const std::vector<model::Id>& parts) {
    return contact::within_offset(contacts_, id, offset, parts, state_);
  };

  sensors_ = std::make_unique<sensor::SensorSystem>(
      sensor::build_sensor_system(model_, node_index_, state_));

  // Output selections, resolved with or without an output directory so that `check` reports
  // their errors too. *DATABASE_HISTORY_SOLID / _SHELL (IDs, _ID, _SET): elout.csv and
  // elout_shell.csv, each element once, direct IDs first, then set members, in deck order;
  // located in `blocks`.
  const auto history_elements = [&](const auto& blocks, const std::vector<model::Id>& ids,
                                    const std::vector<model::SourceLocation>& id_where,
                                    const std::vector<model::Id>& sets,
                                    const std::vector<model::SourceLocation>& set_where,
                                    const std::map<model::Id, model::SolidSet>& set_map,
                                    const char* family, const char* keyword) {
    std::vector<std::pair<model::Id, const model::SourceLocation*>> wanted;
    std::set<model::Id> seen;
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (seen.insert(ids[k]).second) wanted.push_back({ids[k], &id_where[k]});
    }
    for (std::size_t k = 0; k < sets.size(); ++k) {
      const auto it = set_map.find(sets[k]);
      if (it == set_map.end()) {
        throw InputError(model::context_of(set_where[k], "SID"),
                         fmt::format("{}: {} set {} is not defined", keyword, family, sets[k]));
      }
      for (const model::Id id : it->second.elements) {
        if (seen.insert(id).second) wanted.push_back({id, &it->second.where});
      }
    }
    std::vector<output::HistoryElement> out;
    if (wanted.empty()) return out;
    std::map<model::Id, output::HistoryElement> where;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const auto& block_ids = blocks[b].element_id;
      for (std::size_t e = 0; e < block_ids.size(); ++e) where[block_ids[e]] = {b, e};
    }
    for (const auto& [id, card] : wanted) {
      const auto it = where.find(id);
      if (it == where.end()) {
        throw InputError(model::context_of(*card, "EID"),
                         fmt::format("{}: {} element {} does not exist", keyword, family, id));
      }
      out.push_back(it->second);
    }
    return out;
  };
  elout_solids_ = history_elements(
      state_.hex_blocks, model.output.history_solids, model.output.history_solid_where,
      model.output.history_solid_sets, model.output.history_solid_set_where, model.solid_sets,
      "solid", "*DATABASE_HISTORY_SOLID");
  elout_shells_ = history_elements(
      state_.shell_blocks, model.output.history_shells, model.output.history_shell_where,
      model.output.history_shell_sets, model.output.history_shell_set_where, model.shell_sets,
      "shell", "*DATABASE_HISTORY_SHELL");
  cross_sections_ = build_cross_sections(model, state_);

  if (!options_.output_directory.empty()) {
    std::filesystem::create_directories(options_.output_directory);
    const double span = end_time_ > 0.0 ? end_time_ : 1.0;
    glstat_schedule_.interval = default_interval(model.output.glstat_dt, span, 1000.0);
    glstat_ = std::make_unique<output::GlstatWriter>(options_.output_directory / "glstat.csv",
                                                     options_.continuation.glstat);
    if (!model.output.history_nodes.empty()) {
      std::vector<std::int32_t> dense;
      for (const auto id : model.output.history_nodes) {
        dense.push_back(node_index_.at(id, {}, "NID"));
      }
      nodout_schedule_.interval = default_interval(model.output.nodout_dt, span, 1000.0);
      nodout_ = std::make_unique<output::NodoutWriter>(
          options_.output_directory / "nodout.csv", std::move(dense), options_.continuation.nodout);
    }
    if (model.switching.flagged) {
      switch_csv_ = std::make_unique<output::SwitchWriter>(options_.output_directory / "switch.csv",
                                                           options_.continuation.switches);
    }
    if (!rigid_.empty() || model.switching.flagged) {
      // *DATABASE_RBDOUT interval, else about 1000 rows per body and run.
      rbdout_schedule_.interval = default_interval(model.output.rbdout_dt, span, 1000.0);
      rbdout_ = std::make_unique<output::RbdoutWriter>(options_.output_directory / "rbdout.csv",
                                                       options_.continuation.rbdout);
      if (!rigid_.flexible.empty() || !model.part_modes.empty()) {
        modal_csv_ = std::make_unique<output::ModalWriter>(options_.output_directory / "modal.csv",
                                                           options_.continuation.modal);
      }
    }
    if (!sensors_->empty()) {
      sensor_csv_ = std::make_unique<sensor::SensorCsv>(options_.output_directory / "sensor.csv",
                                                        glstat_schedule_.interval,
                                                        options_.continuation.sensor);
    }
    if (!walls_.empty()) {
      // *DATABASE_RWFORC interval, else about 1000 rows per wall and run.
      rwforc_schedule_.interval = default_interval(model.output.rwforc_dt, span, 1000.0);
      rwforc_ = std::make_unique<output::RwforcWriter>(options_.output_directory / "rwforc.csv",
                                                       options_.continuation.rwforc);
    }
    if (!contacts_.empty()) {
      // *DATABASE_RCFORC interval, else about 1000 rows per contact and run.
      rcforc_schedule_.interval = default_interval(model.output.rcforc_dt, span, 1000.0);
      rcforc_ = std::make_unique<output::RcforcWriter>(options_.output_directory / "rcforc.csv",
                                                       options_.continuation.rcforc);
    }
    if (model.output.matsum) {
      part_histories_ = std::make_unique<PartHistories>(state_, rigid_);
      matsum_schedule_.interval = default_interval(model.output.matsum_dt, span, 1000.0);
      matsum_csv_ = std::make_unique<output::CsvFile>(options_.output_directory / "matsum.csv",
                                                      std::string(output::kMatsumHeader),
                                                      options_.continuation.matsum);
    }
    if (model.output.spcforc) {
      spcforc_schedule_.interval = default_interval(model.output.spcforc_dt, span, 1000.0);
      spcforc_csv_ = std::make_unique<output::CsvFile>(options_.output_directory / "spcforc.csv",
                                                       std::string(output::kSpcforcHeader),
                                                       options_.continuation.spcforc);
    }
    if (!elout_solids_.empty()) {
      elout_schedule_.interval = default_interval(model.output.elout_dt, span, 1000.0);
      elout_csv_ = std::make_unique<output::CsvFile>(options_.output_directory / "elout.csv",
                                                     std::string(output::kEloutHeader),
                                                     options_.continuation.elout);
    }
    if (!elout_shells_.empty()) {
      // The same interval as elout.csv (*DATABASE_ELOUT DT), as in LS-DYNA's one elout file.
      elout_shell_schedule_.interval = default_interval(model.output.elout_dt, span, 1000.0);
      elout_shell_csv_ = std::make_unique<output::CsvFile>(
          options_.output_directory / "elout_shell.csv", std::string(output::kEloutShellHeader),
          options_.continuation.elout_shell);
    }
    if (!cross_sections_.empty()) {
      section_rows_.reserve(cross_sections_.size());
      secforc_schedule_.interval = default_interval(model.output.secforc_dt, span, 1000.0);
      secforc_csv_ = std::make_unique<output::CsvFile>(options_.output_directory / "secforc.csv",
                                                       std::string(output::kSecforcHeader),
                                                       options_.continuation.secforc);
    }
    if (model.output.jntforc && !joints_.empty()) {
      jntforc_rows_.reserve(joints_.joints.size());
      jntforc_schedule_.interval = default_interval(model.output.jntforc_dt, span, 1000.0);
      jntforc_csv_ = std::make_unique<output::CsvFile>(options_.output_directory / "jntforc.csv",
                                                       std::string(output::kJntforcHeader),
                                                       options_.continuation.jntforc);
    }
    if (erosion_.enabled()) {
      erosion_csv_ = std::make_unique<output::CsvFile>(options_.output_directory / "erosion.csv",
                                                       std::string(output::kErosionHeader),
                                                       options_.continuation.erosion);
    }
    if (!nodal_constraints_.welds.empty()) {
      swforc_schedule_.interval = default_interval(model.output.swforc_dt, span, 1000.0);
      swforc_csv_ = std::make_unique<output::CsvFile>(options_.output_directory / "swforc.csv",
                                                      std::string(output::kSwforcHeader),
                                                      options_.continuation.swforc);
    }
    if (options_.write_fields) {
      d3plot_schedule_.interval = default_interval(model.output.d3plot_dt, span, 20.0);
      fields_ = std::make_unique<output::FieldWriter>(options_.output_directory);
      d3plot_ = std::make_unique<output::D3plotWriter>(options_.output_directory, model.title);
    }
  }
  if (model.switching.flagged) {
    switcher_ = std::make_unique<switching::PartSwitcher>(model_, state_);
    switcher_->enable_flexible_bodies(mode_loader(), state_);
    automatic_switching_ =
        std::make_unique<switching::AutomaticSwitching>(model_.switching.automatic);
    switch_due_.reserve(model_.switching.automatic.size());
  }
  if (parallel::world().distributed()) start_distributed_run();
  if (!options_.from_dump) initialize();
}

Simulation::~Simulation() = default;

ModeLoader Simulation::mode_loader() const {
  if (options_.mode_loader) return options_.mode_loader;
  return [](const std::filesystem::path& file) { return modal::read_mode_database(file); };
}

void Simulation::initialize() {
  const bool relaxed = options_.relax && dynamic_relaxation_requested(model_);
  if (relaxed) relax_dynamically();
  apply_initial_velocities(model_, node_index_, state_);
  initialize_rigid_velocities(model_, node_index_, rigid_, state_);
  v_previous_ = state_.nodes.v;
  state_.time = 0.0;
  compute_internal_forces();
  compute_contact_forces();
  compute_external_forces();
  check_breakdown();
  scale_masses_if_needed();  // before the initial energy: the run starts with the scaled masses
  update_sensors();
  // Initial kinetic energy and momenta at t = 0 (v^0 plays the role of v^{-1/2}); rigid-body
  // nodes are counted through their bodies.
  const NodalState& nodes = state_.nodes;
  const std::int32_t* body_of = rigid_.empty() ? nullptr : rigid_.body_of_node.data();
  auto sums =
      deterministic_sum<7>(static_cast<std::int64_t>(nodes.size()), reduction_scratch_,
                           [&](std::int64_t i, std::array<double, 7>& acc) {
                             if (body_of && body_of[i] >= 0) return;
                             const double m = nodes.mass[i];
                             const double vx = nodes.v.x[i], vy = nodes.v.y[i], vz = nodes.v.z[i];
                             const double x = nodes.x.x[i], y = nodes.x.y[i], z = nodes.x.z[i];
                             acc[0] += 0.5 * m * (vx * vx + vy * vy + vz * vz);
                             acc[1] += m * vx;
                             acc[2] += m * vy;
                             acc[3] += m * vz;
                             acc[4] += m * (y * vz - z * vy);
                             acc[5] += m * (z * vx - x * vz);
                             acc[6] += m * (x * vy - y * vx);
                           });
  const RigidStepSums rigid_sums = rigid_body_sums(rigid_);
  sums[0] += rigid_sums.kinetic;
  for (int k = 0; k < 3; ++k) {
    sums[1 + k] += rigid_sums.momentum[k];
    sums[4 + k] += rigid_sums.angular_momentum[k];
  }
  {  // nodes with rotations: 1/2 I w.w and their spin I w (bodies count their own nodes)
    const RotationalState& rot = state_.rotations;
    for (std::size_t r = 0; r < rot.size(); ++r) {
      if (body_of && body_of[rot.node[r]] >= 0) continue;
      const double I = rot.inertia[r];
      sums[0] +=
          0.5 * I * (rot.w.x[r] * rot.w.x[r] + rot.w.y[r] * rot.w.y[r] + rot.w.z[r] * rot.w.z[r]);
      sums[4] += I * rot.w.x[r];
      sums[5] += I * rot.w.y[r];
      sums[6] += I * rot.w.z[r];
    }
  }
  energy_.kinetic = sums[0];
  energy_.modal_elastic = rigid_sums.modal_elastic;
  energy_.initial_total = sums[0] + rigid_sums.modal_elastic;
  // After dynamic relaxation the transient starts with the strain (and contact penalty) energy
  // the preload stored: part of the initial total, not work done in the transient.
  if (relaxed) energy_.initial_total += energy_.internal_work + energy_.contact_energy;
  for (int k = 0; k < 3; ++k) {
    energy_.momentum[k] = sums[1 + k];
    energy_.angular_momentum[k] = sums[4 + k];
  }
  state_.dt_prev = 0.0;
  if (switcher_ && !model_.switching.at_start.empty()) {
    apply_switch(0, model_.switching.at_start, {}, 0.0);
  }
  select_time_step();
  initial_dt_ = state_.dt;
  dt_average_ = 0.5 * state_.dt;  // first half step: v^{1/2} = v^0 + dt/2 a^0
}

// Dynamic relaxation (*CONTROL_DYNAMIC_RELAXATION; LS-DYNA keyword manual, "Dynamic
// relaxation"; Underwood, "Dynamic relaxation", in Computational Methods for Transient
// Analysis, 1983): the explicit cycle under the curves flagged SIDR 1 or 2, with every velocity
// multiplied by DRFCTR each cycle, until the distortional kinetic energy has fallen below DRTOL
// times its peak (checked every NRCYCK cycles) or the pseudo-time reaches DRTERM. The
// transient then starts at t = 0 from the relaxed geometry and stresses, at rest (initial
// velocities are applied afterwards, as LS-DYNA's PHASE 0), with the stored energy in the
// initial total. Nothing is written during the phase.
void Simulation::relax_dynamically() {
  const model::DynamicRelaxationControl& control = model_.dynamic_relaxation;
  if (!model_.part_modes.empty()) {
    throw InputError(model::context_of(control.where, "IDRFLG"),
                     "dynamic relaxation with flexible bodies (*PART_MODES) is not supported "
                     "(set IDRFLG -999, or flag no curve with SIDR 1 or 2)");
  }
  for (const auto& v : model_.initial_velocities) {
    if (v.phase == 1) {
      throw InputError(model::context_of(v.where, "PHASE"),
                       "PHASE 1 (initial velocities before dynamic relaxation) is not supported: "
                       "the transient starts at rest after the relaxation, then the initial "
                       "velocities apply (PHASE 0)");
    }
  }
  const DynamicRelaxationPhase phase;
  NodalState& nodes = state_.nodes;
  RotationalState& rot = state_.rotations;
  auto scale_velocities = [&](double f) {
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      nodes.v.x[i] *= f;
      nodes.v.y[i] *= f;
      nodes.v.z[i] *= f;
    }
    for (std::size_t r = 0; r < rot.size(); ++r) {
      rot.w.x[r] *= f;
      rot.w.y[r] *= f;
      rot.w.z[r] *= f;
    }
    for (auto& body : rigid_.bodies) {  // v_node = v_c + w x r scales with both
      body.state.velocity *= f;
      body.state.angular_momentum *= f;
      body.state.angular_velocity *= f;
    }
  };
  // Kinetic energy of the deformable nodes (and their spins) less that of their common
  // translation: what still moves relative to a rigid drift.
  auto distortional_kinetic_energy = [&]() {
    double kinetic = 0.0, mass = 0.0, p[3] = {0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (!rigid_.empty() && rigid_.body_of_node[i] >= 0) continue;
      const double m = nodes.mass[i];
      const double vx = nodes.v.x[i], vy = nodes.v.y[i], vz = nodes.v.z[i];
      kinetic += 0.5 * m * (vx * vx + vy * vy + vz * vz);
      mass += m;
      p[0] += m * vx;
      p[1] += m * vy;
      p[2] += m * vz;
    }
    for (std::size_t r = 0; r < rot.size(); ++r) {
      if (!rigid_.empty() && rigid_.body_of_node[rot.node[r]] >= 0) continue;
      kinetic += 0.5 * rot.inertia[r] *
                 (rot.w.x[r] * rot.w.x[r] + rot.w.y[r] * rot.w.y[r] + rot.w.z[r] * rot.w.z[r]);
    }
    if (mass > 0.0) kinetic -= 0.5 * (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / mass;
    return std::max(kinetic, 0.0);
  };

  scale_velocities(0.0);
  v_previous_ = nodes.v;
  state_.time = 0.0;
  state_.cycle = 0;
  state_.dt_prev = 0.0;
  compute_internal_forces();
  compute_contact_forces();
  compute_external_forces();
  check_breakdown();
  scale_masses_if_needed();
  select_time_step();
  initial_dt_ = state_.dt;
  dt_average_ = 0.5 * state_.dt;
  double peak = 0.0, last = 0.0;
  bool converged = false;
  while (true) {
    update_velocities();
    scale_velocities(control.drfctr);
    update_positions();
    compute_internal_forces();
    compute_contact_forces();
    compute_external_forces();
    check_breakdown();
    scale_masses_if_needed();
    select_time_step();
    ++state_.cycle;
    if (state_.cycle % control.nrcyck == 0) {
      last = distortional_kinetic_energy();
      peak = std::max(peak, last);
      if (peak > 0.0 && last <= control.drtol * peak) {
        converged = true;
        break;
      }
    }
    if (control.drterm > 0.0 && state_.time >= control.drterm) break;
    const bool interrupted = distribution_ ? agreed_interrupt_ != 0 : interrupt::requested() != 0;
    if (interrupted) break;
  }
  relaxation_ = {state_.cycle, state_.time, peak > 0.0 ? last / peak : 0.0, converged};
  if (!converged) {
    warnings_.push_back(
        {{},
         fmt::format("dynamic relaxation stopped at pseudo-time {:.6g} after {} cycles before "
                     "it converged (distortional kinetic energy {:.3g} of its peak, DRTOL {:.3g})"
                     "; the transient starts from that state",
                     state_.time, state_.cycle, relaxation_.kinetic_energy_ratio, control.drtol)});
  }
  // The transient starts here: at rest, t = 0, with the relaxed geometry and element state. The
  // ledger keeps the stored energy (internal work, contact penalty); the work of the loads and
  // of the relaxation damping belongs to the phase, not to the transient.
  scale_velocities(0.0);
  state_.time = 0.0;
  state_.cycle = 0;
  state_.dt = 0.0;
  state_.dt_prev = 0.0;
  initial_dt_ = 0.0;
  energy_.external_work = 0.0;
  energy_.rigidwall_work = 0.0;
  energy_.damping_work = 0.0;
  energy_.switch_energy = 0.0;
  energy_.kinetic = 0.0;
  mass_scaling_.mass_scaling_work = 0.0;
}

// One explicit cycle, from t^n (forces known) to t^{n+1} (forces known). `lap` books the time
// since the last reading to a phase (d3hsp.txt).
void Simulation::cycle() {
  auto since = PhaseClock::now();
  auto lap = [&](PhaseTimes::Phase phase) {
    const auto now = PhaseClock::now();
    phase_times_.seconds[phase] += std::chrono::duration<double>(now - since).count();
    since = now;
  };
  switch_parts_if_due();
  lap(PhaseTimes::kSwitching);
  update_velocities();
  lap(PhaseTimes::kVelocities);
  write_output_if_due(false);
  if (end_reached()) {
    write_output_if_due(true);
    lap(PhaseTimes::kOutput);
    finished_ = true;
    return;
  }
  lap(PhaseTimes::kOutput);
  update_positions();
  lap(PhaseTimes::kPositions);
  compute_internal_forces();
  lap(PhaseTimes::kElements);
  compute_contact_forces();
  lap(PhaseTimes::kContact);
  compute_external_forces();
  check_breakdown();
  lap(PhaseTimes::kLoads);
  update_sensors();
  lap(PhaseTimes::kSensors);
  scale_masses_if_needed();
  select_time_step();
  lap(PhaseTimes::kTimeStep);
  ++state_.cycle;
}

bool Simulation::end_reached() const {
  return interrupt_signal_ != 0 || (end_time_ > 0.0 && state_.time >= end_time_ * (1.0 - 1e-12)) ||
         (end_cycle_ > 0 && state_.cycle >= end_cycle_);
}

void Simulation::enable_restart_dumps(std::unique_ptr<restart::Dumper> dumper) {
  dumper_ = std::move(dumper);
}

// A restart deck's *DEFORMABLE_TO_RIGID / *RIGID_TO_DEFORMABLE, applied in deck order at the
// restart time exactly as an automatic switch would be (switch.csv rows with SWSET 0). The
// first run need not have flagged switching: the switcher is made here if it is missing.
void Simulation::apply_restart_switches(const std::vector<model::RestartSwitch>& switches) {
  if (switches.empty()) return;
  if (!switcher_) {
    switcher_ = std::make_unique<switching::PartSwitcher>(model_, state_);
    switcher_->enable_flexible_bodies(mode_loader(), state_);
  }
  if (!switch_csv_ && !options_.output_directory.empty()) {
    switch_csv_ = std::make_unique<output::SwitchWriter>(options_.output_directory / "switch.csv",
                                                         options_.continuation.switches);
  }
  for (const auto& request : switches) {
    for (const model::Id pid : request.parts) {
      // Any element family (hexahedra, shells, beams).
      const switching::PartBlock* where = switcher_->block_of_part(pid);
      if (!where) {
        throw InputError(model::context_of(request.where, "PID"),
                         fmt::format("part {} has no elements in the restarted model", pid));
      }
      // *MAT_RIGID blocks are the ones without force slots.
      const bool has_force_slots =
          switching::with_block(state_, *where, [](const auto& b) { return b.has_force_slots; });
      if (!has_force_slots &&
          request.direction == model::RestartSwitch::Direction::kRigidToDeformable) {
        throw InputError(model::context_of(request.where, "PID"),
                         fmt::format("part {} is *MAT_RIGID: parts defined rigid in the input "
                                     "are permanently rigid",
                                     pid));
      }
    }
    std::vector<model::PartSwitch> cards;
    for (const model::Id pid : request.parts) {
      model::PartSwitch card;
      card.pid = pid;
      card.lrb = request.lead_rigid_body;
      card.where = request.where;
      cards.push_back(card);
    }
    if (request.direction == model::RestartSwitch::Direction::kDeformableToRigid) {
      apply_switch(0, cards, {}, 0.0);
    } else {
      apply_switch(0, {}, cards, 0.0);
    }
  }
}

void Simulation::run(const std::function<void(const Simulation&)>& on_progress) {
  try {
    while (!finished_) {
      // Between cycles: the state is complete at t^n (forces known), so a dump taken here
      // resumes exactly (restart/dumper.hpp). An interrupt makes this the end of the run: the
      // dump, then one cycle's velocity update and the output of termination.
      if (interrupt_signal_ == 0)
        interrupt_signal_ = distribution_ ? agreed_interrupt_ : interrupt::requested();
      if (dumper_) {
        const auto start = PhaseClock::now();
        dumper_->write_if_due(*this);
        phase_times_.seconds[PhaseTimes::kDumps] +=
            std::chrono::duration<double>(PhaseClock::now() - start).count();
      }
      cycle();
      if (on_progress) on_progress(*this);
    }
  } catch (const SolverError&) {
    // Leave the state at detection readable: one more frame and glstat row.
    write_output_now();
    if (fields_) fields_->write_collection();
    flush_csv_files();
    throw;
  }
  flush_csv_files();
}

// Every CSV file whole on disk (the end of a run, or a blow-up): each writer holds complete rows
// in memory until a buffer fills.
void Simulation::flush_csv_files() {
  for (output::CsvFile* file :
       {matsum_csv_.get(), spcforc_csv_.get(), elout_csv_.get(), elout_shell_csv_.get(),
        secforc_csv_.get(), jntforc_csv_.get(), swforc_csv_.get(), erosion_csv_.get()}) {
    if (file) file->flush();
  }
  if (glstat_) glstat_->flush();
  if (nodout_) nodout_->flush();
  if (rbdout_) rbdout_->flush();
  if (modal_csv_) modal_csv_->flush();
  if (sensor_csv_) sensor_csv_->flush();
  if (rwforc_) rwforc_->flush();
  if (rcforc_) rcforc_->flush();
  if (switch_csv_) switch_csv_->flush();
}

void Simulation::switch_parts_if_due() {
  if (!automatic_switching_ || automatic_switching_->empty()) return;
  // CODE 5: the DEF2RIG control of the set changed status at the last sensor evaluation. ON
  // applies the set, OFF undoes it (docs/sensors.md, docs/switching.md).
  for (const auto& event : sensor::def2rig_events(*sensors_)) {
    for (const auto& set : model_.switching.automatic) {
      if (set.code != 5 || set.swset != event.swset) continue;
      if (event.status_on) {
        apply_switch(set.swset, set.to_rigid, set.to_deformable, set.dtmax);
      } else {  // the reverse switch: R2D parts back to rigid, D2R parts back to deformable
        apply_switch(set.swset, set.to_deformable, set.to_rigid, set.dtmax);
      }
    }
  }
  automatic_switching_->due(state_.time, switch_queries_, switch_due_);
  const auto& due = switch_due_;
  for (const int k : due) {
    const auto& set = model_.switching.automatic[k];
    apply_switch(set.swset, set.to_rigid, set.to_deformable, set.dtmax);
    // NRBF: the nodal rigid bodies besides those merged by the switch (remark 4: all of them).
    double activation = 0.0;
    if (set.nrbf == 1)
      activation = switcher_->delete_nodal_rigid_bodies(state_.time, state_, rigid_);
    if (set.nrbf == 2) {
      activation = switcher_->activate_nodal_rigid_bodies(state_.time, state_, rigid_);
    }
    // NCSF: spot welds and constrained node sets (remark 4: the delete switch acts on all).
    if (set.ncsf == 1) delete_nodal_constraints(nodal_constraints_, rigid_, state_.time);
    if (set.ncsf == 2) {
      activation += activate_nodal_constraints(nodal_constraints_, rigid_, state_, state_.time);
    }
    for (auto& notice : nodal_constraints_.notices) warnings_.push_back({{}, std::move(notice)});
    nodal_constraints_.notices.clear();
    energy_.switch_energy -= activation;
    energy_.kinetic += activation;
    // RWF: remark 4, "all corresponding constraints are deactivated regardless of their
    // relationship to a switched part": every rigid wall (2 activates them all again).
    if (set.rwf != 0) {
      for (const auto& wall : walls_.walls) {
        contact::set_wall_active(walls_, wall.number, set.rwf == 2);
      }
    }
    if (set.nrbf != 0 || set.ncsf != 0) {  // bodies deleted or made: their nodes' body forces
      set_body_force_masses(boundary_, state_.nodes, rigid_.body_of_node, physical_mass());
      compute_external_forces();
    }
    automatic_switching_->fired(k, state_.time);
  }
  if (!due.empty()) {
    for (auto& notice : switcher_->notices) warnings_.push_back({{}, std::move(notice)});
    switcher_->notices.clear();
  }
}

// Between cycles: nodes and bodies at x^n, v^{n-1/2}, forces at t^n. The switch conserves the
// momenta of what it touches; forces are repaired so that the next velocity update sees the
// new rigid bodies (no internal forces from frozen elements) and the new deformable elements
// (their restored stresses at x^n), and the step is cut if a released part needs a smaller one.
void Simulation::apply_switch(model::Id swset, const std::vector<model::PartSwitch>& to_rigid,
                              const std::vector<model::PartSwitch>& to_deformable, double dtmax) {
  // The switch reads and restores element stresses: every rank needs them all.
  if (distribution_) distribution_->gather_element_state(state_);
  std::vector<switching::SwitchEvent> events;
  if (!to_rigid.empty()) {
    events.push_back(switcher_->to_rigid(to_rigid, state_.time, state_, rigid_));
  }
  // Rigid flags of every family's blocks (hexahedra, then shells, then beams) before the release.
  std::vector<bool> was_rigid;
  for (const auto& block : state_.hex_blocks) was_rigid.push_back(block.rigid);
  for (const auto& block : state_.shell_blocks) was_rigid.push_back(block.rigid);
  for (const auto& block : state_.beam_blocks) was_rigid.push_back(block.rigid);
  const std::size_t first_shell = state_.hex_blocks.size();
  const std::size_t first_beam = first_shell + state_.shell_blocks.size();
  // Constraints on nodes that now move with a body do not act (docs/switching.md): say so.
  if (!to_rigid.empty() && !events.empty()) {
    std::int64_t held = 0;
    for (std::size_t i = 0; i < state_.nodes.size(); ++i) {
      if (rigid_.is_rigid(static_cast<std::int32_t>(i)) && boundary_.fixed[i] != 0) ++held;
    }
    if (held > 0) {
      warnings_.push_back({{},
                           fmt::format("t = {:.6g}: {} nodes with SPCs move with rigid "
                                       "bodies after switch set {}; the SPCs do not act "
                                       "on them while they are rigid",
                                       state_.time, held, swset)});
    }
  }
  if (!to_deformable.empty()) {
    events.push_back(switcher_->to_deformable(to_deformable, state_.time, state_, rigid_));
  }
  // *LOAD_BODY acts on a body at its centre, on free nodes directly: f_ext^n with the new split.
  set_body_force_masses(boundary_, state_.nodes, rigid_.body_of_node, physical_mass());
  compute_external_forces();
  // Internal forces of the elements that became deformable, at x^n with their restored
  // stresses (dt = 0: no increment), and the step they allow.
  const element::NodalView view = view_of(state_.nodes);
  const RotationalState& rot = state_.rotations;
  const element::RotationalView rotations{rot.w.x.data(), rot.w.y.data(), rot.w.z.data()};
  double released_dt = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < state_.hex_blocks.size(); ++b) {
    auto& block = state_.hex_blocks[b];
    if (!was_rigid[b] || block.rigid) continue;
    const element::KernelResult r = element::compute_block_forces(block, view, 0.0);
    released_dt = std::min(released_dt, r.min_dt);
  }
  // Shells and beams: their restored stresses and resultants at x^n (dt = 0: no increment; the
  // beam frames were turned with the body, element/switch_state.hpp).
  for (std::size_t b = 0; b < state_.shell_blocks.size(); ++b) {
    auto& block = state_.shell_blocks[b];
    if (!was_rigid[first_shell + b] || block.rigid) continue;
    const element::KernelResult r = element::compute_shell_forces(block, view, rotations, 0.0);
    released_dt = std::min(released_dt, r.min_dt);
  }
  for (std::size_t b = 0; b < state_.beam_blocks.size(); ++b) {
    auto& block = state_.beam_blocks[b];
    if (!was_rigid[first_beam + b] || block.rigid) continue;
    const element::KernelResult r = element::compute_beam_forces(block, view, rotations, 0.0);
    released_dt = std::min(released_dt, r.min_dt);
  }
  if (distribution_) released_dt = distribution_->communicator().min(released_dt);
  element_dt_ = critical_step_of_blocks().first;
  if (dtmax > 0.0 || swset != 0) switch_dt_cap_ = dtmax;
  const double tssfac = model_.timestep.tssfac > 0.0 ? model_.timestep.tssfac : 0.9;
  double cap = tssfac * released_dt;
  if (switch_dt_cap_ > 0.0) cap = std::min(cap, switch_dt_cap_);
  if (state_.dt > 0.0 && state_.dt > cap) {
    state_.dt = cap;
    dt_average_ = 0.5 * (state_.dt_prev + state_.dt);
    // The released elements' forces act from t^n on, so their first velocity kick must respect
    // their own stable step: dt_avg = (dt_prev + dt) / 2 with a long rigid-phase dt_prev would
    // over-kick them and start an instability. Their (self-equilibrated) force slots are
    // scaled to the kick of a half step no longer than the new step; every other force keeps
    // the true dt_avg, so external impulses still add up to the elapsed time, momentum is
    // unchanged and the work balance uses the same scaled forces.
    const double kick = 0.5 * (std::min(state_.dt_prev, cap) + cap) / dt_average_;
    auto scale = [&](auto& blocks, std::size_t first) {
      for (std::size_t b = 0; b < blocks.size(); ++b) {
        auto& block = blocks[b];
        if (!was_rigid[first + b] || block.rigid) continue;
        for (double& f : block.force) f *= kick;
      }
    };
    scale(state_.hex_blocks, 0);
    scale(state_.shell_blocks, first_shell);
    scale(state_.beam_blocks, first_beam);
  }
  // Every family's forces, not only the hexahedra's: shells, beams, springs and joints of the
  // parts that did not switch still act in this cycle.
  gather_internal_forces(false);
  for (auto& event : events) {
    if (event.parts.empty()) continue;
    event.swset = swset;
    energy_.switch_energy += event.kinetic_energy_before - event.kinetic_energy_after;
    // A flexible body released: its modal elastic energy became element strain energy (as far
    // as the restored stress increment holds it; the rest is switch energy).
    energy_.internal_work += event.strain_energy_restored;
    energy_.switch_energy += event.modal_elastic_released - event.strain_energy_restored;
    energy_.modal_elastic -= event.modal_elastic_released;
    energy_.kinetic -= event.kinetic_energy_before - event.kinetic_energy_after;
    if (switch_csv_) {
      output::SwitchRow row;
      row.time = event.time;
      row.swset = swset;
      row.to_rigid = event.to_rigid;
      row.parts.assign(event.parts.begin(), event.parts.end());
      row.kinetic_energy_before = event.kinetic_energy_before;
      row.kinetic_energy_after = event.kinetic_energy_after;
      for (int k = 0; k < 3; ++k) row.momentum[k] = event.momentum[k];
      switch_csv_->write(row);
    }
    switch_events_.push_back(std::move(event));
  }
  energy_.frozen_energy = switcher_->frozen_energy();
  for (auto& notice : switcher_->notices) warnings_.push_back({{}, std::move(notice)});
  switcher_->notices.clear();
}

void Simulation::update_velocities() {
  NodalState& nodes = state_.nodes;
  const std::int64_t n = static_cast<std::int64_t>(nodes.size());
  const double dt_avg = dt_average_;
  // a^n = M^-1 (f_ext - f_int) for every node with mass.
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const double m = nodes.mass[i];
    const double inv_m = m > 0.0 ? 1.0 / m : 0.0;
    nodes.a.x[i] = (nodes.f_ext.x[i] - nodes.f_int.x[i]) * inv_m;
    nodes.a.y[i] = (nodes.f_ext.y[i] - nodes.f_int.y[i]) * inv_m;
    nodes.a.z[i] = (nodes.f_ext.z[i] - nodes.f_int.z[i]) * inv_m;
  }
  constrain_accelerations(boundary_, state_.time, state_);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    v_previous_.x[i] = nodes.v.x[i];
    v_previous_.y[i] = nodes.v.y[i];
    v_previous_.z[i] = nodes.v.z[i];
    nodes.v.x[i] += dt_avg * nodes.a.x[i];
    nodes.v.y[i] += dt_avg * nodes.a.y[i];
    nodes.v.z[i] += dt_avg * nodes.a.z[i];
  }
  if (!nodal_constraints_.ties.empty()) {
    apply_node_set_ties(nodal_constraints_, rigid_, state_, state_.time);
  }
  constrain_velocities(boundary_, state_.time, state_.dt, state_);
  const auto rigid_start = PhaseClock::now();
  apply_rigid_walls();
  // Rigid bodies take the nodal forces on their nodes and set those nodes' velocities.
  const RigidStepSums rigid_sums =
      advance_rigid_bodies(rigid_, boundary_, state_.time, dt_avg, state_.dt, state_);
  {  // booked to its own phase and taken out of the velocity update's (cycle() times it whole)
    const double spent = std::chrono::duration<double>(PhaseClock::now() - rigid_start).count();
    phase_times_.seconds[PhaseTimes::kRigidBodies] += spent;
    phase_times_.seconds[PhaseTimes::kVelocities] -= spent;
  }
  const Vec3Array& vp = v_previous_;
  if (!rigid_.empty() && dt_avg > 0.0) {
    for (const auto& body : rigid_.bodies) {
      for (const std::int32_t i : body.nodes) {  // the acceleration the node actually has
        nodes.a.x[i] = (nodes.v.x[i] - vp.x[i]) / dt_avg;
        nodes.a.y[i] = (nodes.v.y[i] - vp.y[i]) / dt_avg;
        nodes.a.z[i] = (nodes.v.z[i] - vp.z[i]) / dt_avg;
      }
    }
  }

  const std::array<double, 7> rotation_sums = update_rotations(dt_avg);

  // Energy and momenta at n+1/2: d = dt_avg (v^{n-1/2} + v^{n+1/2}) / 2 per DOF. Work is
  // summed over every node (forces on rigid-body nodes do work on the bodies); kinetic energy
  // and momenta of rigid-body nodes are those of their bodies.
  const std::int32_t* body_of = rigid_.empty() ? nullptr : rigid_.body_of_node.data();
  const Vec3Array* contact_force = contacts_.empty() ? nullptr : &contacts_.force;
  const double* modal_velocity =
      rigid_.modal_work_velocity.empty() ? nullptr : rigid_.modal_work_velocity.data();
  const Vec3Array* damping_force = boundary_.damping.empty() ? nullptr : &boundary_.damping.force;
  auto sums = deterministic_sum<11>(
      n, reduction_scratch_, [&](std::int64_t i, std::array<double, 11>& acc) {
        const double m = nodes.mass[i];
        const double vx = nodes.v.x[i], vy = nodes.v.y[i], vz = nodes.v.z[i];
        double dx = 0.5 * dt_avg * (vp.x[i] + vx);
        double dy = 0.5 * dt_avg * (vp.y[i] + vy);
        double dz = 0.5 * dt_avg * (vp.z[i] + vz);
        const double x = nodes.x.x[i], y = nodes.x.y[i], z = nodes.x.z[i];
        const bool rigid_node = body_of && body_of[i] >= 0;
        if (rigid_node) {
          // The body's displacement at the node, dt_avg (v_mid + w_mid x (x^n - x_c^n)): with
          // it the work of the nodal forces equals dt_avg (F . v_mid + T . w_mid), the work the
          // body's momentum update did, so the balance closes at the body (docs/theory.md).
          const RigidBody& body = rigid_.bodies[body_of[i]];
          const Eigen::Vector3d arm(x - body.state.previous_centre.x(),
                                    y - body.state.previous_centre.y(),
                                    z - body.state.previous_centre.z());
          const Eigen::Vector3d d =
              dt_avg * (body.mid_velocity + body.mid_angular_velocity.cross(arm));
          dx = d.x();
          dy = d.y();
          dz = d.z();
          if (modal_velocity) {  // flexible body: the modes' share (docs/flexible_bodies.md)
            dx += dt_avg * modal_velocity[3 * i];
            dy += dt_avg * modal_velocity[3 * i + 1];
            dz += dt_avg * modal_velocity[3 * i + 2];
          }
        }
        acc[1] += nodes.f_int.x[i] * dx + nodes.f_int.y[i] * dy + nodes.f_int.z[i] * dz;
        acc[2] += nodes.f_ext.x[i] * dx + nodes.f_ext.y[i] * dy + nodes.f_ext.z[i] * dz;
        if (contact_force) {  // the contact share of f_ext
          acc[9] += contact_force->x[i] * dx + contact_force->y[i] * dy + contact_force->z[i] * dz;
        }
        if (damping_force) {  // the damping share of f_ext
          acc[10] += damping_force->x[i] * dx + damping_force->y[i] * dy + damping_force->z[i] * dz;
        }
        if (rigid_node) return;
        acc[0] += 0.5 * m * (vx * vx + vy * vy + vz * vz);
        acc[3] += m * vx;
        acc[4] += m * vy;
        acc[5] += m * vz;
        // x^n x v^{n+1/2} equals x^{n+1} x v^{n+1/2}: exactly conserved by the scheme when
        // the internal forces have no resultant moment.
        acc[6] += m * (y * vz - z * vy);
        acc[7] += m * (z * vx - x * vz);
        acc[8] += m * (x * vy - y * vx);
      });
  // Reactions of constrained DOFs: r = m (v+ - v-)/dt_avg - (f_ext - f_int).
  double reaction_work = 0.0;
  if (dt_avg > 0.0) {
    for (const auto i : boundary_.constrained_nodes) {
      // A node of a part switched rigid moves with its body; its SPC does not act meanwhile.
      if (body_of && body_of[i] >= 0) continue;
      const double m = nodes.mass[i];
      const double dvx = nodes.v.x[i] - vp.x[i];
      const double dvy = nodes.v.y[i] - vp.y[i];
      const double dvz = nodes.v.z[i] - vp.z[i];
      const double rx = m * dvx / dt_avg - (nodes.f_ext.x[i] - nodes.f_int.x[i]);
      const double ry = m * dvy / dt_avg - (nodes.f_ext.y[i] - nodes.f_int.y[i]);
      const double rz = m * dvz / dt_avg - (nodes.f_ext.z[i] - nodes.f_int.z[i]);
      reaction_work += 0.5 * dt_avg *
                       (rx * (vp.x[i] + nodes.v.x[i]) + ry * (vp.y[i] + nodes.v.y[i]) +
                        rz * (vp.z[i] + nodes.v.z[i]));
    }
  }
  sums[0] += rigid_sums.kinetic + rotation_sums[0];
  sums[1] += rotation_sums[1];
  sums[2] += rotation_sums[2];
  for (int k = 0; k < 3; ++k) {
    sums[3 + k] += rigid_sums.momentum[k];
    sums[6 + k] += rigid_sums.angular_momentum[k] + rotation_sums[3 + k];
  }
  energy_.kinetic = sums[0];
  // The joint stiffnesses' loads act on the bodies only: their work on them, negated, is the
  // energy the joints stored or dissipated (internal, as the penalty joints' nodal forces).
  energy_.internal_work += sums[1] + rigid_sums.modal_damping_loss -
                           rigid_sums.modal_stiffening_work - rigid_sums.joint_stiffness_work;
  if (part_histories_) part_histories_->add_step_work(state_, rigid_, vp, dt_avg);  // matsum
  if (erosion_.enabled()) {
    erosion_.add_step_work(state_, vp, dt_avg);
    // With the kinetic energy of this half step, which no longer holds the nodes removed since
    // the last one (the ledger took them when they went).
    energy_.eroded_internal = erosion_.ledger().internal_energy;
    energy_.eroded_kinetic = erosion_.ledger().kinetic_energy;
  }
  if (!state_.discrete_blocks.empty()) add_discrete_work(state_, vp, dt_avg);  // glstat columns
  energy_.external_work +=
      sums[2] - sums[9] + reaction_work + rigid_sums.external_work + rigid_sums.modal_inertia_work;
  energy_.contact_energy -= sums[9];
  energy_.damping_work += sums[10] + rigid_sums.damping_work + rotation_sums[6];
  energy_.modal_elastic = rigid_sums.modal_elastic;
  if (!walls_.empty()) {  // already in sums[2] (the wall forces are in f_ext): its share
    energy_.rigidwall_work += contact::rigid_wall_work(walls_, rigid_, vp, state_, dt_avg);
  }
  for (int k = 0; k < 3; ++k) {
    energy_.momentum[k] = sums[3 + k];
    energy_.angular_momentum[k] = sums[6 + k];
  }
  // An elastic body cannot give back more strain energy than it stored: internal work well
  // below zero means a mode is growing without bound (the step exceeds the stability limit;
  // L_e / c is exact for meshes, not for a few elements with free corners).
  // Springs and dampers are left out of this check: their step limit is the exact one of the
  // two-mass system (docs/elements.md), at which the half-step kinetic energy of an oscillating
  // mass swings far above its true energy and the spring's work far below zero without any
  // instability (the check is a heuristic for meshes).
  double discrete_work = 0.0;
  for (const auto& block : state_.discrete_blocks) {
    discrete_work += block.spring_energy + block.damper_energy;
  }
  const double scale = energy_.initial_total + std::abs(energy_.external_work) + energy_.kinetic;
  if (energy_.internal_work - discrete_work < -0.05 * scale && scale > 0.0) {
    throw SolverError(fmt::format(
        "numerical instability at time {:.6g} (cycle {}): internal energy {:.6g} is negative "
        "while kinetic energy grew to {:.6g}; the time step is above the stability limit of "
        "this mesh (smallest element step: element {}). Reduce TSSFAC on *CONTROL_TIMESTEP "
        "(free single elements or meshes of a few elements across need TSSFAC <= 0.55)",
        state_.time, state_.cycle, energy_.internal_work, energy_.kinetic, controlling_element_));
  }
  if (!std::isfinite(rigid_sums.kinetic)) {
    for (const auto& body : rigid_.bodies) {
      if (!std::isfinite(rigid::kinetic_energy(body.state))) {
        throw SolverError(
            fmt::format("non-finite motion of rigid body {} at time {:.6g} (cycle {})", body.id,
                        state_.time, state_.cycle));
      }
    }
  }
  if (!std::isfinite(sums[0])) {
    // Find the first offending node for the message (rare path).
    for (std::int64_t i = 0; i < n; ++i) {
      if (!std::isfinite(nodes.v.x[i] + nodes.v.y[i] + nodes.v.z[i])) {
        throw SolverError(fmt::format("non-finite velocity at node {} at time {:.6g} (cycle {})",
                                      nodes.id[i], state_.time, state_.cycle));
      }
    }
  }
  if (!nodal_constraints_.welds.empty()) {
    // After this step's sums: failed welds leave the rigid system, their nodes keep v^{n+1/2}.
    check_spot_welds(nodal_constraints_, rigid_, state_, vp, dt_avg, state_.time);
  }
  if (!nodal_constraints_.notices.empty()) {
    for (auto& notice : nodal_constraints_.notices) warnings_.push_back({{}, std::move(notice)});
    nodal_constraints_.notices.clear();
  }
}

// Central difference for the rotations, alpha = (m_ext - m_int) / I with an isotropic lumped
// inertia (no gyroscopic term), constrained components held at zero; nodes of rigid bodies turn
// with their body. Returns {kinetic, internal work, external work, spin x, y, z, the damping
// moments' share of the external work} of the step
// with d theta = dt_avg (omega^{n-1/2} + omega^{n+1/2}) / 2, as for the translations.
std::array<double, 7> Simulation::update_rotations(double dt_avg) {
  std::array<double, 7> out{};
  RotationalState& rot = state_.rotations;
  if (rot.empty()) return out;
  const std::int64_t count = static_cast<std::int64_t>(rot.size());
  const std::int32_t* body_of = rigid_.empty() ? nullptr : rigid_.body_of_node.data();
  const std::uint8_t* fixed = boundary_.rotation_fixed.data();
  // Flexible bodies (*PART_MODES of shells, beams): the modal angular velocity of their nodes
  // and its work velocity (solver/flexible_bodies.hpp), zero at other body nodes.
  const double* modal_w =
      rigid_.modal_rotation_velocity.empty() ? nullptr : rigid_.modal_rotation_velocity.data();
  const double* modal_work = rigid_.modal_rotation_work_velocity.empty()
                                 ? nullptr
                                 : rigid_.modal_rotation_work_velocity.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < count; ++r) {
    rot.w_previous.x[r] = rot.w.x[r];
    rot.w_previous.y[r] = rot.w.y[r];
    rot.w_previous.z[r] = rot.w.z[r];
    const std::int32_t i = rot.node[r];
    if (body_of && body_of[i] >= 0) {
      const Eigen::Vector3d& w = rigid_.bodies[body_of[i]].state.angular_velocity;
      rot.w.x[r] = w.x();
      rot.w.y[r] = w.y();
      rot.w.z[r] = w.z();
      if (modal_w) {
        rot.w.x[r] += modal_w[3 * r];
        rot.w.y[r] += modal_w[3 * r + 1];
        rot.w.z[r] += modal_w[3 * r + 2];
      }
      continue;
    }
    const double I = rot.inertia[r];
    const double inv = I > 0.0 ? dt_avg / I : 0.0;
    rot.w.x[r] += inv * (rot.m_ext.x[r] - rot.m_int.x[r]);
    rot.w.y[r] += inv * (rot.m_ext.y[r] - rot.m_int.y[r]);
    rot.w.z[r] += inv * (rot.m_ext.z[r] - rot.m_int.z[r]);
    const std::uint8_t f = fixed[r];
    if (f & 1) rot.w.x[r] = 0.0;
    if (f & 2) rot.w.y[r] = 0.0;
    if (f & 4) rot.w.z[r] = 0.0;
  }
  // Prescribed rotations (DOF 5-8 on nodes); their reaction moments' work is external work.
  const double reaction_work =
      boundary_.prescribed_directions.empty()
          ? 0.0
          : constrain_rotations(boundary_, state_.time, state_.dt, dt_avg, state_);
  const Vec3Array* damping_moment =
      boundary_.damping.empty() || boundary_.damping.moment.size() == 0 ? nullptr
                                                                        : &boundary_.damping.moment;
  out = deterministic_sum<7>(
      count, reduction_scratch_rotations_, [&](std::int64_t r, std::array<double, 7>& acc) {
        const double wx = rot.w.x[r], wy = rot.w.y[r], wz = rot.w.z[r];
        // As for translations: on a flexible body the body's turn dt_avg w_mid plus the modes'
        // R^n Psi_j s_mid (solver/step_rotation.hpp).
        const auto [dx, dy, dz] = step_rotation(rot, rigid_, body_of, modal_work, r, dt_avg);
        const std::int32_t i = rot.node[r];
        acc[1] += rot.m_int.x[r] * dx + rot.m_int.y[r] * dy + rot.m_int.z[r] * dz;
        acc[2] += rot.m_ext.x[r] * dx + rot.m_ext.y[r] * dy + rot.m_ext.z[r] * dz;
        if (damping_moment) {  // the damping share of m_ext
          acc[6] +=
              damping_moment->x[r] * dx + damping_moment->y[r] * dy + damping_moment->z[r] * dz;
        }
        if (body_of && body_of[i] >= 0) return;  // the body holds its kinetic energy and momentum
        const double I = rot.inertia[r];
        acc[0] += 0.5 * I * (wx * wx + wy * wy + wz * wz);
        acc[3] += I * wx;
        acc[4] += I * wy;
        acc[5] += I * wz;
      });
  out[2] += reaction_work;
  return out;
}

// Rigid walls act on v^{n+1/2} of deformable nodes and on the forces that drive the rigid
// bodies, so they come after the nodal constraints and before the bodies advance.
void Simulation::apply_rigid_walls() {
  contact::apply_rigid_walls(walls_, rigid_, boundary_, state_.time, dt_average_, state_.dt,
                             state_.dt_prev, state_);
}

// `force` writes every file that has not yet written this cycle (termination, breakdown).
void Simulation::write_output_if_due(bool force) {
  const double t = state_.time;
  const std::int64_t cycle = state_.cycle;
  auto wanted = [&](OutputSchedule& schedule) {
    return schedule.last_cycle != cycle && (force || schedule.due(t));
  };
  if (distribution_) gather_element_state_for_output(force);
  if (glstat_ && wanted(glstat_schedule_)) {
    output::GlstatRow row;
    row.time = t;
    row.dt = state_.dt;
    row.cycle = cycle;
    row.kinetic_energy = energy_.kinetic;
    row.internal_energy = energy_.internal();
    row.hourglass_energy = energy_.hourglass;
    row.external_work = energy_.external_work;
    row.total_energy = energy_.total();
    row.energy_ratio = energy_.ratio();
    for (int k = 0; k < 3; ++k) {
      row.momentum[k] = energy_.momentum[k];
      row.angular_momentum[k] = energy_.angular_momentum[k];
    }
    row.rigidwall_work = energy_.rigidwall_work;
    row.switch_energy = energy_.switch_energy;
    row.frozen_energy = energy_.frozen_energy;
    row.contact_energy = energy_.contact_energy;
    row.modal_energy = energy_.modal_elastic;
    row.damping_work = energy_.damping_work;
    row.added_mass = mass_scaling_.added_mass;
    row.mass_scaling_work = mass_scaling_.mass_scaling_work;
    row.bulk_viscosity_energy = energy_.bulk_viscosity;
    row.eroded_internal_energy = energy_.eroded_internal;
    row.eroded_kinetic_energy = energy_.eroded_kinetic;
    row.eroded_elements = static_cast<double>(erosion_.ledger().elements);
    for (const auto& block : state_.discrete_blocks) {
      row.spring_energy += block.spring_energy;
      row.damper_energy += block.damper_energy;
    }
    glstat_->write(row);
    glstat_schedule_.mark_written(t, cycle);
  }
  // Flexible bodies: nodes not reconstructed every cycle get their place before nodal output.
  if (!rigid_.flexible.empty() &&
      ((nodout_ && wanted(nodout_schedule_)) || (fields_ && wanted(d3plot_schedule_)))) {
    reconstruct_passive_nodes(rigid_, state_);
  }
  if (nodout_ && wanted(nodout_schedule_)) {
    nodout_->write(state_, v_previous_);
    nodout_schedule_.mark_written(t, cycle);
  }
  if (rbdout_ && wanted(rbdout_schedule_)) {
    rbdout_rows_.clear();
    const double dt_avg = dt_average_;
    for (const auto& body : rigid_.bodies) {
      if (body.weld) continue;  // a spot weld's state is in swforc.csv
      const rigid::RigidBodyState& s = body.state;
      output::RbdoutRow row;
      row.time = t;
      row.body = body.id;
      row.mass = s.mass;
      const Eigen::Matrix3d r = output_rotation(body);
      for (int k = 0; k < 3; ++k) {
        row.x[k] = s.previous_centre[k];
        row.v[k] = 0.5 * (body.velocity_before[k] + s.velocity[k]);
        row.a[k] = dt_avg > 0.0 ? (s.velocity[k] - body.velocity_before[k]) / dt_avg : 0.0;
        row.w[k] = 0.5 * (body.angular_velocity_before[k] + s.angular_velocity[k]);
        for (int c = 0; c < 3; ++c) row.r[3 * k + c] = r(k, c);
      }
      rbdout_rows_.push_back(row);
    }
    rbdout_->write(rbdout_rows_);
    if (modal_csv_) modal_csv_->write(t, rigid_);
    rbdout_schedule_.mark_written(t, cycle);
  }
  if (rwforc_ && wanted(rwforc_schedule_)) {
    rwforc_rows_.clear();
    for (const auto& wall : walls_.walls) {
      output::RwforcRow row;
      row.time = t;
      row.wall = wall.id;
      row.normal_force = wall.normal_force;
      for (int k = 0; k < 3; ++k) row.force[k] = wall.force[k];
      for (int k = 0; k < 3; ++k) row.segment_force[k] = wall.segment_force[k];
      row.displacement = wall.displacement;
      row.velocity = 0.5 * (wall.velocity_before + wall.velocity);
      row.normal_impulse = wall.normal_impulse;
      row.work = wall.work;
      rwforc_rows_.push_back(row);
    }
    rwforc_->write(rwforc_rows_);
    rwforc_schedule_.mark_written(t, cycle);
  }
  if (rcforc_ && wanted(rcforc_schedule_)) {
    rcforc_rows_.clear();
    for (const auto& contact : contacts_.interfaces) {
      output::RcforcRow row;
      row.time = t;
      row.contact = contact.id;
      for (int k = 0; k < 3; ++k) row.slave_force[k] = contact.slave_force[k];
      row.active_nodes = contact.active_nodes;
      rcforc_rows_.push_back(row);
    }
    rcforc_->write(rcforc_rows_);
    rcforc_schedule_.mark_written(t, cycle);
  }
  if (matsum_csv_ && wanted(matsum_schedule_)) {
    auto parts = part_histories_->summaries(state_, rigid_);
    if (mass_scaling_.active()) {
      for (auto& p : parts) p.added_mass = added_mass_of_part(mass_scaling_, state_, p.part);
    }
    matsum_csv_->write_text(output::matsum_text(t, parts));
    matsum_schedule_.mark_written(t, cycle);
  }
  if (spcforc_csv_ && wanted(spcforc_schedule_)) {
    spcforc_csv_->write_text(output::spcforc_text(
        t, constraint_reactions(state_, boundary_, rigid_, v_previous_, dt_average_),
        state_.nodes.id));
    spcforc_schedule_.mark_written(t, cycle);
  }
  if (elout_csv_ && wanted(elout_schedule_)) {
    elout_csv_->write_text(output::elout_text(t, state_, elout_solids_));
    elout_schedule_.mark_written(t, cycle);
  }
  if (elout_shell_csv_ && wanted(elout_shell_schedule_)) {
    elout_shell_csv_->write_text(output::elout_shell_text(t, state_, elout_shells_));
    elout_shell_schedule_.mark_written(t, cycle);
  }
  if (secforc_csv_ && wanted(secforc_schedule_)) {
    if (!distribution_) {  // distributed: summed over the ranks by the gather above
      section_rows_.clear();
      for (const CrossSectionCut& cut : cross_sections_)
        section_rows_.push_back(cut.evaluate(state_));
    }
    secforc_csv_->write_text(output::secforc_text(t, section_rows_));
    secforc_schedule_.mark_written(t, cycle);
  }
  if (jntforc_csv_ && wanted(jntforc_schedule_)) {
    jntforc_rows_.clear();
    for (const SolverJoint& joint : joints_.joints) {
      output::JntforcRow row;
      row.time = t;
      row.joint = joint.id;
      // joint.force and joint.moment act on body A; body B gets the opposite (about N1, which
      // coincides with N2 up to the penalty gap).
      for (int k = 0; k < 3; ++k) {
        row.force[k] = joint.force[k] == 0.0 ? 0.0 : -joint.force[k];
        row.moment[k] = joint.moment[k] == 0.0 ? 0.0 : -joint.moment[k];
      }
      for (const SolverJointStiffness& stiffness : joint_stiffnesses_.joints) {
        if (stiffness.jid != joint.id) continue;
        row.stiffness = stiffness.id;
        row.angle = stiffness.angle;
        row.stiffness_moment = stiffness.moment;
        row.elastic_energy = stiffness.elastic;
        row.dissipated_energy = stiffness.dissipated();
      }
      jntforc_rows_.push_back(row);
    }
    jntforc_csv_->write_text(output::jntforc_text(jntforc_rows_));
    jntforc_schedule_.mark_written(t, cycle);
  }
  if (swforc_csv_ && wanted(swforc_schedule_)) {
    fmt::memory_buffer text;
    for (const SpotWeldState& w : nodal_constraints_.welds) {
      // 17 significant digits, as every CSV file: values read back bit-identical.
      fmt::format_to(std::back_inserter(text), "{:.17g},{},{:.17g},{:.17g},{},{:.17g}\n", t, w.id,
                     w.normal_force, w.shear_force, static_cast<int>(w.status), w.failure_time);
    }
    swforc_csv_->write_text(std::string(text.data(), text.size()));
    swforc_schedule_.mark_written(t, cycle);
  }
  if (fields_ && wanted(d3plot_schedule_)) {
    if (walls_.empty()) {
      fields_->write_frame(state_);
    } else {  // the walls drawn beside the frame (walls.pvd)
      const std::vector<output::WallPatch> patches = contact::wall_patches(walls_, state_);
      output::FrameOptions frame;
      frame.walls = &patches;
      fields_->write_frame(state_, frame);
    }
    if (d3plot_) d3plot_->write_state(state_, d3plot_globals());
    d3plot_schedule_.mark_written(t, cycle);
  }
  if (distribution_) finish_output_on_ranks();
}

output::D3plotGlobals Simulation::d3plot_globals() const {
  output::D3plotGlobals g;
  g.kinetic_energy = energy_.kinetic;
  g.internal_energy = energy_.internal();
  g.total_energy = energy_.total();
  double mass = 0.0;
  // Nodes of rigid bodies count through their bodies (as in the momentum).
  for (std::size_t i = 0; i < state_.nodes.size(); ++i) {
    if (!rigid_.is_rigid(static_cast<std::int32_t>(i))) mass += state_.nodes.mass[i];
  }
  for (const auto& body : rigid_.bodies) mass += body.state.mass;
  for (int k = 0; k < 3; ++k) g.velocity[k] = mass > 0.0 ? energy_.momentum[k] / mass : 0.0;
  return g;
}

void Simulation::write_output_now() {
  write_output_if_due(true);
}

void Simulation::update_positions() {
  NodalState& nodes = state_.nodes;
  const std::int64_t n = static_cast<std::int64_t>(nodes.size());
  const double dt = state_.dt;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    nodes.x.x[i] += dt * nodes.v.x[i];
    nodes.x.y[i] += dt * nodes.v.y[i];
    nodes.x.z[i] += dt * nodes.v.z[i];
  }
  place_curvilinear_nodes(rigid_, state_);
  state_.time += dt;
}

// A block's kernel result: the first failure of the cycle becomes the breakdown message (what
// `describe` says of the failed element, then time and cycle), and the step limit enters the
// cycle's minimum with its controlling element.
template <class Describe>
void Simulation::record_kernel_result(const element::KernelResult& r,
                                      const std::vector<model::Id>& element_id,
                                      Describe&& describe) {
  if (r.failed && breakdown_message_.empty()) {
    breakdown_message_ =
        fmt::format("{} at time {:.6g} (cycle {})", describe(element_id[r.failed_element]),
                    state_.time, state_.cycle);
  }
  if (r.min_dt < element_dt_) {
    element_dt_ = r.min_dt;
    if (r.min_dt_element >= 0) controlling_element_ = element_id[r.min_dt_element];
  }
}

void Simulation::compute_internal_forces() {
  const element::NodalView view = view_of(state_.nodes);
  element_dt_ = std::numeric_limits<double>::infinity();
  if (distribution_) std::fill(rank_block_work_.begin(), rank_block_work_.end(), 0.0);
  for (std::size_t b = 0; b < state_.hex_blocks.size(); ++b) {
    element::HexBlock& block = state_.hex_blocks[b];
    if (block.rigid) continue;  // moved by its body; no stress, no step limit
    const element::KernelResult r = element::compute_block_forces(block, view, state_.dt);
    if (distribution_) {  // summed over the ranks first (viscosity in the second half)
      rank_block_work_[b] = r.hourglass_work;
      rank_block_work_[rank_block_work_.size() / 2 + b] = r.bulk_viscosity_work;
    } else {
      energy_.hourglass += r.hourglass_work;
      energy_.bulk_viscosity += r.bulk_viscosity_work;
      if (part_histories_)
        part_histories_->add_hourglass(b, r.hourglass_work, r.bulk_viscosity_work);
    }
    record_kernel_result(r, block.element_id, [&](model::Id element) {
      return fmt::format(
          "element {} of part {} has non-positive volume {:.6g} (or a non-finite "
          "force)",
          element, block.part_id, r.failed_volume);
    });
  }
  compute_structural_forces();
  if (erosion_.enabled()) erode_failed_elements();
  gather_internal_forces(true);
}

// Failed elements leave the model before their forces are gathered (solver/erosion.hpp): the
// step minimum is taken again without them, contact drops their segments and exposes what they
// covered, and each deletion is a row of erosion.csv.
void Simulation::erode_failed_elements() {
  // ERODE: TSMIN = DTMIN x the first step (*CONTROL_TERMINATION), as an element step before
  // TSSFAC; unknown (0) until the first step is taken.
  const double tssfac = model_.timestep.tssfac > 0.0 ? model_.timestep.tssfac : 0.9;
  erosion_.set_minimum_step(model_.timestep.erode != 0 && initial_dt_ > 0.0
                                ? model_.termination.dtmin * initial_dt_ / tssfac
                                : 0.0);
  std::vector<ElementFailure> failures = erosion_.find_failed_elements(state_, state_.time);
  // Distributed: each rank found failures among its own elements; every rank deletes all of them,
  // in the order one process would (docs/parallel.md). One small collective per cycle.
  if (distribution_) {
    const std::string all = distribution_->communicator().all_gather(pack_failures(failures));
    failures.clear();
    unpack_failures(all, failures);
    std::sort(failures.begin(), failures.end());
  }
  const std::int64_t eroded = erosion_.delete_elements(
      state_, state_.time, failures, rigid_.empty() ? nullptr : &rigid_.body_of_node);
  if (eroded == 0) return;
  if (!contacts_.empty()) contact::update_after_erosion(contacts_, state_);
  if (erosion_csv_) {
    for (const ErosionEvent& event : erosion_.events()) {
      erosion_csv_->write_text(fmt::format("{:.9g},{},{},{},\"{}\"\n", event.time, event.part,
                                           event.element, event.family, event.criterion));
    }
  }
  // The step the remaining elements allow (the kernels' minimum included the deleted ones).
  const auto [step, controlling] = critical_step_of_blocks();
  element_dt_ = step;
  if (controlling != 0) controlling_element_ = controlling;
}

std::pair<double, model::Id> Simulation::critical_step_of_blocks() const {
  const element::NodalView view = view_of(state_.nodes);
  double step = std::numeric_limits<double>::infinity();
  model::Id controlling = 0;
  auto take = [&](const element::KernelResult& r, const std::vector<model::Id>& ids) {
    if (!(r.min_dt < step)) return;
    step = r.min_dt;
    controlling = r.min_dt_element >= 0 ? ids[static_cast<std::size_t>(r.min_dt_element)] : 0;
  };
  for (const auto& block : state_.hex_blocks)
    if (!block.rigid) take(element::block_critical_timestep(block, view), block.element_id);
  for (const auto& block : state_.shell_blocks)
    if (!block.rigid) take(element::shell_critical_timestep(block, view), block.element_id);
  for (const auto& block : state_.beam_blocks)
    if (!block.rigid) take(element::beam_critical_timestep(block, view), block.element_id);
  return {step, controlling};
}

// f_int from every family: the element blocks' force slots (summed over the ranks), then the
// springs, dampers and joints, which every rank computes whole (replicated). `book_work` adds
// the ranks' hourglass and viscous work; a switch re-gathers without booking it again.
void Simulation::gather_internal_forces(bool book_work) {
  assemble_internal_forces(state_);
  assemble_structural_forces(state_);
  if (distribution_) {
    if (book_work)
      sum_partial_forces_across_ranks();
    else
      distribution_->sum_partial_forces(state_, nullptr, true);  // forces and shell/beam moments
  }
  compute_discrete_forces();
  if (!joints_.empty()) {  // penalty springs: their stiffness needs the first step
    prepare_joint_stiffness(joints_, rigid_, state_, initial_dt_);
    add_joint_forces(joints_, state_);
  }
  // Moments on the rigid bodies, applied by their next advance (not nodal forces).
  evaluate_joint_stiffnesses(joint_stiffnesses_, rigid_, state_.dt);
}

// Shell and beam blocks: forces and moments into their slots, the step they allow.
void Simulation::compute_structural_forces() {
  if (state_.shell_blocks.empty() && state_.beam_blocks.empty()) return;
  const element::NodalView view = view_of(state_.nodes);
  const RotationalState& rot = state_.rotations;
  const element::RotationalView rotations{rot.w.x.data(), rot.w.y.data(), rot.w.z.data()};
  std::size_t slot = state_.hex_blocks.size();  // rank_block_work_: shells, then beams
  auto account = [&](const element::KernelResult& r, const auto& block, const char* kind) {
    const std::size_t b = slot++;
    if (distribution_) {  // summed over the ranks first (viscosity in the second half)
      rank_block_work_[b] = r.hourglass_work;
      rank_block_work_[rank_block_work_.size() / 2 + b] = r.bulk_viscosity_work;
    } else {
      energy_.hourglass += r.hourglass_work;
      energy_.bulk_viscosity += r.bulk_viscosity_work;
      if (part_histories_)
        part_histories_->add_hourglass(b, r.hourglass_work, r.bulk_viscosity_work);
    }
    record_kernel_result(r, block.element_id, [&](model::Id element) {
      return fmt::format(
          "{} element {} of part {} has a degenerate shape (non-positive area or "
          "length), a non-finite force or (*MAT_036) a plastic return that did not converge",
          kind, element, block.part_id);
    });
  };
  for (auto& block : state_.shell_blocks) {
    if (block.rigid) {
      ++slot;
      continue;
    }
    account(element::compute_shell_forces(block, view, rotations, state_.dt), block, "shell");
  }
  for (auto& block : state_.beam_blocks) {
    if (block.rigid) {
      ++slot;
      continue;
    }
    account(element::compute_beam_forces(block, view, rotations, state_.dt), block, "beam");
  }
}

// Springs and dampers: forces into their slots, then added to f_int; the step they allow from
// the masses of their nodes (rigid-body nodes count with their body, which part switching may
// change, so the masses are looked up each cycle: a few elements).
void Simulation::compute_discrete_forces() {
  if (state_.discrete_blocks.empty()) return;
  prepare_discrete_time_steps(state_, rigid_);
  const element::NodalView view = view_of(state_.nodes);
  discrete_dt_ = std::numeric_limits<double>::infinity();
  for (auto& block : state_.discrete_blocks) {
    const element::KernelResult r = element::compute_discrete_forces(block, view);
    if (r.min_dt < discrete_dt_ && r.min_dt_element >= 0) {
      discrete_dt_ = r.min_dt;
      discrete_controlling_element_ = block.element_id[r.min_dt_element];
    }
    record_kernel_result(r, block.element_id, [&](model::Id element) {
      return fmt::format(
          "discrete element {} of part {}: its nodes have come together (length "
          "{:.6g}), so the line of action is undefined,",
          element, block.part_id, r.failed_volume);
    });
  }
  assemble_discrete_forces(state_);
}

void Simulation::compute_contact_forces() {
  contact::compute_contact_forces(contacts_, state_, state_.dt);
}

void Simulation::compute_external_forces() {
  solver::compute_external_forces(boundary_, state_.time, state_);
  contact::add_contact_forces(contacts_, state_);
}

void Simulation::check_breakdown() {
  if (!breakdown_message_.empty()) throw SolverError(breakdown_message_);
}

// After the forces at t^{n+1}, before the next step is chosen: state_.dt is still the step just
// taken, as evaluate_sensors expects. DEF2RIG status changes of this cycle are then available
// through sensor::def2rig_events(sensors()).
void Simulation::update_sensors() {
  if (sensors_->empty()) return;
  if (distribution_ && !sensors_->element_sensors.empty()) {
    // The partition's owner of each element (not the kernels' current loops, which an erosion
    // shortens); elements of blocks outside the partition (*MAT_RIGID) count on rank 0.
    const parallel::ElementDistribution& d = *distribution_;
    const sensor::RankShare ranks{
        [&d](int block, std::int64_t element) {
          const auto& owners = d.partition().hex;
          const std::size_t b = static_cast<std::size_t>(block);
          if (b >= owners.size() || owners[b].empty()) return d.communicator().rank() == 0;
          return owners[b][static_cast<std::size_t>(element)] == d.communicator().rank();
        },
        [&d](double* values, std::size_t count) { d.communicator().sum(values, count); }};
    sensor::evaluate_sensors(*sensors_, state_, state_.time, &ranks);
  } else {
    sensor::evaluate_sensors(*sensors_, state_, state_.time);
  }
  if (sensor_csv_) {
    const bool last = (end_time_ > 0.0 && state_.time >= end_time_ * (1.0 - 1e-12)) ||
                      (end_cycle_ > 0 && state_.cycle + 1 >= end_cycle_);
    sensor_csv_->write(*sensors_, last);
  }
}

// Mass scaling (solver/mass_scaling.hpp): at the start, and in any cycle whose smallest element
// step fell below the target. The work of mass added during the run is external work.
void Simulation::scale_masses_if_needed() {
  if (!mass_scaling_.active()) return;
  const double before = mass_scaling_.mass_scaling_work;
  if (scale_masses(mass_scaling_, state_, rigid_.body_of_node, element_dt_, controlling_element_)) {
    // The kinetic energy of v^{n+1/2} with the new masses, as the next velocity update will
    // count it: the balance holds between cycles too, not only after that update.
    const double work = mass_scaling_.mass_scaling_work - before;
    energy_.external_work += work;
    energy_.kinetic += work;
    // The scaling sees the continuum elements only: springs and dampers keep their limit.
    if (discrete_dt_ < element_dt_) {
      element_dt_ = discrete_dt_;
      controlling_element_ = discrete_controlling_element_;
    }
  }
}

void Simulation::select_time_step() {
  const auto& control = model_.timestep;
  const bool relaxing = dynamic_relaxation_running();
  double tssfac = control.tssfac > 0.0 ? control.tssfac : 0.9;
  if (relaxing && model_.dynamic_relaxation.tssfdr > 0.0) tssfac = model_.dynamic_relaxation.tssfdr;
  double dt = tssfac * element_dt_;
  // Step hysteresis (issue 16). The element step follows the current geometry, which oscillates
  // with the very modes the step must resolve: a step that rises and falls with them modulates
  // the central difference at their own frequency and pumps energy into them (a parametric
  // resonance; the energy balance cannot show it, it telescopes). A 4 x 2 shell strip hit in
  // its plane at one node (2.5 m/s) grew without bound at TSSFAC 0.9 and 0.8 while a constant
  // step of the same size stayed bounded. So the step never rises by less than kStepBand: small
  // rises are ignored (the step in force stays, below the element step, hence stable), falls
  // are followed at once. Measured: bounded at TSSFAC 0.9 for 2.5 m/s and at 0.6-0.8 for 25 m/s
  // (docs/elements.md); a run whose step only falls is unchanged.
  constexpr double kStepBand = 0.01;
  if (state_.cycle > 0 && state_.dt > 0.0 && dt > state_.dt && dt < (1.0 + kStepBand) * state_.dt)
    dt = state_.dt;
  if (control.lctm != 0) {
    const auto it = model_.curves.find(control.lctm);
    if (it == model_.curves.end()) {
      // The reader checks this reference; kept for models built in code.
      throw InputError(
          {.file = {}, .line = 0, .keyword = "*CONTROL_TIMESTEP", .card = 1, .field = "LCTM"},
          fmt::format("LCTM refers to load curve {}, which is not defined", control.lctm));
    }
    dt = std::min(dt, model::evaluate(it->second, state_.time));
  }
  if (control.dt_max > 0.0) dt = std::min(dt, control.dt_max);
  if (switch_dt_cap_ > 0.0) dt = std::min(dt, switch_dt_cap_);  // DTMAX of the last switch
  const bool no_element_step = !std::isfinite(element_dt_);
  if (control.dtinit > 0.0 && (state_.cycle == 0 || no_element_step)) {
    // Without deformable elements DTINIT is the step throughout (capped by LCTM above).
    dt = std::min(dt, control.dtinit);
  }
  if (no_element_step && !std::isfinite(dt) && state_.cycle > 0 && state_.dt > 0.0) {
    // Every part was made rigid by switching and nothing else bounds the step: keep the step in
    // force before the switch (what a user expects; rigid bodies alone are integrated stably
    // at any step the loads resolve). Said once; `check` warns about it up front.
    dt = state_.dt;
    // Said once: the notice is looked for among the warnings (a few), only on this path.
    constexpr std::string_view kHeldStep = "keeps the step in force before the switch";
    const bool noted = std::any_of(warnings_.begin(), warnings_.end(), [&](const auto& w) {
      return w.message.find(kHeldStep) != std::string::npos;
    });
    if (!noted) {
      warnings_.push_back(
          {{},
           fmt::format("t = {:.6g}: no deformable element is left after switching and neither "
                       "DTINIT nor LCTM (*CONTROL_TIMESTEP) nor DTMAX "
                       "(*DEFORMABLE_TO_RIGID_AUTOMATIC) sets the step: the run keeps the step "
                       "in force before the switch, dt = {:.6g}",
                       state_.time, dt)});
    }
  }
  if (no_element_step && !std::isfinite(dt)) {
    throw InputError(
        {.file = {}, .line = 0, .keyword = "*CONTROL_TIMESTEP", .card = 1, .field = "DTINIT"},
        "the model has no deformable elements, so nothing limits the time step: "
        "give DTINIT (or LCTM) on *CONTROL_TIMESTEP, or DTMAX on the "
        "*DEFORMABLE_TO_RIGID_AUTOMATIC set that made every part rigid");
  }
  if (!std::isfinite(dt) || dt <= 0.0) {
    throw SolverError(fmt::format("no valid time step at time {:.6g}: element {} gives {:.6g}",
                                  state_.time, controlling_element_, element_dt_));
  }
  if (initial_dt_ > 0.0) {
    const double dtmin_fraction = model_.termination.dtmin > 0.0 ? model_.termination.dtmin : 1e-6;
    if (dt < dtmin_fraction * initial_dt_) {
      throw SolverError(fmt::format(
          "time step collapsed to {:.6g} (initial {:.6g}) at time {:.6g}, controlled by "
          "element {}",
          dt, initial_dt_, state_.time, controlling_element_));
    }
  }
  // Land exactly on the termination time: shorten the step, or stretch it by at most 0.1 %
  // rather than leave a remainder below 1e-3 dt (which was then overshot by a whole step).
  if (!relaxing && end_time_ > 0.0 && state_.time + dt * (1.0 + 1e-3) > end_time_ &&
      end_time_ > state_.time) {
    dt = end_time_ - state_.time;
  }
  state_.dt_prev = state_.dt;
  state_.dt = dt;
  dt_average_ = 0.5 * (state_.dt_prev + state_.dt);
}

}  // namespace rf::solver
