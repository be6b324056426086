// *RIGIDWALL_PLANAR (_ID, _FINITE, _MOVING), *DEFINE_BOX and *DATABASE_RWFORC: fields read
// from fixed-format cards (tests/decks/rigidwall_block.k), and every bad value an error that
// names file, line, keyword and field.
#include <gtest/gtest.h>

#include "keyword_test_util.hpp"

namespace {

TEST(KeywordWall, FixedFormatCardsAreRead) {
  const rf::model::Model m = rf::io::read_deck(rf::test::deck_path("rigidwall_block.k"));
  ASSERT_EQ(m.rigid_walls.size(), 3u);
  const auto& floor = m.rigid_walls[0];
  EXPECT_EQ(floor.number, 1);
  EXPECT_EQ(floor.id, 5);
  EXPECT_EQ(floor.title, "floor");
  EXPECT_EQ(floor.nsid, 1);
  EXPECT_EQ(floor.nsidex, 2);
  EXPECT_EQ(floor.boxid, 3);
  EXPECT_DOUBLE_EQ(floor.offset, 0.5);
  EXPECT_DOUBLE_EQ(floor.birth, 0.001);
  EXPECT_DOUBLE_EQ(floor.death, 2.0);
  EXPECT_DOUBLE_EQ(floor.rwksf, 1.0);
  EXPECT_EQ(floor.tail, (std::array<double, 3>{0.0, 0.0, -0.01}));
  EXPECT_EQ(floor.head, (std::array<double, 3>{0.0, 0.0, 1.0}));
  EXPECT_DOUBLE_EQ(floor.fric, 0.2);
  EXPECT_FALSE(floor.finite);
  EXPECT_FALSE(floor.moving);
  EXPECT_EQ(floor.where.keyword, "*RIGIDWALL_PLANAR_ID");
  EXPECT_EQ(floor.where.line, 50);  // card 1 (NSID ...)

  const auto& ceiling = m.rigid_walls[1];
  EXPECT_EQ(ceiling.number, 2);
  EXPECT_EQ(ceiling.id, 0);
  EXPECT_EQ(ceiling.nsid, 0);
  EXPECT_DOUBLE_EQ(ceiling.death, 1e20);
  EXPECT_DOUBLE_EQ(ceiling.fric, 1.0);
  EXPECT_TRUE(ceiling.finite);
  EXPECT_EQ(ceiling.edge_head, (std::array<double, 3>{1.0, 0.0, 3.01}));
  EXPECT_DOUBLE_EQ(ceiling.lenl, 2.0);
  EXPECT_DOUBLE_EQ(ceiling.lenm, 3.0);
  EXPECT_TRUE(ceiling.moving);
  EXPECT_DOUBLE_EQ(ceiling.mass, 10.0);
  EXPECT_DOUBLE_EQ(ceiling.v0, -1.0);

  // Options in another order: the cards keep their order (ID, 1, 2, FINITE, MOVING).
  const auto& side = m.rigid_walls[2];
  EXPECT_EQ(side.number, 3);
  EXPECT_EQ(side.id, 9);
  EXPECT_TRUE(side.title.empty());
  EXPECT_TRUE(side.finite);
  EXPECT_TRUE(side.moving);
  EXPECT_DOUBLE_EQ(side.lenl, 0.0);
  EXPECT_DOUBLE_EQ(side.lenm, 4.0);
  EXPECT_DOUBLE_EQ(side.mass, 2.5);
  EXPECT_DOUBLE_EQ(side.v0, 0.0);

  ASSERT_EQ(m.boxes.count(3), 1u);
  const auto& box = m.boxes.at(3);
  EXPECT_EQ(box.min, (std::array<double, 3>{-1.0, -1.0, -1.0}));
  EXPECT_EQ(box.max, (std::array<double, 3>{2.0, 2.0, 0.5}));
  EXPECT_DOUBLE_EQ(m.output.rwforc_dt, 1e-3);
  EXPECT_TRUE(m.warnings.empty());
}

TEST(KeywordWall, PenaltyScaleIsIgnoredWithAWarning) {
  const rf::model::Model m =
      rf::io::read_deck_text("*RIGIDWALL_PLANAR\n0,0,0,0,0,0,2.0\n0,0,0,0,0,1\n", "w.k");
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].message.find("RWKSF 2 ignored"), std::string::npos);
  EXPECT_EQ(m.warnings[0].where.line, 2);
}

