// Splits deck text into keyword blocks and dispatches them through the keyword table;
// handles *INCLUDE, *END and the format switches of the keyword line.
#include "io/keyword/reader.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <system_error>

#include "io/keyword/context.hpp"
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
        record_files_(options.record_files) {
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
    finish_model(context_);
    context_.model.parameters = parameters_.values();
    for (const auto& [name, value] : parameters_.unused_overrides()) {
      context_.warn({}, fmt::format("parameter override {}={} matches no *PARAMETER in the deck",
                                    name, value));
    }
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
    std::vector<std::string> options;
    const KeywordEntry* entry = find_keyword(block_in.keyword, options);
    if (!entry) {
      auto& count = context_.model.unknown_keywords[block_in.keyword];
      ++count;
      context_.warn(block_in.location(),
                    fmt::format("keyword {} is not supported; its {} data line(s) were skipped",
                                block_in.keyword, block_in.lines.size()));
      return;
    }
    Block block = block_in;
    block.base = std::string(entry->name);
    block.options = options;
    for (const auto& option : options) {
      bool known = false;
      for (const auto& accepted : entry->options) known |= (accepted == option);
      if (!known) {
        std::string supported;
        for (const auto& accepted : entry->options) {
          if (!supported.empty()) supported += ", ";
          supported += fmt::format("_{}", accepted);
        }
        throw block_error(block, 0, "",
                          fmt::format("option _{} of {} is not supported (supported options: {})",
                                      option, block.base, supported.empty() ? "none" : supported));
      }
    }
    entry->handler(block, context_);
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
    entry->handler(block, context_);
  }

  void include(const std::string& filename, const Card& card) {
    if (filename.empty()) throw card.error("FILENAME", "the file name is empty");
    fs::path path(filename);
    if (path.is_relative()) path = current_dir_ / path;
    const std::string* stored_text = nullptr;
    std::error_code ec;
    if (file_texts_) {
      const auto it = file_texts_->find(path.string());
      if (it == file_texts_->end()) {
        throw card.error("FILENAME", fmt::format("included file '{}' is not among the deck files "
                                                 "the restart dump holds",
                                                 filename));
      }
      stored_text = &it->second;
    } else if (!fs::is_regular_file(path, ec)) {
      throw card.error("FILENAME", fmt::format("included file '{}' does not exist (looked for "
                                               "'{}')",
                                               filename, path.string()));
    }
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
  std::vector<fs::path> open_files_;
  const std::map<std::string, std::string>* file_texts_ = nullptr;
  std::map<std::string, std::string>* record_files_ = nullptr;
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
