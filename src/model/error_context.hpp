// Error context for a definition the model has already stored (checks made after reading).
#pragma once

#include "model/error.hpp"
#include "model/model.hpp"

namespace rf::model {

inline InputErrorContext context_of(const SourceLocation& where, const char* field) {
  InputErrorContext c;
  c.file = where.file;
  c.line = where.line;
  c.keyword = where.keyword;
  c.field = field ? field : "";
  return c;
}

}  // namespace rf::model
