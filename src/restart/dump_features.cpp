// Restart dumps of the features that carry state between cycles besides the mesh and the rigid
// system: part switching (which parts are rigid by switching, their rotation references and
// frozen energy, the automatic sets' arming and delay, deleted nodal rigid bodies), rigid walls
// (activity, moving wall motion, the last forces that switching tests, accumulated impulse and
// work, which nodes are in front) and sensors (values, switch timers, control statuses and the
// DEF2RIG events the next cycle reads). Layout: docs/restart.md.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "restart/dump.hpp"
#include "restart/simulation_access.hpp"
#include "sensor/sensor.hpp"

namespace rf::restart {

namespace {

using io::h5::Group;

template <class T>
std::span<const T> span_of(const std::vector<T>& v) {
  return {v.data(), v.size()};
}

void expect_count(const Group& g, const char* name, std::size_t got, std::size_t want) {
  if (got != want) {
    g.fail(name, fmt::format("holds {} entries, the rebuilt model needs {} (the dump is damaged "
                             "or from another deck)",
                             got, want));
  }
}

void write_switching(solver::Simulation& s, const Group& g, switching::PartSwitcher* switcher,
                     switching::AutomaticSwitching* automatic) {
  (void)s;
  g.set("has_switcher", std::int64_t{switcher != nullptr});
  if (switcher) {
    std::vector<std::int64_t> pids, bodies;
    std::vector<double> offsets, frozen;
    for (const auto& [pid, part] : switcher->switched_parts()) {
      pids.push_back(pid);
      bodies.push_back(part.body_id);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) offsets.push_back(part.rotation_offset(r, c));
      frozen.push_back(part.frozen_energy);
    }
    g.write("switched_parts", span_of(pids));
    g.write("switched_bodies", span_of(bodies));
    g.write("switched_rotation_offsets", span_of(offsets));
    g.write("switched_frozen_energy", span_of(frozen));
    write_bodies(g.create_group("deleted_nodal_bodies"), switcher->deleted_nodal_bodies());
    // Parts that are flexible bodies by switching: the mode frame of their switch
    // (switching/flexible_switching.hpp); the bodies are made again from it on restart.
    if (switching::FlexibleSwitching* flexible = switcher->flexible_bodies()) {
      std::vector<std::int64_t> flexible_parts;
      std::vector<double> frames;
      for (const auto& [pid, frame] : flexible->frames()) {
        flexible_parts.push_back(pid);
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) frames.push_back(frame(r, c));
      }
      g.write("flexible_parts", span_of(flexible_parts));
      g.write("flexible_frames", span_of(frames));
    }
  }
  g.set("has_automatic", std::int64_t{automatic != nullptr});
  if (automatic) {
    std::vector<std::uint8_t> armed, time_used;
    std::vector<std::int64_t> fired;
    for (const auto& st : automatic->states()) {
      armed.push_back(st.armed);
      time_used.push_back(st.time_used);
      fired.push_back(st.fired);
    }
    g.write("armed", span_of(armed));
    g.write("time_used", span_of(time_used));
    g.write("fired", span_of(fired));
    g.set("blocked_until", automatic->blocked_until());
  }
}

