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
      free_(line.text.find(',') != std::string_view::npos),
      parameters_(parameters) {
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

double Card::real(std::size_t i, const char* name, double fallback) const {
  const std::string_view t = text(i);
  if (t.empty()) return fallback;
  if (const auto v = substituted(t, name)) return *v;
  const auto parsed = parse_real(t);
  if (!parsed.value) throw error(name, fmt::format("{} {}", quoted(t), parsed.reason));
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
  if (!parsed.value) throw error(name, fmt::format("{} {}", quoted(t), parsed.reason));
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
