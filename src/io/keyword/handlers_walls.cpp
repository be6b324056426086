// Rigid walls (*RIGIDWALL_PLANAR with _ID, _FINITE, _MOVING, _FORCES; *RIGIDWALL_GEOMETRIC_FLAT,
// _PRISM, _CYLINDER, _SPHERE with _ID, _MOTION, _DISPLAY, _INTERIOR) and *DEFINE_BOX. Card layouts
// follow the LS-DYNA keyword manual (as transcribed in ansys/pydyna). Planar: an optional ID card,
// card 1 NSID NSIDEX BOXID OFFSET BIRTH DEATH RWKSF, card 2 XT YT ZT XH YH ZH FRIC WVEL, the
// _FINITE card XHEV YHEV ZHEV LENL LENM, the _MOVING card MASS V0 and the _FORCES card SOFT SSID
// N1 N2 N3 N4, in that order whatever the order of the option words. The solver side is
// src/contact/rigid_wall.hpp.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "io/keyword/geometry.hpp"
#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

Vec3 read_point(const Card& card, std::size_t first, const char* const names[3]) {
  return {card.real(first, names[0], 0.0), card.real(first + 1, names[1], 0.0),
          card.real(first + 2, names[2], 0.0)};
}

double non_negative(const Card& card, std::size_t i, const char* name, double fallback) {
  const double v = card.real(i, name, fallback);
  if (v < 0.0) throw card.error(name, fmt::format("value {} must not be negative", v));
  return v;
}

model::Id non_negative_id(const Card& card, std::size_t i, const char* name) {
  const model::Id id = card.id(i, name);
  if (id < 0) throw card.error(name, fmt::format("ID {} must not be negative", id));
  return id;
}

// XHEV YHEV ZHEV LENL LENM of a finite (or prism) wall. The l edge must have a part in the
// wall's plane: m = n x l is then defined.
void read_finite_edge(const Card& card, const Vec3& normal, model::RigidWall& wall) {
  static const char* const kEdge[] = {"XHEV", "YHEV", "ZHEV"};
  wall.edge_head = read_point(card, 0, kEdge);
  const Vec3 edge = sub(wall.edge_head, wall.tail);
  const double along_normal = edge[0] * normal[0] + edge[1] * normal[1] + edge[2] * normal[2];
  const Vec3 in_plane{edge[0] - along_normal * normal[0], edge[1] - along_normal * normal[1],
                      edge[2] - along_normal * normal[2]};
  if (!(length(in_plane) > 1e-9 * length(edge))) {
    throw card.error("XHEV",
                     "the edge vector from the tail XT YT ZT to XHEV YHEV ZHEV must be nonzero "
                     "and not along the wall normal");
  }
  wall.lenl = non_negative(card, 3, "LENL", 0.0);
  wall.lenm = non_negative(card, 4, "LENM", 0.0);
}

// The `_ID` card of a rigid wall (planar or geometric): ID and title; an ID used twice is an
// error naming the first definition.
void read_wall_id_card(CardCursor& cursor, int number, const ReaderContext& context,
                       model::RigidWall& wall) {
  const Card id_card = cursor.next(number, Layout{10, 70}, "ID TITLE");
  wall.id = non_negative_id(id_card, 0, "ID");
  wall.title = std::string(id_card.text(1));
  if (wall.id == 0) return;
  for (const auto& other : context.model.rigid_walls) {
    if (other.id == wall.id) {
      throw id_card.error("ID",
                          fmt::format("rigid wall {} is already defined at {}:{} ({})", wall.id,
                                      other.where.file, other.where.line, other.where.keyword));
    }
  }
}

}  // namespace