// *DEFINE_BOX_ADAPTIVE refines the mesh inside the box in LS-DYNA: an unsupported keyword that
// changes the physics, an error unless the user asks to skip it.
TEST(KeywordWall, OtherBoxKeywordsAreUnsupportedPhysics) {
  const std::string deck =
      "*DEFINE_BOX_ADAPTIVE\n1,0,1,0,1,0,1,3\n*DEFINE_BOX_TITLE\nkept\n2,0,1,0,1,0,1\n";
  const std::string message = rf::test::input_error_of(deck, "w.k");
  EXPECT_NE(message.find("w.k:1: *DEFINE_BOX_ADAPTIVE: not supported"), std::string::npos)
      << message;
  rf::io::ReadOptions options;
  options.ignore_unsupported = true;
  const rf::model::Model m = rf::io::read_deck_text(deck, "w.k", ".", options);
  EXPECT_EQ(m.boxes.count(1), 0u);
  EXPECT_EQ(m.boxes.count(2), 1u);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].message.find("*DEFINE_BOX_ADAPTIVE"), std::string::npos);
  EXPECT_NE(m.warnings[0].message.find("--ignore-unsupported"), std::string::npos);
  EXPECT_EQ(m.unknown_keywords.count("*DEFINE_BOX_ADAPTIVE"), 1u);
  ASSERT_EQ(m.ignored_physics.size(), 1u);
}

struct ErrorCase {
  std::string name;
  std::string text;
  std::vector<std::string> expected;  // substrings of the message
};

class KeywordWallError : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(KeywordWallError, MessageLocatesTheProblem) {
  const ErrorCase& c = GetParam();
  const std::string message = rf::test::input_error_of(c.text, "wall.k");
  for (const auto& part : c.expected) {
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
  }
}

// A valid wall; each case breaks one field. Line 1 is the keyword.
std::string wall(const std::string& card1 = "0", const std::string& card2 = "0,0,0,0,0,1",
                 const std::string& options = "", const std::string& extra = "") {
  return "*RIGIDWALL_PLANAR" + options + "\n" + card1 + "\n" + card2 + "\n" + extra;
}

