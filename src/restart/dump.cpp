#include "restart/dump.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <system_error>

#include "element/block_state.hpp"
#include "model/error.hpp"
#include "output/output_directory.hpp"
#include "parallel/communicator.hpp"
#include "restart/simulation_access.hpp"
#include "solver/rotational_state_visit.hpp"

namespace rf::restart {

namespace {

using io::h5::Group;

// ---- Generic helpers -------------------------------------------------------------------------

template <class T>
std::vector<T> read_vector(const Group& g, const std::string& name);
template <>
std::vector<double> read_vector<double>(const Group& g, const std::string& name) {
  return g.read_doubles(name);
}
template <>
std::vector<std::int32_t> read_vector<std::int32_t>(const Group& g, const std::string& name) {
  return g.read_int32(name);
}
template <>
std::vector<std::int64_t> read_vector<std::int64_t>(const Group& g, const std::string& name) {
  return g.read_int64(name);
}
template <>
std::vector<std::uint8_t> read_vector<std::uint8_t>(const Group& g, const std::string& name) {
  return g.read_bytes(name);
}

// Reads a dataset that must have exactly n entries (the size the rebuilt model gives).
template <class T>
std::vector<T> read_exact(const Group& g, const std::string& name, std::size_t n) {
  std::vector<T> v = read_vector<T>(g, name);
  if (v.size() != n) {
    g.fail(name, fmt::format("has {} entries where the model rebuilt from the dump's deck needs "
                             "{} (the dump is damaged or does not belong to this model)",
                             v.size(), n));
  }
  return v;
}

template <class T>
void write_vector(const Group& g, const std::string& name, const std::vector<T>& v) {
  g.write(name, std::span<const T>(v.data(), v.size()));
}

void write_vec3(const Group& g, const std::string& name, const solver::Vec3Array& a) {
  write_vector(g, name + "_x", a.x);
  write_vector(g, name + "_y", a.y);
  write_vector(g, name + "_z", a.z);
}

void read_vec3(const Group& g, const std::string& name, solver::Vec3Array& a, std::size_t n) {
  a.x = read_exact<double>(g, name + "_x", n);
  a.y = read_exact<double>(g, name + "_y", n);
  a.z = read_exact<double>(g, name + "_z", n);
}

// A list of texts as one byte array, each text followed by a NUL.
void write_strings(const Group& g, const std::string& name, const std::vector<std::string>& list) {
  std::string joined;
  for (const auto& s : list) {
    joined += s;
    joined.push_back('\0');
  }
  g.write_text(name, joined);
}

std::vector<std::string> read_strings(const Group& g, const std::string& name, std::size_t n) {
  const std::string joined = g.read_text(name);
  std::vector<std::string> list;
  std::size_t start = 0;
  while (start < joined.size()) {
    const std::size_t end = joined.find('\0', start);
    if (end == std::string::npos) g.fail(name, "is not a list of texts (the dump is damaged)");
    list.push_back(joined.substr(start, end - start));
    start = end + 1;
  }
  if (list.size() != n) {
    g.fail(name, fmt::format("holds {} texts where {} were written (the dump is damaged)",
                             list.size(), n));
  }
  return list;
}

std::size_t count_of(const Group& g, const char* name) {
  const std::int64_t n = g.get_int(name);
  if (n < 0) g.fail(name, "is negative (the dump is damaged)");
  return static_cast<std::size_t>(n);
}

// Time functions by ID: curve, else *FUNCTION, else the constant `scale`.
struct TimeFunctionColumns {
  std::vector<std::int64_t> curve, function;
  std::vector<double> scale, shift;
};

model::Id function_id(const model::Model& model, const model::ExpressionFunction* f) {
  for (const auto& [id, function] : model.functions) {
    if (function.evaluator.get() == f) return id;
  }
  throw std::logic_error("restart dump: a time function is not part of the model");
}

void write_time_functions(const Group& g, const std::string& prefix,
                          const std::vector<const solver::ScaledCurve*>& values,
                          const model::Model& model) {
  TimeFunctionColumns c;
  for (const solver::ScaledCurve* v : values) {
    c.curve.push_back(v->curve ? v->curve->id : 0);
    c.function.push_back(v->function ? function_id(model, v->function) : 0);
    c.scale.push_back(v->scale);
    c.shift.push_back(v->shift);
  }
  write_vector(g, prefix + "_curve", c.curve);
  write_vector(g, prefix + "_function", c.function);
  write_vector(g, prefix + "_scale", c.scale);
  write_vector(g, prefix + "_shift", c.shift);
}

void read_time_functions(const Group& g, const std::string& prefix,
                         const std::vector<solver::ScaledCurve*>& values,
                         const model::Model& model) {
  const std::size_t n = values.size();
  const auto curve = read_exact<std::int64_t>(g, prefix + "_curve", n);
  const auto function = read_exact<std::int64_t>(g, prefix + "_function", n);
  const auto scale = read_exact<double>(g, prefix + "_scale", n);
  const auto shift = read_exact<double>(g, prefix + "_shift", n);
  for (std::size_t i = 0; i < n; ++i) {
    solver::ScaledCurve& v = *values[i];
    v = solver::ScaledCurve{};
    v.scale = scale[i];
    v.shift = shift[i];
    if (curve[i] != 0) {
      const auto it = model.curves.find(curve[i]);
      if (it == model.curves.end()) {
        g.fail(prefix + "_curve", fmt::format("refers to load curve {}, which the model does not "
                                              "define",
                                              curve[i]));
      }
      v.curve = &it->second;
    } else if (function[i] != 0) {
      const auto it = model.functions.find(function[i]);
      if (it == model.functions.end()) {
        g.fail(prefix + "_function",
               fmt::format("refers to *FUNCTION {}, which the model does not define", function[i]));
      }
      v.function = it->second.evaluator.get();
    }
  }
}

void write_locations(const Group& g, const std::string& prefix,
                     const std::vector<const model::SourceLocation*>& where) {
  std::vector<std::string> files, keywords;
  std::vector<std::int32_t> lines;
  for (const auto* w : where) {
    files.push_back(w->file);
    keywords.push_back(w->keyword);
    lines.push_back(w->line);
  }
  write_strings(g, prefix + "_file", files);
  write_strings(g, prefix + "_keyword", keywords);
  write_vector(g, prefix + "_line", lines);
}

void read_locations(const Group& g, const std::string& prefix,
                    const std::vector<model::SourceLocation*>& where) {
  const std::size_t n = where.size();
  const auto files = read_strings(g, prefix + "_file", n);
  const auto keywords = read_strings(g, prefix + "_keyword", n);
  const auto lines = read_exact<std::int32_t>(g, prefix + "_line", n);
  for (std::size_t i = 0; i < n; ++i) *where[i] = {files[i], lines[i], keywords[i]};
}

// Fixed-width double fields of a list of objects, packed object-major (object i at
// [width * i, width * (i + 1))). `get(object)` returns a pointer to the object's `width`
// contiguous doubles (a scalar member or an Eigen vector/matrix's data()).
template <class T, class Get>
void write_packed(const Group& g, const std::string& name, const std::vector<T>& objects, int width,
                  Get get) {
  std::vector<double> packed(objects.size() * static_cast<std::size_t>(width));
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const double* p = get(objects[i]);
    for (int k = 0; k < width; ++k) packed[i * width + k] = p[k];
  }
  write_vector(g, name, packed);
}

template <class T, class Get>
void read_packed(const Group& g, const std::string& name, std::vector<T>& objects, int width,
                 Get get) {
  const auto packed = read_exact<double>(g, name, objects.size() * static_cast<std::size_t>(width));
  for (std::size_t i = 0; i < objects.size(); ++i) {
    double* p = get(objects[i]);
    for (int k = 0; k < width; ++k) p[k] = packed[i * width + k];
  }
}

// ---- Rigid bodies ----------------------------------------------------------------------------

// Every double-valued member of a RigidBody, once: the writer and the reader both walk this list,
// so a member added here is dumped and restored. `visit(name, width, get)`.
template <class Visit>
void visit_body_doubles(Visit&& visit) {
  visit("mass", 1, [](auto& b) { return &b.state.mass; });
  visit("centre", 3, [](auto& b) { return b.state.centre.data(); });
  visit("velocity", 3, [](auto& b) { return b.state.velocity.data(); });
  visit("rotation", 9, [](auto& b) { return b.state.rotation.data(); });
  visit("principal_inertia", 3, [](auto& b) { return b.state.principal_inertia.data(); });
  visit("angular_momentum", 3, [](auto& b) { return b.state.angular_momentum.data(); });
  visit("angular_velocity", 3, [](auto& b) { return b.state.angular_velocity.data(); });
  visit("previous_centre", 3, [](auto& b) { return b.state.previous_centre.data(); });
  visit("previous_rotation", 9, [](auto& b) { return b.state.previous_rotation.data(); });
  visit("reaction_impulse", 3, [](auto& b) { return b.state.reaction_impulse.data(); });
  visit("reaction_angular_impulse", 3,
        [](auto& b) { return b.state.reaction_angular_impulse.data(); });
  visit("initial_rotation", 9, [](auto& b) { return b.initial_rotation.data(); });
  visit("output_axes", 9, [](auto& b) { return b.output_axes.data(); });
  visit("velocity_before", 3, [](auto& b) { return b.velocity_before.data(); });
  visit("angular_velocity_before", 3, [](auto& b) { return b.angular_velocity_before.data(); });
  visit("mid_velocity", 3, [](auto& b) { return b.mid_velocity.data(); });
  visit("mid_angular_velocity", 3, [](auto& b) { return b.mid_angular_velocity.data(); });
  visit("force", 3, [](auto& b) { return b.force.data(); });
  visit("torque", 3, [](auto& b) { return b.torque.data(); });
}

// Velocity constraints, 2 counts and 24 numbers per body: axes and values of the rows in use,
// zeros in the unused slots (which hold indeterminate values in memory, and would make equal
// states give different dumps).
constexpr int kConstraintNumbers = 24;

void pack_constraints(const rigid::VelocityConstraints& c, std::int64_t* counts, double* numbers) {
  counts[0] = c.translation_count;
  counts[1] = c.rotation_count;
  std::fill(numbers, numbers + kConstraintNumbers, 0.0);
  for (int k = 0; k < c.translation_count; ++k) {
    for (int d = 0; d < 3; ++d) numbers[3 * k + d] = c.translation_axis[k][d];
    numbers[18 + k] = c.translation_value[k];
  }
  for (int k = 0; k < c.rotation_count; ++k) {
    for (int d = 0; d < 3; ++d) numbers[9 + 3 * k + d] = c.rotation_axis[k][d];
    numbers[21 + k] = c.rotation_value[k];
  }
}

// False when a count is outside 0..3.
bool unpack_constraints(const std::int64_t* counts, const double* numbers,
                        rigid::VelocityConstraints& c) {
  if (counts[0] < 0 || counts[0] > 3 || counts[1] < 0 || counts[1] > 3) return false;
  c.translation_count = static_cast<int>(counts[0]);
  c.rotation_count = static_cast<int>(counts[1]);
  for (int k = 0; k < 3; ++k) {
    for (int d = 0; d < 3; ++d) {
      c.translation_axis[k][d] = numbers[3 * k + d];
      c.rotation_axis[k][d] = numbers[9 + 3 * k + d];
    }
    c.translation_value[k] = numbers[18 + k];
    c.rotation_value[k] = numbers[21 + k];
  }
  return true;
}

// The permanent constraints (CMO, _SPC) and the last step's (prescribed motion) of each body.
template <class Visit>
void visit_body_constraints(Visit&& visit) {
  visit(
      "constraints", [](auto& b) -> auto& { return b.state.constraints; });
  visit(
      "step_constraints", [](auto& b) -> auto& { return b.step_constraints; });
}

// Integer-valued members, the same way (stored as int64).
template <class Visit>
void visit_body_integers(Visit&& visit) {
  using Body = solver::RigidBody;
  visit(
      "id", [](const Body& b) { return std::int64_t{b.id}; },
      [](Body& b, std::int64_t v) { b.id = v; });
  visit(
      "nodal", [](const Body& b) { return std::int64_t{b.nodal}; },
      [](Body& b, std::int64_t v) { b.nodal = v != 0; });
  visit(
      "weld", [](const Body& b) { return std::int64_t{b.weld}; },
      [](Body& b, std::int64_t v) { b.weld = v != 0; });
  visit(
      "inertia_from_card", [](const Body& b) { return std::int64_t{b.inertia_from_card}; },
      [](Body& b, std::int64_t v) { b.inertia_from_card = v != 0; });
  visit(
      "shares_nodes", [](const Body& b) { return std::int64_t{b.shares_nodes}; },
      [](Body& b, std::int64_t v) { b.shares_nodes = v != 0; });
  visit(
      "update", [](const Body& b) { return static_cast<std::int64_t>(b.update); },
      [](Body& b, std::int64_t v) {
        b.update = v == 0 ? solver::NodeUpdate::kLinear : solver::NodeUpdate::kCurvilinear;
      });
}

}  // namespace