void read_switching(const Group& g, switching::PartSwitcher* switcher,
                    switching::AutomaticSwitching* automatic, std::size_t node_count) {
  if (g.get_int("has_switcher") != 0) {
    if (!switcher) g.fail("has_switcher", "the rebuilt simulation has no part switching");
    const auto pids = g.read_int64("switched_parts");
    const auto bodies = g.read_int64("switched_bodies");
    const auto offsets = g.read_doubles("switched_rotation_offsets");
    const auto frozen = g.read_doubles("switched_frozen_energy");
    expect_count(g, "switched_bodies", bodies.size(), pids.size());
    expect_count(g, "switched_rotation_offsets", offsets.size(), 9 * pids.size());
    expect_count(g, "switched_frozen_energy", frozen.size(), pids.size());
    auto& parts = switcher->switched_parts();
    parts.clear();
    for (std::size_t k = 0; k < pids.size(); ++k) {
      switching::PartSwitcher::SwitchedPart p;
      p.body_id = bodies[k];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) p.rotation_offset(r, c) = offsets[9 * k + 3 * r + c];
      p.frozen_energy = frozen[k];
      parts[pids[k]] = p;
    }
    switcher->deleted_nodal_bodies() = read_bodies(g.group("deleted_nodal_bodies"), node_count);
    if (g.has("flexible_parts")) {
      const auto flexible_parts = g.read_int64("flexible_parts");
      const auto frames = g.read_doubles("flexible_frames");
      expect_count(g, "flexible_frames", frames.size(), 9 * flexible_parts.size());
      if (!flexible_parts.empty() && !switcher->flexible_bodies()) {
        g.fail("flexible_parts", "the rebuilt model has no *PART_MODES on a switched part");
      }
      if (switching::FlexibleSwitching* flexible = switcher->flexible_bodies()) {
        flexible->frames().clear();
        for (std::size_t k = 0; k < flexible_parts.size(); ++k) {
          Eigen::Matrix3d frame;
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) frame(r, c) = frames[9 * k + 3 * r + c];
          flexible->frames()[flexible_parts[k]] = frame;
        }
      }
    }
  }
  if (g.get_int("has_automatic") != 0 && automatic) {
    const auto armed = g.read_bytes("armed");
    const auto time_used = g.read_bytes("time_used");
    const auto fired = g.read_int64("fired");
    auto& states = automatic->mutable_states();
    expect_count(g, "armed", armed.size(), states.size());
    expect_count(g, "time_used", time_used.size(), states.size());
    expect_count(g, "fired", fired.size(), states.size());
    for (std::size_t k = 0; k < states.size(); ++k) {
      states[k].armed = armed[k] != 0;
      states[k].time_used = time_used[k] != 0;
      states[k].fired = static_cast<int>(fired[k]);
    }
    automatic->set_blocked_until(g.get_double("blocked_until"));
  }
}

// Per wall: active, displacement, velocity, velocity_before, normal_force, normal_impulse,
// work, force x y z.
constexpr int kWallNumbers = 10;

void write_walls(const contact::RigidWallSystem& walls, const Group& g) {
  std::vector<double> numbers;
  std::vector<std::uint8_t> in_front;
  std::vector<std::int64_t> in_front_count;
  for (const auto& w : walls.walls) {
    for (const double v :
         {w.active ? 1.0 : 0.0, w.displacement, w.velocity, w.velocity_before, w.normal_force,
          w.normal_impulse, w.work, w.force.x(), w.force.y(), w.force.z()}) {
      numbers.push_back(v);
    }
    in_front.insert(in_front.end(), w.in_front.begin(), w.in_front.end());
    in_front_count.push_back(static_cast<std::int64_t>(w.in_front.size()));
  }
  g.set("count", static_cast<std::int64_t>(walls.walls.size()));
  g.set("cycle_stamp", walls.cycle_stamp);
  g.write("numbers", span_of(numbers));
  g.write("in_front", span_of(in_front));
  g.write("in_front_count", span_of(in_front_count));
  // *RIGIDWALL_PLANAR_FORCES: the segment set's force of the last cycle (x y z per wall).
  std::vector<double> segment_forces;
  for (const auto& w : walls.walls) {
    for (int k = 0; k < 3; ++k) segment_forces.push_back(w.segment_force[k]);
  }
  g.write("segment_forces", span_of(segment_forces));
}

void read_walls(contact::RigidWallSystem& walls, const Group& g) {
  expect_count(g, "count", static_cast<std::size_t>(g.get_int("count")), walls.walls.size());
  walls.cycle_stamp = g.get_int("cycle_stamp");
  const auto numbers = g.read_doubles("numbers");
  const auto in_front = g.read_bytes("in_front");
  const auto counts = g.read_int64("in_front_count");
  expect_count(g, "numbers", numbers.size(), kWallNumbers * walls.walls.size());
  expect_count(g, "in_front_count", counts.size(), walls.walls.size());
  std::size_t at = 0;
  for (std::size_t k = 0; k < walls.walls.size(); ++k) {
    auto& w = walls.walls[k];
    const double* n = &numbers[kWallNumbers * k];
    w.active = n[0] != 0.0;
    w.displacement = n[1];
    w.velocity = n[2];
    w.velocity_before = n[3];
    w.normal_force = n[4];
    w.normal_impulse = n[5];
    w.work = n[6];
    w.force = {n[7], n[8], n[9]};
    expect_count(g, "in_front_count", static_cast<std::size_t>(counts[k]), w.in_front.size());
    if (at + w.in_front.size() > in_front.size()) g.fail("in_front", "is too short");
    std::copy(in_front.begin() + static_cast<long>(at),
              in_front.begin() + static_cast<long>(at + w.in_front.size()), w.in_front.begin());
    at += w.in_front.size();
  }
  if (g.has("segment_forces")) {  // absent in dumps written before it existed
    const auto forces = g.read_doubles("segment_forces");
    expect_count(g, "segment_forces", forces.size(), 3 * walls.walls.size());
    for (std::size_t k = 0; k < walls.walls.size(); ++k) {
      walls.walls[k].segment_force = {forces[3 * k], forces[3 * k + 1], forces[3 * k + 2]};
    }
  }
}

