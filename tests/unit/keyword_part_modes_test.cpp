// *PART_MODES: fields, defaults, the kept-mode and damping cards, the path of the mode file, and
// the clear rejection of what the solver does not support.
#include <gtest/gtest.h>

#include <string>

#include "io/keyword/reader.hpp"
#include "model/error.hpp"

namespace {

// One rigid hexahedron (part 1) and an elastic one (part 2), then `tail`.
std::string deck(const std::string& tail) {
  return "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
         "9,2,0,0\n10,2,1,0\n11,2,0,1\n12,2,1,1\n"
         "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n2,2,2,9,10,3,6,11,12,7\n"
         "*PART\nrigid\n1,1,1\n*PART\nelastic\n2,1,2\n*SECTION_SOLID\n1,1\n"
         "*MAT_RIGID\n1,7850,2e11,0.3\n0,0,0\n*MAT_ELASTIC\n2,7850,2e11,0.3\n"
         "*CONTROL_TERMINATION\n1e-3\n" +
         tail + "*END\n";
}

rf::model::Model read(const std::string& tail) {
  return rf::io::read_deck_text(deck(tail), "/decks/modes/test.k");
}

std::string error_of(const std::string& tail) {
  try {
    read(tail);
  } catch (const rf::InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(KeywordPartModes, FieldsKeptModesAndDamping) {
  const auto m = read(
      "*PART_MODES\n"
      "         1        10         1                   3         1\n"
      "results/modes.h5\n"
      "7,8,9,10,11,12,13,14\n"
      "20,21\n"
      "1,4,0.02\n"
      "5,10,0.05\n");
  ASSERT_EQ(m.part_modes.size(), 1u);
  const auto& p = m.part_modes.at(1);
  EXPECT_EQ(p.nmfb, 10);
  EXPECT_EQ(p.form, 1);
  EXPECT_EQ(p.format, 3);
  EXPECT_EQ(p.kmflag, 1);
  EXPECT_EQ(p.filename, "results/modes.h5");
  EXPECT_EQ(p.path, "/decks/modes/results/modes.h5");  // relative to the deck's directory
  EXPECT_EQ(p.modes, (std::vector<int>{7, 8, 9, 10, 11, 12, 13, 14, 20, 21}));
  ASSERT_EQ(p.damping.size(), 2u);
  EXPECT_EQ(p.damping[1].mstart, 5);
  EXPECT_EQ(p.damping[1].mstop, 10);
  EXPECT_DOUBLE_EQ(p.damping[1].dampf, 0.05);
  EXPECT_EQ(p.where.line, 34);
}

TEST(KeywordPartModes, DefaultsAndAbsolutePath) {
  const auto m = read("*PART_MODES\n1,6,,,3\n/data/modes.h5\n");
  const auto& p = m.part_modes.at(1);
  EXPECT_EQ(p.form, 0);
  EXPECT_EQ(p.kmflag, 0);
  EXPECT_EQ(p.ansid, 0);
  EXPECT_EQ(p.path, "/data/modes.h5");
  EXPECT_TRUE(p.modes.empty());
  EXPECT_TRUE(p.damping.empty());
}

TEST(KeywordPartModes, UnsupportedFieldsAreRejectedByName) {
  // FORMAT 0 (the LS-DYNA default, a NASTRAN punch file) and the other foreign formats.
  for (const char* format : {"0", "2", "4", "5", "7"}) {
    const std::string message =
        error_of(std::string("*PART_MODES\n1,6,0,0,") + format + "\nmodes.h5\n");
    EXPECT_NE(message.find("FORMAT"), std::string::npos) << message;
    EXPECT_NE(message.find("not supported"), std::string::npos) << message;
    EXPECT_NE(message.find("test.k"), std::string::npos) << message;
  }
  EXPECT_NE(error_of("*PART_MODES\n1,6,0,0,3,0,1\nmodes.h5\n").find("NUPDF"), std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,6,0,0,3,0,0,1\nmodes.h5\n").find("SIGREC"), std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,6,2,0,3\nmodes.h5\n").find("FORM"), std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,0,0,0,3\nmodes.h5\n").find("NMFB"), std::string::npos);
}

TEST(KeywordPartModes, InconsistentCardsAreRejected) {
  EXPECT_NE(error_of("*PART_MODES\n2,6,0,0,3\nmodes.h5\n").find("not rigid"), std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n3,6,0,0,3\nmodes.h5\n").find("part 3 is not defined"),
            std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,3,0,0,3,1\nmodes.h5\n7,8\n").find("MODE1"), std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,3,0,0,3,1\nmodes.h5\n7,8,7\n").find("listed twice"),
            std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,3,0,0,3\nmodes.h5\n1,4,0.1\n").find("MSTOP"),
            std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,3,0,0,3\nmodes.h5\n1,2,0.1\n2,3,0.1\n").find("damping"),
            std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,3,0,0,3,0\n\n").find("FILENAME"), std::string::npos);
  EXPECT_NE(error_of("*PART_MODES\n1,3,0,5,3\nmodes.h5\n").find("ANSID"), std::string::npos);
  EXPECT_NE(
      error_of("*PART_MODES\n1,3,0,0,3\nm.h5\n*PART_MODES\n1,3,0,0,3\nm.h5\n").find("already"),
      std::string::npos);
}

// Switching cannot merge a part into a flexible body nor the flexible part into another body.
TEST(KeywordPartModes, SwitchingMergesWithAFlexibleBodyAreRejected) {
  const std::string modes = "*PART_MODES\n1,3,0,0,3\nmodes.h5\n";
  const std::string into = error_of(modes + "*DEFORMABLE_TO_RIGID\n2,1\n");
  EXPECT_NE(into.find("LRB"), std::string::npos) << into;
  EXPECT_NE(into.find("flexible body"), std::string::npos) << into;
  const std::string away = error_of(modes + "*DEFORMABLE_TO_RIGID\n1,2\n");
  EXPECT_NE(away.find("flexible body"), std::string::npos) << away;
}

}  // namespace
