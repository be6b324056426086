// Keyword deck reader: LS-DYNA dialect (fixed-width and free format) today; the IMPETUS
// dialect plugs in beside it. Produces a model::Model or throws rf::InputError (a single
// problem) or rf::InputErrorList (every problem found, grouped by kind).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "model/model.hpp"

namespace rf::io {

enum class Dialect { Auto, LsDyna, Impetus };

struct ReadOptions {
  Dialect dialect = Dialect::Auto;
  // Values that replace *PARAMETER definitions of the same name (CLI --set name=value).
  std::map<std::string, double> parameter_overrides;
  // When set, deck files are taken from this map instead of the disk, keyed by the name the
  // reader gives them (the main deck's path as passed, an include's path joined to the
  // including file's directory): a restart rebuilds the model from the texts in its dump.
  const std::map<std::string, std::string>* file_texts = nullptr;
  // When set, every file read (main deck and includes) is stored here under that name, so that
  // a restart dump can carry the model input.
  std::map<std::string, std::string>* record_files = nullptr;
  // When set and the read ends in an input error, the warnings found before it are stored here
  // (the model that held them is gone): a misspelt *MAT keyword's warning explains the "material
  // is not defined" error that follows, so the CLI prints them first.
  std::vector<model::Warning>* warnings_on_error = nullptr;
  // Skip unsupported keywords that change the physics (warnings, model.ignored_physics)
  // instead of refusing the deck (CLI --ignore-unsupported).
  bool ignore_unsupported = false;
  // Also refuse what `run` would refuse (no *CONTROL_TERMINATION, no elements, nothing that
  // limits the time step, IMFLAG 1 without an eigen analysis): `check` and `run` set it.
  bool check_runnable = false;
};

// Reads a deck file and everything it includes (paths relative to the including file).
model::Model read_deck(const std::filesystem::path& path, const ReadOptions& options = {});

// Reads a deck held in memory; `name` is used in messages and `base_dir` resolves *INCLUDE.
model::Model read_deck_text(std::string_view text, const std::string& name = "<input>",
                            const std::filesystem::path& base_dir = ".",
                            const ReadOptions& options = {});

}  // namespace rf::io
