// What an unsupported LS-DYNA keyword would have done: the rule "no silent change of physics".
//
// A keyword the reader does not read (not in the keyword table, or a registered keyword with an
// option it does not accept) is either output-only (a warning: the results are the same, only a
// file is not written) or changes the physics (an error, unless the user passes
// --ignore-unsupported). The classes are listed in one place, keyword_classes.cpp, mirrored in
// docs/keywords.md ("Unsupported keywords").
#pragma once

#include <string_view>

namespace rf::io {

enum class UnsupportedClass {
  OutputOnly,  // output requests and notes: skipped with a warning
  Physics,     // loads, constraints, materials, controls, ...: an error unless ignored
};

struct UnsupportedKind {
  UnsupportedClass cls = UnsupportedClass::Physics;
  std::string_view what;  // e.g. "a load", "an output request"
};

// Classifies a keyword by its full name (upper case, with '*', without format flags). Anything
// that no rule lists as output-only changes the physics: that is the safe default.
UnsupportedKind classify_unsupported(std::string_view keyword);

}  // namespace rf::io