void write_bodies(const Group& g, const std::vector<solver::RigidBody>& bodies) {
  g.set("count", static_cast<std::int64_t>(bodies.size()));
  visit_body_doubles([&](const std::string& name, int width, auto get) {
    write_packed(g, name, bodies, width, get);
  });
  visit_body_integers([&](const std::string& name, auto get, auto) {
    std::vector<std::int64_t> column;
    for (const auto& b : bodies) column.push_back(get(b));
    write_vector(g, name, column);
  });
  visit_body_constraints([&](const std::string& name, auto get) {
    std::vector<std::int64_t> counts(2 * bodies.size());
    std::vector<double> numbers(kConstraintNumbers * bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      pack_constraints(get(bodies[i]), &counts[2 * i], &numbers[kConstraintNumbers * i]);
    }
    write_vector(g, name + "_counts", counts);
    write_vector(g, name + "_numbers", numbers);
  });
  // Lists of varying length: offsets (count + 1) and the concatenated entries.
  std::vector<std::int64_t> part_offset{0}, node_offset{0}, parts;
  std::vector<std::int32_t> nodes;
  std::vector<double> bx, by, bz;
  for (const auto& b : bodies) {
    parts.insert(parts.end(), b.parts.begin(), b.parts.end());
    part_offset.push_back(static_cast<std::int64_t>(parts.size()));
    nodes.insert(nodes.end(), b.nodes.begin(), b.nodes.end());
    node_offset.push_back(static_cast<std::int64_t>(nodes.size()));
    bx.insert(bx.end(), b.body_coordinates.x.begin(), b.body_coordinates.x.end());
    by.insert(by.end(), b.body_coordinates.y.begin(), b.body_coordinates.y.end());
    bz.insert(bz.end(), b.body_coordinates.z.begin(), b.body_coordinates.z.end());
  }
  write_vector(g, "part_offset", part_offset);
  write_vector(g, "parts", parts);
  write_vector(g, "node_offset", node_offset);
  write_vector(g, "nodes", nodes);
  write_vector(g, "body_coordinates_x", bx);
  write_vector(g, "body_coordinates_y", by);
  write_vector(g, "body_coordinates_z", bz);
}

