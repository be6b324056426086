#include <gtest/gtest.h>

#include "model/curve.hpp"

using rf::model::Curve;
using rf::model::evaluate;

TEST(Curve, InterpolatesAndHoldsEnds) {
  Curve c;
  c.abscissa = {0.0, 1.0, 3.0};
  c.ordinate = {0.0, 2.0, 2.0 + 4.0};
  EXPECT_DOUBLE_EQ(evaluate(c, -1.0), 0.0);
  EXPECT_DOUBLE_EQ(evaluate(c, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(evaluate(c, 2.0), 4.0);
  EXPECT_DOUBLE_EQ(evaluate(c, 10.0), 6.0);
}

TEST(Curve, AppliesLsDynaScaleAndOffsets) {
  // value(t) = SFO * f(t/SFA - OFFA) + OFFO
  Curve c;
  c.abscissa = {0.0, 10.0};
  c.ordinate = {0.0, 10.0};
  c.sfa = 2.0;
  c.sfo = 3.0;
  c.offa = 1.0;
  c.offo = 0.5;
  EXPECT_DOUBLE_EQ(evaluate(c, 6.0), 3.0 * (6.0 / 2.0 - 1.0) + 0.5);
}
