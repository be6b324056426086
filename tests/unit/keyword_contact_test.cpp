// *CONTACT_AUTOMATIC_* (_ID) and *DATABASE_RCFORC: fields read from fixed-format and free-format
// cards, defaults, and every bad value an error that names file, line, keyword and field.
#include <gtest/gtest.h>

#include "keyword_test_util.hpp"

namespace {

// One hexahedron per part (parts 1 and 2) and the sets the contacts name.
const std::string kMesh =
    "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
    "11,0,0,2\n12,1,0,2\n13,1,1,2\n14,0,1,2\n15,0,0,3\n16,1,0,3\n17,1,1,3\n18,0,1,3\n"
    "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n2,2,11,12,13,14,15,16,17,18\n"
    "*PART\na\n1,1,1\n*PART\nb\n2,1,1\n*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,1000,1e7,0.3\n"
    "*SET_PART_LIST\n5\n1,2\n*SET_NODE_LIST\n6\n5,6,7,8\n*SET_SEGMENT\n9\n11,14,13,12\n";

TEST(KeywordContact, FixedFormatCardsAndDefaults) {
  const std::string text =
      kMesh +
      "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n"
      "$#     cid   heading\n"
      "        12plate and head\n"
      "         1         9         3         0\n"
      "       0.3       0.2       1.5       0.0      10.0         0     0.001       2.0\n"
      "       2.0       3.0      0.01      0.02       1.0       1.0       0.5\n"
      "         1      0.25\n"
      "*CONTACT_AUTOMATIC_NODES_TO_SURFACE\n6,2,4,3\n\n\n"
      "*CONTACT_AUTOMATIC_ONE_WAY_SURFACE_TO_SURFACE\n5,9,2,0\n0.4\n\n"
      "*CONTACT_AUTOMATIC_SINGLE_SURFACE\n0\n\n\n"
      "*DATABASE_RCFORC\n1e-4\n";
  const rf::model::Model m = rf::io::read_deck_text(text, "c.k");
  ASSERT_EQ(m.contacts.size(), 4u);
  const auto& a = m.contacts[0];
  EXPECT_EQ(a.number, 1);
  EXPECT_EQ(a.id, 12);
  EXPECT_EQ(a.heading, "plate and head");
  EXPECT_EQ(a.kind, rf::model::ContactKind::SurfaceToSurface);
  EXPECT_EQ(a.ssid, 1);
  EXPECT_EQ(a.msid, 9);
  EXPECT_EQ(a.sstyp, 3);
  EXPECT_EQ(a.mstyp, 0);
  EXPECT_DOUBLE_EQ(a.fs, 0.3);
  EXPECT_DOUBLE_EQ(a.fd, 0.2);
  EXPECT_DOUBLE_EQ(a.dc, 1.5);
  EXPECT_DOUBLE_EQ(a.vdc, 10.0);
  EXPECT_DOUBLE_EQ(a.birth, 0.001);
  EXPECT_DOUBLE_EQ(a.death, 2.0);
  EXPECT_DOUBLE_EQ(a.sfs, 2.0);
  EXPECT_DOUBLE_EQ(a.sfm, 3.0);
  EXPECT_DOUBLE_EQ(a.sst, 0.01);
  EXPECT_DOUBLE_EQ(a.mst, 0.02);
  EXPECT_DOUBLE_EQ(a.fsf, 0.5);
  EXPECT_EQ(a.soft, 1);
  EXPECT_DOUBLE_EQ(a.sofscl, 0.25);
  EXPECT_EQ(a.where.keyword, "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID");

  const auto& b = m.contacts[1];
  EXPECT_EQ(b.id, 2);  // no _ID: numbered by position
  EXPECT_EQ(b.kind, rf::model::ContactKind::NodesToSurface);
  EXPECT_EQ(b.sstyp, 4);
  EXPECT_DOUBLE_EQ(b.fs, 0.0);
  EXPECT_DOUBLE_EQ(b.sfs, 1.0);
  EXPECT_DOUBLE_EQ(b.death, 1e20);
  EXPECT_EQ(b.soft, 0);
  EXPECT_DOUBLE_EQ(b.sofscl, 0.1);

  const auto& c = m.contacts[2];
  EXPECT_EQ(c.kind, rf::model::ContactKind::OneWaySurfaceToSurface);
  EXPECT_DOUBLE_EQ(c.fs, 0.4);
  EXPECT_DOUBLE_EQ(c.fd, 0.4);  // FD blank: equal to FS

  const auto& d = m.contacts[3];
  EXPECT_EQ(d.kind, rf::model::ContactKind::SingleSurface);
  EXPECT_EQ(d.sstyp, 5);  // SSID 0: all parts
  EXPECT_DOUBLE_EQ(m.output.rcforc_dt, 1e-4);
}

struct ErrorCase {
  std::string name;
  std::string text;
  std::vector<std::string> expected;  // substrings of the message
};

class KeywordContactError : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(KeywordContactError, MessageLocatesTheProblem) {
  const ErrorCase& c = GetParam();
  const std::string message = rf::test::input_error_of(c.text, "contact.k");
  for (const auto& part : c.expected) {
    EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in: " << message;
  }
}

// A valid contact after the mesh (39 lines); each case breaks one field. The keyword is line
// 40, card 1 line 41, card 2 line 42, card 3 line 43.
std::string contact(const std::string& card1 = "1,2,3,3", const std::string& card2 = "",
                    const std::string& card3 = "", const std::string& more = "",
                    const std::string& keyword = "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE") {
  return kMesh + keyword + "\n" + card1 + "\n" + card2 + "\n" + card3 + "\n" + more;
}

std::vector<ErrorCase> cases() {
  const std::string s2s = "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE";
  return {
      {"UndefinedPart", contact("1,3,3,3"), {"contact.k:41: " + s2s, "field MSID", "part 3"}},
      {"UndefinedSegmentSet",
       contact("8,2,0,3"),
       {"contact.k:41: " + s2s, "field SSID", "segment set 8 is not defined"}},
      {"UndefinedPartSet", contact("1,4,3,2"), {"field MSID", "part set 4 is not defined"}},
      {"NodeSetOnlyForNodesToSurface",
       contact("6,2,4,3"),
       {"contact.k:41: " + s2s + " card 1 field SSTYP", "SSTYP 4 is not supported"}},
      {"UndefinedNodeSet",
       contact("7,2,4,3", "", "", "", "*CONTACT_AUTOMATIC_NODES_TO_SURFACE"),
       {"field SSID", "node set 7 is not defined"}},
      {"ShellSetType", contact("1,2,1,3"), {"card 1 field SSTYP", "SSTYP 1"}},
      {"MasterNodeSet", contact("1,6,3,4"), {"card 1 field MSTYP", "MSTYP 4"}},
      {"Box", contact("1,2,3,3,1"), {"card 1 field SBOXID", "boxes are not supported"}},
      {"ViscousFriction", contact("1,2,3,3", "0.1,0.1,0,5.0"), {"contact.k:42", "card 2 field VC"}},
      {"NegativeFriction", contact("1,2,3,3", "-0.1"), {"card 2 field FS", "negative"}},
      {"DampingAbove100", contact("1,2,3,3", "0,0,0,0,150"), {"card 2 field VDC", "above 100"}},
      {"DeathBeforeBirth", contact("1,2,3,3", "0,0,0,0,0,0,1.0,0.5"), {"card 2 field DT"}},
      {"NegativeThickness", contact("1,2,3,3", "", "1,1,-0.1"), {"card 3 field SST", "negative"}},
      {"Soft2", contact("1,2,3,3", "", "", "2\n"), {"card 4 field SOFT", "SOFT 2"}},
      {"AirbagCurve", contact("1,2,3,3", "", "", "0,0.1,5\n"), {"card 4 field LCIDAB"}},
      {"SolidThickness",
       contact("1,2,3,3", "", "", "0\n0,0,0,0,0,0,0.5\n"),
       {"card 5 field SLDTHK", "not supported"}},
      {"DuplicateId",
       kMesh + "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n4\n1,2,3,3\n\n\n" +
           "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n4\n2,1,3,3\n\n\n",
       {"field CID", "contact ID 4 is already used"}},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, KeywordContactError, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