// Contacts: per interface soft_dt, slave force x y z, active nodes; per pass (in order) the
// friction springs (3 per slave node) and the side memory of shell segments (the contact normal,
// 3 per slave node, and the segment, 1 per slave node); the nodal contact forces of the last
// evaluation (3 per contact node), which the first cycle after the restart applies and counts.
// The search grids are rebuilt: the contact found does not depend on them (docs/contact.md).
constexpr int kContactNumbers = 5;

void write_contacts(const contact::ContactSystem& contacts, const Group& g) {
  std::vector<double> numbers, springs, normals, forces;
  std::vector<std::int32_t> segments;
  for (const auto& c : contacts.interfaces) {
    for (const double v : {c.soft_dt, c.slave_force[0], c.slave_force[1], c.slave_force[2],
                           static_cast<double>(c.active_nodes)}) {
      numbers.push_back(v);
    }
    for (const auto& pass : c.passes) {
      springs.insert(springs.end(), pass.tangential_force.begin(), pass.tangential_force.end());
      normals.insert(normals.end(), pass.contact_normal.begin(), pass.contact_normal.end());
      segments.insert(segments.end(), pass.contact_segment.begin(), pass.contact_segment.end());
    }
  }
  for (const auto i : contacts.nodes) {
    forces.push_back(contacts.force.x[i]);
    forces.push_back(contacts.force.y[i]);
    forces.push_back(contacts.force.z[i]);
  }
  g.set("count", static_cast<std::int64_t>(contacts.interfaces.size()));
  g.write("numbers", span_of(numbers));
  g.write("friction_springs", span_of(springs));
  g.write("contact_normals", span_of(normals));
  g.write("contact_segments", span_of(segments));
  g.write("nodal_forces", span_of(forces));
}

void read_contacts(contact::ContactSystem& contacts, const Group& g) {
  expect_count(g, "count", static_cast<std::size_t>(g.get_int("count")),
               contacts.interfaces.size());
  const auto numbers = g.read_doubles("numbers");
  const auto springs = g.read_doubles("friction_springs");
  const auto normals = g.read_doubles("contact_normals");
  const auto segments = g.read_int32("contact_segments");
  const auto forces = g.read_doubles("nodal_forces");
  expect_count(g, "numbers", numbers.size(), kContactNumbers * contacts.interfaces.size());
  expect_count(g, "nodal_forces", forces.size(), 3 * contacts.nodes.size());
  std::size_t spring_count = 0;
  for (const auto& c : contacts.interfaces) {
    for (const auto& pass : c.passes) spring_count += pass.tangential_force.size();
  }
  expect_count(g, "friction_springs", springs.size(), spring_count);
  expect_count(g, "contact_normals", normals.size(), spring_count);
  expect_count(g, "contact_segments", segments.size(), spring_count / 3);
  std::size_t at = 0;
  for (std::size_t k = 0; k < contacts.interfaces.size(); ++k) {
    auto& c = contacts.interfaces[k];
    const double* n = &numbers[kContactNumbers * k];
    c.soft_dt = n[0];
    c.slave_force = {n[1], n[2], n[3]};
    c.active_nodes = static_cast<std::int64_t>(n[4]);
    for (auto& pass : c.passes) {
      std::copy(springs.begin() + static_cast<long>(at),
                springs.begin() + static_cast<long>(at + pass.tangential_force.size()),
                pass.tangential_force.begin());
      std::copy(normals.begin() + static_cast<long>(at),
                normals.begin() + static_cast<long>(at + pass.contact_normal.size()),
                pass.contact_normal.begin());
      std::copy(segments.begin() + static_cast<long>(at / 3),
                segments.begin() + static_cast<long>(at / 3 + pass.contact_segment.size()),
                pass.contact_segment.begin());
      at += pass.tangential_force.size();
      pass.grid.built = false;
    }
  }
  for (std::size_t j = 0; j < contacts.nodes.size(); ++j) {
    const auto i = contacts.nodes[j];
    contacts.force.x[i] = forces[3 * j];
    contacts.force.y[i] = forces[3 * j + 1];
    contacts.force.z[i] = forces[3 * j + 2];
  }
}

