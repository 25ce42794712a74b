#include "compare/suggest.hpp"

#include <algorithm>
#include <numeric>

namespace gacompare::compare {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Three rows of the dynamic programme: d[i][j] for prefixes a[0,i) and b[0,j).
  const std::size_t n = b.size();
  std::vector<std::size_t> two(n + 1), one(n + 1), row(n + 1);
  std::iota(one.begin(), one.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (std::size_t j = 1; j <= n; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      row[j] = std::min({one[j] + 1, row[j - 1] + 1, one[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) row[j] = std::min(row[j], two[j - 2] + 1);
    }
    std::swap(two, one);
    std::swap(one, row);
  }
  return one[n];
}

std::string closest(std::string_view word, const std::vector<std::string>& candidates) {
  const std::size_t limit = std::max<std::size_t>(1, word.size() / 3);
  std::string best;
  std::size_t best_distance = limit + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) best = c, best_distance = d;
  }
  return best;
}

std::string not_one_of(std::string_view what, std::string_view word, const std::vector<std::string>& candidates) {
  // Appended piece by piece: GCC 12's "x" + string trips a false -Wrestrict (bug 105651).
  std::string out = "'";
  out.append(word).append("' is not a ").append(what).append(" (");
  for (std::size_t i = 0; i < candidates.size(); ++i)
    out.append(i == 0 ? "" : i + 1 == candidates.size() ? " or " : ", ").append(candidates[i]);
  out.append(")");
  if (const std::string near = closest(word, candidates); !near.empty()) out.append("; did you mean '").append(near).append("'?");
  return out;
}

}  // namespace gacompare::compare
