// What a pair remembers between detections (core/pair_memory.hpp): kept and
// read back by the ordered pair, met again or not in a round, against a
// brute-force map that follows the rules as stated.
#include "core/pair_memory.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>

namespace gacompare::collision {
namespace {

int value_of(PairMemory<int>& m, int i, int j) {
  const int* v = m.find(i, j);
  return v ? *v : 0;
}

TEST(PairMemory, KeepsWhatARoundMetAndForgetsTheRest) {
  PairMemory<int> m;
  m.next();
  EXPECT_EQ(m.find(1, 2), nullptr);
  m.add(1, 2, 10);
  m.add(2, 1, 20);  // the other order is another pair
  m.add(1, 2, 11);  // met twice while new: the last value
  EXPECT_EQ(m.find(1, 2), nullptr);  // new pairs are found from the next round on
  m.next();
  EXPECT_EQ(value_of(m, 1, 2), 11);
  *m.find(1, 2) = 12;  // updated in place, read at once
  EXPECT_EQ(value_of(m, 1, 2), 12);
  EXPECT_EQ(value_of(m, 3, 4), 0);
  m.next();  // (2, 1) was not met in that round
  EXPECT_EQ(m.size(), 1u);
  EXPECT_EQ(value_of(m, 1, 2), 12);
  EXPECT_EQ(m.find(2, 1), nullptr);
  m.next();  // (1, 2) was met in that one
  EXPECT_EQ(m.size(), 1u);
  m.next();  // but not in this one
  EXPECT_EQ(m.size(), 0u);
}

// Seeded random rounds of random pairs against a map: a pair's value is what
// it was last given, found from the round after it was first added, and gone
// after a round that did not meet it.
TEST(PairMemory, FollowsAMapOverRandomRounds) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> body(0, 30), value(1, 1000);
  PairMemory<int> m;
  std::map<std::pair<int, int>, int> known, fresh;  // found now; added this round
  std::map<std::pair<int, int>, bool> met;
  int checked = 0;
  for (int round = 0; round < 200; ++round) {
    m.next();
    for (auto it = known.begin(); it != known.end();) it = met[it->first] ? std::next(it) : known.erase(it);
    for (const auto& [k, v] : fresh) known[k] = v;
    fresh.clear();
    met.clear();
    ASSERT_EQ(m.size(), known.size()) << round;
    for (int q = 0; q < 40; ++q) {
      const std::pair<int, int> k{body(rng), body(rng)};
      const int v = value(rng);
      int* found = m.find(k.first, k.second);
      const auto it = known.find(k);
      ASSERT_EQ(found != nullptr, it != known.end()) << round;
      ++checked;
      if (found) {
        ASSERT_EQ(*found, it->second) << round;
        *found = it->second = v;
      } else {
        m.add(k.first, k.second, v);
        fresh[k] = v;
      }
      met[k] = true;
    }
  }
  EXPECT_EQ(checked, 8000);
}

}  // namespace
}  // namespace gacompare::collision
