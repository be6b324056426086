// Sets beyond the plain lists: *SET_..._LIST_GENERATE (ID ranges), *SET_NODE_GENERAL and
// *SET_PART_GENERAL (rules: all, by part, by box, with deletions), *SET_SOLID lists. Ranges and
// rules name things defined anywhere in the deck, so they are resolved after reading.
#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "io/keyword/handlers.hpp"
#include "io/keyword/number.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

char kind_of(const Block& block) {
  if (block.base.starts_with("*SET_PART")) return 'P';
  if (block.base.starts_with("*SET_SOLID")) return 'S';
  return 'N';
}

const char* kind_name(char kind) {
  return kind == 'P' ? "part set" : kind == 'S' ? "solid set" : "node set";
}

// Card 1 of every set keyword (after the _TITLE card): SID DA1..DA4 SOLVER.
ReaderContext::PendingSet read_head(const Block& block, ReaderContext& context, CardCursor& cursor,
                                    int& n) {
  n = 1;
  if (block.has_option("TITLE")) {
    cursor.next_text(n++, "title");
  }
  const Card head = cursor.next(n, kEightByTen, "SID DA1 DA2 DA3 DA4 SOLVER");
  ReaderContext::PendingSet set;
  set.kind = kind_of(block);
  set.id = head.id(0, "SID");
  if (set.id <= 0) throw head.error("SID", "set ID must be a positive integer");
  set.where = head.location();
  return set;
}

}  // namespace

// *SET_NODE_LIST_GENERATE, *SET_PART_LIST_GENERATE, *SET_SOLID_GENERATE: pairs BnBEG BnEND; every
// defined ID in each closed range belongs to the set.
void set_list_generate(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 1;
  auto set = read_head(block, context, cursor, n);
  static const char* const kFields[] = {"B1BEG", "B1END", "B2BEG", "B2END",
                                        "B3BEG", "B3END", "B4BEG", "B4END"};
  ReaderContext::PendingSet::Rule rule{"RANGE", {}, set.where};
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, "B1BEG B1END ...");
    for (std::size_t pair = 0; pair < 4; ++pair) {
      if (card.blank(2 * pair) && card.blank(2 * pair + 1)) continue;
      const model::Id first = card.id(2 * pair, kFields[2 * pair]);
      const model::Id last = card.id(2 * pair + 1, kFields[2 * pair + 1]);
      if (first <= 0 || last < first) {
        throw card.error(kFields[2 * pair + 1],
                         fmt::format("range {}..{} is not a range of positive IDs", first, last));
      }
      rule.values.push_back(first);
      rule.values.push_back(last);
    }
  }
  if (rule.values.empty()) {
    throw block_error(block, 2, "B1BEG", "no ID range follows the set ID card");
  }
  set.rules.push_back(std::move(rule));
  context.pending_sets.push_back(std::move(set));
}

// *SET_NODE_GENERAL, *SET_PART_GENERAL: OPTION E1..E7 per card, applied in order.
void set_general(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 1;
  auto set = read_head(block, context, cursor, n);
  const bool nodes = set.kind == 'N';
  static const Layout layout = uniform_layout(8, 10);
  static const char* const kFields[] = {"E1", "E2", "E3", "E4", "E5", "E6", "E7"};
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, layout, "OPTION E1..E7");
    const std::string option = to_upper(card.text(0));
    const bool known =
        nodes ? (option == "ALL" || option == "NODE" || option == "DNODE" || option == "PART" ||
                 option == "DPART" || option == "BOX" || option == "DBOX")
              : (option == "ALL" || option == "PART" || option == "DPART");
    if (!known) {
      throw card.error("OPTION", fmt::format("'{}' is not supported (supported: {})", option,
                                             nodes ? "ALL, NODE, DNODE, PART, DPART, BOX, DBOX"
                                                   : "ALL, PART, DPART"));
    }
    ReaderContext::PendingSet::Rule rule{option, {}, card.location()};
    for (std::size_t i = 1; i < 8 && i < std::max<std::size_t>(card.field_count(), 8); ++i) {
      const model::Id id = card.id(i, kFields[i - 1]);
      if (id < 0) throw card.error(kFields[i - 1], fmt::format("ID {} must not be negative", id));
      if (id > 0) rule.values.push_back(id);
    }
    if (option != "ALL" && rule.values.empty()) {
      throw card.error("E1", fmt::format("OPTION {} names no ID", option));
    }
    set.rules.push_back(std::move(rule));
  }
  if (set.rules.empty()) throw block_error(block, 2, "OPTION", "no OPTION card follows");
  context.pending_sets.push_back(std::move(set));
}

