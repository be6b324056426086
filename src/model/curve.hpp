// Evaluation of *DEFINE_CURVE load curves.
#pragma once

#include "model/model.hpp"

namespace rf::model {

// LS-DYNA semantics: value(t) = SFO * f(t / SFA - OFFA) + OFFO with f piecewise linear
// through the points and held constant beyond the first and last abscissa; for
// *DEFINE_CURVE_FUNCTION f is the expression of time.
double evaluate(const Curve& curve, double t);

}  // namespace rf::model
