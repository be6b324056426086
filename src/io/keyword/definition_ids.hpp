// Checks shared by the handlers that define numbered things (parts, materials, sets, sensors,
// EOS, ...): a positive ID and an ID not defined before, each as an error at the card's field.
#pragma once

#include <fmt/format.h>

#include <cstddef>

#include "io/keyword/card.hpp"
#include "model/model.hpp"

namespace rf::io::handlers {

// Field i of the card as an ID that must be positive; `what` names the thing ("material").
inline model::Id positive_id(const Card& card, std::size_t i, const char* field, const char* what) {
  const model::Id id = card.id(i, field);
  if (id <= 0) throw card.error(field, fmt::format("{} ID must be a positive integer", what));
  return id;
}

// Error at the card's field if `map` (by ID, values with a `where`) already holds `id`.
template <typename Map>
void check_unique(const Map& map, model::Id id, const Card& card, const char* field,
                  const char* what) {
  if (const auto it = map.find(id); it != map.end()) {
    const auto& w = it->second.where;
    throw card.error(field, fmt::format("{} {} is already defined at {}:{} ({})", what, id, w.file,
                                        w.line, w.keyword));
  }
}

}  // namespace rf::io::handlers
