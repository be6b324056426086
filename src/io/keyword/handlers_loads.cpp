// Boundary conditions, loads, initial conditions and load curves.
#include <fmt/format.h>

#include <cctype>
#include <cmath>

#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"
#include "model/function.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

// The _ID option adds one card (ID, HEADING) before the data cards; its content names the
// condition in LS-DYNA output only. Returns the number of the first data card.
int skip_id_card(const Block& block, CardCursor& cursor) {
  if (!block.has_option("ID")) return 1;
  cursor.next(1, Layout{10, 70}, "ID HEADING");
  return 2;
}

model::Target node_or_set(const Block& block) {
  return block.base.ends_with("_SET") ? model::Target::NodeSet : model::Target::Node;
}

int translational_dof(const Card& card, const char* field, int dof, const char* extra) {
  if (dof < 1 || dof > 3) {
    throw card.error(field, fmt::format("value {} is not supported (supported: 1, 2, 3 for x, "
                                        "y, z){}",
                                        dof, extra));
  }
  return dof;
}

}  // namespace

void boundary_spc(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const int n = skip_id_card(block, cursor);
  const model::Target target = node_or_set(block);
  const char* id_field = target == model::Target::Node ? "NID" : "NSID";
  static const char* const kDof[] = {"DOFX", "DOFY", "DOFZ", "DOFRX", "DOFRY", "DOFRZ"};
  bool any = false;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    if (any && block.has_option("ID") && looks_like_id_card(block, *cursor.peek())) {
      cursor.next(1, Layout{10, 70}, "ID HEADING");  // the next condition's ID card
      continue;
    }
    const Card card = cursor.next(n, kEightByTen, "NID CID DOFX DOFY DOFZ DOFRX DOFRY DOFRZ");
    model::Spc spc;
    spc.target = target;
    spc.id = card.id(0, id_field);
    if (spc.id <= 0) throw card.error(id_field, "a positive ID is required");
    spc.cid = card.id(1, "CID");
    if (spc.cid != 0) {
      throw card.error("CID", "local coordinate systems are not supported (leave CID blank)");
    }
    for (std::size_t k = 0; k < 6; ++k) {
      const int v = card.flag(2 + k, kDof[k], 0);
      if (v != 0 && v != 1) {
        throw card.error(kDof[k], fmt::format("value {} is not 0 (free) or 1 (fixed)", v));
      }
      (k < 3 ? spc.fix[k] : spc.fix_rot[k - 3]) = (v == 1);
    }
    spc.where = card.location();
    context.model.spcs.push_back(spc);
    any = true;
  }
  if (!any) throw block_error(block, n, id_field, "no constraint card follows the keyword");
}

