// *CONTROL_IMPLICIT_GENERAL and *CONTROL_IMPLICIT_EIGENVALUE: fields, defaults and the errors for
// values that would change the analysis (docs/keywords.md, docs/eigen.md).
#include <gtest/gtest.h>

#include <cmath>

#include "keyword_test_util.hpp"
#include "modal/eigen_analysis.hpp"

namespace {

const std::string kMesh =
    "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
    "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,2\n"
    "*MAT_ELASTIC\n1,7.8e-9,2.1e5,0.3\n";

TEST(KeywordImplicit, EigenvalueCardFieldsAndRequest) {
  const rf::model::Model model = rf::io::read_deck_text(
      kMesh +
          "*CONTROL_IMPLICIT_GENERAL\n"
          "         1     0.001\n"
          "*CONTROL_IMPLICIT_EIGENVALUE\n"
          "        12       0.0         1       2.5         1     1.0e4         2      30.0\n",
      "eig.k");
  const auto& c = model.implicit;
  EXPECT_TRUE(c.general);
  EXPECT_EQ(c.imflag, 1);
  EXPECT_DOUBLE_EQ(c.dt0, 0.001);
  EXPECT_TRUE(c.eigenvalue);
  EXPECT_EQ(c.neig, 12);
  EXPECT_EQ(c.lflag, 1);
  EXPECT_DOUBLE_EQ(c.lftend, 2.5);
  EXPECT_EQ(c.rflag, 1);
  EXPECT_DOUBLE_EQ(c.rhtend, 1e4);
  EXPECT_EQ(c.eigmth, 2);
  EXPECT_DOUBLE_EQ(c.shfscl, 30.0);
  EXPECT_TRUE(rf::modal::deck_requests_eigen_analysis(model));
  const rf::modal::EigenRequest r = rf::modal::request_from_deck(model);
  EXPECT_EQ(r.mode_count, 12);
  EXPECT_TRUE(r.remove_rigid_below);
  EXPECT_DOUBLE_EQ(r.left_frequency, 2.5);
  EXPECT_TRUE(r.limit_above);
  EXPECT_DOUBLE_EQ(r.right_frequency, 1e4);
  EXPECT_NEAR(r.shift, -std::pow(2.0 * M_PI * 30.0, 2), 1e-6);
}

TEST(KeywordImplicit, DefaultsAndExplicitDecks) {
  const rf::model::Model model =
      rf::io::read_deck_text(kMesh + "*CONTROL_IMPLICIT_EIGENVALUE\n20\n", "eig.k");
  EXPECT_EQ(model.implicit.lflag, 0);
  EXPECT_DOUBLE_EQ(model.implicit.lftend, -1e29);
  EXPECT_DOUBLE_EQ(model.implicit.center, 0.0);
  EXPECT_TRUE(rf::modal::deck_requests_eigen_analysis(model));
  const rf::model::Model explicit_deck =
      rf::io::read_deck_text(kMesh +
                                 "*CONTROL_IMPLICIT_GENERAL\n0\n"
                                 "*CONTROL_IMPLICIT_EIGENVALUE\n20\n",
                             "eig.k");
  EXPECT_FALSE(rf::modal::deck_requests_eigen_analysis(explicit_deck));
  EXPECT_FALSE(rf::modal::deck_requests_eigen_analysis(rf::io::read_deck_text(kMesh, "x.k")));
}

TEST(KeywordImplicit, UnsupportedValuesAreLocatedErrors) {
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {"*CONTROL_IMPLICIT_GENERAL\n2\n", "*CONTROL_IMPLICIT_GENERAL card 1 field IMFLAG: value 2"},
      {"*CONTROL_IMPLICIT_EIGENVALUE\n-5\n",
       "*CONTROL_IMPLICIT_EIGENVALUE card 1 field NEIG: value -5: intermittent"},
      {"*CONTROL_IMPLICIT_EIGENVALUE\n0\n", "field NEIG: the number of eigenvalues must be"},
      {"*CONTROL_IMPLICIT_EIGENVALUE\n10,0,0,0,0,0,3\n", "field EIGMTH: value 3 is not supported"},
      {"*CONTROL_IMPLICIT_EIGENVALUE\n10,0,0,0,0,0,111\n",
       "field EIGMTH: value 111 is not supported"},
      {"*CONTROL_IMPLICIT_EIGENVALUE\n10,0,2\n", "field LFLAG: must be 0 or 1"},
      {"*CONTROL_IMPLICIT_EIGENVALUE\n10\n1\n", "card 2 field ISOLID"},
  };
  for (const auto& c : cases) {
    const std::string message = rf::test::input_error_of(kMesh + c.text, "eig.k");
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_NE(message.find("eig.k:"), std::string::npos) << message;
  }
}

TEST(KeywordImplicit, OtherLanczosVariantsWarn) {
  const rf::model::Model model = rf::io::read_deck_text(
      kMesh + "*CONTROL_IMPLICIT_EIGENVALUE\n10,0,0,0,0,0,102\n0,0,0,0,1,1\n", "eig.k");
  int warnings = 0;
  for (const auto& w : model.warnings) {
    warnings += w.message.find("EIGMTH 102") != std::string::npos ||
                w.message.find("MSTRES") != std::string::npos ||
                w.message.find("EVDUMP") != std::string::npos;
  }
  EXPECT_EQ(warnings, 3);
}

}  // namespace
