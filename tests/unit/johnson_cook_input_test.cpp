// Bad *MAT_JOHNSON_COOK / *EOS_LINEAR_POLYNOMIAL / *PART EOSID input: every error names the
// file, line, keyword and field, and says what was expected (checks made while reading and while
// building the solver state).
#include <gtest/gtest.h>

#include <string>

#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

// One hexahedron of part 1 (EOSID `eosid`) with material text `mat` (MID 1) and extra keywords.
std::string deck(const std::string& mat, const std::string& extra = "", int eosid = 1) {
  return "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
         "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\nblock\n1,1,1," +
         std::to_string(eosid) + "\n*SECTION_SOLID\n1,1\n" + mat + extra + "*END\n";
}

const std::string kJc = "*MAT_JOHNSON_COOK\n";
const std::string kCard1 = "1,8960,4.6e10\n";
const std::string kCard2 = "9e7,2.92e8,0.31,0.025,1.09,1356,293,1\n";
const std::string kEos = "*EOS_LINEAR_POLYNOMIAL\n1,0,1.37e11\n";

std::string error_of(const std::string& text) {
  try {
    const model::Model model = io::read_deck_text(text, "jc.k");
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

class JohnsonCookInput : public ::testing::TestWithParam<Case> {};

TEST_P(JohnsonCookInput, ErrorNamesFileLineKeywordAndField) {
  const Case& c = GetParam();
  const std::string message = error_of(c.text);
  ASSERT_FALSE(message.empty()) << "no error for " << c.name;
  for (const auto& part : c.expected)
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
}

std::vector<Case> cases() {
  return {
      {"no_shear_modulus",
       deck(kJc + "1,8960\n" + kCard2, kEos),
       {"jc.k:", "*MAT_JOHNSON_COOK", "G"}},
      {"rateop",
       deck(kJc + "1,8960,4.6e10,0,0,0,0,1\n" + kCard2, kEos),
       {"RATEOP", "not supported"}},
      {"vp", deck(kJc + "1,8960,4.6e10,0,0,0,2\n" + kCard2, kEos), {"VP", "not 0"}},
      {"no_exponent", deck(kJc + kCard1 + "9e7,2.92e8,0\n", kEos), {"N", "positive"}},
      {"no_strength", deck(kJc + kCard1 + "0,0\n", kEos), {"A", "no strength"}},
      {"c_without_epso",
       deck(kJc + kCard1 + "9e7,2.92e8,0.31,0.025\n", kEos),
       {"EPSO", "positive"}},
      {"melt_below_room",
       deck(kJc + kCard1 + "9e7,2.92e8,0.31,0,1,200,293\n", kEos),
       {"TM", "exceed"}},
      {"positive_pc", deck(kJc + kCard1 + kCard2 + "383,1e8\n", kEos), {"PC", "not be positive"}},
      {"spall_type",
       deck(kJc + kCard1 + kCard2 + "383,-1e9,4\n", kEos),
       {"SPALL", "not 0, 1, 2 or 3"}},
      // Fracture: D3..D5 without D1, D2; a non-positive fracture strain; EFMIN, NUMINT.
      {"damage_d3_alone",
       deck(kJc + kCard1 + kCard2 + "383,-1e9,2,0,0,0,-1.5\n", kEos),
       {"jc.k:", "D1", "would be zero"}},
      {"damage_d5_alone", deck(kJc + kCard1 + kCard2 + "383,-1e9,2,0\n0.6\n", kEos), {"D1"}},
      {"damage_negative",
       deck(kJc + kCard1 + kCard2 + "383,-1e9,2,0,0.1,-0.3\n", kEos),
       {"D1", "must be positive"}},
      {"damage_efmin",
       deck(kJc + kCard1 + kCard2 + "383,-1e9,2,0,0.54\n0,0,0,-1\n", kEos),
       {"EFMIN", "positive"}},
      {"damage_numint",
       deck(kJc + kCard1 + kCard2 + "383,-1e9,2,0,0.54\n0,0,0,0,4\n", kEos),
       {"NUMINT", "not supported"}},
      {"eos_c1",
       deck(kJc + kCard1 + kCard2, "*EOS_LINEAR_POLYNOMIAL\n1,0,0\n"),
       {"*EOS_LINEAR_POLYNOMIAL", "C1", "positive"}},
      {"eos_v0", deck(kJc + kCard1 + kCard2, kEos + "0,1.1\n"), {"V0", "not supported"}},
      {"eos_duplicate", deck(kJc + kCard1 + kCard2, kEos + kEos), {"EOSID", "already defined"}},
      {"eos_missing", deck(kJc + kCard1 + kCard2, "", 7), {"*PART", "EOSID", "7", "not defined"}},
      {"eos_on_elastic",
       deck("*MAT_ELASTIC\n1,7800,2e11,0.3\n", kEos),
       {"*PART", "EOSID", "takes no equation of state"}},
      {"no_eos_no_bulk", deck(kJc + kCard1 + kCard2, "", 0), {"*PART", "EOSID", "E and PR"}},
  };
}

INSTANTIATE_TEST_SUITE_P(JohnsonCook, JohnsonCookInput, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

TEST(JohnsonCookInput, ValidCardsBuild) {
  EXPECT_EQ(error_of(deck(kJc + kCard1 + kCard2 + "383,-1e9,2,1\n", kEos + "0,1\n")), "");
  EXPECT_EQ(error_of(deck("*MAT_015_TITLE\ncopper\n" + kCard1 + kCard2, "*EOS_001\n1,0,1.37e11\n")),
            "");
  // Without an EOS: K from E and PR on the card.
  EXPECT_EQ(error_of(deck(kJc + "1,8960,4.6e10,1.2e11,0.3\n" + kCard2, "", 0)), "");
}

// PC blank with the default SPALL 2: the material would spall at the first tension: warned.
TEST(JohnsonCookInput, ZeroPressureCutoffIsWarned) {
  auto warned = [](const std::string& text) {
    const model::Model model = io::read_deck_text(text, "jc.k");
    for (const auto& w : model.warnings)
      if (w.message.find("PC is 0") != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(warned(deck(kJc + kCard1 + kCard2, kEos)));
  EXPECT_TRUE(warned(deck(kJc + kCard1 + kCard2 + "383,0,3\n", kEos)));
  EXPECT_FALSE(warned(deck(kJc + kCard1 + kCard2 + "383,0,1\n", kEos)));
  EXPECT_FALSE(warned(deck(kJc + kCard1 + kCard2 + "383,-1e9\n", kEos)));
}

}  // namespace
}  // namespace rf::test
