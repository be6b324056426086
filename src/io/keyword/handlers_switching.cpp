// Deformable <-> rigid part switching: *DEFORMABLE_TO_RIGID, *DEFORMABLE_TO_RIGID_AUTOMATIC,
// *DEFORMABLE_TO_RIGID_INERTIA (LS-DYNA manual vol. I, *DEFORMABLE_TO_RIGID). Cross
// references (parts, part sets, paired sets, rigid walls, sensors) are checked in
// finish_switching once the whole deck is read. Semantics: docs/switching.md.
#include <fmt/format.h>

#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"
#include "io/keyword/parameters.hpp"

namespace rf::io {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

model::Id positive(const Card& card, std::size_t i, const char* field, const char* what) {
  const model::Id id = card.id(i, field);
  if (id <= 0) throw card.error(field, fmt::format("{} ID must be a positive integer", what));
  return id;
}

model::Id non_negative(const Card& card, std::size_t i, const char* field) {
  const model::Id id = card.id(i, field);
  if (id < 0) throw card.error(field, fmt::format("ID {} must not be negative", id));
  return id;
}

int flag_of(const Card& card, std::size_t i, const char* field, int lo, int hi,
            const char* meaning) {
  const int v = card.flag(i, field, 0);
  if (v < lo || v > hi) {
    throw card.error(field, fmt::format("value {} is not one of {}..{} ({})", v, lo, hi, meaning));
  }
  return v;
}

// D2R / R2D: how many part cards follow (a non-negative count).
int card_count(const Card& card, std::size_t i, const char* field) {
  const int v = card.flag(i, field, 0);
  if (v < 0) throw card.error(field, fmt::format("count {} must not be negative", v));
  return v;
}

// PTYPE: "PART" (default) or "PSET".
bool part_set_type(const Card& card, std::size_t i) {
  const std::string type = to_upper(card.text(i));
  if (type.empty() || type == "PART") return false;
  if (type == "PSET") return true;
  throw card.error("PTYPE", fmt::format("'{}' is not PART or PSET", card.text(i)));
}

model::PartSwitch read_part_switch(const Card& card, bool with_lead) {
  model::PartSwitch s;
  s.pid = positive(card, 0, "PID", "part");
  if (with_lead) {
    s.lrb = non_negative(card, 1, "LRB");
    s.part_set = part_set_type(card, 2);
  } else {
    s.part_set = part_set_type(card, 1);
  }
  s.where = card.location();
  return s;
}

bool blank_lines_only(const CardCursor& cursor, const Block& block) {
  for (std::size_t i = block.lines.size() - cursor.remaining(); i < block.lines.size(); ++i) {
    if (!trim(block.lines[i].text).empty()) return false;
  }
  return true;
}

}  // namespace

