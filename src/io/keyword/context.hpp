// State shared by the keyword handlers while one deck (and its includes) is read.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/keyword/card.hpp"
#include "io/keyword/parameters.hpp"
#include "io/keyword/reader.hpp"
#include "model/model.hpp"

namespace rf::io {

// Headings of the kinds of problems (InputErrorList groups), in the order a user fixes them.
inline constexpr std::string_view kUnsupportedPhysics =
    "keywords that change the physics and are not supported (remove them, or run with "
    "--ignore-unsupported to run without them)";
inline constexpr std::string_view kCardErrors = "errors in cards";
inline constexpr std::string_view kReferenceErrors = "references between definitions";
inline constexpr std::string_view kModelErrors = "the model as a whole";

struct ReaderContext {
  ReaderContext(model::Model& m, ParameterTable& p) : model(m), parameters(p) {}
  model::Model& model;
  ParameterTable& parameters;
  // Reads an included file; `card` locates the *INCLUDE line for error messages.
  std::function<void(const std::string& filename, const Card& card)> include;

  // Where each node and element ID was first defined (file index into model.files, line):
  // nodes carry no SourceLocation of their own, so duplicates are caught while reading.
  std::unordered_map<model::Id, std::pair<int, int>> node_origin;
  std::unordered_map<model::Id, std::pair<int, int>> element_origin;
  int current_file_index = 0;

  // Things that can only be resolved once the whole deck has been read.
  int d3plot_npltc = 0;
  struct HistorySet {
    model::Id nsid = 0;
    model::SourceLocation where;
  };
  std::vector<HistorySet> history_node_sets;
  std::vector<HistorySet> history_nodes;  // individual nodes, kept with their card
  model::SourceLocation lctm_where;
  struct Exemption {
    std::size_t velocity_index = 0;  // into model.initial_velocities
    model::Id nsidex = 0;
    model::SourceLocation where;
  };
  std::vector<Exemption> exemptions;
  // *CONSTRAINED_GENERALIZED_WELD_SPOT: a spot weld of the two nodes of a node set, resolved
  // into model.spot_welds once the sets are complete (finish_model).
  struct GeneralizedWeld {
    model::SpotWeld weld;  // n1, n2 filled from the set
    bool with_id = false;
    model::Id nsid = 0;
  };
  std::vector<GeneralizedWeld> generalized_welds;

  // IMPETUS definitions resolved once the whole deck is read (finish_impetus): generated meshes
  // need IDs above every user-defined one, and *BC_MOTION becomes different model entries for
  // rigid and deformable parts.
  struct Component {
    bool cylinder = false;
    model::Id id = 0;
    model::Id pid = 0;
    std::array<int, 3> divisions{};
    std::array<double, 3> p1{};
    std::array<double, 3> p2{};
    double radius = 0.0;
    model::SourceLocation where;
  };
  struct Merge {
    model::Target target1 = model::Target::All;
    model::Id id1 = 0;
    model::Target target2 = model::Target::All;
    model::Id id2 = 0;
    double tolerance = 0.0;
    model::SourceLocation where;
  };
  struct Motion {
    model::Id id = 0;
    std::string title;
    model::Target target = model::Target::All;
    model::Id target_id = 0;
    std::array<bool, 6> fixed{};  // x y z rx ry rz held
    bool has_motion = false;
    int vad = 2;  // 0 velocity, 1 acceleration, 2 displacement
    int dof = 0;  // 0..5: x y z rx ry rz
    model::Id function = 0;
    double scale = 1.0;
    double birth = 0.0;
    double death = 1e28;
    model::SourceLocation where;
  };
  std::vector<Component> components;
  // A plain *DEFINE_TABLE whose curves are still to come: the next `remaining` keywords must be
  // *DEFINE_CURVE (LS-DYNA reads them as the table's curves, in order).
  struct PendingTable {
    model::Id id = 0;
    std::size_t remaining = 0;
    model::SourceLocation where;
  };
  std::optional<PendingTable> pending_table;
  std::vector<Merge> merges;
  std::vector<Motion> motions;
  double impetus_ascii_dt = 0.0;  // *OUTPUT dt_ascii