// Offsets of a list-valued field: count + 1 ascending values from 0 to `total`.
namespace {

std::vector<std::int64_t> read_offsets(const Group& g, const std::string& name, std::size_t count,
                                       std::size_t total) {
  auto offset = read_exact<std::int64_t>(g, name, count + 1);
  bool valid = offset.front() == 0 && offset.back() == static_cast<std::int64_t>(total);
  for (std::size_t i = 0; valid && i < count; ++i) valid = offset[i] <= offset[i + 1];
  if (!valid) g.fail(name, "are not valid list offsets (the dump is damaged)");
  return offset;
}

}  // namespace

std::vector<solver::RigidBody> read_bodies(const Group& g, std::size_t node_count) {
  std::vector<solver::RigidBody> bodies(count_of(g, "count"));
  const std::size_t n = bodies.size();
  visit_body_doubles([&](const std::string& name, int width, auto get) {
    read_packed(g, name, bodies, width, get);
  });
  visit_body_integers([&](const std::string& name, auto, auto set) {
    const auto column = read_exact<std::int64_t>(g, name, n);
    for (std::size_t i = 0; i < n; ++i) set(bodies[i], column[i]);
  });
  visit_body_constraints([&](const std::string& name, auto get) {
    const auto counts = read_exact<std::int64_t>(g, name + "_counts", 2 * n);
    const auto numbers = read_exact<double>(g, name + "_numbers", kConstraintNumbers * n);
    for (std::size_t i = 0; i < n; ++i) {
      if (!unpack_constraints(&counts[2 * i], &numbers[kConstraintNumbers * i], get(bodies[i]))) {
        g.fail(name + "_counts", "holds a constraint count outside 0..3 (the dump is damaged)");
      }
    }
  });
  const auto parts = g.read_int64("parts");
  const auto nodes = g.read_int32("nodes");
  const auto part_offset = read_offsets(g, "part_offset", n, parts.size());
  const auto node_offset = read_offsets(g, "node_offset", n, nodes.size());
  const auto bx = read_exact<double>(g, "body_coordinates_x", nodes.size());
  const auto by = read_exact<double>(g, "body_coordinates_y", nodes.size());
  const auto bz = read_exact<double>(g, "body_coordinates_z", nodes.size());
  for (const std::int32_t node : nodes) {
    if (node < 0 || static_cast<std::size_t>(node) >= node_count) {
      g.fail("nodes",
             fmt::format("holds node index {} outside the model's {} nodes", node, node_count));
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    auto& b = bodies[i];
    b.parts.assign(parts.begin() + part_offset[i], parts.begin() + part_offset[i + 1]);
    b.nodes.assign(nodes.begin() + node_offset[i], nodes.begin() + node_offset[i + 1]);
    b.body_coordinates.x.assign(bx.begin() + node_offset[i], bx.begin() + node_offset[i + 1]);
    b.body_coordinates.y.assign(by.begin() + node_offset[i], by.begin() + node_offset[i + 1]);
    b.body_coordinates.z.assign(bz.begin() + node_offset[i], bz.begin() + node_offset[i + 1]);
  }
  return bodies;
}

namespace {

void check_body_index(const Group& g, const char* name, std::int64_t index, std::size_t bodies) {
  if (index < 0 || static_cast<std::size_t>(index) >= bodies) {
    g.fail(name, fmt::format("refers to rigid body {} of {} (the dump is damaged)", index, bodies));
  }
}

void check_node_index(const Group& g, const char* name, std::int64_t index, std::size_t nodes) {
  if (index < 0 || static_cast<std::size_t>(index) >= nodes) {
    g.fail(name, fmt::format("holds node index {} outside the model's {} nodes", index, nodes));
  }
}

void check_axis(const Group& g, const char* name, std::int64_t axis) {
  if (axis < 0 || axis > 2) g.fail(name, "holds an axis outside 0..2 (the dump is damaged)");
}

}  // namespace

// ---- Model input -----------------------------------------------------------------------------

void write_model_input(const Group& g, const ModelInput& input) {
  g.set("main_deck", input.main_deck);
  g.set("dialect", input.dialect);
  g.set("file_count", static_cast<std::int64_t>(input.files.size()));
  std::vector<std::string> names;
  std::size_t i = 0;
  for (const auto& [name, text] : input.files) {
    names.push_back(name);
    g.write_text(fmt::format("file_{:04d}", i++), text);
  }
  write_strings(g, "file_names", names);
  std::vector<std::string> override_names;
  std::vector<double> override_values;
  for (const auto& [name, value] : input.overrides) {
    override_names.push_back(name);
    override_values.push_back(value);
  }
  g.set("override_count", static_cast<std::int64_t>(override_names.size()));
  write_strings(g, "override_names", override_names);
  write_vector(g, "override_values", override_values);
}

ModelInput read_model_input(const Group& g) {
  ModelInput input;
  input.main_deck = g.get_string("main_deck");
  input.dialect = g.get_string("dialect");
  const std::size_t files = count_of(g, "file_count");
  const auto names = read_strings(g, "file_names", files);
  for (std::size_t i = 0; i < files; ++i) {
    input.files[names[i]] = g.read_text(fmt::format("file_{:04d}", i));
  }
  if (!input.files.count(input.main_deck)) {
    g.fail("file_names", fmt::format("does not contain the main deck '{}'", input.main_deck));
  }
  const std::size_t overrides = count_of(g, "override_count");
  const auto override_names = read_strings(g, "override_names", overrides);
  const auto override_values = read_exact<double>(g, "override_values", overrides);
  for (std::size_t i = 0; i < overrides; ++i)
    input.overrides[override_names[i]] = override_values[i];
  return input;
}

// ---- Nodes -----------------------------------------------------------------------------------

void write_nodes(const Group& g, const solver::NodalState& nodes,
                 const solver::Vec3Array& v_previous) {
  g.set("count", static_cast<std::int64_t>(nodes.size()));
  write_vector(g, "id", nodes.id);
  write_vec3(g, "x0", nodes.x0);
  write_vec3(g, "x", nodes.x);
  write_vec3(g, "v", nodes.v);
  write_vec3(g, "a", nodes.a);
  write_vec3(g, "f_int", nodes.f_int);
  write_vec3(g, "f_ext", nodes.f_ext);
  write_vector(g, "mass", nodes.mass);
  write_vec3(g, "v_previous", v_previous);
}

void read_nodes(const Group& g, solver::NodalState& nodes, solver::Vec3Array& v_previous) {
  const std::size_t n = nodes.size();
  if (count_of(g, "count") != n) {
    g.fail("count", fmt::format("is {} nodes, the model rebuilt from the dump's deck has {}",
                                g.get_int("count"), n));
  }
  if (read_exact<std::int64_t>(g, "id", n) != nodes.id) {
    g.fail("id", "differs from the node IDs of the model rebuilt from the dump's deck");
  }
  read_vec3(g, "x0", nodes.x0, n);
  read_vec3(g, "x", nodes.x, n);
  read_vec3(g, "v", nodes.v, n);
  read_vec3(g, "a", nodes.a, n);
  read_vec3(g, "f_int", nodes.f_int, n);
  read_vec3(g, "f_ext", nodes.f_ext, n);
  nodes.mass = read_exact<double>(g, "mass", n);
  read_vec3(g, "v_previous", v_previous, n);
}

// ---- Element blocks --------------------------------------------------------------------------

void write_hex_blocks(const Group& g, const std::vector<element::HexBlock>& blocks) {
  g.set("count", static_cast<std::int64_t>(blocks.size()));
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const element::HexBlock& block = blocks[b];
    const Group bg = g.create_group(fmt::format("{:04d}", b));
    bg.set("part_id", std::int64_t{block.part_id});
    bg.set("order", std::int64_t{block.order});
    bg.set("elform", std::int64_t{block.elform});
    bg.set("rigid", std::int64_t{block.rigid});
    bg.set("size", static_cast<std::int64_t>(block.size()));
    write_vector(bg, "element_id", block.element_id);
    element::visit_hex_state(block, [&](const std::string& name, const std::vector<double>& array) {
      write_vector(bg, name, array);
    });
  }
}