void rigidwall_planar(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  model::RigidWall wall;
  wall.number = static_cast<int>(context.model.rigid_walls.size()) + 1;
  wall.finite = block.has_option("FINITE");
  wall.moving = block.has_option("MOVING");
  int n = 1;
  if (block.has_option("ID")) read_wall_id_card(cursor, n++, context, wall);

  const Card c1 = cursor.next(n++, kEightByTen, "NSID NSIDEX BOXID OFFSET BIRTH DEATH RWKSF");
  wall.where = c1.location();
  wall.nsid = non_negative_id(c1, 0, "NSID");
  wall.nsidex = non_negative_id(c1, 1, "NSIDEX");
  wall.boxid = non_negative_id(c1, 2, "BOXID");
  wall.offset = non_negative(c1, 3, "OFFSET", 0.0);
  wall.birth = non_negative(c1, 4, "BIRTH", 0.0);
  wall.death = c1.real(5, "DEATH", 1e20);
  if (wall.death == 0.0) wall.death = 1e20;  // as for prescribed motion: 0 means "never"
  if (wall.death <= wall.birth) {
    throw c1.error("DEATH",
                   fmt::format("DEATH {} must be later than BIRTH {}", wall.death, wall.birth));
  }
  wall.rwksf = c1.real(6, "RWKSF", 1.0);
  if (wall.rwksf < 0.0) {
    throw c1.error("RWKSF", fmt::format("value {} must not be negative", wall.rwksf));
  }
  if (wall.rwksf != 0.0 && wall.rwksf != 1.0) {
    context.warn(c1.location(),
                 fmt::format("RWKSF {} ignored: it scales the penalty stiffness of a penalty "
                             "wall, and this wall is a kinematic constraint without stiffness",
                             wall.rwksf));
  }

  static const char* const kTail[] = {"XT", "YT", "ZT"};
  static const char* const kHead[] = {"XH", "YH", "ZH"};
  const Card c2 = cursor.next(n++, kEightByTen, "XT YT ZT XH YH ZH FRIC WVEL");
  wall.tail = read_point(c2, 0, kTail);
  wall.head = read_point(c2, 3, kHead);
  const auto normal = unit(sub(wall.head, wall.tail));
  if (!normal) {
    throw c2.error("XH",
                   "the head XH YH ZH must differ from the tail XT YT ZT: together they give "
                   "the wall normal");
  }
  wall.fric = c2.real(6, "FRIC", 0.0);
  if (wall.fric == 2.0 || wall.fric == 3.0) {
    throw c2.error("FRIC", fmt::format("FRIC {} (nodes welded to the wall after contact) is not "
                                       "supported; use 0 (frictionless), 0 < FRIC < 1 "
                                       "(Coulomb coefficient) or 1 (no sliding)",
                                       wall.fric));
  }
  if (!(wall.fric >= 0.0 && wall.fric <= 1.0)) {
    throw c2.error("FRIC", fmt::format("value {} is not supported: 0 frictionless, 0 < FRIC < 1 "
                                       "Coulomb coefficient, 1 no sliding (2 and 3, welding, "
                                       "are not supported)",
                                       wall.fric));
  }
  wall.wvel = c2.real(7, "WVEL", 0.0);
  if (wall.wvel != 0.0) {
    throw c2.error("WVEL", fmt::format("WVEL {}: welding of nodes to the wall is not supported "
                                       "(leave WVEL blank or 0)",
                                       wall.wvel));
  }

  if (wall.finite) {
    const Card c3 = cursor.next(n++, kEightByTen, "XHEV YHEV ZHEV LENL LENM");
    read_finite_edge(c3, *normal, wall);
  }
  if (wall.moving) {
    const Card c4 = cursor.next(n++, kEightByTen, "MASS V0");
    wall.mass = c4.real(0, "MASS", 0.0);
    if (!(wall.mass > 0.0)) {
      throw c4.error("MASS",
                     fmt::format("the mass of a moving wall must be positive (got {})", wall.mass));
    }
    wall.v0 = c4.real(1, "V0", 0.0);
  }
  if (block.has_option("FORCES")) {  // the last card, after _FINITE's and _MOVING's
    const Card cf = cursor.next(n++, kEightByTen, "SOFT SSID N1 N2 N3 N4");
    const int soft = cf.flag(0, "SOFT", 0);
    if (soft != 0) {
      throw cf.error("SOFT", fmt::format("SOFT {} (force spike reduction over several cycles) is "
                                         "not supported: the wall stops nodes in one cycle; "
                                         "leave SOFT blank or 0",
                                         soft));
    }
    wall.force_segments = non_negative_id(cf, 1, "SSID");
    // N1..N4 only place the force vector for LS-DYNA's display.
    static const char* const kDisplay[] = {"N1", "N2", "N3", "N4"};
    for (std::size_t k = 0; k < 4; ++k) non_negative_id(cf, 2 + k, kDisplay[k]);
  }
  context.model.rigid_walls.push_back(std::move(wall));
  warn_unread_lines(block, cursor, context);
}

