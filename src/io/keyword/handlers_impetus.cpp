// IMPETUS Afea commands. Card layouts follow the IMPETUS command manual (see
// docs/keywords.md, section "IMPETUS dialect", for every supported field and where the
// reading of a field is ours rather than the manual's). Fields that would change the physics
// but are not implemented are errors; fields that only affect output or the GUI are read and
// reported as ignored.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <unordered_set>

#include "io/keyword/context.hpp"
#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"
#include "mesh/component.hpp"
#include "model/function.hpp"

namespace rf::io {

namespace {

using model::Id;
using model::Target;

// Every IMPETUS card is comma-separated: the layout only matters for fixed-width text.
const Layout kFree = uniform_layout(16, 10);

// Internal section used by IMPETUS parts (IMPETUS has no section cards): linear hexahedra are
// fully integrated, as IMPETUS's own linear hexahedron is, i.e. ELFORM 2 here.
constexpr Id kImpetusSection = -1;

std::string upper_text(const Card& card, std::size_t i) {
  return to_upper(card.text(i));
}

// Entity type letters (N, NS, P, PS, ALL, G) as a model target.
Target entity_type(const Card& card, std::size_t i, const char* field,
                   std::initializer_list<std::string_view> allowed) {
  const std::string t = upper_text(card, i);
  std::string list;
  for (auto a : allowed) {
    if (t == a) {
      if (t == "N") return Target::Node;
      if (t == "NS") return Target::NodeSet;
      if (t == "P") return Target::Part;
      if (t == "PS") return Target::PartSet;
      if (t == "ALL") return Target::All;
      if (t == "G") return Target::Geometry;
    }
    list += (list.empty() ? "" : ", ") + std::string(a);
  }
  throw card.error(field, fmt::format("entity type '{}' is not supported here (supported: {})",
                                      std::string(card.text(i)), list));
}

// Constraint codes 0, X, Y, Z, XY, YZ, ZX, XYZ (any order of the letters).
std::array<bool, 3> axes_code(const Card& card, std::size_t i, const char* field) {
  std::array<bool, 3> fix{};
  const std::string t = upper_text(card, i);
  if (t.empty() || t == "0") return fix;
  for (char c : t) {
    if (c < 'X' || c > 'Z') {
      throw card.error(field, fmt::format("'{}' is not a constraint code (0, X, Y, Z, XY, YZ, "
                                          "ZX or XYZ)",
                                          std::string(card.text(i))));
    }
    fix[static_cast<std::size_t>(c - 'X')] = true;
  }
  return fix;
}

Id positive(const Card& card, std::size_t i, const char* field, const char* what) {
  const Id id = card.id(i, field);
  if (id <= 0) throw card.error(field, fmt::format("{} ID must be a positive integer", what));
  return id;
}

// A count given by an expression such as [%L1/%dx]: must come out (nearly) integral.
int count_field(const Card& card, std::size_t i, const char* field) {
  const double v = card.real(i, field, 0.0);
  const double r = std::round(v);
  if (std::abs(v - r) > 1e-6 * std::max(1.0, std::abs(v)) || r < 1.0 || r > 1e6) {
    throw card.error(field, fmt::format("{} is not a positive whole number of elements", v));
  }
  return static_cast<int>(r);
}

void reject_if_set(const Card& card, std::size_t i, const char* field, const char* why) {
  const std::string_view t = card.text(i);
  if (t.empty() || t == "0") return;
  if (!t.empty() && card.real(i, field, 0.0) == 0.0) return;
  throw card.error(field, fmt::format("is not supported: {}", why));
}

void ignore_if_set(const Card& card, std::size_t i, const char* field, const char* what,
                   ReaderContext& context) {
  const std::string_view t = card.text(i);
  if (t.empty() || t == "0") return;
  context.warn(card.location(),
               fmt::format("{} ({}) is read but not used: {}", field, std::string(t), what));
}

template <typename Map>
void check_unique(const Map& map, Id id, const Card& card, const char* field, const char* what) {
  if (const auto it = map.find(id); it != map.end()) {
    const auto& w = it->second.where;
    throw card.error(field,
                     fmt::format("{} {} is already defined at {}:{}", what, id, w.file, w.line));
  }
}

// Substitutes %name by the parameter's value (full precision) so that a *FUNCTION expression
// depends on t alone.
std::string substitute_parameters(const Card& card, std::string_view text,
                                  const ParameterTable& parameters) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] != '%') {
      out += text[i++];
      continue;
    }
    std::size_t j = i + 1;
    while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_'))
      ++j;
    const std::string_view name = text.substr(i + 1, j - i - 1);
    const auto value = parameters.find(name);
    if (!value) {
      throw card.error("EXPRESSION",
                       fmt::format("parameter %{} is not defined (define it with *PARAMETER "
                                   "before it is used)",
                                   std::string(name)));
    }
    out += fmt::format("({:.17g})", *value);
    i = j;
  }
  return out;
}

// ----------------------------------------------------------------------------------------------

void unit_system(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kFree, "units");
  static const std::unordered_set<std::string> kKnown{
      "SI",       "MMTONS", "MM/TON/S", "CMGUS", "CM/G/US", "IPS",    "MMKGMS",
      "MM/KG/MS", "CMGS",   "CM/G/S",   "MMGMS", "MM/G/MS", "MMMGMS", "MM/MG/MS"};
  const std::string units = upper_text(card, 0);
  if (!kKnown.count(units)) {
    throw card.error("units", fmt::format("'{}' is not a unit system (SI, MMTONS, CMGUS, IPS, "
                                          "MMKGMS, CMGS, MMGMS, MMMGMS)",
                                          std::string(card.text(0))));
  }
  // The numbers of a deck are consistent in its own units; nothing is converted.
  context.model.unit_system = units;
  warn_unread_lines(block, cursor, context);
}

