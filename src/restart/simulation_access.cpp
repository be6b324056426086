#include "restart/simulation_access.hpp"

#include <fmt/format.h>

#include "parallel/distribution.hpp"

#include "sensor/sensor.hpp"
#include "sensor/sensor_output.hpp"

namespace rf::restart {

namespace {

using io::h5::Group;

void write_schedule(const Group& g, const std::string& name, double interval, double next,
                    std::int64_t last_cycle) {
  g.set(name + "_interval", interval);
  g.set(name + "_next", next);
  g.set(name + "_last_cycle", last_cycle);
}

template <class Schedule>
void read_schedule(const Group& g, const std::string& name, Schedule& s) {
  s.interval = g.get_double(name + "_interval");
  s.next = g.get_double(name + "_next");
  s.last_cycle = g.get_int(name + "_last_cycle");
}

}  // namespace

void SimulationAccess::write_members(Simulation& s, const Group& g) {
  const solver::State& st = s.state_;
  g.set("time", st.time);
  g.set("dt", st.dt);
  g.set("dt_prev", st.dt_prev);
  g.set("cycle", st.cycle);
  g.set("generated_node_count", st.generated_node_count);
  g.set("end_time", s.end_time_);
  g.set("end_cycle", s.end_cycle_);
  g.set("element_dt", s.element_dt_);
  g.set("initial_dt", s.initial_dt_);
  g.set("dt_average", s.dt_average_);
  g.set("element_count", s.element_count_);
  g.set("controlling_element", std::int64_t{s.controlling_element_});
  g.set("finished", std::int64_t{s.finished_});
  g.set("breakdown_message", s.breakdown_message_);
  const solver::EnergyAccount& e = s.energy_;
  g.set("energy_kinetic", e.kinetic);
  g.set("energy_internal_work", e.internal_work);
  g.set("energy_hourglass", e.hourglass);
  g.set("energy_bulk_viscosity", e.bulk_viscosity);
  g.set("energy_external_work", e.external_work);
  g.set("energy_initial_total", e.initial_total);
  g.set("energy_switch", e.switch_energy);
  g.set("energy_frozen", e.frozen_energy);
  g.set("energy_rigidwall_work", e.rigidwall_work);
  g.set("energy_contact", e.contact_energy);
  g.set("energy_damping_work", e.damping_work);
  if (s.erosion_.enabled()) {  // what has left the model (solver/erosion.hpp)
    const solver::ErosionLedger& l = s.erosion_.ledger();
    g.set("eroded_internal_energy", l.internal_energy);
    g.set("eroded_kinetic_energy", l.kinetic_energy);
    g.set("eroded_elements", l.elements);
    g.set("eroded_nodes", l.nodes);
    g.set("erosion_impulse_time", s.erosion_.impulse_time());
    for (int k = 0; k < 3; ++k) {
      g.set(fmt::format("eroded_momentum_{}", k), l.momentum[k]);
      g.set(fmt::format("eroded_angular_momentum_{}", k), l.angular_momentum[k]);
    }
  }
  g.set("switch_dt_cap", s.switch_dt_cap_);
  if (!s.joints_.empty()) {  // the last joint forces, which jntforc.csv reports
    std::vector<double> joint_loads;
    for (const auto& joint : s.joints_.joints) {
      for (int k = 0; k < 3; ++k) joint_loads.push_back(joint.force[k]);
      for (int k = 0; k < 3; ++k) joint_loads.push_back(joint.moment[k]);
    }
    g.write("joint_force_moment", std::span<const double>(joint_loads));
  }
  if (!s.joint_stiffnesses_.empty()) {  // angles, friction slips, last moments (history)
    std::vector<double> history;
    for (const auto& j : s.joint_stiffnesses_.joints) {
      history.insert(history.end(), j.angle.begin(), j.angle.end());
      history.insert(history.end(), j.slip.begin(), j.slip.end());
      history.insert(history.end(), j.moment.begin(), j.moment.end());
      history.insert(history.end(), j.torque_b.data(), j.torque_b.data() + 3);
      history.insert(history.end(),
                     {j.absorbed, j.initial_elastic, j.elastic, j.started ? 1.0 : 0.0});
    }
    g.write("joint_stiffness_history", std::span<const double>(history));
  }
  if (!s.nodal_constraints_.empty()) {  // spot welds and node sets: status and last forces
    std::vector<std::int64_t> status;
    std::vector<double> numbers;
    for (const auto& w : s.nodal_constraints_.welds) {
      status.push_back(static_cast<std::int64_t>(w.status));
      numbers.insert(numbers.end(), {w.failure_time, w.normal_force, w.shear_force});
    }
    for (const auto& tie : s.nodal_constraints_.ties) {
      status.push_back(static_cast<std::int64_t>(tie.status));
      numbers.insert(numbers.end(), {tie.failure_time, 0.0, 0.0});
    }
    g.write("nodal_constraint_status", std::span<const std::int64_t>(status));
    g.write("nodal_constraint_numbers", std::span<const double>(numbers));
  }
  for (int k = 0; k < 3; ++k) {
    g.set(fmt::format("energy_momentum_{}", k), e.momentum[k]);
    g.set(fmt::format("energy_angular_momentum_{}", k), e.angular_momentum[k]);
  }
}

void SimulationAccess::read_members(Simulation& s, const Group& g) {
  solver::State& st = s.state_;
  if (g.get_int("generated_node_count") != st.generated_node_count ||
      g.get_int("element_count") != s.element_count_) {
    g.fail("element_count",
           fmt::format("the dump has {} elements and {} generated nodes, the model rebuilt from "
                       "its deck {} and {}",
                       g.get_int("element_count"), g.get_int("generated_node_count"),
                       s.element_count_, st.generated_node_count));
  }
  st.time = g.get_double("time");
  st.dt = g.get_double("dt");
  st.dt_prev = g.get_double("dt_prev");
  st.cycle = g.get_int("cycle");
  s.end_time_ = g.get_double("end_time");
  s.end_cycle_ = g.get_int("end_cycle");
  s.element_dt_ = g.get_double("element_dt");
  s.initial_dt_ = g.get_double("initial_dt");
  s.dt_average_ = g.get_double("dt_average");
  s.controlling_element_ = g.get_int("controlling_element");
  s.finished_ = g.get_int("finished") != 0;
  s.breakdown_message_ = g.get_string("breakdown_message");
  solver::EnergyAccount& e = s.energy_;
  e.kinetic = g.get_double("energy_kinetic");
  e.internal_work = g.get_double("energy_internal_work");
  e.hourglass = g.get_double("energy_hourglass");
  e.bulk_viscosity =
      g.has_attribute("energy_bulk_viscosity") ? g.get_double("energy_bulk_viscosity") : 0.0;
  e.external_work = g.get_double("energy_external_work");
  e.initial_total = g.get_double("energy_initial_total");
  e.switch_energy = g.get_double("energy_switch");
  e.frozen_energy = g.get_double("energy_frozen");
  e.rigidwall_work = g.get_double("energy_rigidwall_work");
  e.contact_energy = g.has_attribute("energy_contact") ? g.get_double("energy_contact") : 0.0;
  e.damping_work =
      g.has_attribute("energy_damping_work") ? g.get_double("energy_damping_work") : 0.0;
  s.switch_dt_cap_ = g.get_double("switch_dt_cap");
  if (!s.joints_.empty() && g.has("joint_force_moment")) {
    const std::vector<double> joint_loads = g.read_doubles("joint_force_moment");
    if (joint_loads.size() != 6 * s.joints_.joints.size()) {
      g.fail("joint_force_moment", fmt::format("holds {} values, the rebuilt model has {} joints",
                                               joint_loads.size(), s.joints_.joints.size()));
    }
    for (std::size_t j = 0; j < s.joints_.joints.size(); ++j) {
      auto& joint = s.joints_.joints[j];
      for (int k = 0; k < 3; ++k) {
        joint.force[k] = joint_loads[6 * j + k];
        joint.moment[k] = joint_loads[6 * j + 3 + k];
      }
    }
  }
  if (!s.joint_stiffnesses_.empty()) {
    constexpr std::size_t kWidth = 16;
    const std::vector<double> history = g.read_doubles("joint_stiffness_history");
    if (history.size() != kWidth * s.joint_stiffnesses_.joints.size()) {
      g.fail("joint_stiffness_history",
             fmt::format("holds {} values, the rebuilt model has {} joint stiffnesses",
                         history.size(), s.joint_stiffnesses_.joints.size()));
    }
    for (std::size_t i = 0; i < s.joint_stiffnesses_.joints.size(); ++i) {
      auto& j = s.joint_stiffnesses_.joints[i];
      const double* h = history.data() + kWidth * i;
      for (int k = 0; k < 3; ++k) {
        j.angle[k] = h[k];
        j.slip[k] = h[3 + k];
        j.moment[k] = h[6 + k];
        j.torque_b[k] = h[9 + k];
      }
      j.absorbed = h[12];
      j.initial_elastic = h[13];
      j.elastic = h[14];
      j.started = h[15] != 0.0;
    }
    solver::apply_joint_stiffness_torques(s.joint_stiffnesses_, s.rigid_);
  }
  if (!s.nodal_constraints_.empty() && g.has("nodal_constraint_status")) {
    auto& nc = s.nodal_constraints_;
    const std::vector<std::int64_t> status = g.read_int64("nodal_constraint_status");
    const std::vector<double> numbers = g.read_doubles("nodal_constraint_numbers");
    const std::size_t count = nc.welds.size() + nc.ties.size();
    if (status.size() != count || numbers.size() != 3 * count) {
      g.fail("nodal_constraint_status",
             fmt::format("holds {} entries, the rebuilt model has {} spot welds and node sets",
                         status.size(), count));
    }
    for (const std::int64_t v : status) {
      if (v < 0 || v > 3) g.fail("nodal_constraint_status", fmt::format("status {} unknown", v));
    }
    for (std::size_t j = 0; j < count; ++j) {
      const auto st = static_cast<solver::ConstraintStatus>(status[j]);
      if (j < nc.welds.size()) {
        auto& w = nc.welds[j];
        w.status = st;
        w.failure_time = numbers[3 * j];
        w.normal_force = numbers[3 * j + 1];
        w.shear_force = numbers[3 * j + 2];
      } else {
        auto& tie = nc.ties[j - nc.welds.size()];
        tie.status = st;
        tie.failure_time = numbers[3 * j];
      }
    }
  }
  for (int k = 0; k < 3; ++k) {
    e.momentum[k] = g.get_double(fmt::format("energy_momentum_{}", k));
    e.angular_momentum[k] = g.get_double(fmt::format("energy_angular_momentum_{}", k));
  }
  if (s.erosion_.enabled()) {
    // The blocks' erosion times came with their state: ownership, live counts and removed nodes
    // follow from them (the ledger first: restore() keeps its node count).
    solver::ErosionLedger& l = s.erosion_.ledger();
    l.internal_energy = g.get_double("eroded_internal_energy");
    l.kinetic_energy = g.get_double("eroded_kinetic_energy");
    l.elements = g.get_int("eroded_elements");
    l.nodes = g.get_int("eroded_nodes");
    s.erosion_.set_impulse_time(
        g.has_attribute("erosion_impulse_time") ? g.get_double("erosion_impulse_time") : st.time);
    for (int k = 0; k < 3; ++k) {
      l.momentum[k] = g.get_double(fmt::format("eroded_momentum_{}", k));
      l.angular_momentum[k] = g.get_double(fmt::format("eroded_angular_momentum_{}", k));
    }
    s.erosion_.restore(st, s.rigid_.empty() ? nullptr : &s.rigid_.body_of_node);
    // Contact's active segments and nodes are derived from the erosion state (contact.hpp).
    if (!s.contacts_.empty()) contact::update_after_erosion(s.contacts_, st);
    e.eroded_internal = l.internal_energy;
    e.eroded_kinetic = l.kinetic_energy;
  }
}

void SimulationAccess::write_output(Simulation& s, const Group& g) {
  g.set("glstat_bytes", s.glstat_ ? s.glstat_->flushed_size() : std::int64_t{-1});
  g.set("nodout_bytes", s.nodout_ ? s.nodout_->flushed_size() : std::int64_t{-1});
  g.set("rbdout_bytes", s.rbdout_ ? s.rbdout_->flushed_size() : std::int64_t{-1});
  g.set("switch_bytes", s.switch_csv_ ? s.switch_csv_->flushed_size() : std::int64_t{-1});
  g.set("sensor_bytes", s.sensor_csv_ ? s.sensor_csv_->flushed_size() : std::int64_t{-1});
  g.set("rwforc_bytes", s.rwforc_ ? s.rwforc_->flushed_size() : std::int64_t{-1});
  g.set("modal_bytes", s.modal_csv_ ? s.modal_csv_->flushed_size() : std::int64_t{-1});
  write_schedule(g, "rwforc", s.rwforc_schedule_.interval, s.rwforc_schedule_.next,
                 s.rwforc_schedule_.last_cycle);
  g.set("rcforc_bytes", s.rcforc_ ? s.rcforc_->flushed_size() : std::int64_t{-1});
  write_schedule(g, "rcforc", s.rcforc_schedule_.interval, s.rcforc_schedule_.next,
                 s.rcforc_schedule_.last_cycle);
  // Per-part and per-element histories (issue 20): sizes, schedules, per-part work so far.
  g.set("matsum_bytes", s.matsum_csv_ ? s.matsum_csv_->flushed_size() : std::int64_t{-1});
  g.set("spcforc_bytes", s.spcforc_csv_ ? s.spcforc_csv_->flushed_size() : std::int64_t{-1});
  g.set("elout_bytes", s.elout_csv_ ? s.elout_csv_->flushed_size() : std::int64_t{-1});
  g.set("secforc_bytes", s.secforc_csv_ ? s.secforc_csv_->flushed_size() : std::int64_t{-1});
  g.set("elout_shell_bytes",
        s.elout_shell_csv_ ? s.elout_shell_csv_->flushed_size() : std::int64_t{-1});
  write_schedule(g, "matsum", s.matsum_schedule_.interval, s.matsum_schedule_.next,
                 s.matsum_schedule_.last_cycle);
  write_schedule(g, "spcforc", s.spcforc_schedule_.interval, s.spcforc_schedule_.next,
                 s.spcforc_schedule_.last_cycle);
  write_schedule(g, "elout", s.elout_schedule_.interval, s.elout_schedule_.next,
                 s.elout_schedule_.last_cycle);
  write_schedule(g, "secforc", s.secforc_schedule_.interval, s.secforc_schedule_.next,
                 s.secforc_schedule_.last_cycle);
  write_schedule(g, "elout_shell", s.elout_shell_schedule_.interval, s.elout_shell_schedule_.next,
                 s.elout_shell_schedule_.last_cycle);
  g.set("jntforc_bytes", s.jntforc_csv_ ? s.jntforc_csv_->flushed_size() : std::int64_t{-1});
  write_schedule(g, "jntforc", s.jntforc_schedule_.interval, s.jntforc_schedule_.next,
                 s.jntforc_schedule_.last_cycle);
  if (s.erosion_csv_) g.set("erosion_bytes", s.erosion_csv_->flushed_size());
  if (s.swforc_csv_) {
    g.set("swforc_bytes", s.swforc_csv_->flushed_size());
    write_schedule(g, "swforc", s.swforc_schedule_.interval, s.swforc_schedule_.next,
                   s.swforc_schedule_.last_cycle);
  }
  if (s.part_histories_) {
    const auto& hourglass = s.part_histories_->hourglass();
    std::vector<double> work = s.part_histories_->internal_work();
    if (!s.dump_rank_part_work_.empty()) {
      // A distributed run: each rank's share, by rank (a restart on as many ranks gives each
      // its own back), and their sum as the parts' work (a restart on another count).
      const std::vector<double>& shares = s.dump_rank_part_work_;
      g.write("part_internal_work_ranks", std::span<const double>(shares.data(), shares.size()));
      std::fill(work.begin(), work.end(), 0.0);
      for (std::size_t k = 0; k < shares.size(); ++k) work[k % work.size()] += shares[k];
    }
    g.write("part_internal_work", std::span<const double>(work.data(), work.size()));
    g.write("part_hourglass", std::span<const double>(hourglass.data(), hourglass.size()));
    const auto& bulk = s.part_histories_->bulk_viscosity();
    g.write("part_bulk_viscosity", std::span<const double>(bulk.data(), bulk.size()));
  }
  write_schedule(g, "glstat", s.glstat_schedule_.interval, s.glstat_schedule_.next,
                 s.glstat_schedule_.last_cycle);
  write_schedule(g, "nodout", s.nodout_schedule_.interval, s.nodout_schedule_.next,
                 s.nodout_schedule_.last_cycle);
  write_schedule(g, "rbdout", s.rbdout_schedule_.interval, s.rbdout_schedule_.next,
                 s.rbdout_schedule_.last_cycle);
  write_schedule(g, "d3plot", s.d3plot_schedule_.interval, s.d3plot_schedule_.next,
                 s.d3plot_schedule_.last_cycle);
  const std::vector<double> no_times;
  const std::vector<std::string> no_files;
  const auto& times = s.fields_ ? s.fields_->frame_times() : no_times;
  const auto& files = s.fields_ ? s.fields_->frame_files() : no_files;
  g.set("frame_count", static_cast<std::int64_t>(times.size()));
  g.write("frame_times", std::span<const double>(times.data(), times.size()));
  std::string joined;
  for (const auto& f : files) {
    joined += f;
    joined.push_back('\0');
  }
  g.write_text("frame_files", joined);
}

void SimulationAccess::read_output(Simulation& s, const Group& g) {
  read_schedule(g, "glstat", s.glstat_schedule_);
  read_schedule(g, "nodout", s.nodout_schedule_);
  read_schedule(g, "rbdout", s.rbdout_schedule_);
  read_schedule(g, "d3plot", s.d3plot_schedule_);
  read_schedule(g, "rwforc", s.rwforc_schedule_);
  if (g.has_attribute("rcforc_bytes")) read_schedule(g, "rcforc", s.rcforc_schedule_);
  if (g.has_attribute("matsum_bytes")) {
    read_schedule(g, "matsum", s.matsum_schedule_);
    read_schedule(g, "spcforc", s.spcforc_schedule_);
    read_schedule(g, "elout", s.elout_schedule_);
  }
  if (g.has_attribute("secforc_bytes")) read_schedule(g, "secforc", s.secforc_schedule_);
  if (g.has_attribute("jntforc_bytes")) read_schedule(g, "jntforc", s.jntforc_schedule_);
  if (g.has_attribute("swforc_bytes")) read_schedule(g, "swforc", s.swforc_schedule_);
  if (g.has_attribute("elout_shell_bytes")) {
    read_schedule(g, "elout_shell", s.elout_shell_schedule_);
  }
  if (s.part_histories_) {
    if (!g.has_attribute("matsum_bytes") || g.get_int("matsum_bytes") < 0) {
      g.fail("matsum_bytes",
             "the dumped run wrote no matsum.csv, so the parts' energies so far are unknown; "
             "add *DATABASE_MATSUM before the run, not at the restart");
    }
    auto& work = s.part_histories_->internal_work();
    auto& hourglass = s.part_histories_->hourglass();
    const auto dumped_work = g.read_doubles("part_internal_work");
    const auto dumped_hourglass = g.read_doubles("part_hourglass");
    if (dumped_work.size() != work.size() || dumped_hourglass.size() != hourglass.size()) {
      g.fail("part_internal_work", "the number of parts differs from the dumped run's");
    }
    work.assign(dumped_work.begin(), dumped_work.end());
    hourglass.assign(dumped_hourglass.begin(), dumped_hourglass.end());
    if (g.has("part_bulk_viscosity")) {
      const auto dumped_bulk = g.read_doubles("part_bulk_viscosity");
      auto& bulk = s.part_histories_->bulk_viscosity();
      if (dumped_bulk.size() != bulk.size()) {
        g.fail("part_bulk_viscosity", "the number of parts differs from the dumped run's");
      }
      bulk.assign(dumped_bulk.begin(), dumped_bulk.end());
    }
  }
  if (s.fields_) {
    const auto frames = read_frames(g);
    s.fields_->resume(frames.times, frames.files);
    // The d3plot database has one state per frame (frames written by an older version without
    // a d3plot: the writer starts a new family).
    if (s.d3plot_) s.d3plot_->resume(static_cast<std::int64_t>(frames.times.size()));
  }
}

bool SimulationAccess::writes_files(const Simulation& s) {
  return !s.distribution_ || s.distribution_->writes_files();
}

void SimulationAccess::resume_on_ranks(Simulation& s, const io::h5::Group& output,
                                       int dumped_ranks) {
  if (!s.distribution_) return;
  const parallel::Communicator& comm = s.distribution_->communicator();
  // The dump holds every element's force slots (gathered before writing); the assembly must
  // see each element once.
  s.distribution_->keep_own_force_slots(s.state_);
  if (s.part_histories_) {
    std::vector<double>& work = s.part_histories_->internal_work();
    const std::size_t parts = work.size();
    const std::size_t rank = static_cast<std::size_t>(comm.rank());
    if (dumped_ranks == comm.size() && output.has("part_internal_work_ranks")) {
      const std::vector<double> shares = output.read_doubles("part_internal_work_ranks");
      if (shares.size() != parts * static_cast<std::size_t>(comm.size())) {
        output.fail("part_internal_work_ranks", "does not hold one share per part and rank");
      }
      std::copy_n(shares.begin() + static_cast<std::ptrdiff_t>(rank * parts), parts, work.begin());
    } else if (rank != 0) {
      // Another rank count: rank 0 carries the parts' work so far, the others start from 0.
      std::fill(work.begin(), work.end(), 0.0);
    }
  }
  // Whether rank 0 writes element output at the first output pass, as the last cycle before the
  // dump agreed: the schedules are the dump's, the time is the pass's.
  s.agreed_output_due_ = comm.max(s.element_output_due() ? 1.0 : 0.0) > 0.0;
}

SimulationAccess::Frames SimulationAccess::read_frames(const Group& g) {
  Frames frames;
  const std::int64_t n = g.get_int("frame_count");
  frames.times = g.read_doubles("frame_times");
  const std::string joined = g.read_text("frame_files");
  std::size_t start = 0;
  while (start < joined.size()) {
    const std::size_t end = joined.find('\0', start);
    if (end == std::string::npos) break;
    frames.files.push_back(joined.substr(start, end - start));
    start = end + 1;
  }
  if (static_cast<std::int64_t>(frames.times.size()) != n ||
      static_cast<std::int64_t>(frames.files.size()) != n) {
    g.fail("frame_files", "does not match frame_times (the dump is damaged)");
  }
  for (const auto& f : frames.files) {
    if (f.empty() || f.find('/') != std::string::npos || f.find("..") != std::string::npos) {
      g.fail("frame_files", fmt::format("holds '{}', which is not a frame file name", f));
    }
  }
  return frames;
}

}  // namespace rf::restart
