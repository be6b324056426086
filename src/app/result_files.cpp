#include "app/result_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <regex>
#include <system_error>

namespace rf::app {

namespace {

namespace fs = std::filesystem;

// One pattern per file or numbered series. The transient list includes the names of the d3plot
// database and the per-part histories (issue 20) so that they too are cleared once written.
const std::vector<std::regex>& patterns(ResultKind kind) {
  static const std::vector<std::regex> transient = [] {
    std::vector<std::regex> p;
    for (
        const char* re :
        {R"((glstat|nodout|rbdout|modal|switch|sensor|rwforc|rcforc|matsum|elout|elout_shell|spcforc|secforc|jntforc|swforc)\.csv)",
         R"(run\.json)", R"(d3hsp\.txt)", R"((d3plot|frames|walls)\.pvd)",
         R"((d3plot|frames|walls)_\d{4,}\.vtu)", R"(d3plot(\d{2,})?)",
         R"(d3dump_\d{4,}\.h5(\.partial)?)", R"(plot_[a-z0-9_]+\.png)"}) {
      p.emplace_back(re);
    }
    return p;
  }();
  static const std::vector<std::regex> eigen = [] {
    std::vector<std::regex> p;
    for (const char* re :
         {R"(modes\.h5)", R"(eigout\.csv)", R"(modes\.pvd)", R"(modes_\d{4,}\.vtu)"}) {
      p.emplace_back(re);
    }
    return p;
  }();
  return kind == ResultKind::kEigen ? eigen : transient;
}

std::vector<std::string> result_files(const fs::path& directory, ResultKind kind) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    std::string name = it->path().filename().string();
    if (is_result_file(name, kind)) names.push_back(std::move(name));
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

bool is_result_file(const std::string& name, ResultKind kind) {
  for (const auto& re : patterns(kind)) {
    if (std::regex_match(name, re)) return true;
  }
  return false;
}

std::vector<std::string> clear_earlier_results(const fs::path& directory, ResultKind kind) {
  std::vector<std::string> removed;
  for (const auto& name : result_files(directory, kind)) {
    std::error_code ec;
    if (fs::remove(directory / name, ec)) removed.push_back(name);
  }
  return removed;
}

std::string list_results(const fs::path& directory, ResultKind kind) {
  // Numbered series (name_NNNN.ext) are counted, everything else listed by name.
  static const std::regex series(R"((.*_)\d{4,}(\.[a-z0-9]+))");
  std::vector<std::string> items;
  std::map<std::string, std::vector<std::string>> members;  // series -> its files
  for (const auto& name : result_files(directory, kind)) {
    std::smatch m;
    if (std::regex_match(name, m, series)) {
      const std::string key = m[1].str() + "NNNN" + m[2].str();
      if (members[key].empty()) items.push_back(key);
      members[key].push_back(name);
    } else {
      items.push_back(name);
    }
  }
  std::string text;
  for (const auto& item : items) {
    if (!text.empty()) text += ", ";
    const auto it = members.find(item);
    if (it == members.end()) {
      text += item;
    } else if (it->second.size() == 1) {
      text += it->second.front();
    } else {
      text += fmt::format("{} ({} files, {} to {})", item, it->second.size(), it->second.front(),
                          it->second.back());
    }
  }
  return text;
}

std::string short_list(const std::vector<std::string>& names, std::size_t shown) {
  std::string text;
  for (std::size_t k = 0; k < std::min(names.size(), shown); ++k) {
    text += fmt::format("{}{}", k ? ", " : "", names[k]);
  }
  if (names.size() > shown) text += fmt::format(" and {} more", names.size() - shown);
  return text;
}

}  // namespace rf::app
