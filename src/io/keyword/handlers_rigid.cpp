// Rigid bodies: coordinate systems and vectors, rigid body constraints, motions and loads.
// Cross references (parts, nodes, sets, systems, curves) are checked in finish.cpp.
#include <fmt/format.h>

#include <cmath>

#include "io/keyword/definition_ids.hpp"
#include "io/keyword/geometry.hpp"
#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

model::Id non_negative_id(const Card& card, std::size_t i, const char* field) {
  const model::Id id = card.id(i, field);
  if (id < 0) throw card.error(field, fmt::format("ID {} must not be negative", id));
  return id;
}

bool only_blank_lines_left(const CardCursor& cursor, const Block& block) {
  for (std::size_t i = block.lines.size() - cursor.remaining(); i < block.lines.size(); ++i) {
    if (!trim(block.lines[i].text).empty()) return false;
  }
  return true;
}

// Title card of a _TITLE option; returns the number of the next card.
int skip_title(const Block& block, CardCursor& cursor, int n) {
  if (!block.has_option("TITLE")) return n;
  cursor.next_text(n, "title");
  return n + 1;
}

Vec3 read_vec3(const Card& card, std::size_t first, const char* const names[3]) {
  return {card.real(first, names[0], 0.0), card.real(first + 1, names[1], 0.0),
          card.real(first + 2, names[2], 0.0)};
}

void add_coordinate_system(ReaderContext& context, const Card& card, model::CoordinateSystem cs) {
  check_unique(context.model.coordinate_systems, cs.id, card, "CID", "coordinate system");
  context.model.coordinate_systems.emplace(cs.id, std::move(cs));
}

int flag_in(const Card& card, std::size_t i, const char* field, int fallback, int low, int high) {
  const int v = card.flag(i, field, fallback);
  if (v < low || v > high) {
    throw card.error(field,
                     fmt::format("value {} is not supported (supported: {}..{})", v, low, high));
  }
  return v;
}

}  // namespace

RigidConstraints read_rigid_constraints(const Card& card) {
  RigidConstraints c;
  c.cmo = card.real(0, "CMO", 0.0);
  c.con1 = card.real(1, "CON1", 0.0);
  c.con2 = card.real(2, "CON2", 0.0);
  if (c.cmo == -1.0) {
    // Local constraints: CON1 names a coordinate system, CON2 is a digit code 'xyzXYZ'.
    if (!(c.con1 > 0.0) || c.con1 != std::trunc(c.con1) || c.con1 > 9.0e15) {
      throw card.error("CON1", fmt::format("CMO -1: CON1 {} must be the ID of a "
                                           "*DEFINE_COORDINATE_ system",
                                           c.con1));
    }
    c.cmo_cid = static_cast<model::Id>(c.con1);
    if (c.con2 < 0.0 || c.con2 > 111111.0 || c.con2 != std::trunc(c.con2)) {
      throw card.error("CON2", fmt::format("CMO -1: CON2 {} is not a code of up to six digits 0 "
                                           "or 1 (e.g. 100001)",
                                           c.con2));
    }
    auto code = static_cast<long>(c.con2);
    for (int k = 5; k >= 0; --k, code /= 10) {
      const long digit = code % 10;
      if (digit > 1) {
        throw card.error("CON2",
                         fmt::format("CMO -1: CON2 {} has a digit other than 0 or 1", c.con2));
      }
      c.local_fix[static_cast<std::size_t>(k)] = digit == 1;
    }
    return c;
  }
  if (c.cmo != 0.0 && c.cmo != 1.0) {
    throw card.error("CMO", fmt::format("CMO {}: value must be -1, 0 or 1", c.cmo));
  }
  for (const auto& [value, name] : {std::pair{c.con1, "CON1"}, std::pair{c.con2, "CON2"}}) {
    if (value < 0.0 || value > 7.0 || value != static_cast<int>(value)) {
      throw card.error(name, fmt::format("value {} is not a code 0..7", value));
    }
  }
  return c;
}

