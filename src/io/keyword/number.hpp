// Number parsing for keyword cards. LS-DYNA decks come from Fortran-era tools, so the
// accepted grammar is wider than C's: "2.1-3" means 2.1e-3, "1.5D3" means 1.5e3, and an
// integer field may be written "4." as long as the value is integral.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rf::io {

// Either a value or a short reason suitable for an error message ("is not a number").
template <typename T>
struct ParsedNumber {
  std::optional<T> value;
  std::string reason;
};

ParsedNumber<double> parse_real(std::string_view text);
ParsedNumber<std::int64_t> parse_integer(std::string_view text);

// Trims blanks (space, tab, CR) from both ends.
std::string_view trim(std::string_view text);

}  // namespace rf::io
