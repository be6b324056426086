#include "io/keyword/restart_deck.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "io/keyword/card.hpp"
#include "io/keyword/parameters.hpp"

namespace rf::io {

namespace {

// Card layouts (LS-DYNA Keyword User's Manual Vol. I, restart section; the *DEFORMABLE_TO_RIGID
// columns agree with ansys/pydyna keyword_classes/auto/deformable/deformable_to_rigid.py):
//   *CONTROL_TERMINATION   ENDTIM ENDCYC DTMIN ENDENG ENDMAS      (8 x 10)
//   *DEFORMABLE_TO_RIGID   PID LRB PTYPE                          (10 10 10), one card per part
//   *RIGID_TO_DEFORMABLE   PID PTYPE                              (10 10), one card per part
const Layout kTermination = uniform_layout(8, 10);
const Layout kDeformableToRigid = {10, 10, 10};
const Layout kRigidToDeformable = {10, 10};

struct Reader {
  const model::Model& model;
  ParameterTable parameters;
  RestartDeck deck;

  explicit Reader(const model::Model& m) : model(m), parameters({}) {
    for (const auto& [name, value] : model.parameters) parameters.define(name, value);
  }

  // PID with PTYPE "PART" (default) or "PSET", expanded to part IDs of the model.
  std::vector<model::Id> parts_of(const Card& card, std::size_t pid_field,
                                  std::size_t ptype_field) const {
    const model::Id pid = card.id(pid_field, "PID");
    std::string ptype = to_upper(card.text(ptype_field));
    if (ptype.empty()) ptype = "PART";
    if (ptype != "PART" && ptype != "PSET") {
      throw card.error(
          "PTYPE", fmt::format("'{}' is not a PID type (PART or PSET)", card.text(ptype_field)));
    }
    if (pid <= 0) throw card.error("PID", "a part (or part set) ID is required");
    if (ptype == "PART") {
      if (!model.parts.count(pid)) {
        throw card.error("PID", fmt::format("part {} is not defined in the dumped model", pid));
      }
      return {pid};
    }
    const auto set = model.part_sets.find(pid);
    if (set == model.part_sets.end()) {
      throw card.error("PID", fmt::format("part set {} is not defined in the dumped model", pid));
    }
    for (const model::Id part : set->second.parts) {
      if (!model.parts.count(part)) {
        throw card.error("PID",
                         fmt::format("part set {} lists part {}, which is not defined", pid, part));
      }
    }
    return set->second.parts;
  }

  void control_termination(const Block& block) {
    CardCursor cursor(block, parameters);
    cursor.skip_blank_lines();
    const auto card = cursor.next_optional(1, kTermination);
    if (!card) return;
    const double endtim = card->real(0, "ENDTIM", 0.0);
    const std::int64_t endcyc = card->integer(1, "ENDCYC", 0);
    if (endtim < 0.0) throw card->error("ENDTIM", "must not be negative");
    if (endcyc < 0) throw card->error("ENDCYC", "must not be negative");
    // Blank or zero keeps the dumped value (as LS-DYNA does for a field left out).
    if (endtim > 0.0) deck.end_time = endtim;
    if (endcyc > 0) deck.end_cycle = endcyc;
    const char* unsupported[] = {"", "", "DTMIN", "ENDENG", "ENDMAS"};
    for (std::size_t i = 2; i < 5; ++i) {
      if (card->real(i, unsupported[i], 0.0) != 0.0) {
        throw card->error(unsupported[i],
                          "cannot be changed on restart (only ENDTIM and ENDCYC "
                          "can)");
      }
    }
    deck.termination_where = card->location();
  }

