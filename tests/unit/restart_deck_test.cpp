// The restart deck reader: LS-DYNA small-restart cards, part sets expanded, everything else
// refused with a message that says what a restart deck may contain.
#include <gtest/gtest.h>

#include "io/keyword/reader.hpp"
#include "io/keyword/restart_deck.hpp"
#include "model/error.hpp"

namespace rf::io {
namespace {

// Three one-element parts and a part set {2, 3}; the reader only needs parts and sets.
model::Model three_parts() {
  model::Model m;
  for (model::Id pid : {1, 2, 3}) m.parts[pid].id = pid;
  m.part_sets[10] = {10, {2, 3}, {}};
  m.parameters["later"] = 7.5e-3;
  return m;
}

std::string error_of(const std::string& text) {
  try {
    read_restart_deck_text(text, "restart.k", three_parts());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RestartDeck, TerminationAndSwitchesInOrder) {
  const RestartDeck deck = read_restart_deck_text(
      "*KEYWORD\n"
      "$ comment\n"
      "*TITLE\nextend and switch\n"
      "*CONTROL_TERMINATION\n"
      "$   endtim    endcyc\n"
      "    5.0e-3\n"
      "*DEFORMABLE_TO_RIGID\n"
      "         1         3      PART\n"
      "10,0,PSET\n"
      "*RIGID_TO_DEFORMABLE\n"
      "         3\n"
      "        10      PSET\n"
      "*END\n"
      "*BOUNDARY_SPC_NODE\n",  // after *END: not read
      "restart.k", three_parts());
  ASSERT_TRUE(deck.end_time.has_value());
  EXPECT_DOUBLE_EQ(*deck.end_time, 5e-3);
  EXPECT_FALSE(deck.end_cycle.has_value());
  EXPECT_EQ(deck.termination_where.line, 7);
  using Direction = model::RestartSwitch::Direction;
  ASSERT_EQ(deck.switches.size(), 4u);
  EXPECT_EQ(deck.switches[0].direction, Direction::kDeformableToRigid);
  EXPECT_EQ(deck.switches[0].parts, std::vector<model::Id>{1});
  EXPECT_EQ(deck.switches[0].lead_rigid_body, 3);
  EXPECT_EQ(deck.switches[0].where.line, 9);
  EXPECT_EQ(deck.switches[1].parts, (std::vector<model::Id>{2, 3}));
  EXPECT_EQ(deck.switches[1].lead_rigid_body, 0);
  EXPECT_EQ(deck.switches[2].direction, Direction::kRigidToDeformable);
  EXPECT_EQ(deck.switches[2].parts, std::vector<model::Id>{3});
  EXPECT_EQ(deck.switches[3].parts, (std::vector<model::Id>{2, 3}));
}

TEST(RestartDeck, EndCycleAndParameters) {
  const RestartDeck deck = read_restart_deck_text("*KEYWORD\n*CONTROL_TERMINATION\n&later,2000\n",
                                                  "restart.k", three_parts());
  EXPECT_DOUBLE_EQ(*deck.end_time, 7.5e-3);
  EXPECT_EQ(*deck.end_cycle, 2000);
}

TEST(RestartDeck, EmptyDeckChangesNothing) {
  const RestartDeck deck = read_restart_deck_text("*KEYWORD\n*END\n", "restart.k", three_parts());
  EXPECT_FALSE(deck.end_time.has_value());
  EXPECT_TRUE(deck.switches.empty());
}

TEST(RestartDeck, OtherKeywordsAreRefusedWithTheList) {
  const std::string message = error_of("*KEYWORD\n*MAT_ELASTIC\n1,7.8e-9,2.1e5,0.3\n");
  EXPECT_NE(message.find("restart.k:2: *MAT_ELASTIC: *MAT_ELASTIC cannot be used in a restart "
                         "deck; a restart deck may contain only *KEYWORD, *TITLE, "
                         "*CONTROL_TERMINATION, *DEFORMABLE_TO_RIGID, *RIGID_TO_DEFORMABLE, *END"),
            std::string::npos)
      << message;
}

TEST(RestartDeck, BadCardsNameTheField) {
  EXPECT_NE(error_of("*DEFORMABLE_TO_RIGID\n4\n")
                .find("restart.k:2: *DEFORMABLE_TO_RIGID card 1 "
                      "field PID: part 4 is not defined"),
            std::string::npos);
  EXPECT_NE(error_of("*DEFORMABLE_TO_RIGID\n11,0,PSET\n").find("part set 11 is not defined"),
            std::string::npos);
  EXPECT_NE(error_of("*DEFORMABLE_TO_RIGID\n1,9\n").find("field LRB: part 9 is not defined"),
            std::string::npos);
  EXPECT_NE(error_of("*RIGID_TO_DEFORMABLE\n1,PARTS\n")
                .find("field PTYPE: 'PARTS' is not a PID "
                      "type (PART or PSET)"),
            std::string::npos);
  EXPECT_NE(error_of("*RIGID_TO_DEFORMABLE\n\n").find("field PID: at least one card"),
            std::string::npos);
  EXPECT_NE(error_of("*RIGID_TO_DEFORMABLE\n0\n")
                .find("field PID: a part (or part set) ID is "
                      "required"),
            std::string::npos);
  EXPECT_NE(error_of("*CONTROL_TERMINATION\n1.0,0,1e-3\n")
                .find("field DTMIN: cannot be changed "
                      "on restart"),
            std::string::npos);
  EXPECT_NE(error_of("*CONTROL_TERMINATION\n-1.0\n").find("field ENDTIM: must not be negative"),
            std::string::npos);
  EXPECT_NE(error_of("stray text\n*KEYWORD\n").find("restart.k:1: text before the first keyword"),
            std::string::npos);
}

TEST(RestartDeck, MissingFile) {
  try {
    read_restart_deck("/nonexistent/restart.k", three_parts());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/restart.k: cannot open the restart deck"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rf::io
