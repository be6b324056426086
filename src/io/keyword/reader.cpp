// Splits deck text into keyword blocks and dispatches them through the keyword table;
// handles *INCLUDE, *END and the format switches of the keyword line.
#include "io/keyword/reader.hpp"

#include <fmt/format.h>

#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>

#include "io/keyword/context.hpp"
#include "io/keyword/keyword_classes.hpp"
#include "io/keyword/number.hpp"

namespace rf::io {

namespace {

namespace fs = std::filesystem;

// Deep enough for any real include tree; stops include chains that a recursion check on
// paths cannot see (e.g. the same file reached through different links).
constexpr int kMaxIncludeDepth = 64;

class DeckReader {
 public:
  DeckReader(model::Model& model, const ReadOptions& options)
      : parameters_(options.parameter_overrides),
        context_(model, parameters_),
        dialect_(options.dialect),
        file_texts_(options.file_texts),
        record_files_(options.record_files),
        ignore_unsupported_(options.ignore_unsupported),
        check_runnable_(options.check_runnable) {
    context_.include = [this](const std::string& filename, const Card& card) {
      include(filename, card);
    };
  }

  void read_text(std::string_view text, const std::string& name, const fs::path& base_dir) {
    if (record_files_) (*record_files_)[name] = std::string(text);
    context_.model.files.push_back(name);
    const int file_index = static_cast<int>(context_.model.files.size()) - 1;
    const int saved_index = context_.current_file_index;
    const fs::path saved_dir = current_dir_;
    context_.current_file_index = file_index;
    current_dir_ = base_dir;
    if (file_index == 0) main_dir_ = base_dir;
    if (dialect_ == Dialect::Auto) {
      const DialectGuess guess = detect_dialect(text);
      dialect_ = guess.dialect;
      context_.model.dialect_reason = guess.reason;
    } else if (file_index == 0) {
      context_.model.dialect_reason = "chosen on the command line";
    }
    context_.model.dialect = dialect_ == Dialect::Impetus ? "impetus" : "lsdyna";
    parameters_.use_impetus_intrinsics(dialect_ == Dialect::Impetus);
    if (dialect_ == Dialect::Impetus) {
      std::string reflowed;  // blocks view it: it lives until they are dispatched
      for (const Block& block : split_impetus(text, name, reflowed)) dispatch_impetus(block);
    } else {
      for (const Block& block : split(text, name)) dispatch(block);
    }
    context_.current_file_index = saved_index;
    current_dir_ = saved_dir;
  }

  void finish() {
    if (context_.pending_table) report_unfinished_table("the deck ends");
    try {
      finish_model(context_);
    } catch (const InputErrorList&) {
      throw;
    } catch (const InputError& e) {
      context_.report(kReferenceErrors, e);
    } catch (const std::exception&) {
      // Definitions left half-read by an error already reported can trip the checks; those
      // errors are the ones to show.
      if (context_.errors.empty()) throw;
    }
    if (check_runnable_) check_runnable(context_);
    context_.model.parameters = parameters_.values();
    for (const auto& [name, value] : parameters_.unused_overrides()) {
      context_.warn({}, fmt::format("parameter override {}={} matches no *PARAMETER in the deck",
                                    name, value));
    }
    auto& errors = context_.errors;
    if (errors.empty()) return;
    // One problem reads best as one line; the heading of the unsupported-physics group says how
    // to go on without them, so that group is always listed.
    if (errors.size() == 1 && context_.dropped_errors == 0 &&
        errors[0].group != kUnsupportedPhysics) {
      throw errors[0].error;
    }
    throw InputErrorList(std::move(errors), context_.dropped_errors);
  }

  // Marks a real file as being read, for include recursion checks.
  void push_file(const fs::path& path) { open_files_.push_back(canonical(path)); }

 private:
  static fs::path canonical(const fs::path& path) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(path, ec);
    return ec ? path.lexically_normal() : p;
  }

