// State shared by the keyword handlers while one deck (and its includes) is read.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/keyword/card.hpp"
#include "io/keyword/parameters.hpp"
#include "model/model.hpp"

namespace rf::io {

struct ReaderContext {
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

// Cross-reference checks and deferred resolution after every file has been read.
void finish_model(ReaderContext& context);

// Reports data lines a handler did not consume.
void warn_unread_lines(const Block& block, CardCursor& cursor, ReaderContext& context);

}  // namespace rf::io
