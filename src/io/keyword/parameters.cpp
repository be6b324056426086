#include "io/keyword/parameters.hpp"

#include <muParser.h>

#include "model/function.hpp"

#include <cctype>
#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>

namespace rf::io {

std::string to_upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

namespace {
// muparser accepts letters, digits and '_' in names; other deck names simply cannot be
// used inside expressions.
bool is_identifier(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
  for (char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  }
  return true;
}
}  // namespace

ParameterTable::ParameterTable(const std::map<std::string, double>& overrides) {
  for (const auto& [written, value] : overrides) {
    // IMPETUS parameters are written %name; --set %type=0 and --set type=0 mean the same.
    const std::string name = written.starts_with('%') ? written.substr(1) : written;
    overrides_[to_upper(name)] = value;
    override_names_[to_upper(name)] = name;
  }
}

double ParameterTable::define(const std::string& name, double value) {
  const std::string key = to_upper(name);
  if (const auto it = overrides_.find(key); it != overrides_.end()) value = it->second;
  auto [it, inserted] = by_key_.try_emplace(key, Entry{name, value, std::nullopt});
  if (!inserted) {
    it->second.value = value;
    it->second.text.reset();
  }
  return value;
}

void ParameterTable::define_text(const std::string& name, const std::string& value) {
  const std::string key = to_upper(name);
  by_key_[key] = Entry{name, 0.0, value};
}

std::optional<double> ParameterTable::find(std::string_view name) const {
  const auto it = by_key_.find(to_upper(name));
  if (it == by_key_.end() || it->second.text) return std::nullopt;
  return it->second.value;
}

bool ParameterTable::contains(std::string_view name) const {
  return by_key_.count(to_upper(name)) > 0;
}

namespace {
bool identifier_start(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool identifier_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
}  // namespace

// LS-DYNA: parameter names in expressions are case-insensitive and may be written bare or as
// "&name". Each name is rewritten to its upper-case key (the only spelling defined to the
// parser), so "TEnd/100" finds tEnd. A name that is neither a parameter, a constant nor a
// function call is reported by name rather than by the parser's position message.
std::string ParameterTable::canonical_expression(const std::string& expression) const {
  std::string out;
  out.reserve(expression.size());
  for (std::size_t i = 0; i < expression.size();) {
    const char c = expression[i];
    const bool ampersand =
        c == '&' && i + 1 < expression.size() && identifier_start(expression[i + 1]);
    if (!ampersand && !identifier_start(c)) {
      // A number such as 1.5e3 keeps its exponent letter.
      if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
        while (i < expression.size() &&
               (identifier_char(expression[i]) || expression[i] == '.' ||
                ((expression[i] == '+' || expression[i] == '-') && i > 0 &&
                 (expression[i - 1] == 'e' || expression[i - 1] == 'E')))) {
          out += expression[i++];
        }
        continue;
      }
      out += c;
      ++i;
      continue;
    }
    if (ampersand) ++i;
    const std::size_t start = i;
    while (i < expression.size() && identifier_char(expression[i])) ++i;
    const std::string name = expression.substr(start, i - start);
    std::size_t next = i;
    while (next < expression.size() && std::isspace(static_cast<unsigned char>(expression[next]))) {
      ++next;
    }
    const bool call = next < expression.size() && expression[next] == '(';
    const std::string key = to_upper(name);
    const auto it = by_key_.find(key);
    if (!call && it != by_key_.end()) {
      if (it->second.text) {
        throw std::runtime_error("parameter '" + name +
                                 "' is a text parameter, a number is needed");
      }
      out += key;
      continue;
    }
    if (!call && key != "PI" && key != "_PI" && key != "_E") {
      throw std::runtime_error("'" + name +
                               "' is not a defined parameter (define it with *PARAMETER or "
                               "*PARAMETER_EXPRESSION before this expression)");
    }
    out += key == "PI" ? std::string("pi") : name;
  }
  return out;
}

double ParameterTable::evaluate(const std::string& expression_in) const {
  try {
    mu::Parser parser;
    if (impetus_) model::define_impetus_intrinsics(parser);
    parser.DefineConst("pi", std::numbers::pi);
    parser.DefineConst("PI", std::numbers::pi);
    const std::string expression = impetus_ ? expression_in : canonical_expression(expression_in);
    for (const auto& [key, entry] : by_key_) {
      if (entry.text) continue;
      if (!impetus_) {
        if (key != "PI" && is_identifier(key)) parser.DefineConst(key, entry.value);
        continue;
      }
      // IMPETUS: the name as written plus its upper- and lower-case spellings.
      std::string lower = key;
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      std::set<std::string> spellings{entry.name, key, lower};
      for (const std::string& spelling : spellings) {
        if (spelling == "pi" || spelling == "PI" || !is_identifier(spelling)) continue;
        parser.DefineConst(spelling, entry.value);
      }
    }
    parser.SetExpr(expression);
    const double value = parser.Eval();
    if (!std::isfinite(value)) throw std::runtime_error("the result is not a finite number");
    return value;
  } catch (const mu::Parser::exception_type& e) {
    throw std::runtime_error(e.GetMsg());
  }
}

std::map<std::string, double> ParameterTable::values() const {
  std::map<std::string, double> out;
  for (const auto& [key, entry] : by_key_) {
    if (!entry.text) out[entry.name] = entry.value;
  }
  return out;
}

std::map<std::string, double> ParameterTable::unused_overrides() const {
  std::map<std::string, double> out;
  for (const auto& [key, value] : overrides_) {
    if (!by_key_.count(key)) out[override_names_.at(key)] = value;
  }
  return out;
}

}  // namespace rf::io