  // Problems found so far (read_deck throws them together once the whole deck is read): a
  // handler's InputError is caught per keyword block, checks after reading report directly.
  std::vector<InputErrorList::Entry> errors;
  std::size_t dropped_errors = 0;  // beyond kMaxReportedErrors
  static constexpr std::size_t kMaxReportedErrors = 200;
  void report(std::string_view group, const InputError& error) {
    if (errors.size() >= kMaxReportedErrors) {
      ++dropped_errors;
      return;
    }
    errors.push_back({std::string(group), error});
  }

  // Sections and materials of unsupported keywords by ID, so that a *PART naming one is told
  // the real cause ("shells are not supported yet").
  struct SkippedDefinition {
    std::string keyword;
    std::string what;
    model::SourceLocation where;
  };
  std::map<model::Id, SkippedDefinition> skipped_sections;
  std::map<model::Id, SkippedDefinition> skipped_materials;
  // Where *CONTROL_TERMINATION and *CONTROL_IMPLICIT_GENERAL are (checks of the whole model).
  model::SourceLocation termination_where;
  // Sets whose content needs the whole deck (*SET_..._GENERATE ranges, *SET_..._GENERAL rules):
  // resolved by finish_sets before any reference is checked.
  struct PendingSet {
    char kind = 'N';  // 'N' node set, 'P' part set, 'S' solid set
    model::Id id = 0;
    model::SourceLocation where;
    struct Rule {
      std::string option;  // RANGE (GENERATE), ALL, NODE, DNODE, PART, DPART, BOX, DBOX
      std::vector<model::Id> values;
      model::SourceLocation where;
    };
    std::vector<Rule> rules;
  };
  std::vector<PendingSet> pending_sets;
  int parameter_duplication = 1;
  std::vector<std::string> include_paths;  // *INCLUDE_PATH folders, as written  //
                                           // *PARAMETER_DUPLICATION DFLAG (LS-DYNA default 1)
  model::SourceLocation implicit_general_where;

  void warn(const model::SourceLocation& where, std::string message) {
    model.warnings.push_back({where, std::move(message)});
  }
  std::string origin_text(const std::pair<int, int>& origin) const;
};

using KeywordHandler = void (*)(const Block& block, ReaderContext& context);

struct KeywordEntry {
  std::string_view name;  // upper case with '*'
  KeywordHandler handler;
  std::vector<std::string_view> options;  // accepted option suffixes
};

// The keyword table. Lookup takes the longest registered name that the keyword starts
// with (followed by '_' or the end) and treats the remaining '_'-separated words as options.
const KeywordEntry* find_keyword(std::string_view keyword, std::vector<std::string>& options);

// IMPETUS commands (handlers_impetus.cpp): exact names, no option suffixes.
const KeywordEntry* find_impetus_command(std::string_view command);

// Which dialect a deck is written in, judged from its content, with the reason in words.
struct DialectGuess {
  Dialect dialect = Dialect::LsDyna;
  std::string reason;
};
DialectGuess detect_dialect(std::string_view text);

// Splits IMPETUS text into command blocks: '#' comment lines and blank lines are dropped, a
// quoted line right after the command becomes the block's title, *END stops reading.
// A deck that arrives as one long line (line breaks lost when copied from a web page) is first
// restored to one command or card per line (reflow_single_line_deck).
// `storage` keeps reflowed text alive as long as the blocks that view it.
std::vector<Block> split_impetus(std::string_view text, const std::string& file_name,
                                 std::string& storage);
std::vector<Block> split_lines(std::string_view text, const std::string& file_name,
                               const std::vector<int>& line_origin);
std::string reflow_single_line_deck(std::string_view line);

// Cross-reference checks and deferred resolution after every file has been read.
void finish_model(ReaderContext& context);
// What `run` would refuse, reported while reading so that `check` finds it too: no end time,
// no elements, nothing that limits the time step, IMFLAG 1 without an eigen analysis.
void check_runnable(ReaderContext& context);
// IMPETUS part of it: generates component meshes, merges nodes, turns *BC_MOTION into
// constraints and prescribed motions (handlers_impetus.cpp). Runs before finish_model's checks.
void finish_impetus(ReaderContext& context);

// Reports data lines a handler did not consume.
void warn_unread_lines(const Block& block, CardCursor& cursor, ReaderContext& context);

// The number of the first data card: 2 after the title line of a `_TITLE` keyword (consumed
// here), else 1.
inline int skip_title(const Block& block, CardCursor& cursor) {
  if (!block.has_option("TITLE")) return 1;
  cursor.next_text(1, "title");
  return 2;
}

}  // namespace rf::io
