// Expressions of time compiled once (IMPETUS *FUNCTION), evaluated cheaply every cycle.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace mu {
class Parser;
}

namespace rf::model {

// f(t) given as text, e.g. "4*pi*(t/0.01)". muparser compiles the expression to bytecode once;
// evaluation then costs tens of nanoseconds. Besides t, the expression may use pi and
// muparser's built-in functions (sin, cos, exp, sqrt, min, max, ...). Not thread-safe: the
// solver evaluates time functions in its serial boundary-condition phases.
class ExpressionFunction {
 public:
  // Throws std::runtime_error with muparser's reason when the expression does not compile or
  // uses an unknown variable. `impetus`: the IMPETUS intrinsic functions (trigonometry in
  // degrees, see define_impetus_intrinsics).
  explicit ExpressionFunction(const std::string& expression, bool impetus = true);
  ~ExpressionFunction();
  ExpressionFunction(const ExpressionFunction&) = delete;
  ExpressionFunction& operator=(const ExpressionFunction&) = delete;

  double operator()(double t) const;
  const std::string& expression() const { return expression_; }

 private:
  std::string expression_;
  std::unique_ptr<mu::Parser> parser_;
  mutable double t_ = 0.0;
};

// LS-DYNA *DEFINE_FUNCTION text "name(a, b, ...) = expression": the arguments are bound by
// position by the keyword that uses the function. The expression uses C's arithmetic and
// <math.h> names (pow, sqrt, exp, log = natural logarithm, log10, fabs/abs, sin... in radians,
// atan2, fmod, floor, ceil, min, max) plus comparisons and "c ? a : b". Besides the arguments,
// the name `time` is the current time (a RigidFlex extension; see docs/sensors.md) unless an
// argument has that name. Compiled once; evaluation does not allocate. Not thread-safe.
class ArgumentFunction {
 public:
  // Throws std::runtime_error with the reason when the text is not of that form or the
  // expression does not compile (unknown names included).
  explicit ArgumentFunction(const std::string& text);
  ~ArgumentFunction();
  ArgumentFunction(const ArgumentFunction&) = delete;
  ArgumentFunction& operator=(const ArgumentFunction&) = delete;

  const std::string& name() const { return name_; }
  const std::vector<std::string>& arguments() const { return arguments_; }
  const std::string& expression() const { return expression_; }
  // `values` has one entry per argument (checked by the caller when it binds the function).
  double operator()(std::span<const double> values, double time) const;

 private:
  std::string name_;
  std::vector<std::string> arguments_;
  std::string expression_;
  std::unique_ptr<mu::Parser> parser_;
  mutable std::vector<double> values_;  // muparser reads the arguments from here; sized once
  mutable double time_ = 0.0;
};

// IMPETUS's intrinsic operations, as its manual defines them: sin cos tan asin acos atan work
// in DEGREES, sinr cosr tanr asinr acosr atanr in radians; also ln, log (= ln), log10, mod,
// sign, floor, ceil, round, H (Heaviside) and erf. Replaces muparser's radian trigonometry.
void define_impetus_intrinsics(mu::Parser& parser);

}  // namespace rf::model
