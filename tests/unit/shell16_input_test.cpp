// *SECTION_SHELL ELFORM 16 and *CONTROL_SHELL THEORY 16 through the reader and the state build:
// accepted values, and unsupported ones refused naming file, line, keyword and field (or the
// element, for a triangle).
#include <gtest/gtest.h>

#include <string>

#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

// Line 1 *KEYWORD, nodes on lines 2-6, the shell on 7-8, part on 9-11, section on 12-14.
std::string deck(const std::string& section, const std::string& extra = "",
                 const std::string& element = "1,1,1,2,3,4") {
  return "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n*ELEMENT_SHELL\n" + element +
         "\n*PART\nsheet\n1,1,1,0,1\n*SECTION_SHELL\n" + section +
         "\n0.01\n*MAT_ELASTIC\n1,7850.0,2.1e11,0.3\n*HOURGLASS\n1,1,0.1\n" + extra + "*END\n";
}

solver::State build(const std::string& text) {
  const model::Model model = io::read_deck_text(text, "s16.k");
  const solver::NodeIndex index(model);
  return solver::build_state(model, index);
}

std::string error_of(const std::string& text) {
  try {
    build(text);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(Shell16Input, Elform16AndTheory16GiveFullyIntegratedBlocks) {
  const solver::State a = build(deck("1,16,0.8333,3"));
  ASSERT_EQ(a.shell_blocks.size(), 1u);
  EXPECT_EQ(a.shell_blocks[0].elform, 16);
  EXPECT_EQ(a.shell_blocks[0].points_per_element(), 12);
  EXPECT_EQ(a.shell_blocks[0].stress.size(), 5u * 12u);
  // ELFORM 0 takes *CONTROL_SHELL THEORY (blank: 2).
  EXPECT_EQ(build(deck("1,0,0.8333,2", "*CONTROL_SHELL\n20,0,-1,0,16\n")).shell_blocks[0].elform,
            16);
  EXPECT_EQ(build(deck("1,0,0.8333,2")).shell_blocks[0].elform, 2);
  // An explicit ELFORM wins over THEORY.
  EXPECT_EQ(build(deck("1,2,0.8333,2", "*CONTROL_SHELL\n20,0,-1,0,16\n")).shell_blocks[0].elform,
            2);
}

TEST(Shell16Input, UnsupportedValuesNameFileLineKeywordAndField) {
  std::string e = error_of(deck("1,5,0.8333,2"));
  EXPECT_NE(e.find("s16.k:13: *SECTION_SHELL card 1 field ELFORM"), std::string::npos) << e;
  EXPECT_NE(e.find("16, fully integrated"), std::string::npos) << e;
  e = error_of(deck("1,16,0.8333,2", "*CONTROL_SHELL\n20,0,-1,0,4\n"));
  EXPECT_NE(e.find("*CONTROL_SHELL card 1 field THEORY"), std::string::npos) << e;
  EXPECT_NE(e.find("16, fully integrated"), std::string::npos) << e;
  // IHQ 8 (LS-DYNA's warping stiffness for type 16) is not supported: an error at the part.
  const std::string ihq8 = deck("1,16,0.8333,2");
  e = error_of(ihq8.substr(0, ihq8.find("*HOURGLASS")) + "*HOURGLASS\n1,8,0.1\n*END\n");
  EXPECT_NE(e.find("s16.k:11: *PART field HGID"), std::string::npos) << e;
  EXPECT_NE(e.find("IHQ=8"), std::string::npos) << e;
  // A triangle: the element and the part are named.
  e = error_of(deck("1,16,0.8333,2", "", "7,1,1,2,3,3"));
  EXPECT_NE(e.find("shell element 7 of part 1 is a triangle"), std::string::npos) << e;
}

}  // namespace
}  // namespace rf::test
