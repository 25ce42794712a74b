#pragma once
// What the family tables (contact_table, stacking_table) share: their list of
// columns from the command line, and their end: how many cases each column
// passed with the seconds its runs took, then why each failure failed.
#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace gacompare::bench {

// A comma-separated list whose every item is one of `allowed`; nullopt otherwise.
// The names of a comma-separated list, in order.
inline std::vector<std::string> comma_list(const std::string& value) {
  std::vector<std::string> out;
  std::stringstream list(value);
  for (std::string c; std::getline(list, c, ',');) out.push_back(c);
  return out;
}

inline std::optional<std::vector<std::string>> column_list(const std::string& value,
                                                           const std::vector<std::string>& allowed) {
  std::vector<std::string> out = comma_list(value);
  for (const auto& c : out)
    if (std::find(allowed.begin(), allowed.end(), c) == allowed.end()) return std::nullopt;
  return out;
}

inline void print_tally(const std::vector<std::string>& columns, const std::map<std::string, int>& passed,
                        const std::map<std::string, double>& wall, int cases, const std::vector<std::string>& failures,
                        const char* why) {
  std::printf("\nPassed:");
  for (const auto& c : columns) {
    const auto p = passed.find(c);
    const auto w = wall.find(c);
    std::printf(" %s %d/%d (%.1f s of runs);", c.c_str(), p == passed.end() ? 0 : p->second, cases,
                w == wall.end() ? 0.0 : w->second);
  }
  std::printf("\n");
  if (failures.empty()) return;
  std::printf("\nWhy each failure failed (%s):\n\n", why);
  for (const auto& f : failures) std::printf("- %s\n", f.c_str());
}

}  // namespace gacompare::bench
