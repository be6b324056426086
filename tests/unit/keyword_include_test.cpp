// *INCLUDE: paths relative to the including file, missing files, recursion.
#include <gtest/gtest.h>

#include "keyword_test_util.hpp"

using rf::io::read_deck;

TEST(KeywordInclude, RelativePathsFollowTheIncludingFile) {
  const auto m = read_deck(rf::test::deck_path("include/main.k"));
  ASSERT_EQ(m.nodes.size(), 3u);
  EXPECT_EQ(m.nodes[0].id, 1);  // from sub/mesh.k
  EXPECT_EQ(m.nodes[1].id, 2);  // from sub/more.k, found relative to sub/
  EXPECT_EQ(m.nodes[2].id, 3);
  EXPECT_DOUBLE_EQ(m.nodes[2].x[0], 2.0);
  ASSERT_EQ(m.files.size(), 3u);
  EXPECT_NE(m.files[2].find("more.k"), std::string::npos);
}

TEST(KeywordInclude, MissingFileNamesTheIncludingLine) {
  try {
    read_deck(rf::test::deck_path("include/missing.k"));
    FAIL() << "no error";
  } catch (const rf::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("missing.k:4: *INCLUDE card 1 field FILENAME"), std::string::npos)
        << message;
    EXPECT_NE(message.find("no_such_file.k"), std::string::npos) << message;
  }
}

TEST(KeywordInclude, RecursionIsAnError) {
  try {
    read_deck(rf::test::deck_path("include/loop_a.k"));
    FAIL() << "no error";
  } catch (const rf::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("loop_b.k:4: *INCLUDE"), std::string::npos) << message;
    EXPECT_NE(message.find("includes itself"), std::string::npos) << message;
  }
}

TEST(KeywordInclude, ErrorsInsideIncludedFilesNameThatFile) {
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_include_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bad.k") << "*NODE\n       1             abc\n";
  const std::string deck = "*INCLUDE\nbad.k\n";
  try {
    rf::io::read_deck_text(deck, "top.k", dir);
    FAIL() << "no error";
  } catch (const rf::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.k:2: *NODE card 1 field X: 'abc' is not a number"),
              std::string::npos)
        << e.what();
  }
}