model::RigidInertia read_rigid_inertia(CardCursor& cursor, int n, int& cards_read) {
  static const char* const kX[] = {"XC", "YC", "ZC"};
  static const char* const kVt[] = {"VTX", "VTY", "VTZ"};
  static const char* const kVr[] = {"VRX", "VRY", "VRZ"};
  static const char* const kXl[] = {"XL", "YL", "ZL"};
  static const char* const kXlip[] = {"XLIP", "YLIP", "ZLIP"};
  static const char* const kI[] = {"IXX", "IXY", "IXZ", "IYY", "IYZ", "IZZ"};
  model::RigidInertia in;
  const Card c1 = cursor.next(n, kEightByTen, "XC YC ZC TM IRCS NODEID");
  in.xc = read_vec3(c1, 0, kX);
  in.tm = c1.real(3, "TM", 0.0);
  if (!(in.tm > 0.0)) {
    throw c1.error("TM", fmt::format("translational mass {} must be positive", in.tm));
  }
  in.ircs = c1.flag(4, "IRCS", 0);
  if (in.ircs != 0 && in.ircs != 1) {
    throw c1.error("IRCS", fmt::format("value {} is not 0 (global tensor) or 1 (principal "
                                       "moments)",
                                       in.ircs));
  }
  in.nodeid = non_negative_id(c1, 5, "NODEID");
  in.where = c1.location();
  const Card c2 = cursor.next(n + 1, kEightByTen, "IXX IXY IXZ IYY IYZ IZZ");
  for (std::size_t k = 0; k < 6; ++k) in.inertia[k] = c2.real(k, kI[k], 0.0);
  for (std::size_t k : {0u, 3u, 5u}) {
    if (!(in.inertia[k] > 0.0)) {
      throw c2.error(kI[k], fmt::format("moment of inertia {} must be positive", in.inertia[k]));
    }
  }
  const Card c3 = cursor.next(n + 2, kEightByTen, "VTX VTY VTZ VRX VRY VRZ");
  in.vt = read_vec3(c3, 0, kVt);
  in.vr = read_vec3(c3, 3, kVr);
  cards_read = 3;
  if (in.ircs == 1) {
    const Card c4 = cursor.next(n + 3, kEightByTen, "XL YL ZL XLIP YLIP ZLIP CID");
    in.xl = read_vec3(c4, 0, kXl);
    in.xlip = read_vec3(c4, 3, kXlip);
    in.cid = non_negative_id(c4, 6, "CID");
    if (in.cid == 0) {
      const auto axes = axes_from(in.xl, in.xlip, 0);
      if (!axes) {
        throw c4.error("XL",
                       "the local x axis XL YL ZL and the in-plane vector XLIP YLIP ZLIP "
                       "must be nonzero and not parallel (or give CID)");
      }
      in.principal_axes = *axes;
    }
    cards_read = 4;
  }
  return in;
}

void define_coordinate_system(const Block& block, ReaderContext& context) {
  static const char* const kO[] = {"XO", "YO", "ZO"};
  static const char* const kL[] = {"XL", "YL", "ZL"};
  static const char* const kP[] = {"XP", "YP", "ZP"};
  CardCursor cursor(block, context.parameters);
  do {
    const int n = skip_title(block, cursor, 1);
    const Card c1 = cursor.next(n, kEightByTen, "CID XO YO ZO XL YL ZL CID2");
    const Card c2 = cursor.next(n + 1, kEightByTen, "XP YP ZP");
    model::CoordinateSystem cs;
    cs.id = positive_id(c1, 0, "CID", "coordinate system");
    cs.kind = model::CoordinateKind::System;
    cs.origin = read_vec3(c1, 1, kO);
    if (c1.id(7, "CID2") != 0) {
      throw c1.error("CID2",
                     "points given in another coordinate system (CID2) are not "
                     "supported; give global coordinates");
    }
    // The manual's construction: x from the origin to the point on the x axis, z normal to
    // the plane of the origin, that point and the in-plane point, y = z x x.
    const auto axes =
        axes_from(sub(read_vec3(c1, 4, kL), cs.origin), sub(read_vec3(c2, 0, kP), cs.origin), 0);
    if (!axes) {
      throw c2.error("XP",
                     "the origin, the point on the x axis (XL YL ZL) and the in-plane "
                     "point (XP YP ZP) must be distinct and not on one line");
    }
    cs.axes = *axes;
    cs.where = c1.location();
    add_coordinate_system(context, c1, std::move(cs));
  } while (!only_blank_lines_left(cursor, block));
}