namespace handlers {

void deformable_to_rigid(const Block& block, ReaderContext& context) {
  auto& switching = context.model.switching;
  switching.flagged = true;
  // The manual allows the keyword without cards: it only flags switching for a restart.
  CardCursor cursor(block, context.parameters);
  int n = 0;
  while (!blank_lines_only(cursor, block)) {
    cursor.skip_blank_lines();
    const Card card = cursor.next(++n, kEightByTen, "PID LRB PTYPE");
    switching.at_start.push_back(read_part_switch(card, true));
  }
}

void deformable_to_rigid_automatic(const Block& block, ReaderContext& context) {
  auto& switching = context.model.switching;
  switching.flagged = true;
  CardCursor cursor(block, context.parameters);
  model::AutomaticSwitchSet set;
  const Card first = cursor.next(1, kEightByTen, "SWSET CODE TIME1 TIME2 TIME3 ENTNO RELSW PAIRED");
  set.swset = positive(first, 0, "SWSET", "switch set");
  for (const auto& other : switching.automatic) {
    if (other.swset == set.swset) {
      throw first.error("SWSET", fmt::format("switch set {} is already defined at {}:{}", set.swset,
                                             other.where.file, other.where.line));
    }
  }
  set.code = flag_of(first, 1, "CODE", 0, 5,
                     "0 time, 1/3 rigid wall force zero/nonzero, 2/4 contact force "
                     "zero/nonzero, 5 sensor");
  // CODE 5: "inputs of column 3 to column 8, TIME1 to PAIRED, are ignored" (manual).
  if (set.code != 5) {
    set.time1 = first.real(2, "TIME1", 0.0);
    set.time2 = first.real(3, "TIME2", 0.0);
    if (set.time2 == 0.0) set.time2 = 1e20;  // manual: 0 means 10^20
    if (set.time2 < set.time1) {
      throw first.error("TIME2", fmt::format("TIME2 = {:g} is before TIME1 = {:g}: the set "
                                             "could never switch",
                                             set.time2, set.time1));
    }
    set.time3 = first.real(4, "TIME3", 0.0);
    if (set.time3 < 0.0) {
      throw first.error("TIME3", fmt::format("delay {:g} must not be negative", set.time3));
    }
    set.entno = non_negative(first, 5, "ENTNO");
    if ((set.code == 2 || set.code == 4) && set.entno == 0) {
      throw first.error("ENTNO", fmt::format("CODE {} needs the ID of the contact whose force is "
                                             "tested (the CID of its *CONTACT_..._ID card, or "
                                             "its position among the contacts without _ID)",
                                             set.code));
    }
    if ((set.code == 1 || set.code == 3) && set.entno == 0) {
      throw first.error("ENTNO", fmt::format("CODE {} needs the number of the rigid wall whose "
                                             "force is tested (1 = first in the deck)",
                                             set.code));
    }
    set.relsw = non_negative(first, 6, "RELSW");
    set.paired = flag_of(first, 7, "PAIRED", -1, 1, "0 not paired, 1 first, -1 second");
    if (set.paired != 0 && set.relsw == 0) {
      throw first.error("RELSW",
                        fmt::format("PAIRED = {} needs the related switch set RELSW", set.paired));
    }
    if (set.paired == 0 && set.relsw != 0) {
      throw first.error("PAIRED", fmt::format("RELSW = {} names a related set but PAIRED is 0: "
                                              "give PAIRED = 1 (this set first) or -1 (second)",
                                              set.relsw));
    }
    if (set.relsw == set.swset) {
      throw first.error("RELSW", "a switch set cannot be paired with itself");
    }
  }
  const Card second = cursor.next(2, kEightByTen, "NRBF NCSF RWF DTMAX D2R R2D OFFSET");
  set.nrbf = flag_of(second, 0, "NRBF", 0, 2, "0 no action, 1 delete, 2 activate");
  set.ncsf = flag_of(second, 1, "NCSF", 0, 2, "0 no change, 1 delete, 2 activate");
  set.rwf = flag_of(second, 2, "RWF", 0, 2, "0 no change, 1 delete, 2 activate");
  set.dtmax = second.real(3, "DTMAX", 0.0);
  if (set.dtmax < 0.0) {
    throw second.error("DTMAX", fmt::format("{:g} must not be negative", set.dtmax));
  }
  const int d2r = card_count(second, 4, "D2R");
  const int r2d = card_count(second, 5, "R2D");
  set.offset = second.real(6, "OFFSET", 0.0);
  if (set.offset < 0.0) {
    throw second.error("OFFSET", fmt::format("{:g} must not be negative", set.offset));
  }
  if (set.offset != 0.0 && set.code != 3 && set.code != 4) {
    context.warn(second.location(), fmt::format("OFFSET = {:g} applies only to CODE 3 and 4; "
                                                "switch set {} has CODE {} and ignores it",
                                                set.offset, set.swset, set.code));
  }
  int n = 3;
  for (int k = 0; k < d2r; ++k) {
    set.to_rigid.push_back(read_part_switch(cursor.next(n, kEightByTen, "PID LRB PTYPE"), true));
  }
  for (int k = 0; k < r2d; ++k) {
    set.to_deformable.push_back(
        read_part_switch(cursor.next(n + 1, kEightByTen, "PID PTYPE"), false));
  }
  if (d2r == 0 && r2d == 0) {
    context.warn(second.location(),
                 fmt::format("switch set {} names no parts (D2R = R2D = 0)", set.swset));
  }
  set.where = first.location();
  if (!blank_lines_only(cursor, block)) {
    throw block_error(block, n + 2, "D2R",
                      fmt::format("more cards follow than D2R = {} and R2D = {} announce (one "
                                  "*DEFORMABLE_TO_RIGID_AUTOMATIC keyword per switch set)",
                                  d2r, r2d));
  }
  switching.automatic.push_back(std::move(set));
}

void deformable_to_rigid_inertia(const Block& block, ReaderContext& context) {
  auto& switching = context.model.switching;
  switching.flagged = true;
  CardCursor cursor(block, context.parameters);
  int n = 0;
  do {
    const Card head = cursor.next(n + 1, kEightByTen, "PID");
    model::SwitchInertia in;
    in.pid = positive(head, 0, "PID", "part");
    if (const auto it = switching.inertia.find(in.pid); it != switching.inertia.end()) {
      throw head.error("PID", fmt::format("part {} already has inertia at {}:{}", in.pid,
                                          it->second.where.file, it->second.where.line));
    }
    const Card mass = cursor.next(n + 2, kEightByTen, "XC YC ZC TM");
    in.xc = {mass.real(0, "XC", 0.0), mass.real(1, "YC", 0.0), mass.real(2, "ZC", 0.0)};
    if (mass.blank(3)) throw mass.error("TM", "the translational mass is required");
    in.tm = mass.real(3, "TM", 0.0);
    if (!(in.tm > 0.0)) throw mass.error("TM", fmt::format("mass {:g} must be positive", in.tm));
    const Card tensor = cursor.next(n + 3, kEightByTen, "IXX IXY IXZ IYY IYZ IZZ");
    static const char* const names[6] = {"IXX", "IXY", "IXZ", "IYY", "IYZ", "IZZ"};
    for (std::size_t k = 0; k < 6; ++k) {
      const bool required = k == 0 || k == 3 || k == 5;  // defaults "none" in the manual
      if (required && tensor.blank(k)) {
        throw tensor.error(names[k], "is required (no default)");
      }
      in.inertia[k] = tensor.real(k, names[k], 0.0);
    }
    in.where = head.location();
    switching.inertia.emplace(in.pid, in);
    n += 3;
  } while (!blank_lines_only(cursor, block));
}

}  // namespace handlers

}  // namespace rf::io