  std::vector<Block> split(std::string_view text, const std::string& name) {
    std::vector<Block> blocks;
    int line_number = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
      if (pos == text.size()) break;
      const auto end = text.find('\n', pos);
      std::string_view line =
          text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
      pos = end == std::string_view::npos ? text.size() : end + 1;
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (line.empty()) {
        if (!blocks.empty()) blocks.back().lines.push_back({line, line_number});
        continue;
      }
      if (line.front() == '$') continue;
      if (line.front() == '*') {
        Block block = keyword_block(line, name, line_number);
        if (block.keyword == "*END") break;
        blocks.push_back(std::move(block));
        continue;
      }
      // Text before the first keyword (LS-DYNA ignores it too).
      if (!blocks.empty()) blocks.back().lines.push_back({line, line_number});
    }
    return blocks;
  }

  Block keyword_block(std::string_view line, const std::string& name, int line_number) {
    Block block;
    block.file = name;
    block.line = line_number;
    const auto blank = line.find_first_of(" \t");
    std::string keyword = to_upper(line.substr(0, blank));
    std::string_view args = blank == std::string_view::npos ? "" : line.substr(blank);
    std::optional<CardFormat> format;
    // "*NODE +", "*NODE+" (long), "*NODE -" (standard), "*NODE %" (10-wide integers).
    const auto flag_format = [](char c) -> std::optional<CardFormat> {
      if (c == '+') return CardFormat::Long;
      if (c == '-') return CardFormat::Standard;
      if (c == '%') return CardFormat::I10;
      return std::nullopt;
    };
    while (keyword.size() > 1) {
      const auto f = flag_format(keyword.back());
      if (!f) break;
      format = f;
      keyword.pop_back();
    }
    std::istringstream tokens{std::string(args)};
    for (std::string token; tokens >> token;) {
      if (token.size() == 1 && flag_format(token[0])) format = flag_format(token[0]);
      if (keyword == "*KEYWORD") {
        const std::string upper = to_upper(token);
        if (upper == "LONG=Y" || upper == "LONG=S") global_format_ = CardFormat::Long;
        if (upper == "LONG=N") global_format_ = CardFormat::Standard;
        if (upper == "LONG=K") global_format_ = CardFormat::I10;
      }
    }
    block.keyword = keyword;
    block.format = format.value_or(global_format_);
    return block;
  }

  void dispatch(const Block& block_in) {
    if (context_.pending_table && block_in.keyword != "*DEFINE_CURVE" &&
        block_in.keyword != "*DEFINE_CURVE_TITLE") {
      report_unfinished_table(
          fmt::format("{} at {}:{} comes first", block_in.keyword, block_in.file, block_in.line));
    }
    std::vector<std::string> options;
    const KeywordEntry* entry = find_keyword(block_in.keyword, options);
    // A registered keyword with an option it does not take is a different keyword
    // (*MAT_ELASTIC_PLASTIC_THERMAL is not *MAT_ELASTIC): classified by its full name.
    bool accepted = entry != nullptr;
    for (const auto& option : options) {
      bool known = false;
      for (const auto& a : entry->options) known |= (a == option);
      accepted &= known;
    }
    if (!accepted) {
      unsupported(block_in, entry);
      return;
    }
    Block block = block_in;
    block.base = std::string(entry->name);
    block.options = options;
    try {
      entry->handler(block, context_);
    } catch (const InputErrorList&) {
      throw;
    } catch (const InputError& e) {
      // The rest of the deck is still read, so that every problem is reported in one pass.
      context_.report(kCardErrors, e);
    }
  }

  // A plain *DEFINE_TABLE must be followed by one *DEFINE_CURVE per value.
  void report_unfinished_table(const std::string& what_came) {
    const auto& pending = *context_.pending_table;
    context_.report(kCardErrors,
                    located_error(pending.where, "TBID",
                                  fmt::format("table {} still needs {} *DEFINE_CURVE keyword(s) "
                                              "right after it (one per VALUE, in order), but {}; "
                                              "or name the curves with *DEFINE_TABLE_2D",
                                              pending.id, pending.remaining, what_came)));
    context_.pending_table.reset();
  }