  void deformable_to_rigid(const Block& block) {
    CardCursor cursor(block, parameters);
    int number = 0;
    for (cursor.skip_blank_lines(); !cursor.at_end(); cursor.skip_blank_lines()) {
      const Card card = cursor.next(++number, kDeformableToRigid, "PID, LRB, PTYPE");
      model::RestartSwitch s;
      s.direction = model::RestartSwitch::Direction::kDeformableToRigid;
      s.parts = parts_of(card, 0, 2);
      s.lead_rigid_body = card.id(1, "LRB");
      if (s.lead_rigid_body < 0) throw card.error("LRB", "must not be negative");
      if (s.lead_rigid_body != 0 && !model.parts.count(s.lead_rigid_body)) {
        throw card.error(
            "LRB", fmt::format("part {} is not defined in the dumped model", s.lead_rigid_body));
      }
      s.where = card.location();
      deck.switches.push_back(std::move(s));
    }
    if (number == 0) throw block_error(block, 1, "PID", "at least one card (PID, LRB, PTYPE)");
  }

  void rigid_to_deformable(const Block& block) {
    CardCursor cursor(block, parameters);
    int number = 0;
    for (cursor.skip_blank_lines(); !cursor.at_end(); cursor.skip_blank_lines()) {
      const Card card = cursor.next(++number, kRigidToDeformable, "PID, PTYPE");
      model::RestartSwitch s;
      s.direction = model::RestartSwitch::Direction::kRigidToDeformable;
      s.parts = parts_of(card, 0, 1);
      s.where = card.location();
      deck.switches.push_back(std::move(s));
    }
    if (number == 0) throw block_error(block, 1, "PID", "at least one card (PID, PTYPE)");
  }

  void dispatch(const Block& block) {
    const std::string& k = block.keyword;
    if (k == "*KEYWORD" || k == "*TITLE") return;
    if (k == "*CONTROL_TERMINATION") return control_termination(block);
    if (k == "*DEFORMABLE_TO_RIGID") return deformable_to_rigid(block);
    if (k == "*RIGID_TO_DEFORMABLE") return rigid_to_deformable(block);
    // Ignoring a card the user meant to change the run would continue a different analysis
    // than the one asked for, so anything else stops the restart.
    throw block_error(block, 0, "",
                      fmt::format("{} cannot be used in a restart deck; a restart deck may "
                                  "contain only {}",
                                  k, kRestartDeckKeywords));
  }
};

std::vector<Block> split_blocks(std::string_view text, const std::string& name) {
  std::vector<Block> blocks;
  int number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = text.find('\n', pos);
    std::string_view line =
        text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
    pos = end == std::string_view::npos ? text.size() : end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!line.empty() && line.front() == '$') continue;
    if (!line.empty() && line.front() == '*') {
      const std::size_t blank = line.find_first_of(" \t");
      std::string keyword = to_upper(line.substr(0, blank));
      CardFormat format = CardFormat::Standard;
      // "*KEY +" / "*KEY+" selects long (20-wide) fields, as in the main deck reader.
      if (keyword.size() > 1 && keyword.back() == '+') {
        keyword.pop_back();
        format = CardFormat::Long;
      } else if (blank != std::string_view::npos &&
                 line.substr(blank).find('+') != std::string_view::npos) {
        format = CardFormat::Long;
      }
      if (keyword == "*END") break;
      Block block;
      block.keyword = keyword;
      block.base = keyword;
      block.file = name;
      block.line = number;
      block.format = format;
      blocks.push_back(std::move(block));
      continue;
    }
    if (blocks.empty()) {
      if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
      throw InputError({name, number, "", 0, ""},
                       "text before the first keyword (a restart deck starts with *KEYWORD)");
    }
    blocks.back().lines.push_back({line, number});
  }
  return blocks;
}

}  // namespace

RestartDeck read_restart_deck_text(std::string_view text, const std::string& name,
                                   const model::Model& model) {
  Reader reader(model);
  // Blocks view `text`; it outlives them.
  for (const Block& block : split_blocks(text, name)) reader.dispatch(block);
  return std::move(reader.deck);
}

RestartDeck read_restart_deck(const std::filesystem::path& path, const model::Model& model) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path.string(), 0, "", 0, ""}, "cannot open the restart deck");
  std::ostringstream content;
  content << in.rdbuf();
  const std::string text = content.str();
  return read_restart_deck_text(text, path.string(), model);
}

}  // namespace rf::io
