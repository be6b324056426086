// Cards of one keyword block and typed access to their fields.
//
// A data line is fixed format (fields of given widths, 10 characters unless the keyword
// says otherwise) unless it contains a comma, in which case it is free format and entry i
// is field i. Blank fields take the caller's default. Numeric fields may be "&name" or
// "-&name" to use a *PARAMETER value.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/keyword/parameters.hpp"
#include "model/error.hpp"
#include "model/model.hpp"

namespace rf::io {

// Field width convention selected on the keyword line.
enum class CardFormat {
  Standard,  // widths as the manual gives them
  Long,      // "*KEY +" or *KEYWORD LONG=Y: every field 20 wide
  I10,       // "*KEY %": 8-wide integer fields become 10 wide
};

struct DataLine {
  std::string_view text;
  int number = 0;  // 1-based line number in its file
};

// One keyword and its data lines (comment lines already removed).
struct Block {
  std::string keyword;               // upper case with '*', e.g. "*SET_NODE_LIST_TITLE"
  std::string base;                  // the registered name it matched, e.g. "*SET_NODE_LIST"
  std::vector<std::string> options;  // remaining suffixes, e.g. {"TITLE"}
  CardFormat format = CardFormat::Standard;
  std::string file;
  int line = 0;
  std::vector<DataLine> lines;
  // IMPETUS dialect: every card is comma-separated (a single field needs no comma), numbers may
  // be "[expression]" or "%name", and a quoted line right after the command is its title.
  bool impetus = false;
  std::string title;

  bool has_option(std::string_view option) const;
  model::SourceLocation location() const { return {file, line, keyword}; }
};

// Widths of the fields of a card in standard format.
using Layout = std::vector<int>;
inline Layout uniform_layout(int count, int width) {
  return Layout(count, width);
}

class Card {
 public:
  Card(const Block& block, const DataLine& line, int card_number, const Layout& layout,
       const ParameterTable& parameters);

  int line_number() const { return line_.number; }
  int card_number() const { return card_number_; }
  bool free_format() const { return free_; }
  std::size_t field_count() const;  // fields present on the line (free) or in the layout

  // Trimmed text of field i; empty when blank or absent.
  std::string_view text(std::size_t i) const;
  bool blank(std::size_t i) const { return text(i).empty(); }

  double real(std::size_t i, const char* name, double fallback) const;
  std::int64_t integer(std::size_t i, const char* name, std::int64_t fallback) const;
  // An integer that must fit an int (flags, codes).
  int flag(std::size_t i, const char* name, int fallback) const;
  // An entity ID; blank gives 0.
  model::Id id(std::size_t i, const char* name) const { return integer(i, name, 0); }

  // Builds an error located at this card and field.
  InputError error(const char* field, const std::string& message) const;
  // Location of this card, for definitions checked after reading.
  model::SourceLocation location() const;

 private:
  std::optional<double> substituted(std::string_view text, const char* name) const;
  std::optional<double> impetus_value(std::string_view text, const char* name) const;

  const Block& block_;
  DataLine line_;
  int card_number_;
  bool free_;
  // Fixed format: "columns A-B ..." and how to write a wider value, for a field that does not
  // parse (a value wider than its column runs into the next field).
  std::string column_hint(std::size_t i) const;

  std::vector<std::string_view> fields_;
  std::vector<std::pair<std::size_t, std::size_t>> columns_;  // fixed format: 1-based first, last
  const ParameterTable& parameters_;
};

// Walks the data lines of a block card by card.
class CardCursor {
 public:
  CardCursor(const Block& block, const ParameterTable& parameters)
      : block_(block), parameters_(parameters) {}

  bool at_end() const { return next_ >= block_.lines.size(); }
  // Skips lines that are entirely blank (used between repeated cards such as nodes).
  void skip_blank_lines();
  // Next card; throws naming `fields` when the block has no more lines.
  Card next(int card_number, const Layout& layout, const char* fields);
  // Next card if present, otherwise nullopt (optional trailing cards).
  std::optional<Card> next_optional(int card_number, const Layout& layout);
  // A line taken verbatim (titles, headings, file names).
  std::string next_text(int card_number, const char* what, bool required = true);
  const DataLine* peek() const { return at_end() ? nullptr : &block_.lines[next_]; }
  std::size_t remaining() const { return block_.lines.size() - next_; }

 private:
  const Block& block_;
  const ParameterTable& parameters_;
  std::size_t next_ = 0;
};

// The _ID forms of loads and boundary conditions: LS-PrePost writes an ID card (ID, HEADING)
// before every data card. Another ID card is recognised by its text after column 10 (or the
// first comma): blank, or not all numbers (a heading).
bool looks_like_id_card(const Block& block, const DataLine& line);

// IMPETUS card fields: split at commas that are not inside [ ], ( ) or quotes, trimmed.
std::vector<std::string_view> split_impetus_fields(std::string_view line);
// "%L1+%L2" -> "L1+L2": parameter names as the expression evaluator knows them.
std::string strip_parameter_marks(std::string_view expression);

// Errors about a whole block (missing cards, unsupported options).
InputError block_error(const Block& block, int card, const char* field, const std::string& message);
InputError located_error(const model::SourceLocation& where, const char* field,
                         const std::string& message);

}  // namespace rf::io