std::vector<ErrorCase> cases() {
  const std::string mesh = "*NODE\n1,0,0,1\n";
  return {
      {"UndefinedNodeSet",
       mesh + wall("7"),
       {"wall.k:4: *RIGIDWALL_PLANAR", "field NSID", "node set 7 is not defined"}},
      {"UndefinedExemptSet",
       mesh + wall("0,8"),
       {"wall.k:4: *RIGIDWALL_PLANAR", "field NSIDEX", "node set 8 is not defined"}},
      {"UndefinedBox",
       mesh + wall("0,0,4"),
       {"wall.k:4: *RIGIDWALL_PLANAR", "field BOXID", "box 4 is not defined (*DEFINE_BOX)"}},
      {"NegativeSet", wall("-1"), {"wall.k:2: *RIGIDWALL_PLANAR card 1 field NSID", "negative"}},
      {"NegativeOffset",
       wall("0,0,0,-1.0"),
       {"wall.k:2: *RIGIDWALL_PLANAR card 1 field OFFSET", "must not be negative"}},
      {"NegativeBirth", wall("0,0,0,0,-1"), {"card 1 field BIRTH", "must not be negative"}},
      {"DeathBeforeBirth",
       wall("0,0,0,0,2.0,1.0"),
       {"wall.k:2: *RIGIDWALL_PLANAR card 1 field DEATH", "later than BIRTH"}},
      {"NegativePenaltyScale", wall("0,0,0,0,0,0,-1"), {"card 1 field RWKSF"}},
      {"NormalOfZeroLength",
       wall("0", "1,2,3,1,2,3"),
       {"wall.k:3: *RIGIDWALL_PLANAR card 2 field XH", "must differ from the tail"}},
      {"Welding",
       wall("0", "0,0,0,0,0,1,2.0"),
       {"wall.k:3: *RIGIDWALL_PLANAR card 2 field FRIC", "welded", "not supported"}},
      {"WeldingWithoutSliding", wall("0", "0,0,0,0,0,1,3.0"), {"card 2 field FRIC", "welded"}},
      {"FrictionAboveOne",
       wall("0", "0,0,0,0,0,1,1.5"),
       {"card 2 field FRIC", "value 1.5 is not supported"}},
      {"NegativeFriction", wall("0", "0,0,0,0,0,1,-0.1"), {"card 2 field FRIC"}},
      {"WeldingVelocity",
       wall("0", "0,0,0,0,0,1,0.0,5.0"),
       {"wall.k:3: *RIGIDWALL_PLANAR card 2 field WVEL", "welding"}},
      {"MissingCard2",
       "*RIGIDWALL_PLANAR\n0\n",
       {"wall.k", "*RIGIDWALL_PLANAR", "XT YT ZT XH YH ZH FRIC WVEL"}},
      {"EdgeAlongNormal",
       wall("0", "0,0,0,0,0,1", "_FINITE", "0,0,5,1,1\n"),
       {"wall.k:4: *RIGIDWALL_PLANAR_FINITE card 3 field XHEV", "not along the wall normal"}},
      {"NegativeLength",
       wall("0", "0,0,0,0,0,1", "_FINITE", "1,0,0,-1,1\n"),
       {"wall.k:4: *RIGIDWALL_PLANAR_FINITE card 3 field LENL", "must not be negative"}},
      {"NegativeWidth", wall("0", "0,0,0,0,0,1", "_FINITE", "1,0,0,1,-1\n"), {"card 3 field LENM"}},
      {"MissingFiniteCard",
       wall("0", "0,0,0,0,0,1", "_FINITE"),
       {"*RIGIDWALL_PLANAR_FINITE", "XHEV YHEV ZHEV LENL LENM"}},
      {"ZeroMass",
       wall("0", "0,0,0,0,0,1", "_MOVING", "0.0,1.0\n"),
       {"wall.k:4: *RIGIDWALL_PLANAR_MOVING card 3 field MASS", "must be positive"}},
      {"MovingCardAfterFinite",
       wall("0", "0,0,0,0,0,1", "_MOVING_FINITE", "1,0,0,1,1\n-5\n"),
       {"wall.k:5: *RIGIDWALL_PLANAR_MOVING_FINITE card 4 field MASS"}},
      {"NegativeId",
       "*RIGIDWALL_PLANAR_ID\n-3\n0\n0,0,0,0,0,1\n",
       {"wall.k:2: *RIGIDWALL_PLANAR_ID card 1 field ID", "negative"}},
      {"DuplicateId",
       "*RIGIDWALL_PLANAR_ID\n3,a\n0\n0,0,0,0,0,1\n*RIGIDWALL_PLANAR_ID\n3,b\n0\n0,0,0,0,0,1\n",
       {"wall.k:6: *RIGIDWALL_PLANAR_ID card 1 field ID",
        "rigid wall 3 is already defined at wall.k:3"}},
      {"UnsupportedOption",
       wall("0", "0,0,0,0,0,1", "_ORTHO"),
       {"wall.k:1: *RIGIDWALL_PLANAR_ORTHO: not supported: a rigid wall",
        "*RIGIDWALL_PLANAR is read, with the options _ID, _FINITE, _MOVING, _FORCES"}},
      {"BadNumber", wall("0,0,0,abc"), {"wall.k:2: *RIGIDWALL_PLANAR card 1 field OFFSET", "abc"}},
      {"BoxMaxBelowMin",
       "*DEFINE_BOX\n1,0,1,0,1,2,1\n",
       {"wall.k:2: *DEFINE_BOX card 1 field ZMX", "below the minimum"}},
      {"BoxWithoutId", "*DEFINE_BOX\n0,0,1,0,1,0,1\n", {"*DEFINE_BOX card 1 field BOXID"}},
      {"DuplicateBox",
       "*DEFINE_BOX\n1,0,1,0,1,0,1\n*DEFINE_BOX\n1,0,1,0,1,0,1\n",
       {"wall.k:4: *DEFINE_BOX card 1 field BOXID", "box 1 is already defined at wall.k:2"}},
      {"NegativeRwforcInterval", "*DATABASE_RWFORC\n-1\n", {"*DATABASE_RWFORC card 1 field DT"}},
      // A fixed-format DT longer than its 10 columns spills into BINARY: an error, not DT = 3.
      {"IntervalOverrunsItsColumns",
       "*DATABASE_RWFORC\n3.0000000000000004e-06\n",
       {"wall.k:2: *DATABASE_RWFORC card 1 field BINARY", "'00000004e-' is not an integer"}},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, KeywordWallError, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