void parameter(const Block& block, ReaderContext& context) {
  int n = 0;
  for (const DataLine& line : block.lines) {
    ++n;
    // %name = expression, "description", rid, quantity
    const std::string_view text = line.text;
    const auto equals = text.find('=');
    const Card card(block, line, n, kFree, context.parameters);
    if (equals == std::string_view::npos) {
      throw card.error("name", "expected '%name = expression, \"description\"'");
    }
    std::string_view name = trim(text.substr(0, equals));
    if (!name.empty() && name.front() == '%') name.remove_prefix(1);
    if (name.empty()) throw card.error("name", "the parameter name is missing");
    for (char c : name) {
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') {
        throw card.error("name", fmt::format("'{}' is not a parameter name (letters, digits, _)",
                                             std::string(name)));
      }
    }
    const auto fields = split_impetus_fields(text.substr(equals + 1));
    const std::string_view expression = fields.empty() ? std::string_view{} : fields[0];
    if (expression.empty()) throw card.error("expression", "the expression is missing");
    std::string_view inner = expression;
    if (inner.front() == '[' && inner.back() == ']') inner = inner.substr(1, inner.size() - 2);
    double value = 0.0;
    try {
      value = context.parameters.evaluate(strip_parameter_marks(inner));
    } catch (const std::exception& e) {
      throw card.error("expression", fmt::format("cannot evaluate '{}': {}",
                                                 std::string(expression.substr(0, 80)), e.what()));
    }
    context.parameters.define(std::string(name), value);
  }
}

void time(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kFree, "t_term");
  auto& m = context.model;
  m.termination.endtim = card.real(0, "t_term", 0.0);
  if (!(m.termination.endtim > 0.0)) throw card.error("t_term", "must be positive");
  m.timestep.tssfac = card.real(1, "sf_dt", 0.9);
  if (!(m.timestep.tssfac > 0.0) || m.timestep.tssfac > 1.0) {
    throw card.error("sf_dt", "the time-step scale factor must lie in (0, 1]");
  }
  reject_if_set(card, 2, "dt_min", "mass scaling is not implemented");
  m.timestep.dt_max = card.real(3, "dt_max", 0.0);
  if (m.timestep.dt_max < 0.0) throw card.error("dt_max", "must not be negative");
  if (m.timestep.dt_max >= 1e10) m.timestep.dt_max = 0.0;
  ignore_if_set(card, 4, "ms_max", "there is no mass scaling", context);
  reject_if_set(card, 5, "t_start", "runs start at t = 0");
  warn_unread_lines(block, cursor, context);
}

void output(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kFree, "dt_imp");
  auto& out = context.model.output;
  out.d3plot_dt = card.real(0, "dt_imp", 0.0);
  const double ascii = card.real(1, "dt_ascii", 0.0);
  if (out.d3plot_dt < 0.0) throw card.error("dt_imp", "must not be negative");
  if (ascii < 0.0) throw card.error("dt_ascii", "must not be negative");
  out.glstat_dt = ascii;
  out.nodout_dt = ascii;
  context.impetus_ascii_dt = ascii;
  ignore_if_set(card, 2, "dt_db", "no database/state files are written", context);
  ignore_if_set(card, 3, "fragment", "no fragment output", context);
  if (const auto second = cursor.next_optional(2, kFree)) {
    ignore_if_set(*second, 0, "nfilter", "all nodal data are written", context);
    ignore_if_set(*second, 1, "efilter", "all element data are written", context);
  }
  warn_unread_lines(block, cursor, context);
}

// Generated meshes are refused above this many elements (all components together) before
// anything is allocated: a slip such as N_1 = 1e6 would otherwise take gigabytes and hours.
constexpr double kMaxGeneratedElements = 50.0e6;

// Radial layers of a generated cylinder for the "mesh density parameter" N_2 (ours: IMPETUS
// does not define the topology), see generate_components.
int cylinder_radial_layers(int n2) {
  return std::max(1, n2 / 2);
}

double component_elements(const ReaderContext::Component& c) {
  const double n0 = c.divisions[0], n1 = c.divisions[1];
  if (c.cylinder) return n0 * (n1 * n1 + 4.0 * n1 * cylinder_radial_layers(c.divisions[1]));
  return n0 * n1 * c.divisions[2];
}

void check_generated_size(const Card& card, const ReaderContext::Component& c,
                          const ReaderContext& context, const char* field) {
  const double elements = component_elements(c);
  double total = elements;
  for (const auto& other : context.components) total += component_elements(other);
  if (elements > kMaxGeneratedElements) {
    throw card.error(field, fmt::format("the component would have {:.3g} elements; at most {:g} "
                                        "million generated elements are supported",
                                        elements, kMaxGeneratedElements / 1e6));
  }
  if (total > kMaxGeneratedElements) {
    throw card.error(field, fmt::format("with this component the generated meshes would have "
                                        "{:.3g} elements together; at most {:g} million are "
                                        "supported",
                                        total, kMaxGeneratedElements / 1e6));
  }
}

