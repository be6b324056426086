#include "model/error.hpp"

#include <fmt/format.h>

#include <algorithm>

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

InputError::InputError(Preformatted, InputErrorContext context, const std::string& what)
    : std::runtime_error(what), context_(std::move(context)), detail_(what) {}

namespace {
// Groups in order of first appearance, each with its count, then its messages indented.
std::string list_text(const std::vector<InputErrorList::Entry>& entries, std::size_t dropped) {
  std::vector<std::string> groups;
  for (const auto& e : entries) {
    if (std::find(groups.begin(), groups.end(), e.group) == groups.end()) groups.push_back(e.group);
  }
  std::string text = fmt::format("{} problems in the deck{}:", entries.size() + dropped,
                                 dropped ? fmt::format(" ({} not listed)", dropped) : "");
  for (const auto& group : groups) {
    std::size_t count = 0;
    for (const auto& e : entries) count += e.group == group;
    text += fmt::format("\n{} ({}):", group, count);
    for (const auto& e : entries) {
      if (e.group == group) text += fmt::format("\n  {}", e.error.what());
    }
  }
  return text;
}
}  // namespace

InputErrorList::InputErrorList(std::vector<Entry> entries, std::size_t dropped)
    : InputError(Preformatted{},
                 entries.empty() ? InputErrorContext{} : entries.front().error.context(),
                 list_text(entries, dropped)),
      entries_(std::move(entries)) {}

}  // namespace rf