void boundary_prescribed_motion(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const int n = skip_id_card(block, cursor);
  const model::Target target = node_or_set(block);
  const char* id_field = target == model::Target::Node ? "NID" : "NSID";
  bool any = false;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    if (any && block.has_option("ID") && looks_like_id_card(block, *cursor.peek())) {
      cursor.next(1, Layout{10, 70}, "ID HEADING");  // the next condition's ID card
      continue;
    }
    const Card card = cursor.next(n, kEightByTen, "NID DOF VAD LCID SF VID DEATH BIRTH");
    model::PrescribedMotion m;
    m.target = target;
    m.id = card.id(0, id_field);
    if (m.id <= 0) throw card.error(id_field, "a positive ID is required");
    const int dof = card.flag(1, "DOF", 0);
    if (dof <= -4 && dof >= -8) {
      throw card.error("DOF", fmt::format("DOF {} is not supported; DOF {} (along the vector "
                                          "VID, or about x, y, z, VID) is",
                                          dof, -dof));
    }
    // 4: translation along VID; 5, 6, 7: rotation about x, y, z; 8: rotation about VID (nodes
    // with rotational DOFs; checked when the model is built, as is VID).
    const bool along_axis = dof >= 4 && dof <= 8;
    const bool rotation = std::abs(dof) >= 9 && std::abs(dof) <= 11;
    if (rotation && dof < 0) {
      throw card.error("DOF", fmt::format("DOF {} (rotation about an axis with the radial motion "
                                          "free) is not supported; DOF {} (radial motion held) "
                                          "is",
                                          dof, -dof));
    }
    m.dof = rotation || along_axis
                ? dof
                : translational_dof(card, "DOF", dof,
                                    "; 4 along VID; 5, 6, 7, 8 rotation about x, y, z, VID; 9, "
                                    "10, 11 for a rotation about an axis parallel to x, y, z");
    m.vad = card.flag(2, "VAD", 0);
    if (m.vad < 0 || m.vad > 2) {
      throw card.error("VAD", fmt::format("value {} is not supported (supported: 0 velocity, "
                                          "1 acceleration, 2 displacement)",
                                          m.vad));
    }
    if (rotation && m.vad == 1) {
      throw card.error("VAD",
                       "VAD 1 (angular acceleration) is not supported with DOF 9, 10, "
                       "11; use 0 (angular velocity, rad/time) or 2 (angle, rad)");
    }
    m.lcid = card.id(3, "LCID");
    if (m.lcid <= 0) throw card.error("LCID", "a load curve ID is required");
    m.sf = card.real(4, "SF", 1.0);
    m.vid = card.id(5, "VID");
    if (m.vid < 0) {
      throw card.error("VID", "local coordinate systems (negative VID) are not supported");
    }
    m.death = card.real(6, "DEATH", 1e28);
    if (m.death == 0.0) m.death = 1e28;  // LS-DYNA: 0 means never removed
    m.birth = card.real(7, "BIRTH", 0.0);
    if (m.death <= m.birth) {
      throw card.error("DEATH",
                       fmt::format("death time {} is not after birth time {}", m.death, m.birth));
    }
    m.where = card.location();
    if (rotation) {
      // The card that locates the axis follows each motion card with |DOF| 9..11.
      const Card axis = cursor.next(n + 1, kEightByTen, "OFFSET1 OFFSET2 LRB NODE1 NODE2");
      m.offset1 = axis.real(0, "OFFSET1", 0.0);
      m.offset2 = axis.real(1, "OFFSET2", 0.0);
      static const char* const kRelative[] = {"LRB", "NODE1", "NODE2"};
      for (std::size_t k = 0; k < 3; ++k) {
        if (axis.id(2 + k, kRelative[k]) != 0) {
          throw axis.error(kRelative[k],
                           "belongs to VAD 4 (relative displacement of rigid "
                           "bodies), which is not supported; leave it blank");
        }
      }
    }
    context.model.prescribed_motions.push_back(m);
    any = true;
  }
  if (!any) throw block_error(block, n, id_field, "no motion card follows the keyword");
}

namespace {

// Card 1 of *DEFINE_CURVE and *DEFINE_CURVE_FUNCTION (after the _TITLE line, if any): LCID SIDR
// SFA SFO OFFA OFFO, checked; `number` is that card's number.
struct CurveHead {
  model::Curve curve;
  Card card;
  int number;
};

CurveHead read_curve_head(const Block& block, CardCursor& cursor, const char* fields) {
  int n = 1;
  if (block.has_option("TITLE")) {
    cursor.next_text(1, "title");
    n = 2;
  }
  const Card head = cursor.next(n, kEightByTen, fields);
  model::Curve c;
  c.id = head.id(0, "LCID");
  if (c.id <= 0) throw head.error("LCID", "a positive curve ID is required");
  c.sidr = head.flag(1, "SIDR", 0);
  if (c.sidr < 0 || c.sidr > 2) {
    throw head.error("SIDR", fmt::format("value {} is not 0, 1 or 2", c.sidr));
  }
  c.sfa = head.real(2, "SFA", 1.0);
  c.sfo = head.real(3, "SFO", 1.0);
  if (c.sfa == 0.0) c.sfa = 1.0;  // LS-DYNA: 0 means the default 1
  if (c.sfo == 0.0) c.sfo = 1.0;
  c.offa = head.real(4, "OFFA", 0.0);
  c.offo = head.real(5, "OFFO", 0.0);
  c.where = head.location();
  return {std::move(c), head, n};
}

}  // namespace

