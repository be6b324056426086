// *PARAMETER and *PARAMETER_EXPRESSION values, looked up by name for "&name" fields.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace rf::io {

class ParameterTable {
 public:
  // `overrides` replace deck values of the same name (case-insensitive, like LS-DYNA).
  explicit ParameterTable(const std::map<std::string, double>& overrides);

  // Defines or redefines a numeric parameter; an override of the same name wins.
  // Returns the value actually stored.
  double define(const std::string& name, double value);
  void define_text(const std::string& name, const std::string& value);

  std::optional<double> find(std::string_view name) const;
  bool contains(std::string_view name) const;

  // Evaluates an expression with every numeric parameter defined so far as a variable and
  // pi available. LS-DYNA names are case-insensitive, bare or "&name". Throws
  // std::runtime_error naming an unknown parameter, or with muparser's reason.
  double evaluate(const std::string& expression) const;
  // IMPETUS decks: expressions use IMPETUS's intrinsic functions (trigonometry in degrees).
  void use_impetus_intrinsics(bool on) { impetus_ = on; }

  // Final values keyed by the name as first written in the deck.
  std::map<std::string, double> values() const;
  // Override names that matched no *PARAMETER (the caller reports them).
  std::map<std::string, double> unused_overrides() const;

 private:
  std::string canonical_expression(const std::string& expression) const;
  struct Entry {
    std::string name;  // as written
    double value = 0.0;
    std::optional<std::string> text;  // C-type parameters
  };
  std::map<std::string, Entry> by_key_;      // key: upper-case name
  std::map<std::string, double> overrides_;  // key: upper-case name
  std::map<std::string, std::string> override_names_;
  bool impetus_ = false;
};

std::string to_upper(std::string_view text);

}  // namespace rf::io