void component(const Block& block, ReaderContext& context, bool cylinder) {
  CardCursor cursor(block, context.parameters);
  ReaderContext::Component c;
  c.cylinder = cylinder;
  if (cylinder) {
    const Card first = cursor.next(1, kFree, "coid pid N_1 N_2");
    c.id = positive(first, 0, "coid", "component");
    c.pid = positive(first, 1, "pid", "part");
    c.divisions[0] = count_field(first, 2, "N_1");
    c.divisions[1] = count_field(first, 3, "N_2");
    reject_if_set(first, 4, "csysid", "give the end points in global coordinates");
    reject_if_set(first, 5, "symmetry", "only full cylinders (symmetry 0) are generated");
    check_generated_size(first, c, context, "N_1");
    const Card second = cursor.next(2, kFree, "x_1 y_1 z_1 x_2 y_2 z_2 R_1");
    c.p1 = {second.real(0, "x_1", 0.0), second.real(1, "y_1", 0.0), second.real(2, "z_1", 0.0)};
    c.p2 = {second.real(3, "x_2", 0.0), second.real(4, "y_2", 0.0), second.real(5, "z_2", 0.0)};
    c.radius = second.real(6, "R_1", 0.0);
    if (!(c.radius > 0.0)) throw second.error("R_1", "the radius must be positive");
    const double r2 = second.real(7, "R_2", c.radius);
    if (std::abs(r2 - c.radius) > 1e-12 * c.radius) {
      throw second.error("R_2", "cones (R_2 different from R_1) are not generated");
    }
    if (c.p1 == c.p2) throw second.error("x_2", "the two end centres coincide");
  } else {
    const Card first = cursor.next(1, kFree, "coid pid N_x N_y N_z");
    c.id = positive(first, 0, "coid", "component");
    c.pid = positive(first, 1, "pid", "part");
    c.divisions = {count_field(first, 2, "N_x"), count_field(first, 3, "N_y"),
                   count_field(first, 4, "N_z")};
    reject_if_set(first, 5, "csysid", "give the corners in global coordinates");
    check_generated_size(first, c, context, "N_x");
    const Card second = cursor.next(2, kFree, "x_1 y_1 z_1 x_2 y_2 z_2");
    c.p1 = {second.real(0, "x_1", 0.0), second.real(1, "y_1", 0.0), second.real(2, "z_1", 0.0)};
    c.p2 = {second.real(3, "x_2", 0.0), second.real(4, "y_2", 0.0), second.real(5, "z_2", 0.0)};
    for (int k = 0; k < 3; ++k) {
      if (c.p1[static_cast<std::size_t>(k)] == c.p2[static_cast<std::size_t>(k)]) {
        throw second.error("x_2", "the box has zero extent in one direction");
      }
    }
  }
  c.where = block.location();
  c.where.line = block.lines.empty() ? block.line : block.lines.front().number;
  context.components.push_back(c);
  warn_unread_lines(block, cursor, context);
}

void component_cylinder(const Block& block, ReaderContext& context) {
  component(block, context, true);
}
void component_box(const Block& block, ReaderContext& context) {
  component(block, context, false);
}

void merge_duplicated_nodes(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (!cursor.at_end()) {
    const Card card = cursor.next(++n, kFree, "entype_s enid_s entype_m enid_m tol");
    ReaderContext::Merge merge;
    merge.target1 = entity_type(card, 0, "entype_s", {"P", "PS", "ALL"});
    merge.id1 = card.id(1, "enid_s");
    merge.target2 = entity_type(card, 2, "entype_m", {"P", "PS", "ALL"});
    merge.id2 = card.id(3, "enid_m");
    merge.tolerance = card.real(4, "tol", 0.0);
    if (merge.tolerance < 0.0) throw card.error("tol", "must not be negative");
    if (card.flag(5, "refine", 0) != 0) {
      ignore_if_set(card, 5, "refine", "there is no mesh refinement, so the order is moot",
                    context);
    }
    merge.where = card.location();
    context.merges.push_back(merge);
  }
}

void mat_elastic(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kFree, "mid rho E nu");
  model::Material mat;
  mat.id = positive(card, 0, "mid", "material");
  mat.keyword = "*MAT_ELASTIC";
  mat.rho = card.real(1, "rho", 0.0);
  mat.e = card.real(2, "E", 0.0);
  mat.pr = card.real(3, "nu", 0.0);
  if (!(mat.rho > 0.0)) throw card.error("rho", "the density must be positive");
  if (!(mat.e > 0.0)) throw card.error("E", "Young's modulus must be positive");
  if (!(mat.pr > -1.0 && mat.pr < 0.5)) throw card.error("nu", "must lie in (-1, 0.5)");
  reject_if_set(card, 4, "did", "damage models are not implemented");
  reject_if_set(card, 5, "thpid", "thermal properties are not implemented");
  if (const auto second = cursor.next_optional(2, kFree)) {
    reject_if_set(*second, 0, "a", "non-linear elasticity is not implemented");
    reject_if_set(*second, 1, "b", "non-linear elasticity is not implemented");
    reject_if_set(*second, 2, "c", "material damping is not implemented");
    reject_if_set(*second, 3, "c_dec", "material damping is not implemented");
  }
  mat.where = card.location();
  check_unique(context.model.materials, mat.id, card, "mid", "material");
  context.model.materials[mat.id] = mat;
  warn_unread_lines(block, cursor, context);
}

