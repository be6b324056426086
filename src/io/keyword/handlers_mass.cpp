// Added masses and mass-proportional damping: *ELEMENT_MASS, *ELEMENT_MASS_PART(_SET),
// *DAMPING_GLOBAL, *DAMPING_PART_MASS(_SET). Card layouts as in the LS-DYNA manual (volume I).
#include <fmt/format.h>

#include <cmath>

#include "io/keyword/handlers.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);
// *ELEMENT_MASS and *ELEMENT_MASS_PART: I8, I8 (or E16), E16, I8 in standard format.
const Layout kElementMass{8, 8, 16, 8};
const Layout kElementMassPart{8, 16, 16, 8};

double non_negative(const Card& card, std::size_t i, const char* name, double fallback) {
  const double value = card.real(i, name, fallback);
  if (!std::isfinite(value) || value < 0.0) {
    throw card.error(name, fmt::format("value {} must be a finite number >= 0", value));
  }
  return value;
}

// STX STY STZ SRX SRY SRZ starting at field `first`. LS-DYNA: if all six are zero (or blank),
// all six default to 1.
void read_direction_scales(const Card& card, std::size_t first, model::MassDamping& damping) {
  static const char* names[6] = {"STX", "STY", "STZ", "SRX", "SRY", "SRZ"};
  std::array<double, 6> s{};
  bool any = false;
  for (int k = 0; k < 6; ++k) {
    s[k] = non_negative(card, first + k, names[k], 0.0);
    any = any || s[k] != 0.0;
  }
  if (!any) s.fill(1.0);
  for (int k = 0; k < 3; ++k) {
    damping.st[k] = s[k];
    damping.sr[k] = s[3 + k];
  }
}

}  // namespace

void element_mass(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  bool any = false;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, kElementMass, "EID NID MASS PID");
    model::PointMass mass;
    mass.id = card.id(0, "EID");
    if (mass.id <= 0) throw card.error("EID", "a positive element ID is required");
    mass.node = card.id(1, "NID");
    if (mass.node <= 0) throw card.error("NID", "a positive node ID is required");
    mass.mass = non_negative(card, 2, "MASS", 0.0);
    mass.part = card.id(3, "PID");
    mass.where = card.location();
    context.model.point_masses.push_back(mass);
    any = true;
  }
  if (!any) throw block_error(block, 1, "EID", "no mass card follows the keyword");
}

void element_mass_part(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const bool set = block.base.ends_with("_SET");
  const char* id_field = set ? "PSID" : "PID";
  bool any = false;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(1, kElementMassPart,
                                  set ? "PSID ADDMASS FINMASS LCID" : "PID ADDMASS FINMASS LCID");
    model::PartMassAddition addition;
    addition.part_set = set;
    addition.id = card.id(0, id_field);
    if (addition.id <= 0) throw card.error(id_field, "a positive ID is required");
    addition.addmass = non_negative(card, 1, "ADDMASS", 0.0);
    addition.finmass = non_negative(card, 2, "FINMASS", 0.0);
    if (addition.addmass > 0.0 && addition.finmass > 0.0) {
      throw card.error("FINMASS", "give either ADDMASS or FINMASS, not both (set the other 0)");
    }
    if (card.id(3, "LCID") != 0) {
      throw card.error("LCID",
                       "a curve for the mass distribution is not supported (leave it "
                       "blank: the mass is distributed in proportion to the lumped "
                       "nodal mass)");
    }
    addition.where = card.location();
    context.model.part_mass_additions.push_back(addition);
    any = true;
  }
  if (!any) throw block_error(block, 1, id_field, "no card follows the keyword");
}

void damping_global(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const Card card = cursor.next(1, kEightByTen, "LCID VALDMP STX STY STZ SRX SRY SRZ");
  model::MassDamping damping;
  damping.global = true;
  damping.lcid = card.id(0, "LCID");
  if (damping.lcid < 0) throw card.error("LCID", "a load curve ID (>= 0) is expected");
  damping.valdmp = non_negative(card, 1, "VALDMP", 0.0);
  read_direction_scales(card, 2, damping);
  damping.where = card.location();
  for (const auto& other : context.model.mass_damping) {
    if (other.global) {
      throw card.error("LCID", fmt::format("*DAMPING_GLOBAL is given twice (first at {}:{})",
                                           other.where.file, other.where.line));
    }
  }
  context.model.mass_damping.push_back(damping);
  warn_unread_lines(block, cursor, context);
}

void damping_part_mass(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  const bool set = block.base.ends_with("_SET");
  const char* id_field = set ? "PSID" : "PID";
  bool any = false;
  int n = 1;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card =
        cursor.next(n, kEightByTen, set ? "PSID LCID SF FLAG STRUC" : "PID LCID SF FLAG STRUC");
    model::MassDamping damping;
    damping.global = false;
    damping.part_set = set;
    damping.id = card.id(0, id_field);
    if (damping.id <= 0) throw card.error(id_field, "a positive ID is required");
    damping.lcid = card.id(1, "LCID");
    if (damping.lcid <= 0) throw card.error("LCID", "a load curve ID is required");
    damping.sf = card.real(2, "SF", 1.0);
    if (!std::isfinite(damping.sf)) throw card.error("SF", "a finite number is expected");
    const int flag = card.flag(3, "FLAG", 0);
    if (flag != 0 && flag != 1) {
      throw card.error("FLAG", fmt::format("value {} is not supported (0 or 1)", flag));
    }
    if (card.flag(4, "STRUC", 0) != 0) {
      throw card.error("STRUC",
                       "STRUC 1 (exclude *ELEMENT_MASS from damping) is not supported; "
                       "leave it 0");
    }
    damping.where = card.location();
    if (flag == 1) {
      const Card scales = cursor.next(n + 1, kEightByTen, "STX STY STZ SRX SRY SRZ");
      read_direction_scales(scales, 0, damping);
    }
    n += flag == 1 ? 2 : 1;
    context.model.mass_damping.push_back(damping);
    any = true;
  }
  if (!any) throw block_error(block, 1, id_field, "no card follows the keyword");
}

}  // namespace rf::io::handlers