void write_discrete_blocks(const Group& g, const std::vector<element::DiscreteBlock>& blocks) {
  std::vector<std::int64_t> part_id, size;
  std::vector<double> spring_energy, damper_energy, axial_force, force;
  for (const auto& block : blocks) {
    part_id.push_back(block.part_id);
    size.push_back(static_cast<std::int64_t>(block.size()));
    spring_energy.push_back(block.spring_energy);
    damper_energy.push_back(block.damper_energy);
    axial_force.insert(axial_force.end(), block.axial_force.begin(), block.axial_force.end());
    force.insert(force.end(), block.force.begin(), block.force.end());
  }
  // The slots of the last evaluation: the next step's work (spring and damper energy) uses them.
  g.write("force", std::span<const double>(force));
  g.write("part_id", std::span<const std::int64_t>(part_id));
  g.write("size", std::span<const std::int64_t>(size));
  g.write("spring_energy", std::span<const double>(spring_energy));
  g.write("damper_energy", std::span<const double>(damper_energy));
  g.write("axial_force", std::span<const double>(axial_force));
}

void read_discrete_blocks(const Group& g, std::vector<element::DiscreteBlock>& blocks) {
  const std::vector<std::int64_t> part_id = g.read_int64("part_id");
  const std::vector<std::int64_t> size = g.read_int64("size");
  const std::vector<double> spring_energy = g.read_doubles("spring_energy");
  const std::vector<double> damper_energy = g.read_doubles("damper_energy");
  const std::vector<double> axial_force = g.read_doubles("axial_force");
  const std::vector<double> force = g.read_doubles("force");
  std::size_t total = 0;
  for (const auto& block : blocks) total += block.size();
  if (part_id.size() != blocks.size() || size.size() != blocks.size() ||
      spring_energy.size() != blocks.size() || damper_energy.size() != blocks.size() ||
      axial_force.size() != total || force.size() != element::kDiscreteSlot * total) {
    g.fail("part_id", fmt::format("describes {} discrete blocks, the model rebuilt from the "
                                  "dump's deck has {}",
                                  part_id.size(), blocks.size()));
  }
  std::size_t at = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    auto& block = blocks[b];
    if (part_id[b] != block.part_id || size[b] != static_cast<std::int64_t>(block.size())) {
      g.fail("part_id", fmt::format("discrete block {} is part {} ({} elements), the rebuilt "
                                    "model has part {} ({} elements)",
                                    b, part_id[b], size[b], block.part_id, block.size()));
    }
    block.spring_energy = spring_energy[b];
    block.damper_energy = damper_energy[b];
    std::copy(axial_force.begin() + static_cast<std::ptrdiff_t>(at),
              axial_force.begin() + static_cast<std::ptrdiff_t>(at + block.size()),
              block.axial_force.begin());
    std::copy(
        force.begin() + static_cast<std::ptrdiff_t>(element::kDiscreteSlot * at),
        force.begin() + static_cast<std::ptrdiff_t>(element::kDiscreteSlot * (at + block.size())),
        block.force.begin());
    at += block.size();
  }
}