void define_curve(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto [c, head, n] = read_curve_head(block, cursor, "LCID SIDR SFA SFO OFFA OFFO DATTYP");
  const int dattyp = head.flag(6, "DATTYP", 0);
  if (dattyp != 0) {
    throw head.error("DATTYP", fmt::format("value {} is not supported (supported: 0, an "
                                           "ordinary time or abscissa curve)",
                                           dattyp));
  }
  static const Layout kPoint{20, 20};
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card point = cursor.next(++n, kPoint, "A1 O1");
    const double a = point.real(0, "A1", 0.0);
    const double o = point.real(1, "O1", 0.0);
    if (!c.abscissa.empty() && a < c.abscissa.back()) {
      throw point.error("A1", fmt::format("abscissa {} is smaller than the previous one {}; "
                                          "points must be in increasing order",
                                          a, c.abscissa.back()));
    }
    c.abscissa.push_back(a);
    c.ordinate.push_back(o);
  }
  if (c.abscissa.empty()) throw head.error("LCID", "the curve has no points");
  if (const auto it = context.model.curves.find(c.id); it != context.model.curves.end()) {
    throw head.error("LCID", fmt::format("curve {} is already defined at {}:{}", c.id,
                                         it->second.where.file, it->second.where.line));
  }
  if (const auto it = context.model.tables.find(c.id); it != context.model.tables.end()) {
    throw head.error("LCID", fmt::format("{} is the ID of the *DEFINE_TABLE at {}:{}; tables and "
                                         "curves may not share IDs",
                                         c.id, it->second.where.file, it->second.where.line));
  }
  // A plain *DEFINE_TABLE takes the curves that follow it, in order.
  if (auto& pending = context.pending_table) {
    context.model.tables.at(pending->id).curves.push_back(c.id);
    if (--pending->remaining == 0) pending.reset();
  }
  context.model.curves.emplace(c.id, std::move(c));
}

// *DEFINE_TABLE: TBID SFA OFFA, then one VALUE per card (20 columns); the table's curves are the
// *DEFINE_CURVE keywords that follow, one per value in the same order (the reader checks that
// nothing else comes between). *DEFINE_TABLE_2D: VALUE LCID cards naming the curves.
void define_table(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 1;
  if (block.has_option("TITLE")) {
    cursor.next_text(1, "title");
    n = 2;
  }
  const bool named = block.has_option("2D");
  const Card head = cursor.next(n, kEightByTen, "TBID SFA OFFA");
  model::Table t;
  t.id = head.id(0, "TBID");
  if (t.id <= 0) throw head.error("TBID", "a positive table ID is required");
  t.sfa = head.real(1, "SFA", 1.0);
  if (t.sfa == 0.0) t.sfa = 1.0;  // as *DEFINE_CURVE: 0 means the default 1
  t.offa = head.real(2, "OFFA", 0.0);
  t.where = head.location();
  static const Layout kValue{20, 20};
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kValue, named ? "VALUE LCID" : "VALUE");
    const double value = card.real(0, "VALUE", 0.0);
    if (!t.values.empty() && !(value > t.values.back())) {
      throw card.error("VALUE", fmt::format("value {} does not increase from the previous one {}; "
                                            "a table's values must increase strictly",
                                            value, t.values.back()));
    }
    if (named) {
      const model::Id lcid = card.id(1, "LCID");
      if (lcid <= 0) throw card.error("LCID", "a *DEFINE_TABLE_2D card needs the curve ID LCID");
      t.curves.push_back(lcid);
    } else if (!card.blank(1)) {
      throw card.error("LCID",
                       "a plain *DEFINE_TABLE takes the *DEFINE_CURVE keywords that follow "
                       "it; name curves with *DEFINE_TABLE_2D");
    }
    t.values.push_back(value);
  }
  if (t.values.empty()) throw head.error("TBID", "the table has no VALUE cards");
  if (const auto it = context.model.tables.find(t.id); it != context.model.tables.end()) {
    throw head.error("TBID", fmt::format("table {} is already defined at {}:{}", t.id,
                                         it->second.where.file, it->second.where.line));
  }
  if (const auto it = context.model.curves.find(t.id); it != context.model.curves.end()) {
    throw head.error("TBID", fmt::format("{} is the ID of the *DEFINE_CURVE at {}:{}; tables and "
                                         "curves may not share IDs",
                                         t.id, it->second.where.file, it->second.where.line));
  }
  if (!named) context.pending_table = ReaderContext::PendingTable{t.id, t.values.size(), t.where};
  context.model.tables.emplace(t.id, std::move(t));
}

