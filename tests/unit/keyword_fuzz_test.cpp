// Damaged decks must end in a model or an rf::InputError, never in another exception or a
// crash. The mutations mimic what happens to real decks: truncated transfers, editing
// slips, binary junk, wrong encodings.
#include <gtest/gtest.h>

#include <chrono>
#include <random>

#include "keyword_test_util.hpp"

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const auto end = text.find('\n', pos);
    lines.push_back(text.substr(pos, end == std::string::npos ? std::string::npos : end - pos));
    pos = end == std::string::npos ? text.size() : end + 1;
  }
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + '\n';
  return out;
}

std::string mutate(const std::string& original, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  };
  std::string text = original;
  const int edits = 1 + static_cast<int>(pick(4));
  for (int e = 0; e < edits; ++e) {
    switch (pick(7)) {
      case 0:  // truncate
        text.resize(pick(text.size() + 1));
        break;
      case 1: {  // delete a line
        auto lines = split_lines(text);
        if (!lines.empty()) lines.erase(lines.begin() + static_cast<long>(pick(lines.size())));
        text = join_lines(lines);
        break;
      }
      case 2: {  // duplicate a line
        auto lines = split_lines(text);
        if (!lines.empty()) {
          const auto i = pick(lines.size());
          lines.insert(lines.begin() + static_cast<long>(i), lines[i]);
        }
        text = join_lines(lines);
        break;
      }
      case 3:  // flip a character to a printable one that matters to the reader
        if (!text.empty()) {
          static const std::string interesting = "0123456789.,-+eE&*$ \tRIC_%abc";
          text[pick(text.size())] = interesting[pick(interesting.size())];
        }
        break;
      case 4:  // insert random bytes, NUL and high bytes included
      {
        std::string junk(1 + pick(16), '\0');
        for (char& c : junk) c = static_cast<char>(pick(256));
        text.insert(pick(text.size() + 1), junk);
      } break;
      case 5: {  // swap two lines
        auto lines = split_lines(text);
        if (lines.size() > 1) std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
        text = join_lines(lines);
        break;
      }
      case 6:  // huge or odd numbers
        if (!text.empty()) {
          static const char* const numbers[] = {
              "1e308", "9999999999999999999", "-1e-320", "1.5", "&x", "-&", "nan", "1+", "--1"};
          text.insert(pick(text.size() + 1), numbers[pick(std::size(numbers))]);
        }
        break;
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
      "*PARAMETER\nR     len        2.0\n*PARAMETER_EXPRESSION\nR area    len*len+sin(pi)\n"
      "*NODE\n       1            &len           &area             0.0\n"
      "*INCLUDE\nno_such_file.k\n",
  };
  std::mt19937_64 rng(20240611);
  const auto start = std::chrono::steady_clock::now();
  int models = 0, errors = 0;
  constexpr int kVariants = 20000;
  for (int i = 0; i < kVariants; ++i) {
    const std::string text = mutate(seeds[static_cast<std::size_t>(i) % seeds.size()], rng);
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
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0);
  EXPECT_GT(models, 0);  // some mutations are harmless
  EXPECT_GT(errors, 0);
}
