// What rebuilds the model of a run: the deck texts as read (main deck and every include), the
// dialect and the --set overrides. A restart dump carries it, so `rigidflex restart` needs no
// file of the original run besides the dump.
#pragma once

#include <map>
#include <string>

namespace rf::restart {

struct ModelInput {
  std::string main_deck;                     // the main deck's name as the reader used it
  std::map<std::string, std::string> files;  // every file read (name -> text), main deck included
  std::string dialect = "auto";              // "auto", "lsdyna" or "impetus", as requested
  std::map<std::string, double> overrides;   // --set name=value
};

}  // namespace rf::restart
