// IMPETUS Afea input: dialect detection and splitting into command blocks. The cards
// themselves are read by the shared Card class (Block::impetus switches it to comma-separated
// fields with [expression] and %parameter values).
#include <algorithm>
#include <array>
#include <cctype>
#include <string>

#include "io/keyword/context.hpp"
#include "io/keyword/number.hpp"

namespace rf::io {

namespace {

// Commands that exist only in IMPETUS decks (LS-DYNA has none of these names).
constexpr std::array<std::string_view, 12> kImpetusOnly{
    "*UNIT_SYSTEM", "*TIME",           "*OUTPUT",      "*COMPONENT_",
    "*BC_MOTION",   "*CHANGE_P-ORDER", "*GEOMETRY_",   "*MERGE_DUPLICATED_NODES",
    "*FUNCTION",    "*OUTPUT_NODE",    "*BC_SYMMETRY", "*CURVE"};

// Markers of an LS-DYNA deck.
constexpr std::array<std::string_view, 5> kLsDynaOnly{"*KEYWORD", "*CONTROL_", "*DATABASE_",
                                                      "*SECTION_", "*DEFINE_"};

std::string keyword_of(std::string_view line) {
  const auto blank = line.find_first_of(" \t\r,");
  return to_upper(line.substr(0, blank));
}

bool matches(const std::string& keyword, std::string_view pattern) {
  if (pattern.back() == '_') return keyword.starts_with(pattern);
  return keyword == pattern;
}

}  // namespace

DialectGuess detect_dialect(std::string_view text) {
  std::string impetus_marker;
  std::string lsdyna_marker;
  int line_number = 0;
  bool in_parameter = false;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const auto end = text.find('\n', pos);
    const std::string_view line =
        trim(text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
    pos = end == std::string_view::npos ? text.size() : end + 1;
    ++line_number;
    if (line.empty()) continue;
    if (line.front() == '$' && lsdyna_marker.empty()) {
      lsdyna_marker = "'$' comment line " + std::to_string(line_number);
    }
    if (line.front() == '*') {
      const std::string keyword = keyword_of(line);
      in_parameter = keyword == "*PARAMETER";
      for (auto pattern : kImpetusOnly) {
        if (impetus_marker.empty() && matches(keyword, pattern)) {
          impetus_marker = keyword + " on line " + std::to_string(line_number);
        }
      }
      for (auto pattern : kLsDynaOnly) {
        if (lsdyna_marker.empty() && matches(keyword, pattern)) {
          lsdyna_marker = keyword + " on line " + std::to_string(line_number);
        }
      }
      continue;
    }
    if (in_parameter && line.front() == '%' && impetus_marker.empty()) {
      impetus_marker = "'%' parameter on line " + std::to_string(line_number);
    }
  }
  if (!impetus_marker.empty() && lsdyna_marker.empty()) {
    return {Dialect::Impetus, "IMPETUS: detected from " + impetus_marker};
  }
  if (!impetus_marker.empty()) {
    return {Dialect::LsDyna, "LS-DYNA: " + lsdyna_marker + " outweighs " + impetus_marker +
                                 " (use --dialect impetus to override)"};
  }
  return {Dialect::LsDyna, "LS-DYNA: no IMPETUS-only command found"};
}

namespace {

bool is_command_char(char c) {
  return std::isupper(static_cast<unsigned char>(c)) ||
         std::isdigit(static_cast<unsigned char>(c)) || c == '_' || c == '-';
}

// Start of a command inside a line: '*' after a blank (or at the start), followed by an upper-case
// command name and a blank or the end. "4*pi" and "[%a*2]" do not qualify.
bool command_starts_at(std::string_view line, std::size_t i) {
  if (line[i] != '*' || (i > 0 && line[i - 1] != ' ' && line[i - 1] != '\t')) return false;
  std::size_t j = i + 1;
  if (j >= line.size() || !std::isupper(static_cast<unsigned char>(line[j]))) return false;
  while (j < line.size() && is_command_char(line[j])) ++j;
  return j == line.size() || line[j] == ' ' || line[j] == '\t';
}

}  // namespace

std::string reflow_single_line_deck(std::string_view line) {
  // Text copied from a web page can arrive with its line breaks turned into blanks, e.g.
  // `*TIME [%tend] *OUTPUT [%tend/5] # # --- MESH --- # *COMPONENT_CYLINDER 1, 1, 20, 4 0, 0, ...`.
  // Line breaks are restored where they must have been: before each command, after a command
  // name, after a leading quoted title, and between two cards, i.e. at a blank that has no
  // comma or '=' on either side and lies outside quotes and brackets. A '#' outside quotes starts
  // a comment that runs to the next command (comments stood on their own lines).
  std::string out;
  int depth = 0;
  bool quoted = false;
  bool comment = false;
  bool after_command = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (!quoted && command_starts_at(line, i)) {
      if (!out.empty()) out += '\n';
      comment = false;
      depth = 0;
      std::size_t j = i + 1;
      while (j < line.size() && is_command_char(line[j])) ++j;
      out += line.substr(i, j - i);
      out += '\n';
      i = j - 1;
      after_command = true;
      continue;
    }
    if (comment) continue;
    if (!quoted && c == '#') {
      comment = true;
      continue;
    }
    if (c == '"') quoted = !quoted;
    if (!quoted) {
      if (c == '[' || c == '(') ++depth;
      if ((c == ']' || c == ')') && depth > 0) --depth;
    }
    if (c == ' ' && !quoted && depth == 0) {
      // Blank run: is it a card boundary?
      std::size_t j = i;
      while (j < line.size() && line[j] == ' ') ++j;
      const char before = out.empty() ? '\n' : out.back();
      const char next = j < line.size() ? line[j] : '\n';
      const bool boundary = before != '\n' && before != ',' && before != '=' && next != ',' &&
                            next != '=' && next != '\n' && !command_starts_at(line, j);
      if (boundary)
        out += '\n';
      else if (before != '\n')
        out += ' ';
      i = j - 1;
      after_command = false;
      continue;
    }
    (void)after_command;
    out += c;
  }
  out += '\n';
  return out;
}

