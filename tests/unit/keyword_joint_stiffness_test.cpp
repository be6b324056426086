// *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED: the four cards in fixed and free format, repeated
// definitions, left-out trailing cards, and the reader's own errors (the references to parts,
// systems, curves and joints are checked when the simulation is built,
// tests/verification/joint_stiffness_test.cpp).
#include <gtest/gtest.h>

#include "keyword_test_util.hpp"

namespace {

using rf::model::JointStiffness;

const JointStiffness& only(const rf::model::Model& m) {
  EXPECT_EQ(m.joint_stiffnesses.size(), 1u);
  return m.joint_stiffnesses.front();
}

void expect_full(const JointStiffness& js) {
  EXPECT_EQ(js.type, JointStiffness::Type::Generalized);
  EXPECT_EQ(js.id, 10);
  EXPECT_EQ(js.pida, 1);
  EXPECT_EQ(js.pidb, 2);
  EXPECT_EQ(js.cida, 3);
  EXPECT_EQ(js.cidb, 4);
  EXPECT_EQ(js.jid, 5);
  EXPECT_EQ(js.lcid, (std::array<rf::model::Id, 3>{6, 7, 8}));
  EXPECT_EQ(js.dlcid, (std::array<rf::model::Id, 3>{9, 11, 12}));
  EXPECT_EQ(js.stiffness, (std::array<double, 3>{100.0, 200.0, 300.0}));
  EXPECT_EQ(js.friction, (std::array<double, 3>{1.5, 2.5, 3.5}));
  EXPECT_EQ(js.negative_stop, (std::array<double, 3>{-10.0, -20.0, -30.0}));
  EXPECT_EQ(js.positive_stop, (std::array<double, 3>{15.0, 25.0, 35.0}));
  EXPECT_EQ(js.where.keyword, "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED");
  EXPECT_EQ(js.card[0].line, 3);
  EXPECT_EQ(js.card[3].line, 6);
}

TEST(KeywordJointStiffness, FixedFormat) {
  const auto m = rf::io::read_deck_text(
      "*KEYWORD\n"
      "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n"
      "        10         1         2         3         4         5\n"
      "         6         7         8         9        11        12\n"
      "     100.0       1.5     200.0       2.5     300.0       3.5\n"
      "     -10.0      15.0     -20.0      25.0     -30.0      35.0\n"
      "*END\n",
      "fixed.k");
  expect_full(only(m));
}

TEST(KeywordJointStiffness, FreeFormatRepeatedWithTrailingCardsLeftOut) {
  const auto m = rf::io::read_deck_text(
      "*KEYWORD\n"
      "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n"
      "10,1,2,3,4,5\n6,7,8,9,11,12\n100.0,1.5,200.0,2.5,300.0,3.5\n"
      "-10.0,15.0,-20.0,25.0,-30.0,35.0\n"
      "20,7,8,9\n0,0,13\n"
      "*END\n",
      "free.k");
  ASSERT_EQ(m.joint_stiffnesses.size(), 2u);
  expect_full(m.joint_stiffnesses[0]);
  const JointStiffness& second = m.joint_stiffnesses[1];
  EXPECT_EQ(second.id, 20);
  EXPECT_EQ(second.cidb, 0);  // CIDB blank: CIDA's system (resolved by the solver)
  EXPECT_EQ(second.jid, 0);
  EXPECT_EQ(second.lcid, (std::array<rf::model::Id, 3>{0, 0, 13}));
  EXPECT_EQ(second.stiffness, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(second.positive_stop, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(second.card[3].line, second.card[1].line);  // left out: the last card read
}

TEST(KeywordJointStiffness, ReaderErrorsNameTheField) {
  const std::string head = "*KEYWORD\n*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n";
  for (const auto& [card, field] : {std::pair{"0,1,2,3\n", "JSID"},
                                    {"10,0,2,3\n", "PIDA"},
                                    {"10,1,0,3\n", "PIDB"},
                                    {"10,1,2,0\n", "CIDA"},
                                    {"10,1,2,3,-1\n", "CIDB"},
                                    {"10,1,2,3,0,-4\n", "JID"}}) {
    const std::string message = rf::test::input_error_of(head + card + "*END\n");
    EXPECT_NE(message.find(field), std::string::npos) << card << ": " << message;
    EXPECT_NE(message.find("bar.k"), std::string::npos) << message;
  }
  const std::string empty = rf::test::input_error_of(head + "*END\n");
  EXPECT_NE(empty.find("no joint stiffness card"), std::string::npos) << empty;
}

}  // namespace