// *DEFINE_CURVE_FUNCTION: the card of *DEFINE_CURVE, then an expression of TIME (muparser with
// C's <math.h> names, case-insensitive, "&name" parameters substituted) on the following lines.
void define_curve_function(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  auto [c, head, n] = read_curve_head(block, cursor, "LCID SIDR SFA SFO OFFA OFFO");
  cursor.skip_blank_lines();
  const DataLine* first = cursor.peek();
  const Card function_card = cursor.next(n + 1, Layout{80}, "FUNCTION");
  std::string text;
  for (const DataLine* line = first; line; line = cursor.peek()) {
    if (line != first) cursor.next(n + 1, Layout{80}, "FUNCTION");
    text += std::string(trim(line->text));
    text += ' ';
  }
  // Parameters as "&name" become their values; names are case-insensitive like LS-DYNA's.
  std::string expression;
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == '&') {
      std::size_t j = i + 1;
      while (j < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) {
        ++j;
      }
      const std::string name = text.substr(i + 1, j - i - 1);
      const auto value = context.parameters.find(name);
      if (!value) {
        throw function_card.error("FUNCTION",
                                  fmt::format("parameter '{}' is not defined (define it with "
                                              "*PARAMETER before it is used)",
                                              name));
      }
      expression += fmt::format("({:.17g})", *value);
      i = j;
      continue;
    }
    if (std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_') {
      std::size_t j = i;
      std::string name;
      while (j < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) {
        name += static_cast<char>(std::tolower(static_cast<unsigned char>(text[j++])));
      }
      expression += name == "pi" ? "_pi" : name;  // muparser's name for the constant
      i = j;
      continue;
    }
    expression += text[i];
    ++i;
  }
  try {
    c.function = std::make_shared<const model::ArgumentFunction>("curve(time) = " + expression);
  } catch (const std::exception& e) {
    throw function_card.error(
        "FUNCTION",
        fmt::format("cannot use '{}': {}", std::string(trim(text)).substr(0, 80), e.what()));
  }
  c.function_text = std::string(trim(text));
  if (const auto it = context.model.curves.find(c.id); it != context.model.curves.end()) {
    throw head.error("LCID", fmt::format("curve {} is already defined at {}:{}", c.id,
                                         it->second.where.file, it->second.where.line));
  }
  context.model.curves.emplace(c.id, std::move(c));
}

namespace {

void reject_rotation(const Card& card, std::size_t first, const char* const names[3]) {
  for (std::size_t k = 0; k < 3; ++k) {
    if (card.real(first + k, names[k], 0.0) != 0.0) {
      throw card.error(names[k],
                       "initial rotational velocities are not supported; use "
                       "*INITIAL_VELOCITY_GENERATION for a spinning body");
    }
  }
}

}  // namespace

void initial_velocity(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 1;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card head = cursor.next(n, kEightByTen, "NSID NSIDEX BOXID IRIGID ICID");
    const model::Id nsid = head.id(0, "NSID");
    const model::Id nsidex = head.id(1, "NSIDEX");
    if (nsid < 0) throw head.error("NSID", "node set ID must not be negative");
    if (nsidex < 0) throw head.error("NSIDEX", "node set ID must not be negative");
    if (head.id(2, "BOXID") != 0) throw head.error("BOXID", "boxes are not supported");
    const int irigid = head.flag(3, "IRIGID", 0);
    if (irigid < -1 || irigid > 1) {
      throw head.error("IRIGID", fmt::format("value {} is not -1, 0 or 1", irigid));
    }
    if (head.id(4, "ICID") != 0) {
      throw head.error("ICID", "local coordinate systems are not supported");
    }
    static const char* const kRot[] = {"VXR", "VYR", "VZR"};
    static const char* const kRotEx[] = {"VXRE", "VYRE", "VZRE"};
    const Card velocity = cursor.next(n + 1, kEightByTen, "VX VY VZ VXR VYR VZR");
    reject_rotation(velocity, 3, kRot);
    model::InitialVelocity v;
    v.target = nsid == 0 ? model::Target::All : model::Target::NodeSet;
    v.id = nsid;
    v.v = {velocity.real(0, "VX", 0.0), velocity.real(1, "VY", 0.0), velocity.real(2, "VZ", 0.0)};
    v.irigid = irigid;
    v.where = head.location();
    context.model.initial_velocities.push_back(v);
    n += 2;
    if (nsidex != 0) {
      context.exemptions.push_back(
          {context.model.initial_velocities.size() - 1, nsidex, head.location()});
      const Card exempt = cursor.next(n, kEightByTen, "VXE VYE VZE VXRE VYRE VZRE");
      reject_rotation(exempt, 3, kRotEx);
      model::InitialVelocity ve;
      ve.target = model::Target::NodeSet;
      ve.id = nsidex;
      ve.v = {exempt.real(0, "VXE", 0.0), exempt.real(1, "VYE", 0.0), exempt.real(2, "VZE", 0.0)};
      ve.where = exempt.location();
      context.model.initial_velocities.push_back(ve);
      ++n;
    }
  }
  if (n == 1) throw block_error(block, 1, "NSID", "card 1 (NSID NSIDEX BOXID ...) is missing");
}

