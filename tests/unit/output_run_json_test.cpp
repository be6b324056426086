// run.json: every key present, strings escaped so the file is valid JSON.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "output/writers.hpp"

namespace rf::output {
namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A strict JSON syntax checker (RFC 8259 grammar, no semantic values): returns true when the
// whole text is one valid JSON value.
class JsonChecker {
 public:
  explicit JsonChecker(const std::string& text) : s_(text) {}
  bool valid() {
    space();
    if (!value()) return false;
    space();
    return p_ == s_.size();
  }

 private:
  void space() {
    while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\n' || s_[p_] == '\t' || s_[p_] == '\r'))
      ++p_;
  }
  bool literal(const char* word) {
    const std::string w(word);
    if (s_.compare(p_, w.size(), w) != 0) return false;
    p_ += w.size();
    return true;
  }
  bool string() {
    if (s_[p_] != '"') return false;
    for (++p_; p_ < s_.size(); ++p_) {
      const auto c = static_cast<unsigned char>(s_[p_]);
      if (c == '"') {
        ++p_;
        return true;
      }
      if (c < 0x20) return false;
      if (c == '\\') {
        ++p_;
        if (p_ >= s_.size()) return false;
        const char e = s_[p_];
        if (e == 'u') {
          for (int k = 0; k < 4; ++k) {
            if (++p_ >= s_.size() || !std::isxdigit(static_cast<unsigned char>(s_[p_])))
              return false;
          }
        } else if (std::string("\"\\/bfnrt").find(e) == std::string::npos) {
          return false;
        }
      }
    }
    return false;
  }
  bool number() {
    const std::size_t start = p_;
    if (s_[p_] == '-') ++p_;
    auto digits = [&] {
      const std::size_t d = p_;
      while (p_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p_]))) ++p_;
      return p_ > d;
    };
    if (p_ < s_.size() && s_[p_] == '0') {
      ++p_;
    } else if (!digits()) {
      return false;
    }
    if (p_ < s_.size() && s_[p_] == '.') {
      ++p_;
      if (!digits()) return false;
    }
    if (p_ < s_.size() && (s_[p_] == 'e' || s_[p_] == 'E')) {
      ++p_;
      if (p_ < s_.size() && (s_[p_] == '+' || s_[p_] == '-')) ++p_;
      if (!digits()) return false;
    }
    return p_ > start;
  }
  bool value() {
    if (p_ >= s_.size()) return false;
    const char c = s_[p_];
    if (c == '{') return container('}', true);
    if (c == '[') return container(']', false);
    if (c == '"') return string();
    if (c == 't') return literal("true");
    if (c == 'f') return literal("false");
    if (c == 'n') return literal("null");
    return number();
  }
  bool container(char close, bool object) {
    ++p_;
    space();
    if (p_ < s_.size() && s_[p_] == close) {
      ++p_;
      return true;
    }
    for (;;) {
      space();
      if (object) {
        if (p_ >= s_.size() || !string()) return false;
        space();
        if (p_ >= s_.size() || s_[p_++] != ':') return false;
        space();
      }
      if (!value()) return false;
      space();
      if (p_ >= s_.size()) return false;
      if (s_[p_] == ',') {
        ++p_;
        continue;
      }
      if (s_[p_] == close) {
        ++p_;
        return true;
      }
      return false;
    }
  }

  const std::string& s_;
  std::size_t p_ = 0;
};

TEST(OutputRunJson, EscapesAndIsValid) {
  const auto path = std::filesystem::temp_directory_path() / "rigidflex_run.json";
  RunSummary summary;
  summary.status = "error termination";
  summary.message = "negative volume in element 12\tat t=1e-3";
  summary.final_time = 1.0 / 3.0;
  summary.cycles = 123456;
  summary.nodes = 27;
  summary.elements = 5;
  summary.wall_seconds = 0.5;
  summary.ns_per_element_cycle = std::numeric_limits<double>::quiet_NaN();
  summary.threads = 2;
  summary.warnings = {"part \"steel\" has\nno material", "back\\slash", std::string("bell\x07")};
  write_run_json(path, summary);
  const std::string json = read_file(path);

  EXPECT_TRUE(JsonChecker(json).valid()) << json;
  for (const char* key : {"status", "message", "final_time", "cycles", "nodes", "elements",
                          "wall_seconds", "ns_per_element_cycle", "threads", "ranks", "warnings"}) {
    EXPECT_NE(json.find(std::string("\"") + key + "\": "), std::string::npos) << key;
  }
  EXPECT_NE(json.find(R"("part \"steel\" has\nno material")"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("back\\slash")"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("bell\u0007")"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("negative volume in element 12\tat t=1e-3")"), std::string::npos);
  EXPECT_NE(json.find("\"final_time\": 0.33333333333333331"), std::string::npos) << json;
  EXPECT_NE(json.find("\"cycles\": 123456"), std::string::npos);
  EXPECT_NE(json.find("\"ranks\": 1"), std::string::npos) << json;
  EXPECT_NE(json.find("\"ns_per_element_cycle\": null"), std::string::npos) << json;
}

TEST(OutputRunJson, EmptyWarningsIsAnEmptyArray) {
  const auto path = std::filesystem::temp_directory_path() / "rigidflex_run_empty.json";
  RunSummary summary;
  summary.status = "normal termination";
  write_run_json(path, summary);
  const std::string json = read_file(path);
  EXPECT_TRUE(JsonChecker(json).valid()) << json;
  EXPECT_NE(json.find("\"warnings\": []"), std::string::npos) << json;
}

TEST(OutputRunJson, CheckerRejectsBrokenJson) {
  EXPECT_FALSE(JsonChecker("{\"a\": \"x\ny\"}").valid());  // raw newline in a string
  EXPECT_FALSE(JsonChecker("{\"a\": NaN}").valid());
  EXPECT_FALSE(JsonChecker("{\"a\": 1,}").valid());
  EXPECT_TRUE(JsonChecker("{\"a\": [1, -2.5e-3, \"q\\\"\"]}").valid());
}

}  // namespace
}  // namespace rf::output