std::vector<Block> split_impetus(std::string_view text, const std::string& file_name,
                                 std::string& storage) {
  // A deck with two commands on one line lost its line breaks in transit: restore them. Each
  // restored line keeps the number of the line it came from, for messages.
  bool reflow = false;
  std::size_t pos = 0;
  while (pos < text.size() && !reflow) {
    const auto end = text.find('\n', pos);
    const std::string_view line =
        text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
    int count = 0;
    for (std::size_t i = 0; i < line.size(); ++i) count += command_starts_at(line, i) ? 1 : 0;
    reflow = count >= 2;
    pos = end == std::string_view::npos ? text.size() : end + 1;
  }
  if (!reflow) return split_lines(text, file_name, {});
  storage.clear();
  std::vector<int> origin;
  pos = 0;
  int number = 0;
  while (pos < text.size()) {
    const auto end = text.find('\n', pos);
    std::string_view line =
        text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
    pos = end == std::string_view::npos ? text.size() : end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string lines = reflow_single_line_deck(line);
    for (char c : lines) {
      if (c == '\n') origin.push_back(number);
    }
    storage += lines;
  }
  return split_lines(storage, file_name, origin);
}

std::vector<Block> split_lines(std::string_view text, const std::string& file_name,
                               const std::vector<int>& line_origin) {
  std::vector<Block> blocks;
  int line_number = 0;
  std::size_t reflowed_index = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const auto end = text.find('\n', pos);
    std::string_view raw =
        text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
    pos = end == std::string_view::npos ? text.size() : end + 1;
    ++line_number;
    if (!line_origin.empty()) {
      line_number =
          line_origin[std::min(line_origin.size(), static_cast<std::size_t>(++reflowed_index)) - 1];
    }
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == '#') continue;
    if (line.front() == '*') {
      Block block;
      block.file = file_name;
      block.line = line_number;
      block.impetus = true;
      block.keyword = keyword_of(line);
      if (block.keyword == "*END") break;
      blocks.push_back(std::move(block));
      continue;
    }
    if (blocks.empty()) continue;  // text before the first command
    Block& block = blocks.back();
    if (block.lines.empty() && block.title.empty() && line.front() == '"') {
      std::string_view title = line.substr(1);
      if (const auto close = title.find('"'); close != std::string_view::npos) {
        title = title.substr(0, close);
      }
      block.title = std::string(title);
      continue;
    }
    block.lines.push_back({line, line_number});
  }
  return blocks;
}

}  // namespace rf::io