void initial_velocity_node(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  static const char* const kRot[] = {"VXR", "VYR", "VZR"};
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, kEightByTen, "NID VX VY VZ VXR VYR VZR ICID");
    model::InitialVelocity v;
    v.target = model::Target::Node;
    v.id = card.id(0, "NID");
    if (v.id <= 0) throw card.error("NID", "a positive node ID is required");
    v.v = {card.real(1, "VX", 0.0), card.real(2, "VY", 0.0), card.real(3, "VZ", 0.0)};
    // Angular velocities act on nodes with rotations (shells, beams); solid nodes have none.
    v.w = {card.real(4, kRot[0], 0.0), card.real(5, kRot[1], 0.0), card.real(6, kRot[2], 0.0)};
    if (card.id(7, "ICID") != 0) {
      throw card.error("ICID", "local coordinate systems are not supported");
    }
    v.where = card.location();
    context.model.initial_velocities.push_back(v);
  }
}

void initial_velocity_generation(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 1;
  do {
    const Card c1 = cursor.next(n, kEightByTen, "ID STYP OMEGA VX VY VZ IVATN ICID");
    model::InitialVelocity v;
    const model::Id id = c1.id(0, "ID");
    const int styp = c1.flag(1, "STYP", 0);
    if (id < 0) throw c1.error("ID", "the set or part ID must not be negative");
    switch (styp) {
      case 1:
        v.target = id == 0 ? model::Target::All : model::Target::PartSet;
        break;
      case 2:
        v.target = id == 0 ? model::Target::All : model::Target::Part;
        break;
      case 3:
        v.target = id == 0 ? model::Target::All : model::Target::NodeSet;
        break;
      default:
        throw c1.error("STYP", fmt::format("value {} is not supported (supported: 1 part set, "
                                           "2 part, 3 node set)",
                                           styp));
    }
    v.id = id;
    v.omega = c1.real(2, "OMEGA", 0.0);
    v.v = {c1.real(3, "VX", 0.0), c1.real(4, "VY", 0.0), c1.real(5, "VZ", 0.0)};
    if (c1.flag(6, "IVATN", 0) != 0) {
      throw c1.error("IVATN", "velocities of constrained (slave) parts are not supported");
    }
    if (c1.id(7, "ICID") != 0) throw c1.error("ICID", "local coordinate systems are not supported");
    v.where = c1.location();
    // Card 2 is only needed for a rotation, but LS-DYNA decks always carry it.
    std::optional<Card> c2;
    if (v.omega != 0.0) {
      c2.emplace(cursor.next(n + 1, kEightByTen, "XC YC ZC NX NY NZ PHASE"));
    } else if (!cursor.at_end()) {
      c2.emplace(cursor.next(n + 1, kEightByTen, "XC YC ZC NX NY NZ PHASE"));
    }
    if (c2) {
      v.point = {c2->real(0, "XC", 0.0), c2->real(1, "YC", 0.0), c2->real(2, "ZC", 0.0)};
      v.axis = {c2->real(3, "NX", 0.0), c2->real(4, "NY", 0.0), c2->real(5, "NZ", 0.0)};
      const double length =
          std::sqrt(v.axis[0] * v.axis[0] + v.axis[1] * v.axis[1] + v.axis[2] * v.axis[2]);
      if (v.omega != 0.0 && !(length > 0.0 && std::isfinite(length))) {
        throw c2->error("NX", "a rotation (OMEGA nonzero) needs a nonzero axis NX NY NZ");
      }
      if (length > 0.0 && std::isfinite(length)) {
        for (double& a : v.axis) a /= length;
      }
      // PHASE 1 (velocities before dynamic relaxation) is refused when the run relaxes.
      v.phase = c2->flag(6, "PHASE", 0);
      if (v.phase != 0 && v.phase != 1) {
        throw c2->error("PHASE", fmt::format("value {} is not 0 or 1", v.phase));
      }
      v.irigid = c2->flag(7, "IRIGID", 0);
      if (v.irigid < -1 || v.irigid > 1) {
        throw c2->error("IRIGID", fmt::format("value {} is not -1, 0 or 1", v.irigid));
      }
    }
    context.model.initial_velocities.push_back(v);
    n += 2;
    cursor.skip_blank_lines();
  } while (!cursor.at_end());
}