void write_sensors(const sensor::SensorSystem& s, const Group& g) {
  g.write("values", span_of(s.values));
  std::vector<double> velocities;
  for (const auto& n : s.node_sensors) {
    velocities.insert(velocities.end(), n.previous_velocity1.begin(), n.previous_velocity1.end());
    velocities.insert(velocities.end(), n.previous_velocity2.begin(), n.previous_velocity2.end());
  }
  g.write("node_previous_velocity", span_of(velocities));
  std::vector<std::uint8_t> flags;
  std::vector<double> times;
  for (const auto& w : s.switches) {
    for (const bool f : {w.condition, w.windowed, w.pending, w.holding, w.output}) {
      flags.push_back(f);
    }
    times.push_back(w.condition_since);
    times.push_back(w.due);
  }
  g.write("switch_flags", span_of(flags));
  g.write("switch_times", span_of(times));
  std::vector<std::uint8_t> control_flags;
  std::vector<std::int64_t> control_counts;
  for (const auto& c : s.controls) {
    control_flags.push_back(c.on);
    control_flags.push_back(c.finished);
    control_counts.push_back(c.next);
    control_counts.push_back(c.passes_done);
  }
  g.write("control_flags", span_of(control_flags));
  g.write("control_counts", span_of(control_counts));
  std::vector<std::int64_t> event_sets;
  std::vector<std::uint8_t> event_status;
  for (const auto& e : s.events) {
    event_sets.push_back(e.swset);
    event_status.push_back(e.status_on);
  }
  g.write("event_swsets", span_of(event_sets));
  g.write("event_status", span_of(event_status));
  g.set("previous_mid_time", s.previous_mid_time);
  g.set("time", s.time);
  g.set("evaluated", std::int64_t{s.evaluated});
  g.set("changed", std::int64_t{s.changed});
}

void read_sensors(sensor::SensorSystem& s, const Group& g) {
  const auto values = g.read_doubles("values");
  expect_count(g, "values", values.size(), s.values.size());
  s.values = values;
  const auto velocities = g.read_doubles("node_previous_velocity");
  expect_count(g, "node_previous_velocity", velocities.size(), 6 * s.node_sensors.size());
  for (std::size_t k = 0; k < s.node_sensors.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      s.node_sensors[k].previous_velocity1[c] = velocities[6 * k + c];
      s.node_sensors[k].previous_velocity2[c] = velocities[6 * k + 3 + c];
    }
  }
  const auto flags = g.read_bytes("switch_flags");
  const auto times = g.read_doubles("switch_times");
  expect_count(g, "switch_flags", flags.size(), 5 * s.switches.size());
  expect_count(g, "switch_times", times.size(), 2 * s.switches.size());
  for (std::size_t k = 0; k < s.switches.size(); ++k) {
    auto& w = s.switches[k];
    w.condition = flags[5 * k] != 0;
    w.windowed = flags[5 * k + 1] != 0;
    w.pending = flags[5 * k + 2] != 0;
    w.holding = flags[5 * k + 3] != 0;
    w.output = flags[5 * k + 4] != 0;
    w.condition_since = times[2 * k];
    w.due = times[2 * k + 1];
  }
  const auto control_flags = g.read_bytes("control_flags");
  const auto control_counts = g.read_int64("control_counts");
  expect_count(g, "control_flags", control_flags.size(), 2 * s.controls.size());
  expect_count(g, "control_counts", control_counts.size(), 2 * s.controls.size());
  for (std::size_t k = 0; k < s.controls.size(); ++k) {
    s.controls[k].on = control_flags[2 * k] != 0;
    s.controls[k].finished = control_flags[2 * k + 1] != 0;
    s.controls[k].next = static_cast<int>(control_counts[2 * k]);
    s.controls[k].passes_done = static_cast<int>(control_counts[2 * k + 1]);
  }
  const auto event_sets = g.read_int64("event_swsets");
  const auto event_status = g.read_bytes("event_status");
  expect_count(g, "event_status", event_status.size(), event_sets.size());
  if (event_sets.size() > s.controls.size()) g.fail("event_swsets", "has too many events");
  s.events.clear();
  for (std::size_t k = 0; k < event_sets.size(); ++k) {
    s.events.push_back({event_sets[k], event_status[k] != 0});
  }
  s.previous_mid_time = g.get_double("previous_mid_time");
  s.time = g.get_double("time");
  s.evaluated = g.get_int("evaluated") != 0;
  s.changed = g.get_int("changed") != 0;
}

