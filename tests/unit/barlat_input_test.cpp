// Bad *MAT_3-PARAMETER_BARLAT (036) input: every error names the file, line, keyword and field
// and says what was expected (values read on the cards, curves and R values resolved when the
// state is built, the material on solids, material axes that leave the shell's plane).
#include <gtest/gtest.h>

#include <string>

#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

const std::string kNodes = "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n";

// One shell of part 1 with material `mat` (MID 1).
std::string shell_deck(const std::string& mat, const std::string& extra = "") {
  return "*KEYWORD\n" + kNodes +
         "*ELEMENT_SHELL\n1,1,1,2,3,4\n*PART\nsheet\n1,1,1\n*SECTION_SHELL\n1,2,0.833,2\n"
         "0.001,0.001,0.001,0.001\n" +
         mat + extra + "*END\n";
}

std::string mat036_card1() {
  return "1,7800,2e11,0.3,1,2e9,2e8,0";
}

// The five cards; `card1`, `card2`, `card3` and the axes cards replaceable.
std::string mat036(const std::string& card1 = "1,7800,2e11,0.3,1,2e9,2e8,0",
                   const std::string& card2 = "6,1.5,1.0,2.0,0,0,0,0",
                   const std::string& card3 = "0,0,0,0,0,0,0,0",
                   const std::string& card4 = "0,0,0,0,0,0,0,0",
                   const std::string& card5 = "0,0,0,0,0,0,0,0") {
  return "*MAT_3-PARAMETER_BARLAT\n" + card1 + "\n" + card2 + "\n" + card3 + "\n" + card4 + "\n" +
         card5 + "\n";
}

std::string error_of(const std::string& text) {
  try {
    const model::Model model = io::read_deck_text(text, "barlat.k");
    const solver::NodeIndex index(model);
    solver::build_state(model, index);
  } catch (const std::exception& e) {  // InputError, or SolverError for element geometry
    return e.what();
  }
  return "";
}

struct Case {
  std::string name;
  std::string text;
  std::vector<std::string> expected;
};

class BarlatInput : public ::testing::TestWithParam<Case> {};

TEST_P(BarlatInput, ErrorNamesFileLineKeywordAndField) {
  const Case& c = GetParam();
  const std::string message = error_of(c.text);
  ASSERT_FALSE(message.empty()) << "no error for " << c.name;
  for (const auto& part : c.expected)
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
}

std::vector<Case> cases() {
  const std::string solid =
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
      "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,1\n" +
      mat036() + "*END\n";
  return {
      {"hr_4",
       shell_deck(mat036("1,7800,2e11,0.3,4,2e9,2e8,0")),
       {"barlat.k:", "*MAT_3-PARAMETER_BARLAT", "HR", "not supported"}},
      {"hr1_no_yield", shell_deck(mat036("1,7800,2e11,0.3,1,2e9,0,0")), {"P2", "yield stress"}},
      {"hr1_etan", shell_deck(mat036("1,7800,2e11,0.3,1,3e11,2e8,0")), {"P1", "[0, E)"}},
      {"hr2_exponent", shell_deck(mat036("1,7800,2e11,0.3,2,5e8,1.5,0")), {"P2", "(0, 1)"}},
      {"m_below_1",
       shell_deck(mat036("1,7800,2e11,0.3,1,2e9,2e8,0", "0.5,1.5,1,2,0,0,0,0")),
       {"M", "at least 1"}},
      {"m_negative",
       shell_deck(mat036("1,7800,2e11,0.3,1,2e9,2e8,0", "-6,1.5,1,2,0,0,0,0")),
       {"M", "Chaboche"}},
      {"r00_zero",
       shell_deck(mat036("1,7800,2e11,0.3,1,2e9,2e8,0", "6,0,1,2,0,0,0,0")),
       {"R00", "positive", "PB"}},
      {"r90_negative",
       shell_deck(mat036("1,7800,2e11,0.3,1,2e9,2e8,0", "6,1.5,1,-2,0,0,0,0")),
       {"R90", "positive"}},
      {"r45_unreachable",
       shell_deck(mat036("1,7800,2e11,0.3,1,2e9,2e8,0", "6,1.5,1e9,2,0,0,0,0")),
       {"barlat.k:", "R45", "no coefficient p"}},
      {"hr3_no_curve", shell_deck(mat036("1,7800,2e11,0.3,3,0,0,0")), {"LCID", "HR 3"}},
      {"hr3_missing_curve",
       shell_deck(mat036("1,7800,2e11,0.3,3,0,0,0", "6,1.5,1,2,9,0,0,0")),
       {"LCID", "9", "not a *DEFINE_CURVE"}},
      {"hr3_decreasing_curve",
       shell_deck(mat036("1,7800,2e11,0.3,3,0,0,0", "6,1.5,1,2,9,0,0,0"),
                  "*DEFINE_CURVE\n9\n0,3e8\n0.1,2e8\n"),
       {"LCID", "decreases"}},
      {"aopt_1",
       shell_deck(mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "1,0,0,0,0,0,0,0")),
       {"AOPT", "not supported"}},
      {"aopt_negative",
       shell_deck(mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "-4,0,0,0")),
       {"AOPT"}},
      {"rate_c",
       shell_deck(mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "0,40,5,0")),
       {"C", "Cowper-Symonds"}},
      {"vlcid", shell_deck(mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "0,0,0,3")), {"VLCID"}},
      {"aopt2_no_vector",
       shell_deck(mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "2,0,0,0,0,0,0,0")),
       {"A1", "AOPT 2"}},
      {"aopt2_vector_along_normal",
       shell_deck(
           mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "2,0,0,0,0,0,0,0", "0,0,0,0,0,1,0,0")),
       {"shell element 1", "AOPT 2", "normal"}},
      {"aopt3_no_vector",
       shell_deck(mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "3,0,0,0,0,0,0,0")),
       {"V1", "AOPT 3"}},
      {"htflag",
       shell_deck(mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "0,0,0,0,0,0,0,0", "0,0,0,0,0,0,0,0",
                         "0,0,0,0,0,0,0,1")),
       {"HTFLAG", "heat treatment"}},
      {"solid_elements", solid, {"*MAT_3-PARAMETER_BARLAT", "shells only"}},
  };
}

INSTANTIATE_TEST_SUITE_P(Mat036, BarlatInput, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

// The accepted forms: AOPT 0, 2 and 3, the _TITLE option and the *MAT_036 name, PB > 0 with
// a, c, h given directly.
TEST(BarlatInputAccepted, GoodCardsBuild) {
  EXPECT_EQ(error_of(shell_deck(mat036())), "");
  EXPECT_EQ(error_of(shell_deck("*MAT_036_TITLE\nsheet steel\n1,7800,2e11,0.3,1,2e9,2e8,0\n"
                                "6,1.5,1,2,0,0,0,0\n2,0,0,0,0,0,0,0\n0,0,0,1,1,0,0,0\n"
                                "0,0,0,0,0,0,0,0\n")),
            "");
  EXPECT_EQ(error_of(shell_deck(mat036(mat036_card1(), "6,1.5,1,2,0,0,0,0", "3,0,0,0,0,0,0,0",
                                       "0,0,0,0,0,0,0,0", "0,1,0,0,0,0,30,0"))),
            "");
  EXPECT_EQ(
      error_of(shell_deck(mat036(mat036_card1(), "6,0.8,1.2,0.9,0,0,0,0", "0,0,0,0,0,1.1,0,0"))),
      "");
}

}  // namespace
}  // namespace rf::test