  // A keyword the reader does not read: output-only ones are warnings, anything else changes
  // the physics and is an error unless the user asked to skip it (keyword_classes.hpp).
  void unsupported(const Block& block, const KeywordEntry* entry) {
    ++context_.model.unknown_keywords[block.keyword];
    const UnsupportedKind kind = classify_unsupported(block.keyword);
    remember_skipped_definition(block, kind);
    std::string read_instead;
    if (entry) {
      std::string accepted;
      for (const auto& a : entry->options)
        accepted += fmt::format("{}_{}", accepted.empty() ? "" : ", ", a);
      read_instead = fmt::format(
          "; {} is read, {}", entry->name,
          accepted.empty() ? "without options" : fmt::format("with the options {}", accepted));
    }
    const std::string lines = fmt::format("{} data line(s)", block.lines.size());
    if (kind.cls == UnsupportedClass::OutputOnly) {
      context_.warn(block.location(), fmt::format("keyword {} ({}) is not supported; its {} were "
                                                  "skipped{}",
                                                  block.keyword, kind.what, lines, read_instead));
      return;
    }
    if (ignore_unsupported_) {
      const std::string message = fmt::format(
          "keyword {} ({}) changes the physics and is not supported; its {} were skipped "
          "because of --ignore-unsupported{}",
          block.keyword, kind.what, lines, read_instead);
      context_.warn(block.location(), message);
      context_.model.ignored_physics.push_back({block.location(), message});
      return;
    }
    context_.report(
        kUnsupportedPhysics,
        block_error(block, 0, "", fmt::format("not supported: {}{}", kind.what, read_instead)));
  }

  // The ID on the first data card of an unsupported *SECTION_ or *MAT_ keyword (after the title
  // card of the _TITLE form), so that a *PART naming it can say why it is missing.
  void remember_skipped_definition(const Block& block, const UnsupportedKind& kind) {
    const bool section = block.keyword.starts_with("*SECTION_");
    const bool material = block.keyword.starts_with("*MAT_");
    if (!section && !material) return;
    const bool titled = block.keyword.find("_TITLE") != std::string::npos;
    std::size_t index = titled ? 1 : 0;
    while (index < block.lines.size() && trim(block.lines[index].text).empty()) ++index;
    if (index >= block.lines.size()) return;
    const std::string_view text = block.lines[index].text;
    const auto comma = text.find(',');
    const std::size_t width = block.format == CardFormat::Long ? 20 : 10;
    const std::string_view field =
        trim(comma != std::string_view::npos ? text.substr(0, comma) : text.substr(0, width));
    const auto id = parse_integer(field).value;
    if (!id || *id <= 0) return;
    auto& skipped = section ? context_.skipped_sections : context_.skipped_materials;
    skipped.try_emplace(*id, ReaderContext::SkippedDefinition{block.keyword, std::string(kind.what),
                                                              block.location()});
  }

  void dispatch_impetus(const Block& block_in) {
    const KeywordEntry* entry = find_impetus_command(block_in.keyword);
    if (!entry) {
      ++context_.model.unknown_keywords[block_in.keyword];
      context_.warn(block_in.location(),
                    fmt::format("command {} is not supported; its {} data line(s) were skipped",
                                block_in.keyword, block_in.lines.size()));
      return;
    }
    Block block = block_in;
    block.base = std::string(entry->name);
    try {
      entry->handler(block, context_);
    } catch (const InputErrorList&) {
      throw;
    } catch (const InputError& e) {
      context_.report(kCardErrors, e);
    }
  }

  // Where an included file is: the including file's folder, then the main deck's, then the
  // *INCLUDE_PATH folders (relative ones taken from the main deck's folder), in that order.
  std::optional<fs::path> locate(const fs::path& name) const {
    std::vector<fs::path> candidates;
    if (name.is_absolute()) {
      candidates.push_back(name);
    } else {
      candidates.push_back(current_dir_ / name);
      candidates.push_back(main_dir_ / name);
      for (const auto& folder : context_.include_paths) {
        const fs::path f(folder);
        candidates.push_back((f.is_absolute() ? f : main_dir_ / f) / name);
      }
    }
    for (const auto& candidate : candidates) {
      if (file_texts_) {
        if (file_texts_->count(candidate.string())) return candidate;
        continue;
      }
      std::error_code ec;
      if (fs::is_regular_file(candidate, ec)) return candidate;
    }
    return std::nullopt;
  }