void read_hex_blocks(const Group& g, std::vector<element::HexBlock>& blocks) {
  if (count_of(g, "count") != blocks.size()) {
    g.fail("count", fmt::format("is {} element blocks, the model rebuilt from the dump's deck has "
                                "{}",
                                g.get_int("count"), blocks.size()));
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    element::HexBlock& block = blocks[b];
    const Group bg = g.group(fmt::format("{:04d}", b));
    if (bg.get_int("part_id") != block.part_id || bg.get_int("order") != block.order ||
        bg.get_int("elform") != block.elform || count_of(bg, "size") != block.size()) {
      g.fail(
          fmt::format("{:04d}", b),
          fmt::format("describes part {} (order {}, ELFORM {}, {} elements), the rebuilt "
                      "model has part {} (order {}, ELFORM {}, {} elements) here",
                      bg.get_int("part_id"), bg.get_int("order"), bg.get_int("elform"),
                      bg.get_int("size"), block.part_id, block.order, block.elform, block.size()));
    }
    if (read_exact<std::int64_t>(bg, "element_id", block.size()) != block.element_id) {
      bg.fail("element_id", "differs from the element IDs of the rebuilt model");
    }
    const bool dumped_rigid = bg.get_int("rigid") != 0;
    if (block.rigid && !dumped_rigid) {
      // *MAT_RIGID blocks have no assembly slots and never become deformable.
      bg.fail("rigid", fmt::format("says *MAT_RIGID part {} was deformable (the dump is "
                                   "damaged or from another deck)",
                                   block.part_id));
    }
    // A part rigid by switching keeps its (zeroed) assembly slots: only the flag changes.
    block.rigid = dumped_rigid;
    element::visit_hex_state(block, [&](const std::string& name, std::vector<double>& array) {
      array = read_exact<double>(bg, name, array.size());
    });
  }
}

// ---- Shells, beams and nodal rotations ---------------------------------------------------------

namespace {

// One group per block of a structural family: what identifies the block (part, ELFORM, rigid
// flag, element IDs) and the arrays its family's visitor names (visit_shell_state,
// visit_beam_state), the material's history fields among them (`history_<name>`).
template <class Block, class VisitState>
void write_structural_blocks(const Group& g, const std::vector<Block>& blocks,
                             VisitState visit_state) {
  g.set("count", static_cast<std::int64_t>(blocks.size()));
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const Block& block = blocks[b];
    const Group bg = g.create_group(fmt::format("{:04d}", b));
    bg.set("part_id", std::int64_t{block.part_id});
    bg.set("elform", std::int64_t{block.elform});
    bg.set("rigid", std::int64_t{block.rigid});
    bg.set("size", static_cast<std::int64_t>(block.size()));
    write_vector(bg, "element_id", block.element_id);
    visit_state(block, [&](const std::string& name, const std::vector<double>& array) {
      write_vector(bg, name, array);
    });
  }
}

template <class Block, class VisitState>
void read_structural_blocks(const Group& g, std::vector<Block>& blocks, const char* family,
                            VisitState visit_state) {
  if (count_of(g, "count") != blocks.size()) {
    g.fail("count", fmt::format("is {} {} blocks, the model rebuilt from the dump's deck has {}",
                                g.get_int("count"), family, blocks.size()));
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    Block& block = blocks[b];
    const std::string name = fmt::format("{:04d}", b);
    const Group bg = g.group(name);
    if (bg.get_int("part_id") != block.part_id || bg.get_int("elform") != block.elform ||
        count_of(bg, "size") != block.size()) {
      g.fail(name,
             fmt::format("describes {} part {} (ELFORM {}, {} elements), the model rebuilt "
                         "from the dump's deck has {} part {} (ELFORM {}, {} elements) here",
                         family, bg.get_int("part_id"), bg.get_int("elform"), bg.get_int("size"),
                         family, block.part_id, block.elform, block.size()));
    }
    if (read_exact<std::int64_t>(bg, "element_id", block.size()) != block.element_id) {
      bg.fail("element_id", fmt::format("differs from the element IDs of {} part {} of the "
                                        "rebuilt model",
                                        family, block.part_id));
    }
    const bool dumped_rigid = bg.get_int("rigid") != 0;
    if (block.rigid && !dumped_rigid) {
      // *MAT_RIGID blocks have no force slots and never become deformable.
      bg.fail("rigid", fmt::format("says *MAT_RIGID {} part {} was deformable (the dump is "
                                   "damaged or from another deck)",
                                   family, block.part_id));
    }
    // A part rigid by switching keeps its (zeroed) force slots: only the flag changes.
    block.rigid = dumped_rigid;
    visit_state(block, [&](const std::string& dataset, std::vector<double>& array) {
      if (!bg.has(dataset)) {
        bg.fail(dataset, fmt::format("is missing: {} part {} of the rebuilt model has this state "
                                     "(another material or formulation than the dumped run's)",
                                     family, block.part_id));
      }
      array = read_exact<double>(bg, dataset, array.size());
    });
  }
}

}  // namespace

void write_shell_blocks(const Group& g, const std::vector<element::ShellBlock>& blocks) {
  write_structural_blocks(
      g, blocks, [](const auto& block, auto&& visit) { element::visit_shell_state(block, visit); });
}

void read_shell_blocks(const Group& g, std::vector<element::ShellBlock>& blocks) {
  read_structural_blocks(g, blocks, "shell", [](auto& block, auto&& visit) {
    element::visit_shell_state(block, visit);
  });
}