void mat_rigid(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kFree, "mid rho");
  model::Material mat;
  mat.id = positive(card, 0, "mid", "material");
  mat.kind = model::MaterialKind::Rigid;
  mat.keyword = "*MAT_RIGID";
  mat.rho = card.real(1, "rho", 0.0);
  if (!(mat.rho > 0.0)) throw card.error("rho", "the density must be positive");
  reject_if_set(card, 5, "thpid", "thermal properties are not implemented");
  mat.where = card.location();
  check_unique(context.model.materials, mat.id, card, "mid", "material");
  context.model.materials[mat.id] = mat;
  warn_unread_lines(block, cursor, context);
}

void part(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto& m = context.model;
  if (!m.solid_sections.count(kImpetusSection)) {
    model::SectionSolid section;
    section.id = kImpetusSection;
    section.elform = 2;
    section.where = block.location();
    m.solid_sections[kImpetusSection] = section;
  }
  int n = 0;
  while (!cursor.at_end()) {
    const Card card = cursor.next(++n, kFree, "pid mid");
    model::Part p;
    p.id = positive(card, 0, "pid", "part");
    p.mid = positive(card, 1, "mid", "material");
    p.secid = kImpetusSection;
    p.title = block.title;
    p.where = card.location();
    ignore_if_set(card, 3, "h", "shell thickness; there are no shells", context);
    p.smoothing_angle = card.real(4, "alpha_max", 0.0);
    if (p.smoothing_angle < 0.0 || p.smoothing_angle > 180.0) {
      throw card.error("alpha_max", "the smoothing angle must lie in [0, 180] degrees");
    }
    reject_if_set(card, 5, "dt_erode", "element erosion is not implemented");
    if (card.field_count() > 6 && !card.blank(6) && card.real(6, "eps_geo_erode", 1e20) < 1e20)
      throw card.error("eps_geo_erode", "is not supported: element erosion is not implemented");
    if (card.field_count() > 7 && !card.blank(7) && card.real(7, "eps_v_erode", 1e20) < 1e20)
      throw card.error("eps_v_erode", "is not supported: element erosion is not implemented");
    reject_if_set(card, 8, "N_perode", "particle conversion is not implemented");
    check_unique(m.parts, p.id, card, "pid", "part");
    m.parts[p.id] = p;
  }
}

void change_p_order(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (!cursor.at_end()) {
    const Card card = cursor.next(++n, kFree, "entype enid order");
    model::POrderChange change;
    change.target = entity_type(card, 0, "entype", {"P", "PS", "ALL"});
    change.id = card.id(1, "enid");
    change.order = card.flag(2, "order", 0);
    if (change.order < 1 || change.order > 3) {
      throw card.error("order", fmt::format("order {} is not supported (1, 2 or 3)", change.order));
    }
    reject_if_set(card, 3, "gid", "the order applies to whole parts (leave gid empty)");
    change.where = card.location();
    context.model.p_order_changes.push_back(change);
  }
}

void bc_motion(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  ReaderContext::Motion base;
  base.title = block.title;
  // The coid line is optional: an entity line starts with a letter.
  int card_number = 1;
  if (const DataLine* line = cursor.peek();
      line && !line->text.empty() && !std::isalpha(static_cast<unsigned char>(line->text[0]))) {
    const Card card = cursor.next(card_number++, kFree, "coid");
    base.id = card.id(0, "coid");
  }
  const Card entity = cursor.next(card_number++, kFree, "entype enid bc_tr bc_rot");
  base.target = entity_type(entity, 0, "entype", {"N", "NS", "P", "PS", "ALL", "G"});
  base.target_id = entity.id(1, "enid");
  const auto tr = axes_code(entity, 2, "bc_tr");
  const auto rot = axes_code(entity, 3, "bc_rot");
  for (int k = 0; k < 3; ++k) {
    base.fixed[static_cast<std::size_t>(k)] = tr[static_cast<std::size_t>(k)];
    base.fixed[static_cast<std::size_t>(k + 3)] = rot[static_cast<std::size_t>(k)];
  }
  reject_if_set(entity, 4, "csysid_tr", "constraints act along the global axes");
  reject_if_set(entity, 5, "csysid_rot",
                "rotations act about the centre of gravity (csysid_rot 0) only");
  base.birth = entity.real(6, "t_beg", 0.0);
  base.death = entity.real(7, "t_end", 1e28);
  base.where = entity.location();
  base.where.keyword = block.keyword;
  context.motions.push_back(base);
  const std::size_t constraint_index = context.motions.size() - 1;
  while (!cursor.at_end()) {
    const Card card = cursor.next(card_number++, kFree, "pmeth direc cid sf fid");
    ReaderContext::Motion motion = base;
    motion.fixed = {};
    motion.has_motion = true;
    const std::string method = upper_text(card, 0);
    if (method == "D") {
      motion.vad = 2;
    } else if (method == "V") {
      motion.vad = 0;
    } else if (method == "A") {
      motion.vad = 1;
    } else {
      throw card.error(
          "pmeth", fmt::format("'{}' is not a motion type (D, V or A)", std::string(card.text(0))));
    }
    static const char* const kDirections[] = {"X", "Y", "Z", "RX", "RY", "RZ"};
    const std::string direction = upper_text(card, 1);
    motion.dof = -1;
    for (int k = 0; k < 6; ++k) {
      if (direction == kDirections[k]) motion.dof = k;
    }
    if (motion.dof < 0) {
      throw card.error("direc", fmt::format("'{}' is not a direction (X, Y, Z, RX, RY, RZ)",
                                            std::string(card.text(1))));
    }
    motion.function = card.id(2, "cid");
    if (motion.function <= 0) {
      throw card.error("cid", "a FUNCTION (or CURVE) ID giving the motion is required");
    }
    motion.scale = card.real(3, "sf", 1.0);
    reject_if_set(card, 4, "fid", "activation functions are not implemented (use t_beg/t_end)");
    motion.where = card.location();
    // A prescribed DOF is no longer held by the constraint code of the same command.
    context.motions[constraint_index].fixed[static_cast<std::size_t>(motion.dof)] = false;
    context.motions.push_back(motion);
  }
}