// *SET_SOLID (and *SET_SOLID_LIST): solid element IDs, eight per card.
void set_solid_list(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  int n = 1;
  auto pending = read_head(block, context, cursor, n);
  model::SolidSet set;
  set.id = pending.id;
  set.where = pending.where;
  while (true) {
    cursor.skip_blank_lines();
    if (cursor.at_end()) break;
    const Card card = cursor.next(++n, kEightByTen, "K1..K8");
    for (std::size_t i = 0; i < card.field_count(); ++i) {
      const model::Id id = card.id(i, "K");
      if (id < 0) throw card.error("K", fmt::format("ID {} must not be negative", id));
      if (id != 0) set.elements.push_back(id);
    }
  }
  // *SET_SOLID(_LIST), *SET_SHELL(_LIST), *SET_BEAM: one reader, one map per family.
  const bool shell = block.base.starts_with("*SET_SHELL");
  const bool beam = block.base.starts_with("*SET_BEAM");
  auto& sets = shell  ? context.model.shell_sets
               : beam ? context.model.beam_sets
                      : context.model.solid_sets;
  const char* family = shell ? "shell" : (beam ? "beam" : "solid");
  if (const auto it = sets.find(set.id); it != sets.end()) {
    throw located_error(set.where, "SID",
                        fmt::format("{} set {} is already defined at {}:{}", family, set.id,
                                    it->second.where.file, it->second.where.line));
  }
  sets.emplace(set.id, std::move(set));
}

// Resolves the pending sets into model.node_sets / part_sets / solid_sets.
void finish_sets(ReaderContext& context) {
  model::Model& m = context.model;
  for (const auto& pending : context.pending_sets) {
    std::set<model::Id> ids;
    for (const auto& rule : pending.rules) {
      const auto& v = rule.values;
      auto in = [&](model::Id id) { return std::find(v.begin(), v.end(), id) != v.end(); };
      std::vector<model::Id> chosen;
      if (rule.option == "RANGE") {
        auto in_range = [&](model::Id id) {
          for (std::size_t k = 0; k + 1 < v.size(); k += 2) {
            if (id >= v[k] && id <= v[k + 1]) return true;
          }
          return false;
        };
        if (pending.kind == 'N') {
          for (const auto& node : m.nodes) {
            if (in_range(node.id)) chosen.push_back(node.id);
          }
        } else if (pending.kind == 'P') {
          for (const auto& [id, part] : m.parts) {
            if (in_range(id)) chosen.push_back(id);
          }
        } else {
          for (const auto& e : m.solids) {
            if (in_range(e.id)) chosen.push_back(e.id);
          }
        }
      } else if (rule.option == "ALL") {
        if (pending.kind == 'N') {
          for (const auto& node : m.nodes) chosen.push_back(node.id);
        } else {
          for (const auto& [id, part] : m.parts) chosen.push_back(id);
        }
      } else if (rule.option == "NODE" || rule.option == "DNODE") {
        chosen = v;
      } else if (rule.option == "PART" || rule.option == "DPART") {
        for (const model::Id pid : v) {
          if (!m.parts.count(pid)) {
            throw located_error(rule.where, "E1",
                                fmt::format("{} {}: part {} is not defined",
                                            kind_name(pending.kind), pending.id, pid));
          }
        }
        if (pending.kind == 'P') {
          chosen = v;
        } else {
          for (const auto& e : m.solids) {
            if (in(e.pid)) chosen.insert(chosen.end(), e.nodes.begin(), e.nodes.end());
          }
          for (const auto& e : m.shells) {
            if (in(e.pid)) chosen.insert(chosen.end(), e.nodes.begin(), e.nodes.end());
          }
          for (const auto& e : m.beams) {  // N1 N2 (N3 only orients the section)
            if (in(e.pid)) chosen.insert(chosen.end(), e.nodes.begin(), e.nodes.begin() + 2);
          }
        }
      } else if (rule.option == "BOX" || rule.option == "DBOX") {
        for (const model::Id box : v) {
          const auto it = m.boxes.find(box);
          if (it == m.boxes.end()) {
            throw located_error(
                rule.where, "E1",
                fmt::format("node set {}: box {} is not defined (*DEFINE_BOX)", pending.id, box));
          }
          for (const auto& node : m.nodes) {
            bool inside = true;
            for (int k = 0; k < 3; ++k) {
              inside &= node.x[k] >= it->second.min[k] && node.x[k] <= it->second.max[k];
            }
            if (inside) chosen.push_back(node.id);
          }
        }
      }
      const bool remove = rule.option.starts_with('D');
      for (const model::Id id : chosen) {
        if (remove)
          ids.erase(id);
        else
          ids.insert(id);
      }
    }
    const std::vector<model::Id> list(ids.begin(), ids.end());
    auto add = [&](auto& map, auto set, const char* what) {
      if (const auto it = map.find(pending.id); it != map.end()) {
        throw located_error(pending.where, "SID",
                            fmt::format("{} {} is already defined at {}:{}", what, pending.id,
                                        it->second.where.file, it->second.where.line));
      }
      map.emplace(pending.id, std::move(set));
    };
    if (pending.kind == 'N') {
      model::NodeSet set{pending.id, list, pending.where};
      add(m.node_sets, std::move(set), "node set");
    } else if (pending.kind == 'P') {
      model::PartSet set{pending.id, list, pending.where};
      add(m.part_sets, std::move(set), "part set");
    } else {
      model::SolidSet set{pending.id, list, pending.where};
      add(m.solid_sets, std::move(set), "solid set");
    }
  }
}

}  // namespace rf::io::handlers
