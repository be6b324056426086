#include "model/function.hpp"

#include <muParser.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

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

double ExpressionFunction::operator()(double t) const {
  t_ = t;
  return parser_->Eval();
}

}  // namespace rf::model