void geometry_seed_coordinate(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card first = cursor.next(1, kFree, "gid");
  model::GeometrySeed seed;
  seed.id = positive(first, 0, "gid", "geometry");
  const Card second = cursor.next(2, kFree, "x y z alpha_c pid");
  seed.point = {second.real(0, "x", 0.0), second.real(1, "y", 0.0), second.real(2, "z", 0.0)};
  seed.feature_angle_deg = second.real(3, "alpha_c", 45.0);
  if (!(seed.feature_angle_deg > 0.0) || seed.feature_angle_deg > 180.0) {
    throw second.error("alpha_c", "the cut-off angle must lie in (0, 180] degrees");
  }
  seed.pid = second.id(4, "pid");
  seed.where = second.location();
  check_unique(context.model.geometry_seeds, seed.id, first, "gid", "geometry");
  context.model.geometry_seeds[seed.id] = seed;
  warn_unread_lines(block, cursor, context);
}

void function(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card first = cursor.next(1, kFree, "fid");
  model::Function f;
  f.id = positive(first, 0, "fid", "function");
  if (first.flag(1, "derivative", 0) != 0) {
    throw first.error("derivative",
                      "only derivative 0 (the expression is f(t) itself) is "
                      "supported");
  }
  if (cursor.at_end()) throw first.error("expression", "card 2 (the expression) is missing");
  const DataLine& line = block.lines[block.lines.size() - cursor.remaining()];
  const Card card = cursor.next(2, kFree, "expression");
  f.expression = substitute_parameters(card, trim(line.text), context.parameters);
  try {
    f.evaluator = std::make_shared<model::ExpressionFunction>(f.expression, true);
  } catch (const std::exception& e) {
    throw card.error("expression",
                     fmt::format("cannot compile '{}': {} (variables: t; trigonometry in "
                                 "degrees, sinr/cosr/... in radians)",
                                 std::string(trim(line.text)).substr(0, 80), e.what()));
  }
  f.where = card.location();
  check_unique(context.model.functions, f.id, first, "fid", "function");
  context.model.functions[f.id] = f;
  warn_unread_lines(block, cursor, context);
}

void rigid_body_update(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kFree, "type");
  const int type = card.flag(0, "type", 0);
  if (type < 0 || type > 2) throw card.error("type", fmt::format("{} is not 0, 1 or 2", type));
  context.model.rigid_body_update = type;
  warn_unread_lines(block, cursor, context);
}

void node(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (!cursor.at_end()) {
    const Card card = cursor.next(++n, kFree, "nid x y z");
    model::Node node;
    node.id = positive(card, 0, "nid", "node");
    node.x = {card.real(1, "x", 0.0), card.real(2, "y", 0.0), card.real(3, "z", 0.0)};
    const auto fix = axes_code(card, 4, "bc");
    node.tc = (fix[0] ? 1 : 0) + (fix[1] ? 2 : 0) + (fix[2] ? 4 : 0);
    // *NODE TC codes: 1 x, 2 y, 3 z, 4 xy, 5 yz, 6 zx, 7 xyz.
    static const int kCode[8] = {0, 1, 2, 4, 3, 6, 5, 7};
    node.tc = kCode[node.tc];
    const auto [it, inserted] = context.node_origin.try_emplace(
        node.id, std::pair{context.current_file_index, card.line_number()});
    if (!inserted) {
      throw card.error("nid", fmt::format("node {} is already defined at {}", node.id,
                                          context.origin_text(it->second)));
    }
    context.model.nodes.push_back(node);
  }
}

void element_solid(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  static const char* const kNodes[] = {"n1", "n2", "n3", "n4", "n5", "n6", "n7", "n8"};
  int n = 0;
  while (!cursor.at_end()) {
    const Card card = cursor.next(++n, kFree, "eid pid n1..n8");
    model::SolidElement e;
    e.id = positive(card, 0, "eid", "element");
    e.pid = positive(card, 1, "pid", "part");
    for (std::size_t k = 0; k < 8; ++k) e.nodes[k] = positive(card, 2 + k, kNodes[k], "node");
    e.where = card.location();
    const auto [it, inserted] = context.element_origin.try_emplace(
        e.id, std::pair{context.current_file_index, card.line_number()});
    if (!inserted) {
      throw card.error("eid", fmt::format("element {} is already defined at {}", e.id,
                                          context.origin_text(it->second)));
    }
    context.model.solids.push_back(e);
  }
}

