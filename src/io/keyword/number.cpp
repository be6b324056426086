#include "io/keyword/number.hpp"

#include <array>
#include <charconv>
#include <cmath>

namespace rf::io {

std::string_view trim(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

namespace {

// Long enough for any sensible free-format number; longer text is rejected rather than
// truncated so that a value is never silently changed.
constexpr std::size_t kMaxNumberLength = 64;

// Rewrites Fortran spellings into what std::from_chars accepts: D/d exponents become 'e',
// an exponent sign without a letter ("2.1-3") gets an 'e', and a leading '+' is dropped.
// Returns the length written, or 0 when the text cannot be a number.
std::size_t normalize(std::string_view text, std::array<char, kMaxNumberLength + 2>& out) {
  if (text.empty() || text.size() > kMaxNumberLength) return 0;
  std::size_t n = 0;
  bool has_exponent_letter = false;
  bool seen_digit = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c >= '0' && c <= '9') {
      seen_digit = true;
      out[n++] = c;
    } else if (c == '.') {
      out[n++] = c;
    } else if (c == 'e' || c == 'E' || c == 'd' || c == 'D') {
      if (has_exponent_letter || !seen_digit) return 0;
      has_exponent_letter = true;
      out[n++] = 'e';
    } else if (c == '+' || c == '-') {
      const bool at_start = (i == 0);
      const bool after_letter = n > 0 && out[n - 1] == 'e';
      if (!at_start && !after_letter) {
        // Fortran "2.1-3": a sign inside the number starts the exponent.
        if (has_exponent_letter || !seen_digit) return 0;
        has_exponent_letter = true;
        out[n++] = 'e';
      }
      if (c == '-')
        out[n++] = c;
      else if (!at_start)
        out[n++] = c;  // from_chars accepts '+' only in the exponent
    } else {
      return 0;
    }
    if (n > kMaxNumberLength) return 0;
  }
  return seen_digit ? n : 0;
}

}  // namespace

ParsedNumber<double> parse_real(std::string_view text) {
  text = trim(text);
  std::array<char, kMaxNumberLength + 2> buffer{};
  const std::size_t n = normalize(text, buffer);
  if (n == 0) return {std::nullopt, "is not a number"};
  double value = 0.0;
  const auto [end, ec] = std::from_chars(buffer.data(), buffer.data() + n, value);
  if (ec == std::errc::result_out_of_range) return {std::nullopt, "is out of range"};
  if (ec != std::errc() || end != buffer.data() + n) return {std::nullopt, "is not a number"};
  if (!std::isfinite(value)) return {std::nullopt, "is out of range"};
  return {value, {}};
}

ParsedNumber<std::int64_t> parse_integer(std::string_view text) {
  text = trim(text);
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') {
    digits.remove_prefix(1);
    if (!digits.empty() && digits.front() == '-') return {std::nullopt, "is not an integer"};
  }
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc() && end == digits.data() + digits.size() && !digits.empty()) {
    return {value, {}};
  }
  if (ec == std::errc::result_out_of_range) return {std::nullopt, "is out of range"};
  // "4." or "1e3": accept when the value is integral and exactly representable.
  const auto real = parse_real(text);
  if (!real.value) return {std::nullopt, "is not an integer"};
  const double v = *real.value;
  if (std::abs(v) > 9.0e15) return {std::nullopt, "is out of range"};
  if (v != std::trunc(v)) return {std::nullopt, "is not an integer"};
  return {static_cast<std::int64_t>(v), {}};
}

}  // namespace rf::io
