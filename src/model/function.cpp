#include "model/function.hpp"

#include <muParser.h>

#include <cctype>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string_view>

namespace rf::model {

namespace {
constexpr double kDegree = std::numbers::pi / 180.0;
double sin_deg(double x) {
  return std::sin(x * kDegree);
}
double cos_deg(double x) {
  return std::cos(x * kDegree);
}
double tan_deg(double x) {
  return std::tan(x * kDegree);
}
double asin_deg(double x) {
  return std::asin(x) / kDegree;
}
double acos_deg(double x) {
  return std::acos(x) / kDegree;
}
double atan_deg(double x) {
  return std::atan(x) / kDegree;
}
double sin_rad(double x) {
  return std::sin(x);
}
double cos_rad(double x) {
  return std::cos(x);
}
double tan_rad(double x) {
  return std::tan(x);
}
double asin_rad(double x) {
  return std::asin(x);
}
double acos_rad(double x) {
  return std::acos(x);
}
double atan_rad(double x) {
  return std::atan(x);
}
double natural_log(double x) {
  return std::log(x);
}
double floor_of(double x) {
  return std::floor(x);
}
double ceil_of(double x) {
  return std::ceil(x);
}
double round_of(double x) {
  return std::round(x);
}
double heaviside(double x) {
  return x >= 0.0 ? 1.0 : 0.0;
}
double erf_of(double x) {
  return std::erf(x);
}
double modulo(double a, double b) {
  return std::fmod(a, b);
}
double power(double a, double b) {
  return std::pow(a, b);
}
double absolute(double a) {
  return std::fabs(a);
}
double arc_tangent2(double y, double x) {
  return std::atan2(y, x);
}
double exponential(double x) {
  return std::exp(x);
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool is_identifier(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (const char c : s) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return true;
}
}  // namespace

void define_impetus_intrinsics(mu::Parser& parser) {
  parser.DefineFun("sin", sin_deg);
  parser.DefineFun("cos", cos_deg);
  parser.DefineFun("tan", tan_deg);
  parser.DefineFun("asin", asin_deg);
  parser.DefineFun("acos", acos_deg);
  parser.DefineFun("atan", atan_deg);
  parser.DefineFun("sinr", sin_rad);
  parser.DefineFun("cosr", cos_rad);
  parser.DefineFun("tanr", tan_rad);
  parser.DefineFun("asinr", asin_rad);
  parser.DefineFun("acosr", acos_rad);
  parser.DefineFun("atanr", atan_rad);
  parser.DefineFun("ln", natural_log);
  parser.DefineFun("log", natural_log);
  parser.DefineFun("floor", floor_of);
  parser.DefineFun("ceil", ceil_of);
  parser.DefineFun("round", round_of);
  parser.DefineFun("H", heaviside);
  parser.DefineFun("erf", erf_of);
  parser.DefineFun("mod", modulo);
}

ExpressionFunction::ExpressionFunction(const std::string& expression, bool impetus)
    : expression_(expression), parser_(std::make_unique<mu::Parser>()) {
  try {
    if (impetus) define_impetus_intrinsics(*parser_);
    parser_->DefineConst("pi", std::numbers::pi);
    parser_->DefineConst("PI", std::numbers::pi);
    parser_->DefineVar("t", &t_);
    parser_->DefineVar("T", &t_);
    parser_->SetExpr(expression);
    // Evaluating once makes muparser report syntax errors and unknown names now.
    t_ = 0.0;
    parser_->Eval();
  } catch (const mu::Parser::exception_type& e) {
    throw std::runtime_error(e.GetMsg());
  }
}

ExpressionFunction::~ExpressionFunction() = default;

ArgumentFunction::ArgumentFunction(const std::string& text)
    : parser_(std::make_unique<mu::Parser>()) {
  // name(a, b, ...) = expression
  const std::string_view all = trimmed(text);
  const auto open = all.find('(');
  const auto close = all.find(')');
  const auto equals = close == std::string_view::npos ? close : all.find('=', close);
  if (open == std::string_view::npos || close == std::string_view::npos || close < open ||
      equals == std::string_view::npos ||
      !trimmed(all.substr(close + 1, equals - close - 1)).empty()) {
    throw std::runtime_error(
        "expected the form name(a, b, ...) = expression (C function bodies with braces are not "
        "supported)");
  }
  name_ = std::string(trimmed(all.substr(0, open)));
  if (!is_identifier(name_)) {
    throw std::runtime_error("'" + name_ + "' is not a function name");
  }
  std::string_view list = all.substr(open + 1, close - open - 1);
  if (!trimmed(list).empty()) {
    while (true) {
      const auto comma = list.find(',');
      const std::string argument(trimmed(list.substr(0, comma)));
      if (!is_identifier(argument)) {
        throw std::runtime_error("argument '" + argument + "' is not a name");
      }
      for (const auto& earlier : arguments_) {
        if (earlier == argument) throw std::runtime_error("argument '" + argument + "' repeats");
      }
      arguments_.push_back(argument);
      if (comma == std::string_view::npos) break;
      list.remove_prefix(comma + 1);
    }
  }
  expression_ = std::string(trimmed(all.substr(equals + 1)));
  if (!expression_.empty() && expression_.back() == ';') expression_.pop_back();
  if (trimmed(expression_).empty()) throw std::runtime_error("the expression is empty");
  values_.assign(arguments_.size(), 0.0);
  try {
    // C's <math.h> meanings where muparser's differ or are missing.
    parser_->DefineFun("log", natural_log);
    parser_->DefineFun("pow", power);
    parser_->DefineFun("fabs", absolute);
    parser_->DefineFun("atan2", arc_tangent2);
    parser_->DefineFun("fmod", modulo);
    parser_->DefineFun("floor", floor_of);
    parser_->DefineFun("ceil", ceil_of);
    parser_->DefineFun("exp", exponential);
    for (std::size_t k = 0; k < arguments_.size(); ++k) {
      parser_->DefineVar(arguments_[k], &values_[k]);
    }
    bool time_is_argument = false;
    for (const auto& a : arguments_) time_is_argument |= (a == "time");
    if (!time_is_argument) parser_->DefineVar("time", &time_);
    parser_->SetExpr(expression_);
    parser_->Eval();  // reports syntax errors and unknown names now
  } catch (const mu::Parser::exception_type& e) {
    throw std::runtime_error(e.GetMsg());
  }
}

ArgumentFunction::~ArgumentFunction() = default;

double ArgumentFunction::operator()(std::span<const double> values, double time) const {
  const std::size_t n = values.size() < values_.size() ? values.size() : values_.size();
  for (std::size_t k = 0; k < n; ++k) values_[k] = values[k];
  time_ = time;
  return parser_->Eval();
}

double ExpressionFunction::operator()(double t) const {
  t_ = t;
  return parser_->Eval();
}

}  // namespace rf::model
