// Bad *MAT_PLASTIC_KINEMATIC / *MAT_PIECEWISE_LINEAR_PLASTICITY input: every error names the
// file, line, keyword and field, and says what was expected. Errors found while reading (card
// values) and while building the solver state (curves, element families) are both covered.
#include <gtest/gtest.h>

#include <string>

#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

// One hexahedron of part 1 with material `mat` (MID 1) and any extra keywords.
std::string deck(const std::string& mat, const std::string& extra = "") {
  return "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
         "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,1\n" +
         mat + extra + "*END\n";
}

// Reads and builds the state; returns the InputError message, or "" if none.
std::string error_of(const std::string& text) {
  try {
    const model::Model model = io::read_deck_text(text, "plastic.k");
    const solver::NodeIndex index(model);
    solver::build_state(model, index);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

struct Case {
  std::string name;
  std::string text;
  std::vector<std::string> expected;
};

class PlasticInput : public ::testing::TestWithParam<Case> {};

TEST_P(PlasticInput, ErrorNamesFileLineKeywordAndField) {
  const Case& c = GetParam();
  const std::string message = error_of(c.text);
  ASSERT_FALSE(message.empty()) << "no error for " << c.name;
  for (const auto& part : c.expected)
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
}

const std::string k003 = "*MAT_PLASTIC_KINEMATIC\n";
const std::string k024 = "*MAT_PIECEWISE_LINEAR_PLASTICITY\n";

std::vector<Case> cases() {
  return {
      {"etan_not_below_e",
       deck(k003 + "1,7800,2e11,0.3,2e8,2e11,1\n"),
       {"plastic.k:", "*MAT_PLASTIC_KINEMATIC", "ETAN", "[0, E)"}},
      {"negative_sigy", deck(k003 + "1,7800,2e11,0.3,-1,0,1\n"), {"SIGY", "positive"}},
      {"beta_out_of_range", deck(k003 + "1,7800,2e11,0.3,2e8,0,1.5\n"), {"BETA", "[0, 1]"}},
      {"src_without_srp",
       deck(k003 + "1,7800,2e11,0.3,2e8,0,1\n40,0,0,0\n"),
       {"SRP", "both SRC and SRP"}},
      {"vp_003", deck(k003 + "1,7800,2e11,0.3,2e8,0,1\n0,0,0,2\n"), {"VP", "not 0"}},
      {"etan_024", deck(k024 + "1,7800,2e11,0.3,2e8,3e11\n"), {"*MAT_PIECEWISE", "ETAN"}},
      {"tdel_negative", deck(k024 + "1,7800,2e11,0.3,2e8,0,0,-1e-9\n"), {"TDEL", "non-negative"}},
      {"vp3_shells_only", deck(k024 + "1,7800,2e11,0.3,2e8,0\n0,0,0,0,3\n"), {"VP", "shells"}},
      {"fs_negative",
       deck(k003 + "1,7800,2e11,0.3,2e8,0,1\n0,0,-0.3,0\n"),
       {"FS", "must not be negative"}},
      {"fail_negative", deck(k024 + "1,7800,2e11,0.3,2e8,0,-1\n"), {"FAIL", "user"}},
      {"no_hardening", deck(k024 + "1,7800,2e11,0.3,0,0\n"), {"SIGY", "LCSS"}},
      {"lcss_missing",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,5,0,0\n"),
       {"plastic.k:", "LCSS", "5 is not a *DEFINE_CURVE"}},
      {"lcsr_names_a_table",
       deck(k024 + "1,7800,2e11,0.3,2e8,0\n0,0,0,7,0\n",
            "*DEFINE_TABLE\n7\n10\n*DEFINE_CURVE\n71\n0,2e8\n1,3e8\n"),
       {"LCSR", "*DEFINE_TABLE, which only LCSS accepts"}},
      {"table_with_c_and_p",
       deck(k024 + "1,7800,2e11,0.3,0,0\n40,5,7,0,0\n",
            "*DEFINE_TABLE\n7\n10\n*DEFINE_CURVE\n71\n0,2e8\n1,3e8\n"),
       {"field C", "*DEFINE_TABLE", "must be blank"}},
      {"table_curve_softening",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,7,0,0\n",
            "*DEFINE_TABLE\n7\n10\n100\n*DEFINE_CURVE\n71\n0,2e8\n1,3e8\n"
            "*DEFINE_CURVE\n72\n0,3e8\n1,2e8\n"),
       {"LCSS", "table 7, curve 72", "decreases"}},
      {"table_values_not_increasing",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,7,0,0\n", "*DEFINE_TABLE\n7\n10\n10\n"),
       {"plastic.k:", "*DEFINE_TABLE", "VALUE", "increase"}},
      {"table_curves_do_not_follow",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,7,0,0\n",
            "*DEFINE_TABLE\n7\n10\n100\n*DEFINE_CURVE\n71\n0,2e8\n1,3e8\n*DEFINE_CURVE_"
            "FUNCTION\n72\nmax(time,1)\n"),
       {"plastic.k:", "TBID", "table 7 still needs 1 *DEFINE_CURVE", "*DEFINE_CURVE_FUNCTION"}},
      {"table_at_end_of_deck",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,7,0,0\n", "*DEFINE_TABLE\n7\n10\n"),
       {"TBID", "still needs 1", "the deck ends"}},
      {"table_2d_missing_curve",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,7,0,0\n", "*DEFINE_TABLE_2D\n7\n10,71\n"),
       {"LCID", "curve 71", "not a *DEFINE_CURVE"}},
      {"table_shares_a_curve_id",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,7,0,0\n",
            "*DEFINE_CURVE\n7\n0,2e8\n1,3e8\n*DEFINE_TABLE_2D\n7\n10,7\n"),
       {"TBID", "may not share IDs"}},
      {"curve_decreasing",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,5,0,0\n",
            "*DEFINE_CURVE\n5\n0,2e8\n0.1,3e8\n0.2,2.5e8\n"),
       {"LCSS", "curve 5", "decreases"}},
      {"curve_negative",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,5,0,0\n", "*DEFINE_CURVE\n5\n0,-2e8\n0.1,3e8\n"),
       {"LCSS", "positive"}},
      {"table_not_increasing",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,0,0,0\n0,0.1,0.05\n2e8,3e8,3.5e8\n"),
       {"EPS", "does not increase"}},
      {"table_softening",
       deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,0,0,0\n0,0.1,0.2\n2e8,3e8,2.9e8\n"),
       {"ES", "decreases"}},
      {"lcsr_negative",
       deck(k024 + "1,7800,2e11,0.3,2e8,0\n0,0,0,6,0\n", "*DEFINE_CURVE\n6\n0,1\n10,-1\n"),
       {"LCSR", "positive"}},
      {"vp1_needs_sigy",
       deck(k024 + "1,7800,2e11,0.3,0,0\n40,5,5,0,1\n", "*DEFINE_CURVE\n5\n0,2e8\n1,3e8\n"),
       {"SIGY", "VP 1"}},
      {"plastic_on_p_order",
       deck(k003 + "1,7800,2e11,0.3,2e8,0,1\n", "*CHANGE_P-ORDER\nP,1,2\n"),
       {"MID", "order 2", "elastic materials only"}},
  };
}