// IDs of a set card: single IDs or ranges "a..b".
void read_id_list(const Card& card, std::vector<Id>& out, const char* field) {
  for (std::size_t i = 0; i < card.field_count(); ++i) {
    const std::string_view t = card.text(i);
    if (t.empty()) continue;
    if (const auto dots = t.find(".."); dots != std::string_view::npos) {
      const auto a = parse_integer(trim(t.substr(0, dots)));
      const auto b = parse_integer(trim(t.substr(dots + 2)));
      if (!a.value || !b.value || *a.value > *b.value || *b.value - *a.value > 10000000) {
        throw card.error(field, fmt::format("'{}' is not a range a..b", std::string(t)));
      }
      for (Id id = *a.value; id <= *b.value; ++id) out.push_back(id);
      continue;
    }
    out.push_back(positive(card, i, field, "entity"));
  }
}

void set_node(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card first = cursor.next(1, kFree, "setid");
  model::NodeSet set;
  set.id = positive(first, 0, "setid", "set");
  set.where = first.location();
  int n = 1;
  while (!cursor.at_end()) read_id_list(cursor.next(++n, kFree, "nid"), set.nodes, "nid");
  check_unique(context.model.node_sets, set.id, first, "setid", "node set");
  context.model.node_sets[set.id] = set;
}

void set_part(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card first = cursor.next(1, kFree, "setid");
  model::PartSet set;
  set.id = positive(first, 0, "setid", "set");
  set.where = first.location();
  int n = 1;
  while (!cursor.at_end()) read_id_list(cursor.next(++n, kFree, "pid"), set.parts, "pid");
  check_unique(context.model.part_sets, set.id, first, "setid", "part set");
  context.model.part_sets[set.id] = set;
}

void initial_velocity(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (!cursor.at_end()) {
    const Card card = cursor.next(++n, kFree, "entype enid v_x0 v_y0 v_z0 w_x w_y w_z");
    model::InitialVelocity v;
    v.target = entity_type(card, 0, "entype", {"N", "NS", "P", "PS", "ALL"});
    v.id = card.id(1, "enid");
    v.v = {card.real(2, "v_x0", 0.0), card.real(3, "v_y0", 0.0), card.real(4, "v_z0", 0.0)};
    const std::array<double, 3> w{card.real(5, "w_x", 0.0), card.real(6, "w_y", 0.0),
                                  card.real(7, "w_z", 0.0)};
    v.omega = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    if (v.omega > 0.0) v.axis = {w[0] / v.omega, w[1] / v.omega, w[2] / v.omega};
    v.where = card.location();
    // The optional second card: centre of rotation, velocity gradient, coordinate system.
    if (const DataLine* next = cursor.peek();
        next && !next->text.empty() && !std::isalpha(static_cast<unsigned char>(next->text[0]))) {
      const Card second = cursor.next(++n, kFree, "x_0 y_0 z_0 dv_x dv_y dv_z csysid");
      v.point = {second.real(0, "x_0", 0.0), second.real(1, "y_0", 0.0),
                 second.real(2, "z_0", 0.0)};
      reject_if_set(second, 3, "dv_x", "velocity gradients are not implemented");
      reject_if_set(second, 4, "dv_y", "velocity gradients are not implemented");
      reject_if_set(second, 5, "dv_z", "velocity gradients are not implemented");
      reject_if_set(second, 6, "csysid", "velocities are given in global axes");
    }
    context.model.initial_velocities.push_back(v);
  }
}

void output_node(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (!cursor.at_end()) {
    const Card card = cursor.next(++n, kFree, "entype enid");
    const Target target = entity_type(card, 0, "entype", {"N", "NS"});
    ReaderContext::HistorySet entry{card.id(1, "enid"), card.location()};
    if (target == Target::Node) {
      context.history_nodes.push_back(entry);
      context.model.output.history_nodes.push_back(entry.nsid);
    } else {
      context.history_node_sets.push_back(entry);
    }
  }
}

void include(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  if (cursor.at_end()) throw block_error(block, 1, "filename", "the file name is missing");
  const DataLine& line = *cursor.peek();
  const Card card = cursor.next(1, kFree, "filename");
  std::string name(trim(line.text));
  if (name.size() >= 2 && name.front() == '"' && name.back() == '"') {
    name = name.substr(1, name.size() - 2);
  }
  if (!cursor.at_end()) {
    throw block_error(block, 2, "sf_x",
                      "scaling, offsets and transformations of included files are not "
                      "supported");
  }
  context.include(name, card);
}

void end_ignored(const Block&, ReaderContext&) {}

// --- after the whole deck: generated meshes, merged nodes, boundary conditions --------------

Id max_node_id(const model::Model& m) {
  Id id = 0;
  for (const auto& n : m.nodes) id = std::max(id, n.id);
  return id;
}

Id max_element_id(const model::Model& m) {
  Id id = 0;
  for (const auto& e : m.solids) id = std::max(id, e.id);
  return id;
}

void generate_components(ReaderContext& context) {
  auto& m = context.model;
  Id next_node = max_node_id(m) + 1;
  Id next_element = max_element_id(m) + 1;
  std::unordered_set<Id> component_ids;
  for (const auto& c : context.components) {
    if (!component_ids.insert(c.id).second) {
      throw located_error(c.where, "coid", fmt::format("component {} is defined twice", c.id));
    }
    mesh::GeneratedMesh generated;
    try {
      if (c.cylinder) {
        mesh::CylinderDivisions d;
        d.axial = c.divisions[0];
        // IMPETUS calls N_2 a "mesh density parameter" without defining the topology; ours:
        // a central N_2 x N_2 square and max(1, N_2 / 2) radial layers, 4 N_2 elements around.
        d.square = c.divisions[1];
        d.radial = cylinder_radial_layers(c.divisions[1]);
        generated = mesh::generate_cylinder(c.p1, c.p2, c.radius, d);
        m.cylinder_surfaces.push_back({c.pid, c.p1, c.p2, c.radius, 360.0 / (4.0 * d.square)});
      } else {
        generated = mesh::generate_box(c.p1, c.p2, c.divisions[0], c.divisions[1], c.divisions[2]);
      }
    } catch (const std::exception& e) {
      throw located_error(c.where, "", e.what());
    }
    const Id first = next_node;
    for (const auto& x : generated.nodes) {
      model::Node n;
      n.id = next_node++;
      n.x = x;
      m.nodes.push_back(n);
    }
    for (const auto& hex : generated.hexes) {
      model::SolidElement e;
      e.id = next_element++;
      e.pid = c.pid;
      for (std::size_t k = 0; k < 8; ++k) e.nodes[k] = first + hex[k];
      e.where = c.where;
      m.solids.push_back(e);
    }
  }
}

