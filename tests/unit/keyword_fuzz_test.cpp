// Damaged decks must end in a model or an rf::InputError, never in another exception or a
// crash. The mutations mimic what happens to real decks: truncated transfers, editing
// slips, binary junk, wrong encodings.
#include <gtest/gtest.h>

#include "deck_mutation.hpp"
#include "keyword_test_util.hpp"

namespace {

std::string mutate(const std::string& original, rf::test::DeckMutator& m) {
  std::string text = original;
  const int edits = 1 + static_cast<int>(m.pick(4));
  for (int e = 0; e < edits; ++e) {
    switch (m.pick(7)) {
      case 0:
        m.truncate(text);
        break;
      case 1:
        m.delete_line(text);
        break;
      case 2:
        m.duplicate_line(text);
        break;
      case 3:
        m.replace_character(text, "0123456789.,-+eE&*$ \tRIC_%abc");
        break;
      case 4:
        m.insert_junk(text);
        break;
      case 5:
        m.swap_lines(text);
        break;
      case 6: {  // huge or odd numbers
        static const char* const numbers[] = {
            "1e308", "9999999999999999999", "-1e-320", "1.5", "&x", "-&", "nan", "1+", "--1"};
        text.insert(m.pick(text.size() + 1), numbers[m.pick(std::size(numbers))]);
        break;
      }
    }
  }
  return text;
}

}  // namespace

TEST(KeywordFuzz, DamagedDecksGiveModelOrInputError) {
  const std::vector<std::string> seeds = {
      rf::test::read_text_file(rf::test::deck_path("block_fixed.k")),
      rf::test::read_text_file(rf::test::deck_path("block_free.k")),
      rf::test::read_text_file(rf::test::deck_path("rigid_fixed.k")),
      rf::test::read_text_file(rf::test::deck_path("rigidwall_block.k")),
      "*PARAMETER\nR     len        2.0\n*PARAMETER_EXPRESSION\nR area    len*len+sin(pi)\n"
      "*NODE\n       1            &len           &area             0.0\n"
      "*INCLUDE\nno_such_file.k\n",
  };
  rf::test::DeckMutator mutator(20240611);
  int models = 0, errors = 0;
  constexpr int kVariants = 20000;
  for (int i = 0; i < kVariants; ++i) {
    const std::string text = mutate(seeds[static_cast<std::size_t>(i) % seeds.size()], mutator);
    try {
      rf::io::read_deck_text(text, "fuzz.k", RIGIDFLEX_TEST_DECKS);
      ++models;
    } catch (const rf::InputError& e) {
      // Every error must say where it happened.
      ASSERT_FALSE(e.context().file.empty()) << e.what();
      ++errors;
    } catch (const std::exception& e) {
      FAIL() << "variant " << i << " threw a non-InputError: " << e.what() << "\n--- deck ---\n"
             << text;
    }
  }
  EXPECT_GT(models, 0);  // some mutations are harmless
  EXPECT_GT(errors, 0);
}
