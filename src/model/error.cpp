#include "model/error.hpp"

#include <fmt/format.h>

namespace rf {

namespace {
std::string format_input_error(const InputErrorContext& c, const std::string& message) {
  std::string where;
  if (!c.file.empty()) where += c.file;
  if (c.line > 0) where += fmt::format(":{}", c.line);
  if (!where.empty()) where += ": ";
  std::string what;
  if (!c.keyword.empty()) what += c.keyword;
  if (c.card > 0) what += fmt::format(" card {}", c.card);
  if (!c.field.empty()) what += fmt::format(" field {}", c.field);
  if (!what.empty()) what += ": ";
  return fmt::format("{}{}{}", where, what, message);
}
}  // namespace

InputError::InputError(InputErrorContext context, const std::string& message)
    : std::runtime_error(format_input_error(context, message)),
      context_(std::move(context)),
      detail_(message) {}

}  // namespace rf