// Flexible bodies (*PART_MODES): the modal state; the modes themselves come from the mode
// database again when the deck is rebuilt.
void write_flexible(const solver::RigidSystem& rigid, const Group& g) {
  g.set("count", static_cast<std::int64_t>(rigid.flexible.size()));
  for (std::size_t k = 0; k < rigid.flexible.size(); ++k) {
    const auto& f = rigid.flexible[k];
    const Group b = g.create_group(fmt::format("body_{}", k));
    b.set("body", static_cast<std::int64_t>(f.body));
    b.set("part", static_cast<std::int64_t>(f.part));
    b.write("q", span_of(f.q));
    b.write("s", span_of(f.s));
    b.write("q_previous", span_of(f.q_previous));
    b.write("s_mid", span_of(f.s_mid));
  }
}

void read_flexible(solver::RigidSystem& rigid, const Group& g) {
  expect_count(g, "count", static_cast<std::size_t>(g.get_int("count")), rigid.flexible.size());
  for (auto& body : rigid.bodies) body.flexible = -1;
  // Matched by part: bodies made flexible by switching are rebuilt after those of the deck.
  std::vector<modal::FlexibleBody> dumped_order;
  for (std::size_t k = 0; k < rigid.flexible.size(); ++k) {
    const Group b = g.group(fmt::format("body_{}", k));
    const auto index = b.get_int("body");
    const auto it = std::find_if(rigid.flexible.begin(), rigid.flexible.end(),
                                 [&](const auto& f) { return f.part == b.get_int("part"); });
    if (index < 0 || static_cast<std::size_t>(index) >= rigid.bodies.size() ||
        it == rigid.flexible.end()) {
      b.fail("body", "does not match the flexible bodies of the rebuilt model");
    }
    dumped_order.push_back(std::move(*it));
    it->part = -1;  // taken
  }
  rigid.flexible = std::move(dumped_order);
  for (std::size_t k = 0; k < rigid.flexible.size(); ++k) {
    auto& f = rigid.flexible[k];
    const Group b = g.group(fmt::format("body_{}", k));
    const auto index = b.get_int("body");
    f.body = static_cast<int>(index);
    rigid.bodies[f.body].flexible = static_cast<int>(k);
    for (auto [name, array] :
         {std::pair{"q", &f.q}, std::pair{"s", &f.s}, std::pair{"q_previous", &f.q_previous},
          std::pair{"s_mid", &f.s_mid}}) {
      const auto values = b.read_doubles(name);
      expect_count(b, name, values.size(), f.mode_count);
      *array = values;
    }
  }
}

// Mass scaling (solver/mass_scaling.hpp): the element factors of the hexahedron, shell and beam
// blocks and the running sums; the nodal masses are in /nodes and the rotational inertias in
// /rotations, the physical masses are rebuilt from the deck.
void write_mass_scaling(const solver::MassScaling& m, const Group& g) {
  g.set("started", std::int64_t{m.started});
  g.set("added_mass", m.added_mass);
  g.set("mass_scaling_work", m.mass_scaling_work);
  g.set("rescaled_cycles", m.rescaled_cycles);
  for (const auto& [family, factors] :
       {std::pair{"hex", &m.hex_factor}, std::pair{"shell", &m.shell_factor},
        std::pair{"beam", &m.beam_factor}}) {
    g.set(fmt::format("{}_blocks", family), static_cast<std::int64_t>(factors->size()));
    for (std::size_t b = 0; b < factors->size(); ++b) {
      g.write(fmt::format("{}_factor_{}", family, b), span_of((*factors)[b]));
    }
  }
}

// The factors of one family's blocks; each block's step_scale is sqrt(s_e), as scale_masses
// sets it. A dump without the family's count (shells and beams) is a dump of a model without it.
template <class Block>
void read_mass_factors(const Group& g, const char* family, std::vector<Block>& blocks,
                       std::vector<std::vector<double>>& factors) {
  const std::string count = fmt::format("{}_blocks", family);
  const std::int64_t n = g.has_attribute(count) ? g.get_int(count) : 0;
  if (n != 0 && n != static_cast<std::int64_t>(blocks.size())) {
    g.fail(count,
           fmt::format("is {}, the rebuilt model has {} {} blocks", n, blocks.size(), family));
  }
  factors.assign(static_cast<std::size_t>(n), {});
  for (std::size_t b = 0; b < factors.size(); ++b) {
    const std::string name = fmt::format("{}_factor_{}", family, b);
    std::vector<double> factor = g.read_doubles(name);
    auto& block = blocks[b];
    if (factor.empty()) {  // a block that was rigid throughout
      block.step_scale.clear();
    } else {
      expect_count(g, name.c_str(), factor.size(), block.size());
      block.step_scale.resize(factor.size());
      for (std::size_t e = 0; e < factor.size(); ++e) {
        if (!(factor[e] > 0.0) || !std::isfinite(factor[e])) {
          g.fail(name, "holds a mass factor that is not positive (the dump is damaged)");
        }
        block.step_scale[e] = std::sqrt(factor[e]);
      }
    }
    factors[b] = std::move(factor);
  }
}

