// Edits that damage a deck the way real decks get damaged (truncated transfers, editing slips,
// binary junk), shared by the fuzz tests of both dialects. Deterministic for a given seed.
#pragma once

#include <random>
#include <string>
#include <utility>
#include <vector>

namespace rf::test {

class DeckMutator {
 public:
  explicit DeckMutator(std::uint64_t seed) : rng_(seed) {}

  // A uniform index below n (0 when n is 0).
  std::size_t pick(std::size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_);
  }

  void truncate(std::string& text) { text.resize(pick(text.size() + 1)); }

  void delete_line(std::string& text) {
    auto lines = split_lines(text);
    if (!lines.empty()) lines.erase(lines.begin() + static_cast<long>(pick(lines.size())));
    text = join_lines(lines);
  }

  void duplicate_line(std::string& text) {
    auto lines = split_lines(text);
    if (!lines.empty()) {
      const auto i = pick(lines.size());
      lines.insert(lines.begin() + static_cast<long>(i), lines[i]);
    }
    text = join_lines(lines);
  }

  void swap_lines(std::string& text) {
    auto lines = split_lines(text);
    if (lines.size() > 1) std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
    text = join_lines(lines);
  }

  // One character replaced by one of `alphabet` (characters that matter to the reader).
  void replace_character(std::string& text, const std::string& alphabet) {
    if (!text.empty()) text[pick(text.size())] = alphabet[pick(alphabet.size())];
  }

  // 1 to 16 random bytes, NUL and high bytes included, inserted anywhere.
  void insert_junk(std::string& text) {
    std::string junk(1 + pick(16), '\0');
    for (char& c : junk) c = static_cast<char>(pick(256));
    text.insert(pick(text.size() + 1), junk);
  }

  static std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t pos = 0;
    while (pos < text.size()) {
      const auto end = text.find('\n', pos);
      lines.push_back(text.substr(pos, end == std::string::npos ? std::string::npos : end - pos));
      pos = end == std::string::npos ? text.size() : end + 1;
    }
    return lines;
  }

  static std::string join_lines(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += l + '\n';
    return out;
  }

 private:
  std::mt19937_64 rng_;
};

}  // namespace rf::test
