#include "model/curve.hpp"

#include <algorithm>
#include <array>

#include "model/function.hpp"

namespace rf::model {

double evaluate(const Curve& curve, double t) {
  if (curve.function) {
    const double s = (curve.sfa != 0.0 ? t / curve.sfa : t) - curve.offa;
    const std::array<double, 1> argument{s};
    return curve.sfo * (*curve.function)(argument, s) + curve.offo;
  }
  const auto& xs = curve.abscissa;
  const auto& ys = curve.ordinate;
  if (xs.empty()) return curve.offo;
  const double s = (curve.sfa != 0.0 ? t / curve.sfa : t) - curve.offa;
  double f;
  if (s <= xs.front()) {
    f = ys.front();
  } else if (s >= xs.back()) {
    f = ys.back();
  } else {
    const auto it = std::upper_bound(xs.begin(), xs.end(), s);
    const std::size_t i = static_cast<std::size_t>(it - xs.begin());
    const double x0 = xs[i - 1], x1 = xs[i];
    const double w = x1 > x0 ? (s - x0) / (x1 - x0) : 1.0;
    f = ys[i - 1] + w * (ys[i] - ys[i - 1]);
  }
  return curve.sfo * f + curve.offo;
}

}  // namespace rf::model