void read_mass_scaling(solver::MassScaling& m, solver::State& state, const Group& g) {
  m.started = g.get_int("started") != 0;
  m.added_mass = g.get_double("added_mass");
  m.mass_scaling_work = g.get_double("mass_scaling_work");
  m.rescaled_cycles = g.get_int("rescaled_cycles");
  read_mass_factors(g, "hex", state.hex_blocks, m.hex_factor);
  read_mass_factors(g, "shell", state.shell_blocks, m.shell_factor);
  read_mass_factors(g, "beam", state.beam_blocks, m.beam_factor);
}

}  // namespace

void SimulationAccess::write_features(Simulation& s, const Group& g) {
  write_switching(s, g.create_group("switching"), s.switcher_.get(), s.automatic_switching_.get());
  write_walls(s.walls_, g.create_group("walls"));
  if (!s.contacts_.empty()) write_contacts(s.contacts_, g.create_group("contacts"));
  if (s.sensors_) write_sensors(*s.sensors_, g.create_group("sensors"));
  if (!s.rigid_.flexible.empty()) write_flexible(s.rigid_, g.create_group("flexible"));
  if (s.mass_scaling_.active()) write_mass_scaling(s.mass_scaling_, g.create_group("mass_scaling"));
}

void SimulationAccess::read_features(Simulation& s, const Group& g) {
  const Group sw = g.group("switching");
  if (sw.get_int("has_switcher") != 0 && !s.switcher_) {
    // The dumped run switched parts on a restart deck without flagging switching.
    s.switcher_ = std::make_unique<switching::PartSwitcher>(s.model_, s.state_);
    s.switcher_->enable_flexible_bodies(s.mode_loader(), s.state_);
  }
  read_switching(sw, s.switcher_.get(), s.automatic_switching_.get(), s.state_.nodes.size());
  if (s.switcher_) s.energy_.frozen_energy = s.switcher_->frozen_energy();
  read_walls(s.walls_, g.group("walls"));
  if (!s.contacts_.empty()) {
    if (!g.has("contacts")) {
      g.fail("contacts", "is missing: the dump was written without contacts, the deck has some");
    }
    read_contacts(s.contacts_, g.group("contacts"));
  }
  if (s.sensors_ && g.has("sensors")) read_sensors(*s.sensors_, g.group("sensors"));
  // Flexible bodies made by switching: again from their mode frames and restored bodies.
  if (s.switcher_ && s.switcher_->flexible_bodies()) {
    auto* flexible = s.switcher_->flexible_bodies();
    const auto frames = flexible->frames();
    for (const auto& [pid, frame] : frames) {
      int index = -1;
      for (std::size_t b = 0; b < s.rigid_.bodies.size(); ++b) {
        const auto& parts = s.rigid_.bodies[b].parts;
        if (std::find(parts.begin(), parts.end(), pid) != parts.end()) index = static_cast<int>(b);
      }
      if (index < 0) sw.fail("flexible_parts", fmt::format("part {} has no rigid body", pid));
      flexible->rebuild(pid, index, frame, s.state_, s.rigid_);
    }
  }
  if (!s.rigid_.flexible.empty()) {
    if (!g.has("flexible")) g.fail("flexible", "is missing: the dump has no flexible bodies");
    read_flexible(s.rigid_, g.group("flexible"));
    s.energy_.modal_elastic = solver::rigid_body_sums(s.rigid_).modal_elastic;
  }
  if (s.mass_scaling_.active()) {
    if (!g.has("mass_scaling")) {
      g.fail("mass_scaling",
             "is missing: the dump was written without mass scaling (DT2MS), "
             "the deck has it");
    }
    read_mass_scaling(s.mass_scaling_, s.state_, g.group("mass_scaling"));
  }
}

}  // namespace rf::restart
