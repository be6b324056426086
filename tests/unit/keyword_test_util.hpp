// Helpers shared by the keyword reader tests.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/keyword/reader.hpp"
#include "model/error.hpp"

namespace rf::test {

inline std::filesystem::path deck_path(const std::string& name) {
  return std::filesystem::path(RIGIDFLEX_TEST_DECKS) / name;
}

inline std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Reads `text` and returns the InputError message; fails the test if no InputError.
inline std::string input_error_of(const std::string& text, const std::string& name = "bar.k") {
  try {
    rf::io::read_deck_text(text, name);
  } catch (const rf::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for deck:\n" << text;
  return {};
}

}  // namespace rf::test
