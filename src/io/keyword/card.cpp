#include "io/keyword/card.hpp"

#include <fmt/format.h>

#include <climits>
#include <cmath>

#include "io/keyword/number.hpp"

namespace rf::io {

bool Block::has_option(std::string_view option) const {
  for (const auto& o : options) {
    if (o == option) return true;
  }
  return false;
}

InputError block_error(const Block& block, int card, const char* field,
                       const std::string& message) {
  return InputError({block.file, block.line, block.keyword, card, field ? field : ""}, message);
}

InputError located_error(const model::SourceLocation& where, const char* field,
                         const std::string& message) {
  return InputError({where.file, where.line, where.keyword, 0, field ? field : ""}, message);
}

namespace {

int effective_width(int width, CardFormat format) {
  switch (format) {
    case CardFormat::Long:
      return 20;
    case CardFormat::I10:
      return width == 8 ? 10 : width;
    case CardFormat::Standard:
      break;
  }
  return width;
}

// Shows offending text safely: binary garbage must not end up raw in a message.
std::string quoted(std::string_view text) {
  std::string out = "'";
  for (char c : text.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 32 && u < 127)
      out += c;
    else
      out += fmt::format("\\x{:02x}", u);
  }
  if (text.size() > 40) out += "...";
  return out + "'";
}

}  // namespace

