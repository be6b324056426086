// *PARAMETER, *PARAMETER_EXPRESSION, &name substitution and command-line overrides.
#include <gtest/gtest.h>

#include "keyword_test_util.hpp"

using rf::io::read_deck_text;
using rf::io::ReadOptions;

namespace {

const char* const kDeck =
    "*PARAMETER\n"
    "R     rho    7.85e-9Iseven             7\n"
    "R len, 2.5\n"
    "*PARAMETER_EXPRESSION\n"
    "R area    len*len\n"
    "R ang, min(pi, 4) / 2\n"
    "I half    seven/2\n"
    "*NODE\n"
    "       1            &len           -&len           &area\n"
    "&seven,&ang,0,0\n"
    "*MAT_ELASTIC\n"
    "         1      &rho     2.1e5       0.3\n";

}  // namespace

TEST(KeywordParameter, ValuesExpressionsAndSubstitution) {
  const auto m = read_deck_text(kDeck);
  ASSERT_EQ(m.nodes.size(), 2u);
  EXPECT_DOUBLE_EQ(m.nodes[0].x[0], 2.5);
  EXPECT_DOUBLE_EQ(m.nodes[0].x[1], -2.5);
  EXPECT_DOUBLE_EQ(m.nodes[0].x[2], 6.25);
  EXPECT_EQ(m.nodes[1].id, 7);
  EXPECT_DOUBLE_EQ(m.nodes[1].x[0], 3.14159265358979323846 / 2);
  EXPECT_DOUBLE_EQ(m.materials.at(1).rho, 7.85e-9);
  EXPECT_DOUBLE_EQ(m.parameters.at("half"), 3.0);  // I type truncates
  EXPECT_DOUBLE_EQ(m.parameters.at("area"), 6.25);
  EXPECT_EQ(m.parameters.size(), 6u);
}

TEST(KeywordParameter, OverridesReplaceDeckValuesAndFeedExpressions) {
  ReadOptions options;
  options.parameter_overrides["LEN"] = 3.0;  // case-insensitive match
  const auto m = read_deck_text(kDeck, "p.k", ".", options);
  EXPECT_DOUBLE_EQ(m.nodes[0].x[0], 3.0);
  EXPECT_DOUBLE_EQ(m.nodes[0].x[2], 9.0);  // area = len*len uses the override
  EXPECT_DOUBLE_EQ(m.parameters.at("len"), 3.0);
  EXPECT_TRUE(m.warnings.empty());
}

TEST(KeywordParameter, UnusedOverrideWarns) {
  ReadOptions options;
  options.parameter_overrides["nosuch"] = 1.0;
  const auto m = read_deck_text(kDeck, "p.k", ".", options);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].message.find("nosuch"), std::string::npos);
}

TEST(KeywordParameter, IntegerFieldRejectsFractionalParameter) {
  const std::string message = rf::test::input_error_of(
      "*PARAMETER\nR  id       1.5\n*NODE\n    &id             0.0             0.0             "
      "0.0\n");
  EXPECT_NE(message.find("bar.k:4: *NODE card 1 field NID"), std::string::npos) << message;
}

TEST(KeywordParameter, BadExpressionNamesTheExpression) {
  const std::string message = rf::test::input_error_of("*PARAMETER_EXPRESSION\nR x       2*(3+\n");
  EXPECT_NE(message.find("bar.k:2: *PARAMETER_EXPRESSION card 1 field EXPRESSION"),
            std::string::npos)
      << message;
}