INSTANTIATE_TEST_SUITE_P(Plasticity, PlasticInput, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

TEST(PlasticInput, ValidCardsBuild) {
  EXPECT_EQ(error_of(deck(k003 + "1,7800,2e11,0.3,2e8,2e9,0.5\n40.4,5,0,1\n")), "");
  EXPECT_EQ(error_of(deck("*MAT_024_TITLE\nsteel\n1,7800,2e11,0.3,0,0\n0,0,5,0,0\n",
                          "*DEFINE_CURVE\n5\n0,2e8\n0.1,3e8\n1,4e8\n")),
            "");
  EXPECT_EQ(error_of(deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,0,0,0\n0,0.1,0.3\n2e8,3e8,3.5e8\n")),
            "");
  // LCSS as a table: curves following a plain table, or named by _2D.
  EXPECT_EQ(error_of(deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,7,0,0\n",
                          "*DEFINE_TABLE_TITLE\nrates\n7\n-2.3\n4.6\n*DEFINE_CURVE\n71\n0,"
                          "2e8\n1,3e8\n*DEFINE_CURVE_TITLE\nfast\n72\n0,3e8\n1,4e8\n")),
            "");
  EXPECT_EQ(error_of(deck(k024 + "1,7800,2e11,0.3,0,0\n0,0,7,0,0\n",
                          "*DEFINE_CURVE\n71\n0,2e8\n1,3e8\n*DEFINE_TABLE_2D\n7\n10,71\n")),
            "");
  // LS-DYNA's FAIL default 10^20 means no failure.
  EXPECT_EQ(error_of(deck(k024 + "1,7800,2e11,0.3,2e8,0,1e21\n")), "");
}

}  // namespace
}  // namespace rf::test