Card::Card(const Block& block, const DataLine& line, int card_number, const Layout& layout,
           const ParameterTable& parameters)
    : block_(block),
      line_(line),
      card_number_(card_number),
      free_(block.impetus || line.text.find(',') != std::string_view::npos),
      parameters_(parameters) {
  if (block.impetus) {
    fields_ = split_impetus_fields(line.text);
    return;
  }
  if (free_) {
    std::string_view rest = line.text;
    while (true) {
      const auto comma = rest.find(',');
      fields_.push_back(trim(rest.substr(0, comma)));
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    return;
  }
  std::size_t offset = 0;
  for (int width : layout) {
    const auto w = static_cast<std::size_t>(effective_width(width, block.format));
    columns_.emplace_back(offset + 1, offset + w);
    if (offset >= line.text.size()) {
      fields_.emplace_back();
    } else {
      fields_.push_back(trim(line.text.substr(offset, w)));
    }
    offset += w;
  }
}

std::size_t Card::field_count() const {
  return fields_.size();
}

std::string_view Card::text(std::size_t i) const {
  return i < fields_.size() ? fields_[i] : std::string_view{};
}

InputError Card::error(const char* field, const std::string& message) const {
  return InputError({block_.file, line_.number, block_.keyword, card_number_, field}, message);
}

model::SourceLocation Card::location() const {
  return {block_.file, line_.number, block_.keyword};
}

std::optional<double> Card::substituted(std::string_view text, const char* name) const {
  if (block_.impetus) return impetus_value(text, name);
  bool negate = false;
  if (text.size() >= 2 && text[0] == '-' && text[1] == '&') {
    negate = true;
    text.remove_prefix(2);
  } else if (!text.empty() && text[0] == '&') {
    text.remove_prefix(1);
  } else {
    return std::nullopt;
  }
  text = trim(text);
  if (text.empty()) throw error(name, "'&' must be followed by a parameter name");
  const auto value = parameters_.find(text);
  if (!value) {
    if (parameters_.contains(text)) {
      throw error(
          name, fmt::format("parameter {} is a text parameter, a number is needed", quoted(text)));
    }
    throw error(name, fmt::format("parameter {} is not defined (define it with *PARAMETER "
                                  "before it is used)",
                                  quoted(text)));
  }
  return negate ? -*value : *value;
}

// IMPETUS: "[expression]" anywhere a number is expected, or a parameter "%name" on its own
// (optionally negated). Parameter names inside expressions are written with their '%'.
std::optional<double> Card::impetus_value(std::string_view text, const char* name) const {
  if (text.front() == '[') {
    if (text.back() != ']') throw error(name, fmt::format("{} has no closing ']'", quoted(text)));
    const std::string_view inner = trim(text.substr(1, text.size() - 2));
    if (inner.empty()) throw error(name, "the expression in [ ] is empty");
    try {
      return parameters_.evaluate(strip_parameter_marks(inner));
    } catch (const std::exception& e) {
      throw error(name, fmt::format("cannot evaluate {}: {}", quoted(text), e.what()));
    }
  }
  bool negate = false;
  if (text.size() >= 2 && text[0] == '-' && text[1] == '%') {
    negate = true;
    text.remove_prefix(1);
  }
  if (text.front() != '%') return std::nullopt;
  const std::string_view parameter = trim(text.substr(1));
  const auto value = parameters_.find(parameter);
  if (!value) {
    throw error(name, fmt::format("parameter {} is not defined (define it with *PARAMETER "
                                  "before it is used)",
                                  quoted(text)));
  }
  return negate ? -*value : *value;
}

bool looks_like_id_card(const Block& block, const DataLine& line) {
  const std::string_view text = line.text;
  std::vector<std::string_view> rest;
  if (const auto comma = text.find(','); comma != std::string_view::npos) {
    std::string_view tail = text.substr(comma + 1);
    while (true) {
      const auto next = tail.find(',');
      rest.push_back(trim(tail.substr(0, next)));
      if (next == std::string_view::npos) break;
      tail.remove_prefix(next + 1);
    }
  } else {
    const std::size_t width = block.format == CardFormat::Long ? 20 : 10;
    for (std::size_t offset = width; offset < text.size(); offset += width) {
      rest.push_back(trim(text.substr(offset, width)));
    }
  }
  bool any = false;
  for (const std::string_view field : rest) {
    if (field.empty()) continue;
    any = true;
    const bool parameter = field.front() == '&' || field.starts_with("-&");
    if (!parameter && !parse_real(field).value) return true;
  }
  return !any;
}

std::vector<std::string_view> split_impetus_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  int depth = 0;
  bool in_quotes = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') in_quotes = !in_quotes;
    if (in_quotes) continue;
    if (c == '[' || c == '(') ++depth;
    if ((c == ']' || c == ')') && depth > 0) --depth;
    if (c == ',' && depth == 0) {
      fields.push_back(trim(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  fields.push_back(trim(line.substr(start)));
  return fields;
}

std::string strip_parameter_marks(std::string_view expression) {
  std::string out;
  out.reserve(expression.size());
  for (char c : expression) {
    if (c != '%') out += c;
  }
  return out;
}

namespace {

// A digit run cut at a column boundary: "0.0040000000000000001" in a 10-column field reads
// 0.00400000, then 0000000000, then 01, all valid numbers. A fixed-format field that touches the
// field before it without a blank and starts with a zero followed by another digit is such a
// continuation: nobody writes a number with a leading zero on purpose.
bool continues_previous_field(std::string_view line, std::pair<std::size_t, std::size_t> columns,
                              std::string_view value) {
  const std::size_t first = columns.first;
  if (first < 2 || first - 1 >= line.size() || value.size() < 2) return false;
  const char before = line[first - 2], start = line[first - 1];
  return before >= '0' && before <= '9' && start == '0' && value.front() == '0' &&
         value[1] >= '0' && value[1] <= '9';
}

}  // namespace

std::string Card::column_hint(std::size_t i) const {
  if (free_ || i >= columns_.size()) return {};
  const auto [first, last] = columns_[i];
  const std::string_view raw =
      first - 1 < line_.text.size() ? line_.text.substr(first - 1, last - first + 1) : "";
  // Only when the field touches a neighbour without a blank between: then a value wider than
  // its column is the likely cause.
  const std::string_view line = line_.text;
  const bool joined_left = first > 1 && first - 1 <= line.size() && line[first - 2] != ' ' &&
                           !raw.empty() && raw.front() != ' ';
  const bool joined_right = last < line.size() && line[last - 1] != ' ' && line[last] != ' ';
  if (!joined_left && !joined_right) return {};
  return fmt::format(
      " (columns {}-{} of this fixed-format card hold {}; a value wider than its "
      "{} columns runs into the next field: write the card in free format, with "
      "commas between the values, or use the long format, '+' after the keyword "
      "or *KEYWORD LONG=Y, with 20 columns per field)",
      first, last, quoted(raw), last - first + 1);
}

double Card::real(std::size_t i, const char* name, double fallback) const {
  const std::string_view t = text(i);
  if (t.empty()) return fallback;
  if (const auto v = substituted(t, name)) return *v;
  const auto parsed = parse_real(t);
  if (!parsed.value) {
    throw error(name, fmt::format("{} {}{}", quoted(t), parsed.reason, column_hint(i)));
  }
  if (!free_ && i < columns_.size() && continues_previous_field(line_.text, columns_[i], t)) {
    throw error(name, fmt::format("{} continues the digits of the field before it{}", quoted(t),
                                  column_hint(i)));
  }
  return *parsed.value;
}

std::int64_t Card::integer(std::size_t i, const char* name, std::int64_t fallback) const {
  const std::string_view t = text(i);
  if (t.empty()) return fallback;
  if (const auto v = substituted(t, name)) {
    if (*v != std::trunc(*v) || std::abs(*v) > 9.0e15) {
      throw error(name, fmt::format("parameter value {} is not an integer", *v));
    }
    return static_cast<std::int64_t>(*v);
  }
  const auto parsed = parse_integer(t);
  if (!parsed.value) {
    throw error(name, fmt::format("{} {}{}", quoted(t), parsed.reason, column_hint(i)));
  }
  if (!free_ && i < columns_.size() && continues_previous_field(line_.text, columns_[i], t)) {
    throw error(name, fmt::format("{} continues the digits of the field before it{}", quoted(t),
                                  column_hint(i)));
  }
  return *parsed.value;
}

int Card::flag(std::size_t i, const char* name, int fallback) const {
  const std::int64_t v = integer(i, name, fallback);
  if (v < INT_MIN || v > INT_MAX) throw error(name, fmt::format("value {} is out of range", v));
  return static_cast<int>(v);
}

void CardCursor::skip_blank_lines() {
  while (!at_end() && trim(block_.lines[next_].text).empty()) ++next_;
}

Card CardCursor::next(int card_number, const Layout& layout, const char* fields) {
  if (at_end()) {
    const int line = block_.lines.empty() ? block_.line : block_.lines.back().number;
    throw InputError({block_.file, line, block_.keyword, card_number, ""},
                     fmt::format("card {} ({}) is missing", card_number, fields));
  }
  return Card(block_, block_.lines[next_++], card_number, layout, parameters_);
}

std::optional<Card> CardCursor::next_optional(int card_number, const Layout& layout) {
  if (at_end()) return std::nullopt;
  return Card(block_, block_.lines[next_++], card_number, layout, parameters_);
}

std::string CardCursor::next_text(int card_number, const char* what, bool required) {
  if (at_end()) {
    if (!required) return {};
    const int line = block_.lines.empty() ? block_.line : block_.lines.back().number;
    throw InputError({block_.file, line, block_.keyword, card_number, ""},
                     fmt::format("card {} ({}) is missing", card_number, what));
  }
  return std::string(trim(block_.lines[next_++].text));
}

}  // namespace rf::io