void load_node(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const model::Target target = node_or_set(block);
  const char* id_field = target == model::Target::Node ? "NID" : "NSID";
  bool any = false;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, kEightByTen, "NID DOF LCID SF CID M1 M2 M3");
    model::NodalLoad load;
    load.target = target;
    load.id = card.id(0, id_field);
    if (load.id <= 0) throw card.error(id_field, "a positive ID is required");
    const int dof = card.flag(1, "DOF", 0);
    if (dof == 4 || dof == 8) {
      throw card.error("DOF", fmt::format("value {} (a follower {} along the normal of nodes M1 "
                                          "M2 M3) is not supported; use DOF 1-3 (forces) or 5-7 "
                                          "(moments about x, y, z)",
                                          dof, dof == 4 ? "force" : "moment"));
    }
    load.dof = dof >= 5 && dof <= 7
                   ? dof
                   : translational_dof(card, "DOF", dof, "; 5, 6, 7 for moments about x, y, z");
    load.lcid = card.id(2, "LCID");
    if (load.lcid <= 0) throw card.error("LCID", "a load curve ID is required");
    load.sf = card.real(3, "SF", 1.0);
    if (card.id(4, "CID") != 0) {
      throw card.error("CID", "local coordinate systems are not supported");
    }
    static const char* const kFollower[] = {"M1", "M2", "M3"};
    for (std::size_t k = 0; k < 3; ++k) {
      if (card.id(5 + k, kFollower[k]) != 0) {
        throw card.error(kFollower[k],
                         "follower loads (nodes M1 M2 M3) are not supported; "
                         "leave M1 M2 M3 blank");
      }
    }
    load.where = card.location();
    context.model.nodal_loads.push_back(load);
    any = true;
  }
  if (!any) throw block_error(block, 1, id_field, "no load card follows the keyword");
}

namespace {

// LCID SF AT of a pressure card at fields first..first+2.
void read_pressure_history(const Card& card, std::size_t first, model::PressureLoad& load) {
  load.lcid = card.id(first, "LCID");
  if (load.lcid < 0) {
    throw card.error("LCID", fmt::format("negative LCID {} (a *DEFINE_FUNCTION of time and "
                                         "position) is not supported; give a *DEFINE_CURVE",
                                         load.lcid));
  }
  if (load.lcid == 0) throw card.error("LCID", "a load curve ID is required");
  load.sf = card.real(first + 1, "SF", 1.0);
  load.at = card.real(first + 2, "AT", 0.0);
  if (!std::isfinite(load.sf) || !std::isfinite(load.at)) {
    throw card.error(std::isfinite(load.sf) ? "AT" : "SF", "the value is not a finite number");
  }
}

// Fields of a card that this reader does not take must be blank: LS-DYNA versions add fields
// (death times, options) whose silent loss would change the physics.
void require_blank(const Card& card, std::size_t first, std::size_t last) {
  for (std::size_t i = first; i <= last; ++i) {
    if (!card.blank(i)) {
      throw card.error(fmt::format("field {}", i + 1).c_str(),
                       fmt::format("'{}' is given, but this field is not read by RigidFlex (its "
                                   "meaning would be lost); leave it blank",
                                   card.text(i)));
    }
  }
}

// Reads the cards of a pressure keyword: with _ID, each data card may be preceded by its own
// ID card (as LS-PrePost writes them). `read_card` reads one data card.
template <typename ReadCard>
void read_pressure_cards(const Block& block, ReaderContext& context, const char* fields,
                         const char* first_field, ReadCard read_card) {
  CardCursor cursor(block, context.parameters);
  const int n = skip_id_card(block, cursor);
  bool any = false;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    if (any && block.has_option("ID") && looks_like_id_card(block, *cursor.peek())) {
      cursor.next(1, Layout{10, 70}, "ID HEADING");  // the next load's ID card
      continue;
    }
    const Card card = cursor.next(n, kEightByTen, fields);
    model::PressureLoad load = read_card(card);
    load.where = card.location();
    context.model.pressure_loads.push_back(load);
    any = true;
  }
  if (!any) throw block_error(block, n, first_field, "no load card follows the keyword");
}

}  // namespace