void rigidwall_geometric(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  model::RigidWall wall;
  using Shape = model::RigidWall::Shape;
  const std::string_view base = block.base;
  wall.shape = base.ends_with("_PRISM")      ? Shape::Prism
               : base.ends_with("_CYLINDER") ? Shape::Cylinder
               : base.ends_with("_SPHERE")   ? Shape::Sphere
                                             : Shape::Flat;
  wall.number = static_cast<int>(context.model.rigid_walls.size()) + 1;
  wall.motion = block.has_option("MOTION");
  wall.interior = block.has_option("INTERIOR");
  int n = 1;
  if (block.has_option("ID")) read_wall_id_card(cursor, n++, context, wall);
  const Card c1 = cursor.next(n++, kEightByTen, "NSID NSIDEX BOXID BIRTH DEATH");
  wall.where = c1.location();
  wall.nsid = non_negative_id(c1, 0, "NSID");
  wall.nsidex = non_negative_id(c1, 1, "NSIDEX");
  wall.boxid = non_negative_id(c1, 2, "BOXID");
  wall.birth = non_negative(c1, 3, "BIRTH", 0.0);
  wall.death = c1.real(4, "DEATH", 1e20);
  if (wall.death == 0.0) wall.death = 1e20;
  if (wall.death <= wall.birth) {
    throw c1.error("DEATH",
                   fmt::format("DEATH {} must be later than BIRTH {}", wall.death, wall.birth));
  }

  static const char* const kTail[] = {"XT", "YT", "ZT"};
  static const char* const kHead[] = {"XH", "YH", "ZH"};
  const Card c2 = cursor.next(n++, kEightByTen, "XT YT ZT XH YH ZH FRIC");
  wall.tail = read_point(c2, 0, kTail);
  wall.head = read_point(c2, 3, kHead);
  const auto normal = unit(sub(wall.head, wall.tail));
  if (!normal && wall.shape != Shape::Sphere) {
    throw c2.error("XH", wall.shape == Shape::Cylinder
                             ? "the head XH YH ZH must differ from the tail XT YT ZT: together "
                               "they give the cylinder's axis"
                             : "the head XH YH ZH must differ from the tail XT YT ZT: together "
                               "they give the wall's outward normal");
  }
  wall.fric = c2.real(6, "FRIC", 0.0);
  if (!(wall.fric >= 0.0 && wall.fric <= 1.0)) {
    throw c2.error("FRIC", fmt::format("value {} is not supported: 0 frictionless, 0 < FRIC < 1 "
                                       "Coulomb coefficient, 1 no sliding",
                                       wall.fric));
  }

  if (wall.shape == Shape::Flat || wall.shape == Shape::Prism) {
    const bool prism = wall.shape == Shape::Prism;
    const Card c3 = cursor.next(
        n++, kEightByTen, prism ? "XHEV YHEV ZHEV LENL LENM LENP" : "XHEV YHEV ZHEV LENL LENM");
    wall.finite = true;
    read_finite_edge(c3, *normal, wall);
    if (prism) {
      wall.lenp = c3.real(5, "LENP", 0.0);
      if (!(wall.lenp > 0.0)) {
        throw c3.error("LENP", fmt::format("the depth of the prism behind its face must be "
                                           "positive (got {})",
                                           wall.lenp));
      }
    }
  } else if (wall.shape == Shape::Cylinder) {
    const Card c3 = cursor.next(n++, kEightByTen, "RADCYL LENCYL NSEGS");
    wall.radius = c3.real(0, "RADCYL", 0.0);
    if (!(wall.radius > 0.0)) {
      throw c3.error("RADCYL", fmt::format("the radius must be positive (got {})", wall.radius));
    }
    wall.lencyl = non_negative(c3, 1, "LENCYL", 0.0);
    const int nsegs = c3.flag(2, "NSEGS", 0);
    if (nsegs != 0) {
      throw c3.error("NSEGS", fmt::format("NSEGS {} (force output per subsection of the "
                                          "cylinder) is not supported; leave NSEGS blank or 0",
                                          nsegs));
    }
  } else {
    const Card c3 = cursor.next(n++, kEightByTen, "RADSPH");
    wall.radius = c3.real(0, "RADSPH", 0.0);
    if (!(wall.radius > 0.0)) {
      throw c3.error("RADSPH", fmt::format("the radius must be positive (got {})", wall.radius));
    }
  }

  if (wall.motion) {
    const Card c4 = cursor.next(n++, kEightByTen, "LCID OPT VX VY VZ");
    wall.motion_lcid = c4.id(0, "LCID");
    if (wall.motion_lcid <= 0) throw c4.error("LCID", "a load curve ID is required");
    wall.motion_opt = c4.flag(1, "OPT", 0);
    if (wall.motion_opt != 0 && wall.motion_opt != 1) {
      throw c4.error("OPT", fmt::format("value {} is not supported (0 velocity, 1 displacement)",
                                        wall.motion_opt));
    }
    static const char* const kDirection[] = {"VX", "VY", "VZ"};
    const Vec3 direction = read_point(c4, 2, kDirection);
    const auto dir = unit(direction);
    if (!dir) throw c4.error("VX", "the direction VX VY VZ of the motion must be nonzero");
    wall.motion_direction = *dir;
  }
  if (block.has_option("DISPLAY")) {
    cursor.next(n++, kEightByTen, "PID RO E PR");
    context.warn(block.location(),
                 "_DISPLAY: the display part (PID RO E PR) of a geometric rigid "
                 "wall has no effect here (the wall is not drawn as a part)");
  }
  context.model.rigid_walls.push_back(std::move(wall));
  warn_unread_lines(block, cursor, context);
}