  void include(const std::string& filename, const Card& card) {
    if (filename.empty()) throw card.error("FILENAME", "the file name is empty");
    const auto found = locate(fs::path(filename));
    const fs::path looked =
        fs::path(filename).is_relative() ? current_dir_ / filename : fs::path(filename);
    if (!found && file_texts_) {
      throw card.error("FILENAME", fmt::format("included file '{}' is not among the deck files "
                                               "the restart dump holds",
                                               filename));
    }
    if (!found) {
      std::string where = fmt::format("'{}'", looked.string());
      if (fs::path(filename).is_relative()) {
        if (main_dir_ != current_dir_)
          where += fmt::format(", '{}'", (main_dir_ / filename).string());
        for (const auto& folder : context_.include_paths) {
          const fs::path f(folder);
          where +=
              fmt::format(", '{}'", ((f.is_absolute() ? f : main_dir_ / f) / filename).string());
        }
      }
      throw card.error("FILENAME", fmt::format("included file '{}' does not exist (looked for "
                                               "{})",
                                               filename, where));
    }
    const fs::path path = *found;
    const std::string* stored_text = file_texts_ ? &file_texts_->at(path.string()) : nullptr;
    const fs::path canon = canonical(path);
    for (const auto& open : open_files_) {
      if (open == canon) {
        throw card.error("FILENAME", fmt::format("'{}' includes itself (directly or through "
                                                 "other includes)",
                                                 filename));
      }
    }
    if (static_cast<int>(open_files_.size()) >= kMaxIncludeDepth) {
      throw card.error("FILENAME",
                       fmt::format("includes are nested more than {} deep", kMaxIncludeDepth));
    }
    std::string text;
    if (stored_text) {
      text = *stored_text;
    } else {
      std::ifstream in(path, std::ios::binary);
      if (!in) throw card.error("FILENAME", fmt::format("cannot open '{}'", path.string()));
      std::ostringstream content;
      content << in.rdbuf();
      text = content.str();
    }
    open_files_.push_back(canon);
    read_text(text, path.string(), path.parent_path());
    open_files_.pop_back();
  }

  ParameterTable parameters_;
  ReaderContext context_;
  Dialect dialect_ = Dialect::Auto;  // decided by the main deck, kept for its includes
  CardFormat global_format_ = CardFormat::Standard;
  fs::path current_dir_;
  fs::path main_dir_;  // the main deck's folder
  std::vector<fs::path> open_files_;
  const std::map<std::string, std::string>* file_texts_ = nullptr;
  std::map<std::string, std::string>* record_files_ = nullptr;
  bool ignore_unsupported_ = false;
  bool check_runnable_ = false;
};

}  // namespace

// Runs `read` (reading into `model`); on an input error hands the warnings so far to
// ReadOptions::warnings_on_error before passing the error on.
template <class Read>
void keeping_warnings(const model::Model& model, const ReadOptions& options, const Read& read) {
  try {
    read();
  } catch (const InputError&) {
    if (options.warnings_on_error) *options.warnings_on_error = model.warnings;
    throw;
  }
}

model::Model read_deck_text(std::string_view text, const std::string& name,
                            const std::filesystem::path& base_dir, const ReadOptions& options) {
  model::Model model;
  DeckReader reader(model, options);
  keeping_warnings(model, options, [&] {
    reader.read_text(text, name, base_dir);
    reader.finish();
  });
  return model;
}

model::Model read_deck(const std::filesystem::path& path, const ReadOptions& options) {
  if (options.file_texts) {
    const auto it = options.file_texts->find(path.string());
    if (it == options.file_texts->end()) {
      throw InputError({path.string(), 0, "", 0, ""}, "the deck is not among the given deck texts");
    }
    model::Model model;
    DeckReader reader(model, options);
    reader.push_file(path);
    keeping_warnings(model, options, [&] {
      reader.read_text(it->second, path.string(), path.parent_path());
      reader.finish();
    });
    return model;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path.string(), 0, "", 0, ""}, "cannot open the deck file");
  std::ostringstream content;
  content << in.rdbuf();
  const std::string text = content.str();
  model::Model model;
  DeckReader reader(model, options);
  reader.push_file(path);
  keeping_warnings(model, options, [&] {
    reader.read_text(text, path.string(), path.parent_path());
    reader.finish();
  });
  return model;
}

}  // namespace rf::io
