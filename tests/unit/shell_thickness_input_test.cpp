// *CONTROL_SHELL ISTUPD through the reader and the state build: 1 and 4 turn the thickness
// update on (element/shell_block.cpp, section 12), the thick-shell options 2 and 3 and any other
// value are refused naming file, line, keyword and field, as are PSSTUPD (a part set) and a
// *CONTROL_CONTACT THKCHG that asks the contacts to follow the thickness.
#include <gtest/gtest.h>

#include <string>

#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

// Line 1 *KEYWORD, nodes on lines 2-6, the shell on 7-8, part on 9-11, section on 12-14,
// material 15-16, hourglass 17-18; `extra` from line 19.
std::string deck(const std::string& extra) {
  return "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n*ELEMENT_SHELL\n1,1,1,2,3,4\n"
         "*PART\nsheet\n1,1,1,0,1\n*SECTION_SHELL\n1,2,0.8333,2\n0.01\n"
         "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7850.0,2.1e11,0.3,2e8,1e9\n*HOURGLASS\n1,1,0.1\n" +
         extra + "*END\n";
}

solver::State build(const std::string& text) {
  const model::Model model = io::read_deck_text(text, "thk.k");
  const solver::NodeIndex index(model);
  return solver::build_state(model, index);
}

std::string error_of(const std::string& text) {
  try {
    build(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ShellThicknessInput, Istupd1And4TurnTheUpdateOn) {
  EXPECT_EQ(build(deck("")).shell_blocks[0].thickness_update, 0);
  EXPECT_EQ(build(deck("*CONTROL_SHELL\n20,0,-1,0\n")).shell_blocks[0].thickness_update, 0);
  EXPECT_EQ(build(deck("*CONTROL_SHELL\n20,0,-1,1\n")).shell_blocks[0].thickness_update, 1);
  EXPECT_EQ(build(deck("*CONTROL_SHELL\n20,0,-1,4\n")).shell_blocks[0].thickness_update, 4);
  // Fixed format (columns 31-40).
  EXPECT_EQ(build(deck("*CONTROL_SHELL\n      20.0         0        -1         1\n"))
                .shell_blocks[0]
                .thickness_update,
            1);
  // The initial thickness is kept apart from the current one.
  const solver::State s = build(deck("*CONTROL_SHELL\n20,0,-1,1\n"));
  EXPECT_EQ(s.shell_blocks[0].element_thickness0, s.shell_blocks[0].element_thickness);
  // THKCHG without a thickness update changes nothing and is accepted.
  EXPECT_EQ(error_of(deck("*CONTROL_CONTACT\n0.1,0,0,0,0,1\n")), "");
}

TEST(ShellThicknessInput, OtherValuesNameFileLineKeywordAndField) {
  for (const char* value : {"2", "3"}) {
    const std::string e = error_of(deck(std::string("*CONTROL_SHELL\n20,0,-1,") + value + "\n"));
    EXPECT_NE(e.find("thk.k:20: *CONTROL_SHELL card 1 field ISTUPD"), std::string::npos) << e;
    EXPECT_NE(e.find(std::string("ISTUPD ") + value + " (thickness change of thick shells"),
              std::string::npos)
        << e;
  }
  for (const char* value : {"5", "-1"}) {
    const std::string e = error_of(deck(std::string("*CONTROL_SHELL\n20,0,-1,") + value + "\n"));
    EXPECT_NE(e.find("thk.k:20: *CONTROL_SHELL card 1 field ISTUPD"), std::string::npos) << e;
    EXPECT_NE(e.find("is not a thickness change option"), std::string::npos) << e;
  }
  // PSSTUPD (the part set the update applies to) is not supported: every shell part thins.
  std::string e = error_of(deck("*CONTROL_SHELL\n20,0,-1,1\n1.0,0,0,0,0\n7\n"));
  EXPECT_NE(e.find("thk.k:22: *CONTROL_SHELL card 3 field PSSTUPD"), std::string::npos) << e;
  // The contacts keep the initial thickness: THKCHG 1 with a thickness update is refused.
  e = error_of(deck("*CONTROL_SHELL\n20,0,-1,1\n*CONTROL_CONTACT\n0.1,0,0,0,0,1\n"));
  EXPECT_NE(e.find("thk.k:22: *CONTROL_CONTACT field THKCHG"), std::string::npos) << e;
  EXPECT_NE(e.find("keep the initial shell thickness"), std::string::npos) << e;
  e = error_of(deck("*CONTROL_CONTACT\n0.1,0,0,0,0,3\n"));
  EXPECT_NE(e.find("thk.k:20: *CONTROL_CONTACT card 1 field THKCHG"), std::string::npos) << e;
}

}  // namespace
}  // namespace rf::test
