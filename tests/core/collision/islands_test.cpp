// core/collision/islands.hpp: the islands of a collision step against connected
// components found by brute force (breadth-first search over the candidate
// pairs), on hand-made and seeded random graphs.
#include "core/collision/islands.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <queue>
#include <random>
#include <set>

namespace gacompare::core {
namespace {

// The islands by their definition: components of the moving bodies under the
// pairs of two moving bodies; each with the static bodies its pairs meet.
std::vector<std::vector<int>> brute_force(std::size_t n, const std::vector<char>& is_static,
                                          const std::vector<std::pair<int, int>>& pairs) {
  std::vector<std::vector<int>> next(n);
  std::vector<char> in_pair(n, 0);
  for (const auto& [i, j] : pairs) {
    if (is_static[i] && is_static[j]) continue;
    in_pair[i] = in_pair[j] = 1;
    if (!is_static[i] && !is_static[j]) next[i].push_back(j), next[j].push_back(i);
  }
  std::vector<char> seen(n, 0);
  std::vector<std::vector<int>> out;
  for (std::size_t s = 0; s < n; ++s) {
    if (seen[s] || is_static[s] || !in_pair[s]) continue;
    std::vector<int> movers;
    std::queue<int> q;
    q.push(static_cast<int>(s));
    seen[s] = 1;
    while (!q.empty()) {
      const int b = q.front();
      q.pop();
      movers.push_back(b);
      for (const int c : next[b])
        if (!seen[c]) seen[c] = 1, q.push(c);
    }
    std::set<int> statics;
    for (const auto& [i, j] : pairs) {
      const bool mine_i = std::find(movers.begin(), movers.end(), i) != movers.end();
      const bool mine_j = std::find(movers.begin(), movers.end(), j) != movers.end();
      if (mine_i && is_static[j]) statics.insert(j);
      if (mine_j && is_static[i]) statics.insert(i);
    }
    std::sort(movers.begin(), movers.end());
    movers.insert(movers.end(), statics.begin(), statics.end());
    out.push_back(movers);
  }
  return out;
}

std::vector<std::vector<int>> members(const std::vector<Island>& islands) {
  std::vector<std::vector<int>> out;
  for (const auto& is : islands) out.push_back(is.bodies);
  return out;
}

TEST(Islands, StaticBodiesJoinIslandsButNeverLinkThem) {
  // 0 and 1 static (a floor and a wall); 2–3 touch; 4 rests on the floor
  // alone; 5 touches nothing; 3 and 4 both touch the floor.
  const std::vector<char> is_static{1, 1, 0, 0, 0, 0};
  const std::vector<std::pair<int, int>> pairs{{0, 1}, {0, 3}, {0, 4}, {1, 2}, {2, 3}};
  const auto islands = islands_of(6, is_static, pairs);
  ASSERT_EQ(islands.size(), 2u);
  EXPECT_EQ(islands[0].bodies, (std::vector<int>{2, 3, 0, 1}));
  EXPECT_EQ(islands[0].moving, 2u);
  EXPECT_EQ(islands[1].bodies, (std::vector<int>{4, 0}));
  EXPECT_EQ(islands[1].moving, 1u);
  // Every pair with a moving body is in exactly one island; the static pair in none.
  std::multiset<std::size_t> held;
  for (const auto& is : islands) held.insert(is.pairs.begin(), is.pairs.end());
  EXPECT_EQ(held, (std::multiset<std::size_t>{1, 2, 3, 4}));
}

TEST(Islands, NoPairsNoIslands) {
  EXPECT_TRUE(islands_of(4, std::vector<char>(4, 0), {}).empty());
}

// Seeded random graphs of 1 to 60 bodies, a fifth of them static, sparse to
// dense: the islands are exactly the brute-force components, each pair lies
// in the island of its moving bodies.
TEST(Islands, MatchBruteForceComponentsOnRandomGraphs) {
  std::mt19937_64 rng(14);
  for (int trial = 0; trial < 500; ++trial) {
    const std::size_t n = 1 + rng() % 60;
    std::vector<char> is_static(n);
    for (auto& s : is_static) s = rng() % 5 == 0;
    std::set<std::pair<int, int>> unique;
    const std::size_t edges = rng() % (2 * n + 1);
    for (std::size_t e = 0; e < edges && n > 1; ++e) {
      int i = static_cast<int>(rng() % n), j = static_cast<int>(rng() % n);
      if (i == j) continue;
      unique.insert({std::min(i, j), std::max(i, j)});
    }
    const std::vector<std::pair<int, int>> pairs(unique.begin(), unique.end());
    const auto islands = islands_of(n, is_static, pairs);
    EXPECT_EQ(members(islands), brute_force(n, is_static, pairs)) << "trial " << trial;
    // The order the contact solves and the state hash depend on: islands by
    // their smallest body, each one's moving bodies and then its static
    // ones ascending, its pairs in candidate order.
    for (std::size_t k = 0; k < islands.size(); ++k) {
      const auto& is = islands[k];
      const auto moving_end = is.bodies.begin() + static_cast<long>(is.moving);
      EXPECT_TRUE(std::is_sorted(is.bodies.begin(), moving_end)) << "trial " << trial;
      EXPECT_TRUE(std::is_sorted(moving_end, is.bodies.end())) << "trial " << trial;
      EXPECT_TRUE(std::is_sorted(is.pairs.begin(), is.pairs.end())) << "trial " << trial;
      if (k > 0) {
        EXPECT_LT(islands[k - 1].bodies.front(), is.bodies.front()) << "trial " << trial;
      }
    }
    for (const auto& is : islands)
      for (const std::size_t k : is.pairs) {
        const auto [i, j] = pairs[k];
        const int mover = is_static[i] ? j : i;
        EXPECT_TRUE(std::find(is.bodies.begin(), is.bodies.begin() + static_cast<long>(is.moving), mover) !=
                    is.bodies.begin() + static_cast<long>(is.moving));
      }
  }
}

}  // namespace
}  // namespace gacompare::core