std::unordered_set<Id> parts_of(const model::Model& m, Target target, Id id,
                                const model::SourceLocation& where, const char* field) {
  std::unordered_set<Id> parts;
  if (target == Target::All) {
    for (const auto& [pid, p] : m.parts) parts.insert(pid);
    for (const auto& e : m.solids) parts.insert(e.pid);
  } else if (target == Target::Part) {
    parts.insert(id);
  } else {
    const auto it = m.part_sets.find(id);
    if (it == m.part_sets.end()) {
      throw located_error(where, field, fmt::format("part set {} is not defined", id));
    }
    parts.insert(it->second.parts.begin(), it->second.parts.end());
  }
  return parts;
}

void merge_nodes(ReaderContext& context) {
  auto& m = context.model;
  for (const auto& merge : context.merges) {
    const auto slave_parts = parts_of(m, merge.target1, merge.id1, merge.where, "enid_s");
    const auto master_parts = parts_of(m, merge.target2, merge.id2, merge.where, "enid_m");
    std::unordered_map<Id, std::size_t> index_of;
    for (std::size_t i = 0; i < m.nodes.size(); ++i) index_of[m.nodes[i].id] = i;
    std::vector<Id> slave_ids, master_ids;
    std::unordered_set<Id> seen_slave, seen_master;
    for (const auto& e : m.solids) {
      for (Id n : e.nodes) {
        // An undefined node is reported with its element by the model checks that follow.
        if (!index_of.count(n)) continue;
        if (slave_parts.count(e.pid) && seen_slave.insert(n).second) slave_ids.push_back(n);
        if (master_parts.count(e.pid) && seen_master.insert(n).second) master_ids.push_back(n);
      }
    }
    std::vector<std::array<double, 3>> slave_x, master_x;
    for (Id n : slave_ids) slave_x.push_back(m.nodes[index_of.at(n)].x);
    for (Id n : master_ids) master_x.push_back(m.nodes[index_of.at(n)].x);
    const auto nearest = mesh::nearest_within(master_x, slave_x, merge.tolerance);
    std::unordered_map<Id, Id> replace;
    for (std::size_t i = 0; i < slave_ids.size(); ++i) {
      if (nearest[i] < 0) continue;
      const Id target = master_ids[static_cast<std::size_t>(nearest[i])];
      if (target != slave_ids[i]) replace[slave_ids[i]] = target;
    }
    if (replace.empty()) {
      context.warn(merge.where, "no nodes were close enough to merge (check tol)");
      continue;
    }
    // A master node that is itself replaced (overlapping entities): follow to the end.
    for (auto& [from, to] : replace) {
      for (std::size_t hops = 0; hops < replace.size(); ++hops) {
        const auto next = replace.find(to);
        if (next == replace.end() || next->second == to) break;
        to = next->second;
      }
    }
    for (auto& e : m.solids) {
      bool changed = false;
      for (Id& n : e.nodes) {
        if (const auto it = replace.find(n); it != replace.end()) {
          n = it->second;
          changed = true;
        }
      }
      if (!changed) continue;
      for (std::size_t a = 0; a < e.nodes.size(); ++a) {
        for (std::size_t b = a + 1; b < e.nodes.size(); ++b) {
          if (e.nodes[a] != e.nodes[b]) continue;
          throw located_error(merge.where, "tol",
                              fmt::format("merging within tol = {:g} makes two corners of "
                                          "element {} one node ({}): the tolerance must be "
                                          "well below the element size",
                                          merge.tolerance, e.id, e.nodes[a]));
        }
      }
    }
    for (auto& [sid, set] : m.node_sets) {
      for (Id& n : set.nodes) {
        if (const auto it = replace.find(n); it != replace.end()) n = it->second;
      }
    }
    std::erase_if(m.nodes, [&](const model::Node& n) { return replace.count(n.id) > 0; });
    for (const auto& [from, to] : replace) context.node_origin.erase(from);
    m.merged_node_count += static_cast<std::int64_t>(replace.size());
  }
}

bool part_is_rigid(const model::Model& m, Id pid) {
  const auto p = m.parts.find(pid);
  if (p == m.parts.end()) return false;
  const auto mat = m.materials.find(p->second.mid);
  return mat != m.materials.end() && mat->second.kind == model::MaterialKind::Rigid;
}

