// *CONTROL_BULK_VISCOSITY and the *HOURGLASS Q1/Q2 fields: defaults (on, as in LS-DYNA),
// per-part overrides, the IMPETUS dialect (off), and bad values as errors naming file, line,
// keyword and field.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "io/keyword/reader.hpp"
#include "model/error.hpp"
#include "solver/build_state.hpp"

namespace rf::test {
namespace {

// Two hexahedra, parts 1 (HGID 1 when `hourglass` is given) and 2 (no HGID), plus `extra`.
std::string deck(const std::string& extra, const std::string& hourglass = "") {
  std::string s =
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
      "9,2,0,0\n10,2,1,0\n11,2,0,1\n12,2,1,1\n"
      "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n2,2,2,9,10,3,6,11,12,7\n"
      "*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,7850.0,2.1e11,0.3\n";
  s +=
      hourglass.empty() ? "*PART\none\n1,1,1\n" : "*PART\none\n1,1,1,0,1\n*HOURGLASS\n" + hourglass;
  s += "*PART\ntwo\n2,1,1\n";
  return s + extra + "*END\n";
}

solver::State build(const model::Model& model) {
  const solver::NodeIndex index(model);
  return solver::build_state(model, index);
}

// Reads and builds; the InputError message, or "" when there is none.
std::string error_of(const std::string& text) {
  try {
    build(io::read_deck_text(text, "bv.k"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const element::BulkViscositySettings& settings(const solver::State& s, model::Id part) {
  for (const auto& b : s.hex_blocks)
    if (b.part_id == part) return b.bulk_viscosity;
  throw std::runtime_error("no block");
}

TEST(BulkViscosityInput, OnWithLsDynaDefaultsWithoutTheCard) {
  const model::Model model = io::read_deck_text(deck(""), "bv.k");
  EXPECT_EQ(model.bulk_viscosity.q1, 1.5);
  EXPECT_EQ(model.bulk_viscosity.q2, 0.06);
  EXPECT_EQ(model.bulk_viscosity.type, 1);
  const solver::State s = build(model);
  EXPECT_EQ(settings(s, 1).q1, 1.5);
  EXPECT_EQ(settings(s, 1).q2, 0.06);
  EXPECT_TRUE(settings(s, 2).on());
}

TEST(BulkViscosityInput, BlankFieldsAreDefaultsAndValuesAreRead) {
  auto m = io::read_deck_text(deck("*CONTROL_BULK_VISCOSITY\n\n"), "bv.k");
  EXPECT_EQ(m.bulk_viscosity.q1, 1.5);
  EXPECT_EQ(m.bulk_viscosity.q2, 0.06);
  m = io::read_deck_text(
      deck("*CONTROL_BULK_VISCOSITY\n       2.0      0.10        -1         0         1\n"),
      "bv.k");
  EXPECT_EQ(m.bulk_viscosity.q1, 2.0);
  EXPECT_EQ(m.bulk_viscosity.q2, 0.10);
  EXPECT_EQ(m.bulk_viscosity.type, -1);  // no shells: the same as TYPE 1
  const solver::State s = build(m);
  EXPECT_EQ(settings(s, 2).q1, 2.0);
  EXPECT_EQ(settings(s, 2).q2, 0.10);
}

TEST(BulkViscosityInput, ZeroCoefficientsSwitchItOff) {
  const solver::State s =
      build(io::read_deck_text(deck("*CONTROL_BULK_VISCOSITY\n0.0,0.0\n"), "bv.k"));
  EXPECT_FALSE(settings(s, 1).on());
  EXPECT_FALSE(settings(s, 2).on());
}

TEST(BulkViscosityInput, HourglassCardOverridesPerPartAndBlankFieldsInherit) {
  // Part 1: *HOURGLASS Q1 given, Q2 blank; part 2: the control card.
  const solver::State s = build(io::read_deck_text(
      deck("*CONTROL_BULK_VISCOSITY\n1.2,0.05\n", "1,1,0.1,0,3.0,,,\n"), "bv.k"));
  EXPECT_EQ(settings(s, 1).q1, 3.0);
  EXPECT_EQ(settings(s, 1).q2, 0.05);
  EXPECT_EQ(settings(s, 2).q1, 1.2);
  EXPECT_EQ(settings(s, 2).q2, 0.05);
}

TEST(BulkViscosityInput, ImpetusDecksHaveNone) {
  model::Model m = io::read_deck_text(deck(""), "bv.k");
  m.dialect = "impetus";
  const solver::State s = build(m);
  EXPECT_FALSE(settings(s, 1).on());
  EXPECT_FALSE(settings(s, 2).on());
}

// A shell part (3, with HGID 3 when `hourglass` is given) next to the two hexahedra.
std::string shell_deck(const std::string& control, const std::string& hourglass = "") {
  return deck(control + "*SECTION_SHELL\n3,2\n0.01\n" +
              (hourglass.empty() ? "*PART\nsheet\n3,3,1\n"
                                 : "*PART\nsheet\n3,3,1,0,3\n*HOURGLASS\n" + hourglass) +
              "*ELEMENT_SHELL\n10,3,1,2,3,4\n");
}

const element::BulkViscositySettings& shell_settings(const solver::State& s) {
  return s.shell_blocks.at(0).bulk_viscosity;
}

// LS-DYNA's TYPE 1 (the default) leaves shells without bulk viscosity; TYPE -1 and -2 give them
// the control card's coefficients, or their part's *HOURGLASS Q1/Q2.
TEST(BulkViscosityInput, ShellsTakeItOnlyWithANegativeType) {
  EXPECT_FALSE(shell_settings(build(io::read_deck_text(shell_deck(""), "bv.k"))).on());
  EXPECT_FALSE(shell_settings(build(io::read_deck_text(
                                  shell_deck("*CONTROL_BULK_VISCOSITY\n1.5,0.06,1\n"), "bv.k")))
                   .on());
  for (const char* type : {"-1", "-2"}) {
    const solver::State s = build(io::read_deck_text(
        shell_deck(fmt::format("*CONTROL_BULK_VISCOSITY\n1.2,0.05,{}\n", type)), "bv.k"));
    EXPECT_EQ(shell_settings(s).q1, 1.2) << type;
    EXPECT_EQ(shell_settings(s).q2, 0.05) << type;
    EXPECT_EQ(settings(s, 1).q1, 1.2) << "solids keep theirs";
  }
  const solver::State s = build(io::read_deck_text(
      shell_deck("*CONTROL_BULK_VISCOSITY\n1.5,0.06,-2\n", "3,4,0.05,0,2.0,0.1\n"), "bv.k"));
  EXPECT_EQ(shell_settings(s).q1, 2.0);
  EXPECT_EQ(shell_settings(s).q2, 0.1);
}

struct ErrorCase {
  std::string name;
  std::string text;
  std::vector<std::string> expected;  // substrings of the message
};

class BulkViscosityError : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(BulkViscosityError, MessageLocatesTheProblem) {
  const ErrorCase& c = GetParam();
  const std::string message = error_of(c.text);
  ASSERT_FALSE(message.empty()) << c.name;
  for (const auto& part : c.expected)
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
}

// The control card is on line 29 of deck() (its first line after the second *PART).
INSTANTIATE_TEST_SUITE_P(
    Cases, BulkViscosityError,
    ::testing::Values(
        ErrorCase{"NegativeQ1",
                  deck("*CONTROL_BULK_VISCOSITY\n-1.5,0.06\n"),
                  {"bv.k:29: *CONTROL_BULK_VISCOSITY card 1 field Q1", "must not be negative"}},
        ErrorCase{"NegativeQ2",
                  deck("*CONTROL_BULK_VISCOSITY\n1.5,-0.06\n"),
                  {"bv.k:29: *CONTROL_BULK_VISCOSITY card 1 field Q2", "must not be negative"}},
        ErrorCase{
            "Type2",
            deck("*CONTROL_BULK_VISCOSITY\n1.5,0.06,2\n"),
            {"bv.k:29: *CONTROL_BULK_VISCOSITY card 1 field TYPE", "type 2 is not supported"}},
        ErrorCase{"BadBtype",
                  deck("*CONTROL_BULK_VISCOSITY\n1.5,0.06,1,3\n"),
                  {"bv.k:29: *CONTROL_BULK_VISCOSITY card 1 field BTYPE", "0..2"}},
        ErrorCase{"HourglassNegativeQ1",
                  deck("", "1,1,0.1,0,-2.0\n"),
                  {"*HOURGLASS card 1 field Q1", "must not be negative"}},
        ErrorCase{"BeamsWithBtype1",
                  deck("*CONTROL_BULK_VISCOSITY\n1.5,0.06,1,1\n*SECTION_BEAM\n3,3\n1.0e-4\n"
                       "*PART\nbar\n3,3,1\n*ELEMENT_BEAM\n10,3,1,9\n"),
                  {"bv.k:29: *CONTROL_BULK_VISCOSITY", "field BTYPE", "beams", "use BTYPE 0"}}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace rf::test
