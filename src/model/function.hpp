// Expressions of time compiled once (IMPETUS *FUNCTION), evaluated cheaply every cycle.
#pragma once

#include <memory>
#include <string>

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

// IMPETUS's intrinsic operations, as its manual defines them: sin cos tan asin acos atan work
// in DEGREES, sinr cosr tanr asinr acosr atanr in radians; also ln, log (= ln), log10, mod,
// sign, floor, ceil, round, H (Heaviside) and erf. Replaces muparser's radian trigonometry.
void define_impetus_intrinsics(mu::Parser& parser);

}  // namespace rf::model
