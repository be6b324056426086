// *DEFORMABLE_TO_RIGID, _AUTOMATIC and _INERTIA: every field read as the manual lays it out,
// and each bad value named with file, line, keyword and field.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "keyword_test_util.hpp"

namespace {

using rf::test::input_error_of;

// Two deformable parts (1, 2) and a rigid part 3, one hexahedron each, part set 7 = {1, 2}.
std::string base() {
  std::string s = "*NODE\n";
  int id = 1;
  for (int block = 0; block < 3; ++block) {
    for (int k = 0; k < 8; ++k) {
      const int x = (k == 1 || k == 2 || k == 5 || k == 6) ? 1 : 0;
      const int y = (k == 2 || k == 3 || k == 6 || k == 7) ? 1 : 0;
      const int z = k >= 4 ? 1 : 0;
      s += fmt::format("{},{},{},{}\n", id++, x + 2 * block, y, z);
    }
  }
  s += "*ELEMENT_SOLID\n";
  for (int block = 0; block < 3; ++block) {
    s += fmt::format("{},{}", block + 1, block + 1);
    for (int k = 1; k <= 8; ++k) s += fmt::format(",{}", 8 * block + k);
    s += "\n";
  }
  s += "*PART\np1\n1,1,1\n*PART\np2\n2,1,1\n*PART\np3\n3,1,2\n*SECTION_SOLID\n1,1\n"
       "*MAT_ELASTIC\n1,1000,1e7,0.3\n*MAT_RIGID\n2,1000,1e7,0.3\n"
       "*SET_PART_LIST\n7\n1,2\n*CONTROL_TERMINATION\n1.0\n";
  return s;
}

TEST(SwitchingReader, ReadsEveryFieldOfAPairedSet) {
  const auto m = rf::io::read_deck_text(
      base() +
          "*DEFORMABLE_TO_RIGID\n7,3,PSET\n"
          "*DEFORMABLE_TO_RIGID_AUTOMATIC\n"
          "$ swset code time1 time2 time3 entno relsw paired\n"
          "        20         0       0.1       0.0      0.05         0        10         1\n"
          "         1         2         1     0.002         2         1       0.0\n"
          "         1         0      PART\n"
          "         2         3      part\n"
          "         7      PSET\n"
          "*DEFORMABLE_TO_RIGID_AUTOMATIC\n"
          "10,0,0.3,0.4,0,0,20,-1\n0,0,0,0,0,1\n1\n"
          "*DEFORMABLE_TO_RIGID_INERTIA\n2\n1,2,3,10\n4,0.1,0.2,5,0.3,6\n",
      "ok.k");
  const auto& sw = m.switching;
  EXPECT_TRUE(sw.flagged);
  ASSERT_EQ(sw.at_start.size(), 1u);
  EXPECT_TRUE(sw.at_start[0].part_set);
  EXPECT_EQ(sw.at_start[0].lrb, 3);
  ASSERT_EQ(sw.automatic.size(), 2u);
  const auto& a = sw.automatic[0];
  EXPECT_EQ(a.swset, 20);
  EXPECT_EQ(a.code, 0);
  EXPECT_EQ(a.time1, 0.1);
  EXPECT_EQ(a.time2, 1e20);  // 0 means 10^20
  EXPECT_EQ(a.time3, 0.05);
  EXPECT_EQ(a.relsw, 10);
  EXPECT_EQ(a.paired, 1);
  EXPECT_EQ(a.nrbf, 1);
  EXPECT_EQ(a.ncsf, 2);
  EXPECT_EQ(a.rwf, 1);
  EXPECT_EQ(a.dtmax, 0.002);
  ASSERT_EQ(a.to_rigid.size(), 2u);
  EXPECT_EQ(a.to_rigid[1].pid, 2);
  EXPECT_EQ(a.to_rigid[1].lrb, 3);
  ASSERT_EQ(a.to_deformable.size(), 1u);
  EXPECT_TRUE(a.to_deformable[0].part_set);
  EXPECT_EQ(sw.automatic[1].paired, -1);
  const auto& in = sw.inertia.at(2);
  EXPECT_EQ(in.tm, 10.0);
  EXPECT_EQ(in.xc[2], 3.0);
  EXPECT_EQ(in.inertia[4], 0.3);
  // An empty *DEFORMABLE_TO_RIGID only flags switching (for a restart).
  EXPECT_TRUE(
      rf::io::read_deck_text(base() + "*DEFORMABLE_TO_RIGID\n", "flag.k").switching.flagged);
}

struct BadCase {
  std::string cards;
  std::string expected;  // file:line: keyword ... field
};

TEST(SwitchingReader, BadValuesNameFileLineKeywordAndField) {
  const std::string head = base();
  const int first = 1 + static_cast<int>(std::count(head.begin(), head.end(), '\n'));
  const std::string d2r = "*DEFORMABLE_TO_RIGID_AUTOMATIC\n";
  const std::vector<BadCase> cases = {
      {"*DEFORMABLE_TO_RIGID\n99\n",
       fmt::format("bad.k:{}: *DEFORMABLE_TO_RIGID field PID: part 99 is not defined", first + 1)},
      {"*DEFORMABLE_TO_RIGID\n8,0,PSET\n", "field PID: part set 8 (PTYPE PSET) is not defined"},
      {"*DEFORMABLE_TO_RIGID\n1,0,PARTS\n", "field PTYPE: 'PARTS' is not PART or PSET"},
      {"*DEFORMABLE_TO_RIGID\n3\n", "field PID: part 3 is *MAT_RIGID"},
      {"*DEFORMABLE_TO_RIGID\n1,2\n", "field LRB: part 2 is neither *MAT_RIGID nor switched"},
      {d2r + "5,0,0,0,0,0,0,1\n0,0,0,0,1,0\n1\n", "field RELSW: PAIRED = 1 needs the related"},
      {d2r + "5,0,0,0,0,0,6,0\n0,0,0,0,1,0\n1\n", "field PAIRED: RELSW = 6 names a related set"},
      {d2r + "5,0,0,0,0,0,6,1\n0,0,0,0,1,0\n1\n",
       "field RELSW: related switch set 6 is not defined"},
      {d2r + "5,0,0,0,0,0,6,1\n0,0,0,0,1,0\n1\n" + d2r + "6,0,0,0,0,0,5,1\n0,0,0,0,0,1\n1\n",
       "a pair names each other"},
      {d2r + "5,5\n0,0,0,0,1,0\n1\n",
       "field CODE: CODE 5: switch set 5 is controlled by *SENSOR_CONTROL"},
      {d2r + "5,2,0,0,0,3\n0,0,0,0,1,0\n1\n",
       "field ENTNO: CODE 2 tests contact 3, and this deck defines no contact with that ID"},
      {d2r + "5,4,0,0,0,0\n0,0,0,0,1,0\n1\n", "field ENTNO: CODE 4 needs the ID of the contact"},
      {d2r + "5,3,0,0,0,0\n0,0,0,0,1,0\n1\n",
       "field ENTNO: CODE 3 needs the number of the rigid wall"},
      {d2r + "5,1,0,0,0,1\n0,0,0,0,1,0\n1\n",
       "tests rigid wall 1, and this deck defines 0 *RIGIDWALL_PLANAR"},
      {d2r + "5,6\n0,0,0,0,1,0\n1\n", "field CODE: value 6 is not one of 0..5"},
      {d2r + "5,0,2.0,1.0\n0,0,0,0,1,0\n1\n", "field TIME2: TIME2 = 1 is before TIME1 = 2"},
      {d2r + "5,0,0,0,-1\n0,0,0,0,1,0\n1\n", "field TIME3: delay -1 must not be negative"},
      {d2r + "5,0\n3,0,0,0,1,0\n1\n", "field NRBF: value 3 is not one of 0..2"},
      {d2r + "5,0\n0,0,0,-1,1,0\n1\n", "field DTMAX: -1 must not be negative"},
      {d2r + "5,0\n0,0,0,0,2,0\n1\n", "*DEFORMABLE_TO_RIGID_AUTOMATIC card 3"},
      {d2r + "5,0\n0,0,0,0,1,0\n1\n2\n", "more cards follow than D2R = 1"},
      {d2r + "5,0\n", "card 2"},
      {d2r + "5,0\n0,0,0,0,0,1\n3\n", "field PID: part 3 is *MAT_RIGID: parts defined rigid"},
      {d2r + "5,0\n0,0,0,0,1,0\n1\n" + d2r + "5,0\n0,0,0,0,1,0\n2\n",
       "field SWSET: switch set 5 is already defined"},
      {"*DEFORMABLE_TO_RIGID_INERTIA\n1\n0,0,0\n1,0,0,1,0,1\n",
       "field TM: the translational mass is required"},
      {"*DEFORMABLE_TO_RIGID_INERTIA\n1\n0,0,0,-2\n1,0,0,1,0,1\n",
       "field TM: mass -2 must be positive"},
      {"*DEFORMABLE_TO_RIGID_INERTIA\n1\n0,0,0,2\n1,0,0,,0,1\n", "field IYY: is required"},
      {"*DEFORMABLE_TO_RIGID_INERTIA\n3\n0,0,0,2\n1,0,0,1,0,1\n",
       "field PID: part 3 is *MAT_RIGID"},
      {"*DEFORMABLE_TO_RIGID_INERTIA\n9\n0,0,0,2\n1,0,0,1,0,1\n",
       "field PID: part 9 is not defined"},
  };
  for (const auto& c : cases) {
    const std::string message = input_error_of(base() + c.cards, "bad.k");
    EXPECT_NE(message.find(c.expected), std::string::npos) << "deck tail:\n"
                                                           << c.cards << "\nmessage: " << message;
    EXPECT_NE(message.find("bad.k:"), std::string::npos) << message;
  }
}

}  // namespace