void write_beam_blocks(const Group& g, const std::vector<element::BeamBlock>& blocks) {
  write_structural_blocks(
      g, blocks, [](const auto& block, auto&& visit) { element::visit_beam_state(block, visit); });
}

void read_beam_blocks(const Group& g, std::vector<element::BeamBlock>& blocks) {
  read_structural_blocks(g, blocks, "beam", [](auto& block, auto&& visit) {
    element::visit_beam_state(block, visit);
  });
}

void write_rotations(const Group& g, const solver::RotationalState& rotations) {
  g.set("count", static_cast<std::int64_t>(rotations.size()));
  write_vector(g, "node", rotations.node);
  solver::visit_rotational_state(rotations,
                                 [&](const std::string& name, const std::vector<double>& array) {
                                   write_vector(g, name, array);
                                 });
}

void read_rotations(const Group& g, solver::RotationalState& rotations) {
  const std::size_t n = rotations.size();
  if (count_of(g, "count") != n) {
    g.fail("count", fmt::format("is {} nodes with rotations, the model rebuilt from the dump's "
                                "deck has {}",
                                g.get_int("count"), n));
  }
  if (read_exact<std::int32_t>(g, "node", n) != rotations.node) {
    g.fail("node",
           "differs from the nodes with rotations of the model rebuilt from the dump's "
           "deck");
  }
  solver::visit_rotational_state(rotations, [&](const std::string& name, std::vector<double>& a) {
    a = read_exact<double>(g, name, a.size());
  });
}

// ---- Rigid system ----------------------------------------------------------------------------

void write_rigid_system(const Group& g, const solver::RigidSystem& rigid,
                        const model::Model& model) {
  write_vector(g, "body_of_node", rigid.body_of_node);
  write_bodies(g.create_group("bodies"), rigid.bodies);

  const Group mg = g.create_group("motions");
  const auto& motions = rigid.motions;
  mg.set("count", static_cast<std::int64_t>(motions.size()));
  std::vector<std::int32_t> body, vad;
  std::vector<std::uint8_t> rotation, body_fixed;
  std::vector<const solver::ScaledCurve*> values;
  std::vector<const model::SourceLocation*> where;
  for (const auto& m : motions) {
    body.push_back(m.body);
    vad.push_back(m.vad);
    rotation.push_back(m.rotation);
    body_fixed.push_back(m.body_fixed);
    values.push_back(&m.value);
    where.push_back(&m.where);
  }
  write_vector(mg, "body", body);
  write_vector(mg, "vad", vad);
  write_vector(mg, "rotation", rotation);
  write_vector(mg, "body_fixed", body_fixed);
  write_packed(mg, "axis", motions, 3, [](auto& m) { return m.axis.data(); });
  write_packed(mg, "birth", motions, 1, [](auto& m) { return &m.birth; });
  write_packed(mg, "death", motions, 1, [](auto& m) { return &m.death; });
  write_packed(mg, "reference", motions, 1, [](auto& m) { return &m.reference; });
  write_packed(mg, "travelled", motions, 1, [](auto& m) { return &m.travelled; });
  write_time_functions(mg, "value", values, model);
  write_locations(mg, "where", where);

  const Group lg = g.create_group("loads");
  const auto& loads = rigid.loads;
  lg.set("count", static_cast<std::int64_t>(loads.size()));
  std::vector<std::int32_t> load_body, axis;
  std::vector<std::uint8_t> moment;
  std::vector<const solver::ScaledCurve*> load_values;
  for (const auto& l : loads) {
    load_body.push_back(l.body);
    axis.push_back(l.axis);
    moment.push_back(l.moment);
    load_values.push_back(&l.value);
  }
  write_vector(lg, "body", load_body);
  write_vector(lg, "axis", axis);
  write_vector(lg, "moment", moment);
  write_time_functions(lg, "value", load_values, model);
}

void read_rigid_system(const Group& g, solver::RigidSystem& rigid, const model::Model& model,
                       std::size_t node_count) {
  rigid.bodies = read_bodies(g.group("bodies"), node_count);
  const std::size_t bodies = rigid.bodies.size();
  rigid.body_of_node = g.read_int32("body_of_node");
  // Empty when the model has no rigid bodies (RigidSystem::is_rigid), else one per node.
  if (!rigid.body_of_node.empty() && rigid.body_of_node.size() != node_count) {
    g.fail("body_of_node", fmt::format("has {} entries for a model of {} nodes",
                                       rigid.body_of_node.size(), node_count));
  }
  for (const std::int32_t b : rigid.body_of_node) {
    if (b < -1 || b >= static_cast<std::int64_t>(bodies)) {
      g.fail("body_of_node", fmt::format("refers to rigid body {} of {}", b, bodies));
    }
  }

  const Group mg = g.group("motions");
  const std::size_t nm = count_of(mg, "count");
  rigid.motions.assign(nm, solver::RigidMotion{});
  const auto body = read_exact<std::int32_t>(mg, "body", nm);
  const auto vad = read_exact<std::int32_t>(mg, "vad", nm);
  const auto rotation = read_exact<std::uint8_t>(mg, "rotation", nm);
  const auto body_fixed = read_exact<std::uint8_t>(mg, "body_fixed", nm);
  std::vector<solver::ScaledCurve*> values;
  std::vector<model::SourceLocation*> where;
  for (std::size_t i = 0; i < nm; ++i) {
    auto& m = rigid.motions[i];
    check_body_index(mg, "body", body[i], bodies);
    if (vad[i] < 0 || vad[i] > 2) mg.fail("vad", "holds a VAD outside 0..2");
    m.body = body[i];
    m.vad = vad[i];
    m.rotation = rotation[i] != 0;
    m.body_fixed = body_fixed[i] != 0;
    values.push_back(&m.value);
    where.push_back(&m.where);
  }
  read_packed(mg, "axis", rigid.motions, 3, [](auto& m) { return m.axis.data(); });
  read_packed(mg, "birth", rigid.motions, 1, [](auto& m) { return &m.birth; });
  read_packed(mg, "death", rigid.motions, 1, [](auto& m) { return &m.death; });
  read_packed(mg, "reference", rigid.motions, 1, [](auto& m) { return &m.reference; });
  read_packed(mg, "travelled", rigid.motions, 1, [](auto& m) { return &m.travelled; });
  read_time_functions(mg, "value", values, model);
  read_locations(mg, "where", where);

  const Group lg = g.group("loads");
  const std::size_t nl = count_of(lg, "count");
  rigid.loads.assign(nl, solver::RigidLoadTerm{});
  const auto load_body = read_exact<std::int32_t>(lg, "body", nl);
  const auto axis = read_exact<std::int32_t>(lg, "axis", nl);
  const auto moment = read_exact<std::uint8_t>(lg, "moment", nl);
  std::vector<solver::ScaledCurve*> load_values;
  for (std::size_t i = 0; i < nl; ++i) {
    auto& l = rigid.loads[i];
    check_body_index(lg, "body", load_body[i], bodies);
    check_axis(lg, "axis", axis[i]);
    l.body = load_body[i];
    l.axis = axis[i];
    l.moment = moment[i] != 0;
    load_values.push_back(&l.value);
  }
  read_time_functions(lg, "value", load_values, model);
}