// *LOAD_SEGMENT(_ID): LCID SF AT N1 N2 N3 N4 (N5: quadratic segments, not supported).
void load_segment(const Block& block, ReaderContext& context) {
  read_pressure_cards(block, context, "LCID SF AT N1 N2 N3 N4 N5", "LCID", [](const Card& card) {
    model::PressureLoad load;
    load.target = model::PressureTarget::Segment;
    read_pressure_history(card, 0, load);
    static const char* const kNode[] = {"N1", "N2", "N3", "N4"};
    for (std::size_t k = 0; k < 4; ++k) {
      load.nodes[k] = card.id(3 + k, kNode[k]);
      if (load.nodes[k] < 0 || (k < 3 && load.nodes[k] == 0)) {
        throw card.error(kNode[k], fmt::format("node ID {} is not valid (N1, N2, N3 are "
                                               "required; N4 blank or = N3 for a triangle)",
                                               load.nodes[k]));
      }
    }
    if (load.nodes[3] == 0) load.nodes[3] = load.nodes[2];  // triangle
    if (card.id(7, "N5") != 0) {
      throw card.error("N5",
                       "quadratic segments (mid-side nodes N5-N8) are not supported; "
                       "give 4-node segments");
    }
    // Repeated nodes other than N3 = N4 make no segment (LS-DYNA's triangle is N3 = N4).
    const auto& q = load.nodes;
    for (std::size_t a = 0; a < 4; ++a) {
      for (std::size_t b = a + 1; b < 4; ++b) {
        if (q[a] == q[b] && !(a == 2 && b == 3)) {
          throw card.error(kNode[b], fmt::format("node {} appears twice in the segment {} {} "
                                                 "{} {} (only N3 = N4 is allowed: a "
                                                 "triangle)",
                                                 q[b], q[0], q[1], q[2], q[3]));
        }
      }
    }
    return load;
  });
}

// *LOAD_SEGMENT_SET(_ID): SSID LCID SF AT.
void load_segment_set(const Block& block, ReaderContext& context) {
  read_pressure_cards(block, context, "SSID LCID SF AT", "SSID", [](const Card& card) {
    model::PressureLoad load;
    load.target = model::PressureTarget::SegmentSet;
    load.id = card.id(0, "SSID");
    if (load.id <= 0) throw card.error("SSID", "a positive segment set ID is required");
    read_pressure_history(card, 1, load);
    require_blank(card, 4, 7);
    return load;
  });
}

// *LOAD_SHELL_ELEMENT(_ID): EID LCID SF AT; *LOAD_SHELL_SET(_ID): ESID LCID SF AT.
void load_shell(const Block& block, ReaderContext& context) {
  const bool set = block.base.ends_with("_SET");
  const char* id_field = set ? "ESID" : "EID";
  read_pressure_cards(
      block, context, set ? "ESID LCID SF AT" : "EID LCID SF AT", id_field, [&](const Card& card) {
        model::PressureLoad load;
        load.target = set ? model::PressureTarget::ShellSet : model::PressureTarget::Shell;
        load.id = card.id(0, id_field);
        if (load.id <= 0) {
          throw card.error(id_field, set ? "a positive shell set ID is required"
                                         : "a positive shell element ID is "
                                           "required");
        }
        read_pressure_history(card, 1, load);
        require_blank(card, 4, 7);
        return load;
      });
}

void load_body(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kEightByTen, "LCID SF LCIDDR XC YC ZC CID");
  model::BodyLoad load;
  const char axis = block.base.back();
  load.direction = axis - 'X';
  load.lcid = card.id(0, "LCID");
  if (load.lcid <= 0) throw card.error("LCID", "a load curve ID is required");
  load.sf = card.real(1, "SF", 1.0);
  if (card.id(2, "LCIDDR") != 0) {
    context.warn(card.location(), "LCIDDR ignored: dynamic relaxation is not supported");
  }
  if (card.id(6, "CID") != 0) throw card.error("CID", "local coordinate systems are not supported");
  load.where = card.location();
  context.model.body_loads.push_back(load);
  warn_unread_lines(block, cursor, context);
}

}  // namespace rf::io::handlers
