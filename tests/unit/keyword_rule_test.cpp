// The rule "no silent change of physics", every problem in one pass, and the reader features
// real decks need (issue 21). Expected values come from the LS-DYNA conventions the keyword
// manual states (card layouts, DFLAG meanings), not from our own output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/keyword/keyword_classes.hpp"
#include "keyword_test_util.hpp"
#include "model/curve.hpp"

namespace {

using rf::io::read_deck_text;
using rf::io::ReadOptions;
using rf::model::Model;

// One unit cube hexahedron, part 1, elastic, end time 1; 21 lines. `extra` starts on line 22.
std::string cube(const std::string& extra = "") {
  return "*KEYWORD\n"
         "*NODE\n"
         "1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
         "*ELEMENT_SOLID\n"
         "1,1,1,2,3,4,5,6,7,8\n"
         "*PART\n"
         "block\n"
         "1,1,1\n"
         "*SECTION_SOLID\n"
         "1,1\n"
         "*MAT_ELASTIC\n"
         "1,1.0,100.0,0.3\n"
         "*CONTROL_TERMINATION\n"
         "1.0\n" +
         extra;
}

std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

ReadOptions ignoring() {
  ReadOptions options;
  options.ignore_unsupported = true;
  return options;
}

// --- the classes -----------------------------------------------------------------------------

TEST(KeywordClasses, OutputOnlyKeywordsAreNamed) {
  using rf::io::UnsupportedClass;
  for (const char* k :
       {"*DATABASE_ELOUT", "*DATABASE_BINARY_D3THDT", "*CONTROL_ENERGY", "*CONTROL_OUTPUT",
        "*CONTROL_OUTPUT_TITLE", "*CONTROL_MPP_IO_NODUMP", "*INTERFACE_SPRINGBACK_LSDYNA"}) {
    EXPECT_EQ(rf::io::classify_unsupported(k).cls, UnsupportedClass::OutputOnly) << k;
  }
}

TEST(KeywordClasses, EverythingElseChangesThePhysics) {
  using rf::io::UnsupportedClass;
  for (const char* k :
       {"*LOAD_SEGMENT", "*CONTROL_ACCURACY", "*CONTROL_CONTACT", "*CONTROL_SOLID",
        "*CONTROL_SHELL", "*CONTROL_BULK_VISCOSITY", "*CONTROL_ENERGY_EXTRA_SOMETHING_ELSE_X",
        "*MAT_ELASTIC_PLASTIC_THERMAL", "*EOS_LINEAR_POLYNOMIAL", "*NODE_MERGE_SET",
        "*ELEMENT_SHELL", "*SECTION_SHELL_TITLE", "*CASE_BEGIN_1", "*ALE_MULTI-MATERIAL_GROUP",
        "*ICFD_PART", "*EM_CONTROL", "*NOT_A_KEYWORD", "*CONTROL_OUTPUTS"}) {
    EXPECT_EQ(rf::io::classify_unsupported(k).cls, UnsupportedClass::Physics) << k;
  }
  EXPECT_EQ(rf::io::classify_unsupported("*SECTION_TSHELL").what,
            "a thick-shell section: thick shells are not supported yet");
  EXPECT_EQ(rf::io::classify_unsupported("*NOT_A_KEYWORD").what, "an unknown keyword");
}

// --- the rule ------------------------------------------------------------------------------------

TEST(KeywordRule, PhysicsKeywordsAreErrorsListedWithTheirLines) {
  const std::string deck = cube(
      "*LOAD_SEGMENT_NONUNIFORM\n1,1.0\n"    // line 22
      "*CONTROL_ACCURACY\n1,4\n"             // line 24
      "*DATABASE_SBTOUT\n1e-3\n"             // line 26: output-only, a warning
      "*LOAD_SEGMENT_NONUNIFORM\n2,1.0\n");  // line 28
  const std::string message = rf::test::input_error_of(deck, "d.k");
  EXPECT_NE(message.find("3 problems in the deck"), std::string::npos) << message;
  EXPECT_NE(message.find("--ignore-unsupported"), std::string::npos) << message;
  EXPECT_NE(message.find("d.k:22: *LOAD_SEGMENT_NONUNIFORM: not supported: a load"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("d.k:24: *CONTROL_ACCURACY: not supported: a solver control"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("d.k:28: *LOAD_SEGMENT_NONUNIFORM"), std::string::npos) << message;
  EXPECT_EQ(message.find("SBTOUT"), std::string::npos) << message;
}

TEST(KeywordRule, IgnoreUnsupportedSkipsThemWithWarnings) {
  const std::string deck = cube("*LOAD_SEGMENT_NONUNIFORM\n1,1.0\n*DATABASE_SBTOUT\n1e-3\n");
  const Model m = read_deck_text(deck, "d.k", ".", ignoring());
  ASSERT_EQ(m.ignored_physics.size(), 1u);
  EXPECT_EQ(m.ignored_physics[0].where.line, 22);
  EXPECT_EQ(m.ignored_physics[0].where.keyword, "*LOAD_SEGMENT_NONUNIFORM");
  EXPECT_NE(m.ignored_physics[0].message.find("skipped because of --ignore-unsupported"),
            std::string::npos);
  ASSERT_EQ(m.warnings.size(), 2u);  // the skipped load and the output request
  EXPECT_NE(m.warnings[1].message.find("*DATABASE_SBTOUT (an output request)"), std::string::npos);
}

TEST(KeywordRule, KeywordsAreClassifiedByTheirFullName) {
  const std::string message = rf::test::input_error_of(
      cube("*MAT_ELASTIC_PLASTIC_THERMAL\n2,1.0\n*NODE_MERGE_SET\n1\n"), "d.k");
  EXPECT_NE(message.find("d.k:22: *MAT_ELASTIC_PLASTIC_THERMAL: not supported: a material"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("d.k:24: *NODE_MERGE_SET: not supported: a node definition"),
            std::string::npos)
      << message;
  EXPECT_EQ(message.find("option _PLASTIC"), std::string::npos) << message;
}

TEST(KeywordRule, CaseBlocksAreRefused) {
  const std::string message = rf::test::input_error_of(
      cube("*CASE_BEGIN_1\n*INITIAL_VELOCITY_NODE\n1,1.0\n*CASE_END_1\n"), "d.k");
  EXPECT_NE(message.find("d.k:22: *CASE_BEGIN_1: not supported: a load case"), std::string::npos)
      << message;
  EXPECT_NE(message.find("d.k:25: *CASE_END_1"), std::string::npos) << message;
}

// --- every problem in one pass -------------------------------------------------------------------

TEST(KeywordRule, PartsWithUnsupportedSectionsNameTheRealCause) {
  std::string extra = "*SECTION_TSHELL_TITLE\nskin\n2,1\n1.0\n";  // lines 22-25
  for (int p = 2; p <= 4; ++p) extra += "*PART\nshell part\n" + std::to_string(p) + ",2,1\n";
  const std::string message = rf::test::input_error_of(cube(extra), "d.k");
  EXPECT_NE(message.find("d.k:22: *SECTION_TSHELL_TITLE: not supported: a thick-shell section: "
                         "thick shells are not supported yet"),
            std::string::npos)
      << message;
  EXPECT_EQ(count_of(message,
                     "a *SECTION_TSHELL_TITLE at d.k:22: a thick-shell section: thick shells are "
                     "not supported yet"),
            3u)
      << message;
  EXPECT_NE(message.find("d.k:28: *PART field SECID: part 2 uses section 2"), std::string::npos)
      << message;
  EXPECT_EQ(message.find("not defined by a *SECTION_SOLID"), std::string::npos) << message;
}

TEST(KeywordRule, EveryCardErrorIsReportedInOnePass) {
  const std::string deck = cube(
      "*NODE\n9,abc,0,0\n"        // line 23: bad number
      "*SET_NODE_LIST\n1\n1.5\n"  // line 26: fraction in an integer field
      "*PART\nsecond\n5,1,7\n");  // line 29: material 7 is not defined
  const std::string message = rf::test::input_error_of(deck, "d.k");
  EXPECT_NE(message.find("3 problems in the deck"), std::string::npos) << message;
  EXPECT_NE(message.find("errors in cards (2):"), std::string::npos) << message;
  EXPECT_NE(message.find("d.k:23: *NODE card 1 field X: 'abc' is not a number"), std::string::npos)
      << message;
  EXPECT_NE(message.find("d.k:26: *SET_NODE_LIST card 2 field NID"), std::string::npos) << message;
  EXPECT_NE(message.find("references between definitions (1):"), std::string::npos) << message;
  EXPECT_NE(message.find("d.k:29: *PART field MID: part 5 refers to material 7"), std::string::npos)
      << message;
}

TEST(KeywordRule, TheListIsCappedAndCountsTheRest) {
  std::string extra;
  for (int i = 0; i < 250; ++i) extra += "*NODE\n" + std::to_string(100 + i) + ",x,0,0\n";
  try {
    read_deck_text(cube(extra), "d.k");
    ADD_FAILURE() << "no error";
  } catch (const rf::InputErrorList& e) {
    EXPECT_EQ(e.entries().size(), 200u);
    EXPECT_NE(std::string(e.what()).find("250 problems in the deck (50 not listed)"),
              std::string::npos);
  }
}

// --- what `run` would refuse, found by `check` ---------------------------------------------------

std::string runnable_error(const std::string& deck, bool ignore = false) {
  ReadOptions options;
  options.check_runnable = true;
  options.ignore_unsupported = ignore;
  try {
    read_deck_text(deck, "d.k", ".", options);
  } catch (const rf::InputError& e) {
    return e.what();
  }
  return {};
}

TEST(KeywordRule, MissingTerminationIsLocated) {
  std::string deck = cube();
  deck = deck.substr(0, deck.find("*CONTROL_TERMINATION"));
  EXPECT_NE(runnable_error(deck).find("d.k:1: the deck has no *CONTROL_TERMINATION"),
            std::string::npos);
  EXPECT_NE(runnable_error(deck + "*CONTROL_TERMINATION\n0.0\n")
                .find("d.k:20: *CONTROL_TERMINATION field ENDTIM: ENDTIM is not positive"),
            std::string::npos);
  EXPECT_EQ(runnable_error(cube()), "");
}

TEST(KeywordRule, NoElementsListsTheSkippedElementKeywords) {
  const std::string deck =
      "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n*ELEMENT_TSHELL\n1,1,1,2,3,4\n"
      "*CONTROL_TERMINATION\n1.0\n";
  const std::string plain = runnable_error(deck);
  EXPECT_NE(plain.find("d.k:6: *ELEMENT_TSHELL: not supported: thick-shell elements"),
            std::string::npos)
      << plain;
  const std::string ignored = runnable_error(deck, true);
  EXPECT_NE(ignored.find("d.k:1: the model has no elements or rigid bodies to simulate; skipped "
                         "element keywords: *ELEMENT_TSHELL (1 block(s))"),
            std::string::npos)
      << ignored;
}

TEST(KeywordRule, AllRigidWithoutTimeStepIsRefused) {
  std::string deck = cube("*MAT_RIGID\n2,1.0,100.0,0.3\n");
  deck.replace(deck.find("1,1,1\n*SECTION"), 5, "1,1,2");
  EXPECT_NE(runnable_error(deck).find("d.k:1: the model has no deformable elements, so nothing "
                                      "limits the time step"),
            std::string::npos)
      << runnable_error(deck);
  EXPECT_EQ(runnable_error(deck + "*CONTROL_TIMESTEP\n1e-3\n"), "");
}

TEST(KeywordRule, ImplicitWithoutEigenvalueCardIsFoundByCheck) {
  const std::string message = runnable_error(cube("*CONTROL_IMPLICIT_GENERAL\n1,0.01\n"));
  EXPECT_NE(message.find("d.k:22: *CONTROL_IMPLICIT_GENERAL card 1 field IMFLAG"),
            std::string::npos)
      << message;
}

// --- parameters ----------------------------------------------------------------------------------

TEST(KeywordParameters, ExpressionsSeeEarlierNamesCaseInsensitively) {
  const Model m = read_deck_text(
      "*PARAMETER\nR tEnd     2.0\n*PARAMETER_EXPRESSION\nR dt      TEnd/100.0\n"
      "R both    &TEND + dt*100\n");
  EXPECT_DOUBLE_EQ(m.parameters.at("dt"), 0.02);
  EXPECT_DOUBLE_EQ(m.parameters.at("both"), 4.0);
}

TEST(KeywordParameters, UnknownNameInAnExpressionIsNamed) {
  const std::string message = rf::test::input_error_of(
      "*PARAMETER\nR tEnd     2.0\n*PARAMETER_EXPRESSION\nR dt      tEnd2/100.0\n");
  EXPECT_NE(message.find("bar.k:4: *PARAMETER_EXPRESSION card 1 field EXPRESSION"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("'tEnd2' is not a defined parameter"), std::string::npos) << message;
}

TEST(KeywordParameters, DuplicationFollowsDflag) {
  // LS-DYNA's default (DFLAG 1): the first definition is kept, with a warning.
  const Model first = read_deck_text("*PARAMETER\nR a,1.0\n*PARAMETER\nR a,2.0\n");
  EXPECT_DOUBLE_EQ(first.parameters.at("a"), 1.0);
  ASSERT_EQ(first.warnings.size(), 1u);
  EXPECT_NE(first.warnings[0].message.find("parameter a is defined again"), std::string::npos);
  const Model replaced = read_deck_text(
      "*PARAMETER_DUPLICATION\n4\n*PARAMETER\nR a,1.0\n*PARAMETER_EXPRESSION\nR a,2.0*3\n");
  EXPECT_DOUBLE_EQ(replaced.parameters.at("a"), 6.0);
  EXPECT_TRUE(replaced.warnings.empty());
  const std::string error = rf::test::input_error_of(
      "*PARAMETER_DUPLICATION\n3\n*PARAMETER\nR a,1.0\n*PARAMETER\nR a,2.0\n");
  EXPECT_NE(error.find("bar.k:6: *PARAMETER card 1 field PRMR1: parameter a is defined again"),
            std::string::npos)
      << error;
}

// --- reader gaps ---------------------------------------------------------------------------------

TEST(KeywordReader, GenerateAndGeneralSets) {
  const Model m =
      read_deck_text(cube("*SET_NODE_LIST_GENERATE_TITLE\nends\n10\n1,2,7,100\n"
                          "*SET_PART_LIST_GENERATE\n11\n1,5\n"
                          "*SET_NODE_GENERAL\n12\nPART,1\nDNODE,1,2\n"
                          "*DEFINE_BOX\n3,-0.5,0.5,-0.5,1.5,-0.5,0.5\n"
                          "*SET_NODE_GENERAL\n13\nBOX,3\n"
                          "*SET_PART_GENERAL\n14\nALL\n"
                          "*SET_SOLID_TITLE\nall solids\n15\n1\n"
                          "*SET_SOLID_GENERATE\n16\n1,9\n"));
  using V = std::vector<rf::model::Id>;
  EXPECT_EQ(m.node_sets.at(10).nodes, (V{1, 2, 7, 8}));
  EXPECT_EQ(m.part_sets.at(11).parts, (V{1}));
  EXPECT_EQ(m.node_sets.at(12).nodes, (V{3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(m.node_sets.at(13).nodes, (V{1, 4}));
  EXPECT_EQ(m.part_sets.at(14).parts, (V{1}));
  EXPECT_EQ(m.solid_sets.at(15).elements, (V{1}));
  EXPECT_EQ(m.solid_sets.at(16).elements, (V{1}));
}

TEST(KeywordReader, CurveFunctionIsAnExpressionOfTime) {
  const Model m = read_deck_text(
      "*PARAMETER\nR amp,3.0\n*DEFINE_CURVE_FUNCTION_TITLE\nramp\n7,0,2.0,0.5\n"
      "&amp*SIN(2*PI*time) +\n time\n");
  const auto& c = m.curves.at(7);
  // SFO * f(t / SFA) with f(s) = 3 sin(2 pi s) + s.
  for (double t : {0.0, 0.3, 1.1}) {
    const double s = t / 2.0;
    EXPECT_NEAR(rf::model::evaluate(c, t), 0.5 * (3.0 * std::sin(2.0 * M_PI * s) + s), 1e-10);
  }
  const std::string bad = rf::test::input_error_of("*DEFINE_CURVE_FUNCTION\n7\nsin(tim)\n");
  EXPECT_NE(bad.find("bar.k:3: *DEFINE_CURVE_FUNCTION card 2 field FUNCTION"), std::string::npos)
      << bad;
}

TEST(KeywordReader, IdCardBeforeEveryDataCardAsLsPrePostWritesThem) {
  const Model m = read_deck_text(
      cube("*SET_NODE_LIST\n1\n1,2\n"
           "*BOUNDARY_SPC_SET_ID\n"
           "         1fixed base\n"
           "         1         0         1         1         1         0         0         0\n"
           "         2\n"
           "         1         0         0         0         1         0         0         0\n"));
  ASSERT_EQ(m.spcs.size(), 2u);
  EXPECT_TRUE(m.spcs[0].fix[0]);
  EXPECT_FALSE(m.spcs[1].fix[0]);
  EXPECT_TRUE(m.spcs[1].fix[2]);
}

TEST(KeywordReader, FixedFormatValueWiderThanItsColumnIsExplained) {
  const std::string message =
      rf::test::input_error_of(cube("*MAT_ELASTIC\n         2   7.85e-09  2.1e+05       0.3\n"));
  EXPECT_NE(message.find("card 1 field E"), std::string::npos) << message;
  EXPECT_NE(message.find("columns 21-30"), std::string::npos) << message;
  EXPECT_NE(message.find("free format"), std::string::npos) << message;
  EXPECT_NE(message.find("long format"), std::string::npos) << message;
}

// A value whose digits run on into the next fields still parses there ("0.0040000000000000001"
// as ENDTIM reads 0.00400000, ENDCYC 0000000000, DTMIN 01 = 1): the field that continues a digit
// run with a leading zero is refused, with the columns and the fix. Fully packed fields of
// ordinary numbers (no leading zero) stay valid.
TEST(KeywordReader, DigitsRunningIntoTheNextFieldAreRefused) {
  const std::string message =
      rf::test::input_error_of(cube("*CONTROL_TERMINATION\n0.0040000000000000001\n"));
  EXPECT_NE(message.find("card 1 field ENDCYC"), std::string::npos) << message;
  EXPECT_NE(message.find("continues the digits"), std::string::npos) << message;
  EXPECT_NE(message.find("columns 11-20"), std::string::npos) << message;
  EXPECT_NE(message.find("free format"), std::string::npos) << message;
  const Model packed =
      read_deck_text(cube("*MAT_ELASTIC\n         27.85000e-92.1000e+050.30000000\n"));
  EXPECT_DOUBLE_EQ(packed.materials.at(2).e, 2.1e5);
}

TEST(KeywordReader, FourNodeSolidIsATetrahedron) {
  const Model m = read_deck_text(cube("*ELEMENT_SOLID\n2,1,1,2,3,5\n"));
  ASSERT_EQ(m.solids.size(), 2u);
  EXPECT_EQ(m.solids[1].nodes, (std::array<rf::model::Id, 8>{1, 2, 3, 5, 5, 5, 5, 5}));
}

TEST(KeywordReader, KeywordIdAndContactTitleAreRead) {
  const Model m =
      read_deck_text(cube("*KEYWORD_ID\nmodel 12 revision 3\n"
                          "*SET_PART_LIST\n1\n1\n"
                          "*CONTACT_AUTOMATIC_SINGLE_SURFACE_TITLE\n"
                          "        42self contact\n1,0,2\n0.1\n\n"));
  ASSERT_EQ(m.contacts.size(), 1u);
  EXPECT_EQ(m.contacts[0].id, 42);
  EXPECT_EQ(m.contacts[0].heading, "self contact");
}

TEST(KeywordReader, IncludePathsAndNestedIncludes) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / "rigidflex_include_path_test";
  fs::remove_all(root);
  fs::create_directories(root / "mesh");
  fs::create_directories(root / "lib");
  auto write = [](const fs::path& p, const std::string& text) { std::ofstream(p) << text; };
  // mesh/part.k includes nodes.k next to it; material.k is found through *INCLUDE_PATH.
  write(root / "main.k",
        "*KEYWORD\n*INCLUDE_PATH_RELATIVE\nlib\n*INCLUDE\nmesh/part.k\n*INCLUDE\nmaterial.k\n");
  write(root / "mesh" / "part.k",
        "*INCLUDE\nnodes.k\n*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\np\n1,1,1\n");
  write(root / "mesh" / "nodes.k",
        "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n");
  write(root / "lib" / "material.k", "*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,1.0,100.0,0.3\n");
  const Model m = rf::io::read_deck(root / "main.k");
  EXPECT_EQ(m.nodes.size(), 8u);
  EXPECT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.files.size(), 4u);
  fs::remove_all(root);
}

}  // namespace