void define_box(const Block& block, ReaderContext& context) {
  for (const auto& option : block.options) {
    if (option == "TITLE") continue;
    ++context.model.unknown_keywords[block.keyword];
    context.warn(block.location(),
                 fmt::format("keyword {} is not supported (only *DEFINE_BOX and "
                             "*DEFINE_BOX_TITLE are); its {} data line(s) were skipped",
                             block.keyword, block.lines.size()));
    return;
  }
  CardCursor cursor(block, context.parameters);
  int n = 1;
  if (block.has_option("TITLE")) cursor.next_text(n++, "title");
  const Card card = cursor.next(n, kEightByTen, "BOXID XMN XMX YMN YMX ZMN ZMX");
  model::Box box;
  box.id = card.id(0, "BOXID");
  if (box.id <= 0) throw card.error("BOXID", "box ID must be a positive integer");
  if (const auto it = context.model.boxes.find(box.id); it != context.model.boxes.end()) {
    const auto& w = it->second.where;
    throw card.error("BOXID", fmt::format("box {} is already defined at {}:{} ({})", box.id, w.file,
                                          w.line, w.keyword));
  }
  static const char* const kMin[] = {"XMN", "YMN", "ZMN"};
  static const char* const kMax[] = {"XMX", "YMX", "ZMX"};
  for (std::size_t k = 0; k < 3; ++k) {
    box.min[k] = card.real(1 + 2 * k, kMin[k], 0.0);
    box.max[k] = card.real(2 + 2 * k, kMax[k], 0.0);
    if (box.max[k] < box.min[k]) {
      throw card.error(kMax[k],
                       fmt::format("maximum {} is below the minimum {}", box.max[k], box.min[k]));
    }
  }
  box.where = card.location();
  context.model.boxes.emplace(box.id, box);
  warn_unread_lines(block, cursor, context);
}

void check_rigid_walls(const model::Model& model) {
  for (const auto& wall : model.rigid_walls) {
    for (const auto& [set, field] : {std::pair{wall.nsid, "NSID"}, {wall.nsidex, "NSIDEX"}}) {
      if (set != 0 && !model.node_sets.count(set)) {
        throw located_error(wall.where, field, fmt::format("node set {} is not defined", set));
      }
    }
    if (wall.boxid != 0 && !model.boxes.count(wall.boxid)) {
      throw located_error(wall.where, "BOXID",
                          fmt::format("box {} is not defined (*DEFINE_BOX)", wall.boxid));
    }
    if (wall.force_segments != 0 && !model.segment_sets.count(wall.force_segments)) {
      throw located_error(wall.where, "SSID",
                          fmt::format("segment set {} is not defined", wall.force_segments));
    }
    if (wall.motion && !model.curves.count(wall.motion_lcid)) {
      throw located_error(wall.where, "LCID",
                          fmt::format("load curve {} is not defined", wall.motion_lcid));
    }
  }
}

}  // namespace rf::io::handlers