void define_coordinate_vector(const Block& block, ReaderContext& context) {
  static const char* const kX[] = {"XX", "YX", "ZX"};
  static const char* const kV[] = {"XV", "YV", "ZV"};
  CardCursor cursor(block, context.parameters);
  do {
    const int n = skip_title(block, cursor, 1);
    const Card card = cursor.next(n, kEightByTen, "CID XX YX ZX XV YV ZV NID");
    model::CoordinateSystem cs;
    cs.id = positive_id(card, 0, "CID", "coordinate system");
    cs.kind = model::CoordinateKind::Vector;
    if (card.id(7, "NID") != 0) {
      throw card.error("NID",
                       "a system rotating with a node (NID) is not supported; leave NID "
                       "blank for a fixed system");
    }
    const auto axes = axes_from(read_vec3(card, 1, kX), read_vec3(card, 4, kV), 0);
    if (!axes) {
      throw card.error("XV",
                       "the x axis (XX YX ZX) and the in-plane vector (XV YV ZV) must be "
                       "nonzero and not parallel");
    }
    cs.axes = *axes;  // origin at (0, 0, 0)
    cs.where = card.location();
    add_coordinate_system(context, card, std::move(cs));
  } while (!only_blank_lines_left(cursor, block));
}

void define_coordinate_nodes(const Block& block, ReaderContext& context) {
  static const char* const kN[] = {"N1", "N2", "N3"};
  CardCursor cursor(block, context.parameters);
  do {
    const int n = skip_title(block, cursor, 1);
    const Card card = cursor.next(n, kEightByTen, "CID N1 N2 N3 FLAG DIR");
    model::CoordinateSystem cs;
    cs.id = positive_id(card, 0, "CID", "coordinate system");
    cs.kind = model::CoordinateKind::Nodes;
    for (std::size_t k = 0; k < 3; ++k) cs.nodes[k] = positive_id(card, 1 + k, kN[k], "node");
    if (cs.nodes[0] == cs.nodes[1] || cs.nodes[0] == cs.nodes[2] || cs.nodes[1] == cs.nodes[2]) {
      throw card.error("N3", "N1, N2 and N3 must be three different nodes");
    }
    const int flag = card.flag(4, "FLAG", 0);
    if (flag == 1) {
      throw card.error("FLAG",
                       "systems updated with the nodes (FLAG 1) are not supported; "
                       "leave FLAG blank for a fixed system");
    }
    if (flag != 0) throw card.error("FLAG", fmt::format("value {} is not 0 or 1", flag));
    const std::string_view dir = card.text(5);
    if (dir.empty() || dir == "X" || dir == "x") {
      cs.dir = 'X';
    } else if (dir == "Y" || dir == "y") {
      cs.dir = 'Y';
    } else if (dir == "Z" || dir == "z") {
      cs.dir = 'Z';
    } else {
      throw card.error("DIR", "value must be X, Y or Z");
    }
    cs.where = card.location();  // axes and origin follow from the nodes in finish.cpp
    add_coordinate_system(context, card, std::move(cs));
  } while (!only_blank_lines_left(cursor, block));
}

void define_vector(const Block& block, ReaderContext& context) {
  static const char* const kT[] = {"XT", "YT", "ZT"};
  static const char* const kH[] = {"XH", "YH", "ZH"};
  CardCursor cursor(block, context.parameters);
  do {
    const int n = skip_title(block, cursor, 1);
    const Card card = cursor.next(n, kEightByTen, "VID XT YT ZT XH YH ZH CID");
    model::Vector v;
    v.id = positive_id(card, 0, "VID", "vector");
    v.tail = read_vec3(card, 1, kT);
    v.head = read_vec3(card, 4, kH);
    v.cid = non_negative_id(card, 7, "CID");
    const auto direction = unit(sub(v.head, v.tail));
    if (!direction) throw card.error("XH", "head and tail coincide: the vector has no direction");
    v.direction = *direction;  // rotated into global axes in finish.cpp when CID is given
    v.where = card.location();
    check_unique(context.model.vectors, v.id, card, "VID", "vector");
    context.model.vectors.emplace(v.id, std::move(v));
  } while (!only_blank_lines_left(cursor, block));
}

