// Errors in user input. Every message names where it happened so that a CAE engineer can
// go straight to the card: file, line, keyword, card and field, and what was expected.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace rf {

struct InputErrorContext {
  std::string file;
  int line = 0;            // 1-based; 0 when not tied to a line
  std::string keyword;     // e.g. "*SECTION_SOLID"
  int card = 0;            // 1-based card number within the keyword; 0 when not applicable
  std::string field;       // field name as in the manual, e.g. "ELFORM"
};

// Thrown for any problem with the deck. what() is the full one-line message.
class InputError : public std::runtime_error {
 public:
  InputError(InputErrorContext context, const std::string& message);
  const InputErrorContext& context() const { return context_; }
  const std::string& detail() const { return detail_; }

 protected:
  // For InputErrorList: `what` is already the full text.
  struct Preformatted {};
  InputError(Preformatted, InputErrorContext context, const std::string& what);

 private:
  InputErrorContext context_;
  std::string detail_;
};

// Every problem the reader found in one pass, grouped by kind (io::read_deck collects them
// instead of stopping at the first). what() lists them all, one per line; context() is the
// first one's.
class InputErrorList : public InputError {
 public:
  struct Entry {
    std::string group;  // heading of its kind, e.g. "errors in cards"
    InputError error;
  };
  // `dropped`: problems found beyond the cap and not listed.
  InputErrorList(std::vector<Entry> entries, std::size_t dropped);
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::vector<Entry> entries_;
};

// Thrown when the solution breaks down (NaN, negative volume, time-step collapse).
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rf
