// Malformed input: every error must name file, line, keyword, card and field.
#include <gtest/gtest.h>

#include "keyword_test_util.hpp"

namespace {

// A valid one-element model; cases append or replace pieces of it.
std::string deck(const std::string& mesh_extra = "", const std::string& tail = "",
                 const std::string& section = "         1         1\n",
                 const std::string& mat = "         1    7.8e-9     2.1e5       0.3\n",
                 const std::string& part = "         1         1         1\n") {
  return "*KEYWORD\n"
         "*NODE\n"
         "1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n" +
         mesh_extra +
         "*ELEMENT_SOLID\n"
         "       1       1       1       2       3       4       5       6       7       8\n"
         "*PART\n"
         "block\n" +
         part + "*SECTION_SOLID\n" + section + "*MAT_ELASTIC\n" + mat +
         "*DEFINE_CURVE\n"
         "         1\n"
         "0.0,0.0\n1.0,1.0\n" +
         tail;
}

struct ErrorCase {
  std::string name;
  std::string text;
  std::vector<std::string> expected;  // substrings of the message
};

class KeywordError : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(KeywordError, MessageLocatesTheProblem) {
  const ErrorCase& c = GetParam();
  const std::string message = rf::test::input_error_of(c.text, "bar.k");
  for (const auto& part : c.expected) {
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
  }
}

std::vector<ErrorCase> cases() {
  return {
      {"BadNumber",
       deck("*NODE\n       9             abc             0.0             0.0\n"),
       {"bar.k:12: *NODE card 1 field X: 'abc' is not a number"}},
      {"UnsupportedElform",
       deck("", "", "         1        13\n"),
       {"bar.k:17: *SECTION_SOLID card 1 field ELFORM: value 13 is not supported "
        "(supported: 1, 2)"}},
      {"UnknownNodeInElement",
       "*NODE\n1,0,0,0\n*ELEMENT_SOLID\n1,1,1,1,1,1,1,1,1,99\n*PART\np\n1,1,1\n"
       "*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,1.0,1.0,0.3\n",
       {"bar.k:4: *ELEMENT_SOLID", "field N8", "node 99"}},
      {"UnknownPartInElement",
       "*NODE\n1,0,0,0\n*ELEMENT_SOLID\n1,5,1,1,1,1,1,1,1,1\n",
       {"bar.k:4: *ELEMENT_SOLID", "field PID", "part 5"}},
      {"MissingPartMaterial",
       deck("", "", "         1         1\n", "         2    7.8e-9     2.1e5       0.3\n"),
       {"bar.k:15: *PART", "field MID", "material 1"}},
      {"UndefinedParameter",
       deck("*NODE\n       9         &nosuch             0.0             0.0\n"),
       {"bar.k:12: *NODE card 1 field X", "'nosuch' is not defined"}},
      {"MissingInclude",
       "*KEYWORD\n*INCLUDE\nnot_there.k\n",
       {"bar.k:3: *INCLUDE card 1 field FILENAME", "not_there.k"}},
      {"DuplicateNode",
       deck("*NODE\n       5             0.0             0.0             0.0\n"),
       {"bar.k:12: *NODE card 1 field NID", "node 5 is already defined at bar.k:7"}},
      {"DuplicateElement",
       deck("", "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n"),
       {"bar.k:25: *ELEMENT_SOLID card 1 field EID", "element 1 is already defined"}},
      {"DuplicatePart",
       deck("", "*PART\nagain\n1,1,1\n"),
       {"bar.k:26: *PART card 2 field PID", "part 1 is already defined at bar.k:15"}},
      {"NegativeDensity",
       deck("", "", "         1         1\n", "         1   -7.8e-9     2.1e5       0.3\n"),
       {"bar.k:19: *MAT_ELASTIC card 1 field RO", "must be positive"}},
      {"PoissonRatioTooLarge",
       deck("", "", "         1         1\n", "         1    7.8e-9     2.1e5       0.5\n"),
       {"bar.k:19: *MAT_ELASTIC card 1 field PR", "(-1, 0.5)"}},
      {"MassScaling",
       deck("", "*CONTROL_TIMESTEP\n       0.0       0.9         0       0.0   -1.0e-6\n"),
       {"bar.k:25: *CONTROL_TIMESTEP card 1 field DT2MS", "mass scaling is not supported"}},
      {"UnsupportedDof",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,7,0,1\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_NODE card 1 field DOF", "value 7 is not supported"}},
      {"UnsupportedVad",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,1,3,1\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_NODE card 1 field VAD"}},
      {"BoundaryUnknownCurve",
       deck("", "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,1,0,4\n"),
       {"bar.k:25: *BOUNDARY_PRESCRIBED_MOTION_NODE", "field LCID", "load curve 4"}},
      {"SpcUnknownSet",
       deck("", "*BOUNDARY_SPC_SET\n3,0,1,1,1\n"),
       {"bar.k:25: *BOUNDARY_SPC_SET", "field NSID", "node set 3"}},
      {"SetUnknownNode",
       deck("", "*SET_NODE_LIST\n1\n1,2,77\n"),
       {"bar.k:25: *SET_NODE_LIST", "field NID", "node 77"}},
      {"IntegerWithFraction",
       deck("", "*SET_NODE_LIST\n1\n1.5\n"),
       {"bar.k:26: *SET_NODE_LIST card 2 field NID", "'1.5' is not an integer"}},
      {"MissingCard",
       deck("", "*INITIAL_VELOCITY\n0\n"),
       {"bar.k:25: *INITIAL_VELOCITY card 2", "missing"}},
      {"UnsupportedOption",
       deck("", "*PART_CONTACT\np\n2,1,1\n"),
       {"bar.k:24: *PART_CONTACT", "option _CONTACT"}},
      {"RotationalVelocity",
       deck("", "*INITIAL_VELOCITY_NODE\n1,0,0,0,1.0\n"),
       {"bar.k:25: *INITIAL_VELOCITY_NODE card 1 field VXR"}},
      {"DecreasingCurve",
       deck("", "*DEFINE_CURVE\n2\n1.0,0\n0.5,0\n"),
       {"bar.k:27: *DEFINE_CURVE card 3 field A1", "increasing"}},
      {"HugeNumber",
       deck("*NODE\n       9          1e9999             0.0             0.0\n"),
       {"bar.k:12: *NODE card 1 field X", "out of range"}},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, KeywordError, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

TEST(KeywordErrorContext, ErrorCarriesStructuredContext) {
  try {
    rf::io::read_deck_text(deck("", "", "         1        13\n"), "bar.k");
    FAIL() << "no error";
  } catch (const rf::InputError& e) {
    EXPECT_EQ(e.context().file, "bar.k");
    EXPECT_EQ(e.context().line, 17);
    EXPECT_EQ(e.context().keyword, "*SECTION_SOLID");
    EXPECT_EQ(e.context().card, 1);
    EXPECT_EQ(e.context().field, "ELFORM");
  }
}

TEST(KeywordErrorContext, BaseDeckIsValid) {
  EXPECT_NO_THROW(rf::io::read_deck_text(deck(), "bar.k"));
}

}  // namespace