// *BC_MOTION on rigid parts: the body's DOFs (held ones as zero prescribed displacement);
// on everything else: nodal constraints and prescribed motion.
void resolve_motions(ReaderContext& context) {
  auto& m = context.model;
  for (const auto& motion : context.motions) {
    const bool rigid_target = motion.target == Target::Part && part_is_rigid(m, motion.target_id);
    if (motion.target == Target::Part && !m.parts.count(motion.target_id)) {
      throw located_error(motion.where, "enid",
                          fmt::format("part {} is not defined", motion.target_id));
    }
    if (rigid_target) {
      auto add = [&](int dof, int vad, Id function, double scale) {
        model::RigidPrescribedMotion pm;
        pm.pid = motion.target_id;
        pm.dof = dof < 3 ? dof + 1 : dof + 2;  // 1,2,3 translation; 5,6,7 rotation
        pm.vad = vad;
        pm.function = function;
        pm.sf = scale;
        pm.birth = motion.birth;
        pm.death = motion.death;
        pm.where = motion.where;
        m.rigid_prescribed_motions.push_back(pm);
      };
      for (int k = 0; k < 6; ++k) {
        if (motion.fixed[static_cast<std::size_t>(k)]) add(k, 2, 0, 0.0);
      }
      if (motion.has_motion) add(motion.dof, motion.vad, motion.function, motion.scale);
      continue;
    }
    if (motion.target == Target::PartSet || motion.target == Target::All) {
      // Rigid parts inside a set are addressed through their nodes, which the body owns:
      // refuse rather than silently ignoring the condition on them.
      for (Id pid : parts_of(m, motion.target, motion.target_id, motion.where, "enid")) {
        if (part_is_rigid(m, pid)) {
          throw located_error(motion.where, "enid",
                              fmt::format("the entity contains rigid part {}; give rigid parts "
                                          "their own *BC_MOTION with entity type P",
                                          pid));
        }
      }
    }
    for (int k = 3; k < 6; ++k) {
      if (motion.fixed[static_cast<std::size_t>(k)] || (motion.has_motion && motion.dof == k)) {
        throw located_error(motion.where, motion.has_motion ? "direc" : "bc_rot",
                            "rotational DOFs exist only for rigid parts (solid element nodes "
                            "have translations only)");
      }
    }
    if (motion.fixed[0] || motion.fixed[1] || motion.fixed[2]) {
      if (motion.birth != 0.0 || motion.death < 1e27) {
        throw located_error(motion.where, "t_beg",
                            "time-limited constraints on nodes are not supported (give the "
                            "motion as prescribed zero velocity instead)");
      }
      model::Spc spc;
      spc.target = motion.target;
      spc.id = motion.target_id;
      spc.fix = {motion.fixed[0], motion.fixed[1], motion.fixed[2]};
      spc.where = motion.where;
      m.spcs.push_back(spc);
    }
    if (motion.has_motion) {
      model::PrescribedMotion pm;
      pm.target = motion.target;
      pm.id = motion.target_id;
      pm.dof = motion.dof + 1;
      pm.vad = motion.vad;
      pm.function = motion.function;
      pm.sf = motion.scale;
      pm.birth = motion.birth;
      pm.death = motion.death;
      pm.where = motion.where;
      m.prescribed_motions.push_back(pm);
    }
  }
}

}  // namespace

const KeywordEntry* find_impetus_command(std::string_view command) {
  static const std::vector<KeywordEntry> entries{
      {"*UNIT_SYSTEM", unit_system, {}},
      {"*PARAMETER", parameter, {}},
      {"*TIME", time, {}},
      {"*OUTPUT", output, {}},
      {"*COMPONENT_CYLINDER", component_cylinder, {}},
      {"*COMPONENT_BOX", component_box, {}},
      {"*MERGE_DUPLICATED_NODES", merge_duplicated_nodes, {}},
      {"*MAT_ELASTIC", mat_elastic, {}},
      {"*MAT_RIGID", mat_rigid, {}},
      {"*PART", part, {}},
      {"*CHANGE_P-ORDER", change_p_order, {}},
      {"*BC_MOTION", bc_motion, {}},
      {"*GEOMETRY_SEED_COORDINATE", geometry_seed_coordinate, {}},
      {"*FUNCTION", function, {}},
      {"*RIGID_BODY_UPDATE", rigid_body_update, {}},
      {"*NODE", node, {}},
      {"*ELEMENT_SOLID", element_solid, {}},
      {"*SET_NODE", set_node, {}},
      {"*SET_PART", set_part, {}},
      {"*INITIAL_VELOCITY", initial_velocity, {}},
      {"*OUTPUT_NODE", output_node, {}},
      {"*INCLUDE", include, {}},
      {"*KEYWORD", end_ignored, {}},
  };
  for (const auto& entry : entries) {
    if (entry.name == command) return &entry;
  }
  return nullptr;
}

void finish_impetus(ReaderContext& context) {
  if (context.model.dialect != "impetus") return;
  generate_components(context);
  merge_nodes(context);
  resolve_motions(context);
  // IMPETUS's default frame interval (*OUTPUT dt_imp blank or no *OUTPUT): t_term / 100.
  auto& m = context.model;
  if (m.output.d3plot_dt <= 0.0 && m.termination.endtim > 0.0) {
    m.output.d3plot_dt = m.termination.endtim / 100.0;
  }
  // IMPETUS writes rigid body histories with its ASCII output; so do we (rbdout.csv).
  for (const auto& [mid, mat] : context.model.materials) {
    if (mat.kind == model::MaterialKind::Rigid) {
      context.model.output.rbdout = true;
      context.model.output.rbdout_dt = context.impetus_ascii_dt;
    }
  }
}

}  // namespace rf::io
