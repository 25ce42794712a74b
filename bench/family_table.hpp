#pragma once
// The end of a family table (contact_table, stacking_table): how many cases
// each column passed with the seconds its runs took, then why each failure
// failed.
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace gacompare::bench {

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
  std::printf("\n\nWhy each failure failed (%s):\n\n", why);
  for (const auto& f : failures) std::printf("- %s\n", f.c_str());
}

}  // namespace gacompare::bench