// ---- Boundary conditions ---------------------------------------------------------------------

void write_boundary(const Group& g, const solver::Boundary& boundary, const model::Model& model) {
  write_vector(g, "fixed", boundary.fixed);
  write_vector(g, "constrained_nodes", boundary.constrained_nodes);
  write_vector(g, "body_force_mass", boundary.body_force_mass);
  // The damping forces in f_ext (their work share is summed in the next cycle); the damping
  // terms themselves are rebuilt from the deck.
  if (!boundary.damping.empty()) write_vec3(g, "damping_force", boundary.damping.force);
  if (!boundary.damping.empty() && boundary.damping.moment.size() > 0)
    write_vec3(g, "damping_moment", boundary.damping.moment);

  const Group pg = g.create_group("prescribed");
  const auto& prescribed = boundary.prescribed;
  pg.set("count", static_cast<std::int64_t>(prescribed.size()));
  std::vector<std::int32_t> node, axis, vad;
  std::vector<const solver::ScaledCurve*> values;
  for (const auto& p : prescribed) {
    node.push_back(p.node);
    axis.push_back(p.axis);
    vad.push_back(p.vad);
    values.push_back(&p.value);
  }
  write_vector(pg, "node", node);
  write_vector(pg, "axis", axis);
  write_vector(pg, "vad", vad);
  write_packed(pg, "birth", prescribed, 1, [](auto& p) { return &p.birth; });
  write_packed(pg, "death", prescribed, 1, [](auto& p) { return &p.death; });
  write_time_functions(pg, "value", values, model);
  // DOF 9..11 (rotation about an axis): the axis and its centre; absent in older dumps.
  std::vector<std::int32_t> rotation;
  for (const auto& p : prescribed) rotation.push_back(p.rotation);
  write_vector(pg, "rotation", rotation);
  write_packed(pg, "centre", prescribed, 2, [](auto& p) { return p.centre.data(); });

  const Group fg = g.create_group("nodal_forces");
  fg.set("count", static_cast<std::int64_t>(boundary.nodal_forces.size()));
  std::vector<std::int32_t> force_node, force_axis;
  std::vector<const solver::ScaledCurve*> force_values;
  for (const auto& f : boundary.nodal_forces) {
    force_node.push_back(f.node);
    force_axis.push_back(f.axis);
    force_values.push_back(&f.value);
  }
  write_vector(fg, "node", force_node);
  write_vector(fg, "axis", force_axis);
  write_time_functions(fg, "value", force_values, model);

  const Group ag = g.create_group("body_accelerations");
  ag.set("count", static_cast<std::int64_t>(boundary.body_accelerations.size()));
  std::vector<std::int32_t> acceleration_axis;
  std::vector<const solver::ScaledCurve*> acceleration_values;
  for (const auto& a : boundary.body_accelerations) {
    acceleration_axis.push_back(a.axis);
    acceleration_values.push_back(&a.value);
  }
  write_vector(ag, "axis", acceleration_axis);
  write_time_functions(ag, "value", acceleration_values, model);
}

void read_boundary(const Group& g, solver::Boundary& boundary, const model::Model& model) {
  const std::size_t n = boundary.fixed.size();  // one per node in the rebuilt model
  boundary.fixed = read_exact<std::uint8_t>(g, "fixed", n);
  boundary.constrained_nodes = g.read_int32("constrained_nodes");
  for (const auto i : boundary.constrained_nodes) check_node_index(g, "constrained_nodes", i, n);
  boundary.body_force_mass =
      read_exact<double>(g, "body_force_mass", boundary.body_force_mass.size());
  if (!boundary.damping.empty()) {
    if (!g.has("damping_force_x")) {
      g.fail("damping_force",
             "is missing: the dump was written without the deck's *DAMPING_* "
             "cards");
    }
    read_vec3(g, "damping_force", boundary.damping.force, n);
    if (boundary.damping.moment.size() > 0) {
      if (!g.has("damping_moment_x")) {
        g.fail("damping_moment",
               "is missing: the dump was written by a version that did not damp "
               "the spins of shell and beam nodes; restart with that version");
      }
      read_vec3(g, "damping_moment", boundary.damping.moment, boundary.damping.moment.size());
    }
  }

  const Group pg = g.group("prescribed");
  const std::size_t np = count_of(pg, "count");
  boundary.prescribed.assign(np, solver::PrescribedDof{});
  const auto node = read_exact<std::int32_t>(pg, "node", np);
  const auto axis = read_exact<std::int32_t>(pg, "axis", np);
  const auto vad = read_exact<std::int32_t>(pg, "vad", np);
  std::vector<solver::ScaledCurve*> values;
  for (std::size_t i = 0; i < np; ++i) {
    auto& p = boundary.prescribed[i];
    check_node_index(pg, "node", node[i], n);
    check_axis(pg, "axis", axis[i]);
    if (vad[i] < 0 || vad[i] > 2) pg.fail("vad", "holds a VAD outside 0..2");
    p.node = node[i];
    p.axis = axis[i];
    p.vad = vad[i];
    values.push_back(&p.value);
  }
  read_packed(pg, "birth", boundary.prescribed, 1, [](auto& p) { return &p.birth; });
  read_packed(pg, "death", boundary.prescribed, 1, [](auto& p) { return &p.death; });
  read_time_functions(pg, "value", values, model);
  if (pg.has("rotation")) {
    const auto rotation = read_exact<std::int32_t>(pg, "rotation", np);
    for (std::size_t i = 0; i < np; ++i) {
      if (rotation[i] < -1 || rotation[i] > 2) pg.fail("rotation", "holds an axis outside -1..2");
      boundary.prescribed[i].rotation = rotation[i];
    }
    read_packed(pg, "centre", boundary.prescribed, 2, [](auto& p) { return p.centre.data(); });
  }

  const Group fg = g.group("nodal_forces");
  const std::size_t nf = count_of(fg, "count");
  boundary.nodal_forces.assign(nf, solver::NodalForce{});
  const auto force_node = read_exact<std::int32_t>(fg, "node", nf);
  const auto force_axis = read_exact<std::int32_t>(fg, "axis", nf);
  std::vector<solver::ScaledCurve*> force_values;
  for (std::size_t i = 0; i < nf; ++i) {
    check_node_index(fg, "node", force_node[i], n);
    check_axis(fg, "axis", force_axis[i]);
    boundary.nodal_forces[i].node = force_node[i];
    boundary.nodal_forces[i].axis = force_axis[i];
    force_values.push_back(&boundary.nodal_forces[i].value);
  }
  read_time_functions(fg, "value", force_values, model);

  const Group ag = g.group("body_accelerations");
  const std::size_t na = count_of(ag, "count");
  boundary.body_accelerations.assign(na, solver::BodyAcceleration{});
  const auto acceleration_axis = read_exact<std::int32_t>(ag, "axis", na);
  std::vector<solver::ScaledCurve*> acceleration_values;
  for (std::size_t i = 0; i < na; ++i) {
    check_axis(ag, "axis", acceleration_axis[i]);
    boundary.body_accelerations[i].axis = acceleration_axis[i];
    acceleration_values.push_back(&boundary.body_accelerations[i].value);
  }
  read_time_functions(ag, "value", acceleration_values, model);
}

