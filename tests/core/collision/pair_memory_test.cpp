// What a pair remembers between detections (core/collision/pair_memory.hpp): kept and
// read back by the ordered pair, met again or not in a round, against a
// brute-force map that follows the rules as stated.
#include "core/collision/pair_memory.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>

namespace gacompare::collision {
namespace {

TEST(PairMemory, KeepsWhatARoundMetAndForgetsTheRest) {
  PairMemory<int> m;
  m.next();
  EXPECT_EQ(m.at(1, 2), 0);  // new
  m.at(1, 2) = 10;
  m.at(2, 1) = 20;  // the other order is another pair
  EXPECT_EQ(m.at(1, 2), 10);
  m.next();
  EXPECT_EQ(m.at(1, 2), 10);
  EXPECT_EQ(m.size(), 2u);
  m.next();  // (2, 1) was not met in the last round
  EXPECT_EQ(m.size(), 1u);
  EXPECT_EQ(m.at(1, 2), 10);
  EXPECT_EQ(m.at(2, 1), 0);  // forgotten: afresh
  m.next();
  m.next();  // nothing met in the last round
  EXPECT_EQ(m.size(), 0u);
  EXPECT_EQ(m.at(1, 2), 0);
}

// Seeded random rounds of random pairs against a map, with enough pairs to
// make the table grow and pass its periodic clean-up: a pair reads what it
// was last given if a detection of the last round or of this one met it, else 0.
TEST(PairMemory, FollowsAMapOverRandomRounds) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> body(0, 60), value(1, 1000);
  PairMemory<int> m;
  std::map<std::pair<int, int>, std::pair<int, int>> model;  // pair -> (value, round last met)
  int checked = 0;
  for (int round = 1; round <= 300; ++round) {
    m.next();
    const int pairs = round % 50 < 25 ? 40 : 400;  // rounds with few pairs, then with many
    for (int q = 0; q < pairs; ++q) {
      const std::pair<int, int> k{body(rng), body(rng)};
      const auto it = model.find(k);
      const int expected = it != model.end() && it->second.second >= round - 1 ? it->second.first : 0;
      int& v = m.at(k.first, k.second);
      ASSERT_EQ(v, expected) << "round " << round;
      ++checked;
      v = value(rng);
      model[k] = {v, round};
    }
    std::size_t live = 0;
    for (const auto& [k, e] : model) live += e.second >= round - 1;
    ASSERT_EQ(m.size(), live) << "round " << round;
  }
  EXPECT_GT(checked, 50000);
}

// The determinism check's mode (set_move_pair_tables): an insertion moves the
// entries, so a pointer kept across it no longer reaches its pair's value,
// while every answer stays what the rules say (the same random rounds, with
// every insertion moving the table).
TEST(PairMemory, MovedTablesMoveEveryEntryAndAnswerTheSame) {
  set_move_pair_tables(true);
  PairMemory<int> m;
  m.next();
  for (int k = 0; k < 20; ++k) m.at(k, k + 1) = k + 1;
  int* before = m.find(3, 4);
  ASSERT_NE(before, nullptr);
  m.at(100, 101) = 7;  // an insertion
  int* after = m.find(3, 4);
  ASSERT_NE(after, nullptr);
  EXPECT_EQ(*after, 4);
  EXPECT_NE(before, after);
  m.at(3, 4) = 5;  // found, not inserted: nothing moves
  EXPECT_EQ(m.find(3, 4), after);

  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> body(0, 30);
  PairMemory<int> moved;
  std::map<std::pair<int, int>, std::pair<int, int>> model;
  for (int round = 1; round <= 40; ++round) {
    moved.next();
    for (int q = 0; q < 60; ++q) {
      const std::pair<int, int> k{body(rng), body(rng)};
      const auto it = model.find(k);
      const int expected = it != model.end() && it->second.second >= round - 1 ? it->second.first : 0;
      ASSERT_EQ(moved.at(k.first, k.second), expected) << "round " << round;
      moved.at(k.first, k.second) = round * 100 + q;
      model[k] = {round * 100 + q, round};
    }
  }
  set_move_pair_tables(false);
}

}  // namespace
}  // namespace gacompare::collision