void constrained_rigid_bodies(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, "PIDL PIDC IFLAG");
    model::RigidBodyMerge merge;
    merge.lead = positive_id(card, 0, "PIDL", "part");
    merge.constrained = positive_id(card, 1, "PIDC", "part");
    if (merge.lead == merge.constrained) {
      throw card.error("PIDC", fmt::format("part {} cannot be merged into itself", merge.lead));
    }
    merge.iflag = flag_in(card, 2, "IFLAG", 0, 0, 1);
    merge.where = card.location();
    context.model.rigid_body_merges.push_back(merge);
  }
  if (n == 0) throw block_error(block, 1, "PIDL", "no PIDL PIDC card follows the keyword");
}

void constrained_extra_nodes(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const bool set = block.base.ends_with("_SET");
  const char* id_field = set ? "NSID" : "NID";
  const char* fields = set ? "PID NSID IFLAG" : "PID NID IFLAG";
  int n = 0;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, fields);
    model::ExtraNodes extra;
    extra.pid = positive_id(card, 0, "PID", "part");
    extra.target = set ? model::Target::NodeSet : model::Target::Node;
    extra.id = positive_id(card, 1, id_field, set ? "node set" : "node");
    extra.iflag = flag_in(card, 2, "IFLAG", 0, 0, 1);
    extra.where = card.location();
    context.model.extra_nodes.push_back(extra);
  }
  if (n == 0)
    throw block_error(block, 1, "PID", fmt::format("no {} card follows the keyword", fields));
}

void constrained_nodal_rigid_body(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const bool spc = block.has_option("SPC");
  const bool inertia = block.has_option("INERTIA");
  int n = skip_title(block, cursor, 1);
  do {
    const Card card = cursor.next(n++, kEightByTen, "PID CID NSID PNODE IPRT DRFLAG RRFLAG");
    model::NodalRigidBody body;
    body.pid = positive_id(card, 0, "PID", "nodal rigid body");
    body.cid = non_negative_id(card, 1, "CID");
    body.nsid = non_negative_id(card, 2, "NSID");
    if (body.nsid == 0) body.nsid = body.pid;  // manual: NSID 0 means the set ID equals PID
    body.pnode = card.id(3, "PNODE");
    body.iprt = flag_in(card, 4, "IPRT", 0, 0, 2);
    for (const auto& [i, name] : {std::pair{5u, "DRFLAG"}, std::pair{6u, "RRFLAG"}}) {
      if (card.flag(i, name, 0) != 0) {
        throw card.error(name,
                         "release of nodal degrees of freedom is not supported (leave "
                         "DRFLAG and RRFLAG blank or 0)");
      }
    }
    body.where = card.location();
    if (spc) {
      const auto c = read_rigid_constraints(cursor.next(n++, kEightByTen, "CMO CON1 CON2"));
      body.cmo = c.cmo;
      body.con1 = c.con1;
      body.con2 = c.con2;
      body.cmo_cid = c.cmo_cid;
      body.cmo_local_fix = c.local_fix;
    }
    if (inertia) {
      int cards = 0;
      body.inertia = read_rigid_inertia(cursor, n, cards);
      n += cards;
    }
    check_unique(context.model.nodal_rigid_bodies, body.pid, card, "PID", "nodal rigid body");
    context.model.nodal_rigid_bodies.emplace(body.pid, std::move(body));
  } while (!only_blank_lines_left(cursor, block));
}