// ---- Dump schedule ---------------------------------------------------------------------------

void write_dump_schedule(const Group& g, const DumpSchedule& schedule) {
  g.set("interval", schedule.interval);
  g.set("next", schedule.next);
  g.set("at_termination", std::int64_t{schedule.at_termination});
  g.set("last_cycle", schedule.last_cycle);
  g.set("count", schedule.count);
}

DumpSchedule read_dump_schedule(const Group& g) {
  DumpSchedule s;
  s.interval = g.get_double("interval");
  s.next = g.get_double("next");
  s.at_termination = g.get_int("at_termination") != 0;
  s.last_cycle = g.get_int("last_cycle");
  s.count = g.get_int("count");
  return s;
}

// ---- Whole dump ------------------------------------------------------------------------------

void write_restart_dump(solver::Simulation& sim, const std::filesystem::path& path) {
  const Dumper* dumper = SimulationAccess::dumper(sim);
  if (dumper == nullptr) throw std::logic_error("write_restart_dump: restart dumps not enabled");
  const model::Model& model = SimulationAccess::model(sim);
  solver::State& state = SimulationAccess::state(sim);
  // Written under a temporary name and renamed: a dump interrupted by a full disk, an error or
  // kill -9 leaves the previous dumps as they were (tests/cli_dump_kill.sh); fsync before the
  // rename so that the new name never points at data still in the page cache.
  std::filesystem::path partial = path;
  partial += ".partial";
  try {
    {
      io::h5::File file = io::h5::File::create(partial);
      {
        const Group root = file.root();
        root.set("format", std::string(kDumpFormat));
        root.set("dump_version", kDumpVersion);
        root.set("rigidflex_version", std::string(RIGIDFLEX_VERSION));
        root.set("time", state.time);
        root.set("cycle", state.cycle);
        root.set("threads", static_cast<std::int64_t>(omp_get_max_threads()));
        // The dumped run's MPI rank count: a restart on as many continues it bit for bit.
        root.set("ranks", static_cast<std::int64_t>(parallel::world().size()));
        write_model_input(root.create_group("model"), dumper->input());
        write_nodes(root.create_group("nodes"), state.nodes, SimulationAccess::v_previous(sim));
        write_hex_blocks(root.create_group("blocks"), state.hex_blocks);
        if (!state.discrete_blocks.empty()) {
          write_discrete_blocks(root.create_group("discrete"), state.discrete_blocks);
        }
        if (!state.shell_blocks.empty()) {
          write_shell_blocks(root.create_group("shells"), state.shell_blocks);
        }
        if (!state.beam_blocks.empty()) {
          write_beam_blocks(root.create_group("beams"), state.beam_blocks);
        }
        if (!state.rotations.empty()) {
          write_rotations(root.create_group("rotations"), state.rotations);
        }
        write_rigid_system(root.create_group("rigid"), SimulationAccess::rigid(sim), model);
        write_boundary(root.create_group("boundary"), SimulationAccess::boundary(sim), model);
        SimulationAccess::write_members(sim, root.create_group("simulation"));
        SimulationAccess::write_output(sim, root.create_group("output"));
        SimulationAccess::write_features(sim, root.create_group("features"));
        write_dump_schedule(root.create_group("dumps"), dumper->schedule());
      }
      file.close();
    }
    output::sync_file(partial);
    std::error_code ec;
    std::filesystem::rename(partial, path, ec);
    if (ec) {
      throw std::runtime_error(
          fmt::format("cannot write restart dump '{}': {}", path.string(), ec.message()));
    }
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw;
  }
  output::sync_directory_of(path);
}

DumpHeader read_dump_header(const io::h5::File& file, const std::filesystem::path& path) {
  const Group root = file.root();
  const InputErrorContext where{path.string(), 0, "", 0, ""};
  if (!root.has_attribute("format") || root.get_string("format") != kDumpFormat) {
    throw InputError(where,
                     "not a RigidFlex restart dump (an HDF5 file without the dump's "
                     "format marker)");
  }
  DumpHeader h;
  h.version = root.get_int("dump_version");
  h.rigidflex_version = root.has_attribute("rigidflex_version")
                            ? root.get_string("rigidflex_version")
                            : std::string("unknown");
  if (h.version != kDumpVersion) {
    throw InputError(where,
                     fmt::format("restart dump version {} (written by RigidFlex {}); this "
                                 "RigidFlex ({}) reads dump version {} only: restart with "
                                 "the RigidFlex that wrote the dump",
                                 h.version, h.rigidflex_version, RIGIDFLEX_VERSION, kDumpVersion));
  }
  h.time = root.get_double("time");
  h.cycle = root.get_int("cycle");
  h.threads = static_cast<int>(root.get_int("threads"));
  h.ranks = root.has_attribute("ranks") ? static_cast<int>(root.get_int("ranks")) : 1;
  return h;
}

}  // namespace rf::restart
