// The restart deck of `rigidflex restart DUMP RESTART_DECK`: LS-DYNA's small restart input
// (Keyword User's Manual Vol. I, "Restart Input Data"), limited to what a restart can change
// here: the termination and rigid/deformable part switching. docs/restart.md lists the cards.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/model.hpp"
#include "model/restart_switch.hpp"

namespace rf::io {

struct RestartDeck {
  // *CONTROL_TERMINATION: a new end time and/or end cycle (absent: as in the dump).
  std::optional<double> end_time;
  std::optional<std::int64_t> end_cycle;
  model::SourceLocation termination_where;
  // *DEFORMABLE_TO_RIGID and *RIGID_TO_DEFORMABLE cards in input order, part sets expanded.
  std::vector<model::RestartSwitch> switches;
};

// The keywords a restart deck may contain (for messages and docs).
inline constexpr std::string_view kRestartDeckKeywords =
    "*KEYWORD, *TITLE, *CONTROL_TERMINATION, *DEFORMABLE_TO_RIGID, *RIGID_TO_DEFORMABLE, *END";

// Reads a restart deck. `model` is the model the dump was made from: part and part-set IDs are
// checked against it and its *PARAMETER values can be used as &name. Any other keyword is an
// rf::InputError that lists what a restart deck may contain.
RestartDeck read_restart_deck(const std::filesystem::path& path, const model::Model& model);
RestartDeck read_restart_deck_text(std::string_view text, const std::string& name,
                                   const model::Model& model);

}  // namespace rf::io
