// core/collision/sleep.hpp: the sleeping sets' bookkeeping, by hand-made cases.
#include "core/collision/sleep.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace gacompare::core {
namespace {

// Bodies 0 (static floor), 1–3 and 4–5 asleep as two sets, 6 awake.
SleepState two_sets() {
  SleepState s(7);
  const std::vector<int> a{1, 2, 3}, b{4, 5};
  s.fall_asleep(a);
  s.fall_asleep(b);
  return s;
}
const std::vector<char> kStatic{1, 0, 0, 0, 0, 0, 0};

TEST(SleepState, FallingAsleepMarksTheSetAndCountsItsBodies) {
  const SleepState s = two_sets();
  EXPECT_EQ(s.sleeping, 5u);
  for (std::size_t k = 0; k < 7; ++k) EXPECT_EQ(s.is_asleep(k), k >= 1 && k <= 5) << k;
}

TEST(SleepState, AnAwakeBodyWithinReachWakesItsWholeSetOnly) {
  SleepState s = two_sets();
  s.still_for.assign(7, 0.3);
  // 6 reaches 2: the set {1, 2, 3} wakes and starts its stillness afresh; {4, 5} sleeps on.
  const std::vector<std::pair<int, int>> reached{{2, 6}};
  EXPECT_EQ(s.wake_reached(kStatic, reached), 1);
  for (std::size_t k = 0; k < 7; ++k) EXPECT_EQ(s.is_asleep(k), k == 4 || k == 5) << k;
  EXPECT_EQ(s.sleeping, 2u);
  for (int k : {1, 2, 3}) EXPECT_EQ(s.still_for[static_cast<std::size_t>(k)], 0.0);
  EXPECT_EQ(s.still_for[4], 0.3);
}

TEST(SleepState, NeitherTheFloorNorAnotherSleepingSetWakesASet) {
  SleepState s = two_sets();
  const std::vector<std::pair<int, int>> pairs{{0, 1}, {0, 4}, {3, 4}};
  EXPECT_EQ(s.wake_reached(kStatic, pairs), 0);
  EXPECT_EQ(s.sleeping, 5u);
}

TEST(SleepState, TwoPairsIntoOneSetWakeItOnceAndItsSlotIsReused) {
  SleepState s = two_sets();
  const std::vector<std::pair<int, int>> reached{{1, 6}, {3, 6}};
  EXPECT_EQ(s.wake_reached(kStatic, reached), 1);
  EXPECT_FALSE(s.wake(1));  // awake already
  const std::vector<int> c{6};
  s.fall_asleep(c);
  EXPECT_EQ(s.sets.size(), 2u);  // the woken set's slot holds the new one
  EXPECT_EQ(s.set_of[6], 0);
  EXPECT_EQ(s.sleeping, 3u);
}

}  // namespace
}  // namespace gacompare::core