void boundary_prescribed_motion_rigid(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 1;
  if (block.has_option("ID")) {
    cursor.next(1, Layout{10, 70}, "ID HEADING");  // names the motion in output only
    n = 2;
  }
  bool any = false;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    if (any && block.has_option("ID") && looks_like_id_card(block, *cursor.peek())) {
      cursor.next(1, Layout{10, 70}, "ID HEADING");  // the next motion's ID card
      continue;
    }
    const Card card = cursor.next(n, kEightByTen, "PID DOF VAD LCID SF VID DEATH BIRTH");
    model::RigidPrescribedMotion m;
    m.pid = positive_id(card, 0, "PID", "part");
    m.dof = card.flag(1, "DOF", 0);
    if (m.dof < 1 || m.dof > 8) {
      throw card.error("DOF", fmt::format("value {} is not supported (supported: 1, 2, 3 "
                                          "translation x, y, z; 4 translation along VID; 5, 6, "
                                          "7 rotation about x, y, z; 8 rotation about VID)",
                                          m.dof));
    }
    m.vad = card.flag(2, "VAD", 0);
    if (m.vad < 0 || m.vad > 2) {
      throw card.error("VAD", fmt::format("value {} is not supported (supported: 0 velocity, "
                                          "1 acceleration, 2 displacement)",
                                          m.vad));
    }
    m.lcid = card.id(3, "LCID");
    if (m.lcid <= 0) throw card.error("LCID", "a load curve ID is required");
    m.sf = card.real(4, "SF", 1.0);
    m.vid = non_negative_id(card, 5, "VID");
    if ((m.dof == 4 || m.dof == 8) && m.vid == 0) {
      throw card.error("VID", fmt::format("DOF {} needs a vector VID (*DEFINE_VECTOR)", m.dof));
    }
    m.death = card.real(6, "DEATH", 1e28);
    if (m.death == 0.0) m.death = 1e28;  // LS-DYNA: 0 means never removed
    m.birth = card.real(7, "BIRTH", 0.0);
    if (m.death <= m.birth) {
      throw card.error("DEATH",
                       fmt::format("death time {} is not after birth time {}", m.death, m.birth));
    }
    m.local = block.has_option("LOCAL");
    m.where = card.location();
    context.model.rigid_prescribed_motions.push_back(m);
    any = true;
  }
  if (!any) throw block_error(block, n, "PID", "no motion card follows the keyword");
}

void load_rigid_body(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  bool any = false;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, kEightByTen, "PID DOF LCID SF CID M1 M2 M3");
    model::RigidLoad load;
    load.pid = positive_id(card, 0, "PID", "part");
    load.dof = card.flag(1, "DOF", 0);
    if (load.dof == 4 || load.dof == 8) {
      throw card.error("DOF", fmt::format("value {}: follower forces and moments are not "
                                          "supported",
                                          load.dof));
    }
    if (load.dof < 1 || load.dof > 7) {
      throw card.error("DOF", fmt::format("value {} is not supported (supported: 1, 2, 3 force "
                                          "x, y, z; 5, 6, 7 moment about x, y, z)",
                                          load.dof));
    }
    load.lcid = card.id(2, "LCID");
    if (load.lcid <= 0) throw card.error("LCID", "a load curve ID is required");
    load.sf = card.real(3, "SF", 1.0);
    if (card.id(4, "CID") != 0) {
      throw card.error("CID", "local coordinate systems are not supported (leave CID blank)");
    }
    // M1..M3 only define follower directions (DOF 4, 8), which are rejected above.
    load.where = card.location();
    context.model.rigid_loads.push_back(load);
    any = true;
  }
  if (!any) throw block_error(block, 1, "PID", "no load card follows the keyword");
}

void rigid_body_update(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  if (const auto card = cursor.next_optional(1, kEightByTen)) {
    context.model.rigid_body_update = flag_in(*card, 0, "TYPE", 0, 0, 2);
  }
  warn_unread_lines(block, cursor, context);
}

void control_rigid(const Block& block, ReaderContext& context) {
  // Its options (joint treatment, rigid-deformable switching by *DEFORMABLE_TO_RIGID,
  // metal forming) concern features RigidFlex does not have; saying so beats silence.
  context.warn(block.location(),
               "*CONTROL_RIGID is read but ignored: RigidFlex uses its own "
               "rigid body settings");
}

}  // namespace rf::io::handlers
