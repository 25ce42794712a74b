// core/parallel.hpp: every index once, on any number of threads, and an
// item's exception in the caller; append_picked gives the serial loop's list
// (brute force) for any thread count, grain and list it appends to, and
// merge_sorted std::merge's, equal items in the same order; erase_flagged
// the unflagged items in order; copy_on_threads a plain copy.
#include "core/parallel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <span>
#include <utility>
#include <stdexcept>
#include <thread>
#include <vector>

namespace gacompare::core {
namespace {

// Restores one thread after each test: the pool is process-wide.
class Parallel : public ::testing::Test {
 protected:
  void TearDown() override { set_threads(1); }
};

TEST_F(Parallel, EveryIndexRunsOnceForAnyThreadCountAndGrain) {
  for (int t : {1, 2, 3, 8})
    for (std::size_t n : {0u, 1u, 63u, 64u, 1000u, 12345u})
      for (std::size_t grain : {1u, 7u, 32u}) {
        set_threads(t);
        std::vector<int> hits(n, 0);
        for_each_index(n, [&](std::size_t k) { hits[k] += 1; }, grain);
        for (std::size_t k = 0; k < n; ++k) ASSERT_EQ(hits[k], 1) << "threads " << t << " n " << n << " k " << k;
      }
}

TEST_F(Parallel, AppendPickedGivesTheSerialListForAnyThreadCount) {
  for (int t : {1, 2, 3})
    for (std::size_t n : {0u, 5u, 64u, 1000u, 12345u})
      for (std::size_t grain : {1u, 7u, 256u}) {
        set_threads(t);
        // Every third item and every item whose index has bit 4 set, squared.
        const auto pick = [](std::size_t k) { return k % 3 == 0 || (k & 16) != 0; };
        const auto item = [](std::size_t k) { return static_cast<long>(k * k); };
        std::vector<long> expected = {-1, -2}, got = {-1, -2};
        for (std::size_t k = 0; k < n; ++k)
          if (pick(k)) expected.push_back(item(k));
        append_picked(got, n, pick, item, grain);
        ASSERT_EQ(got, expected) << "threads " << t << " n " << n << " grain " << grain;
      }
}

// Stability is seen in the pairs' second members: equal keys with a's
// second member 0 and b's 1 must come out a's first, as std::merge puts them.
TEST_F(Parallel, MergeSortedGivesStdMergeForAnyThreadCountAndSplit) {
  std::mt19937 random(29);
  for (int t : {1, 2, 3})
    for (const auto& [na, nb] : {std::pair{0, 100}, {100, 0}, {1, 1}, {50, 5000}, {5000, 50}, {3000, 3000}})
      for (std::size_t grain : {1u, 7u, 256u}) {
        set_threads(t);
        std::uniform_int_distribution<int> key(0, (na + nb) / 4 + 1);  // many repeats within and across the lists
        std::vector<std::pair<int, int>> a(static_cast<std::size_t>(na)), b(static_cast<std::size_t>(nb));
        for (auto& x : a) x = {key(random), 0};
        for (auto& x : b) x = {key(random), 1};
        std::ranges::sort(a), std::ranges::sort(b);
        std::vector<std::pair<int, int>> want(a.size() + b.size());
        const auto by_key = [](const auto& x, const auto& y) { return x.first < y.first; };
        std::merge(a.begin(), a.end(), b.begin(), b.end(), want.begin(), by_key);
        // Merged by the key alone, as std::merge above: wrap the pairs so that < compares keys.
        struct Key {
          std::pair<int, int> p;
          bool operator<(const Key& o) const { return p.first < o.p.first; }
        };
        std::vector<Key> ka, kb, kgot;
        for (const auto& x : a) ka.push_back({x});
        for (const auto& x : b) kb.push_back({x});
        merge_sorted(ka, kb, kgot, grain);
        ASSERT_EQ(kgot.size(), want.size());
        for (std::size_t k = 0; k < want.size(); ++k)
          ASSERT_EQ(kgot[k].p, want[k]) << "threads " << t << " sizes " << na << ", " << nb << " grain " << grain << " at " << k;
      }
}

// erase_flagged keeps exactly the unflagged items, in order (brute force),
// for any thread count and block split.
TEST_F(Parallel, EraseFlaggedKeepsTheRestInOrder) {
  std::mt19937 random(7);
  for (int t : {1, 2, 3})
    for (const bool fine : {false, true})
      for (const std::size_t n : {0u, 1u, 9u, 20000u}) {
        set_threads(t), set_fine_grains(fine);
        std::vector<int> list(n);
        std::vector<char> drop(n);
        std::vector<int> want;
        for (std::size_t k = 0; k < n; ++k) {
          list[k] = static_cast<int>(random() % 1000);
          drop[k] = random() % 3 == 0;
          if (!drop[k]) want.push_back(list[k]);
        }
        erase_flagged(list, drop, 256);
        ASSERT_EQ(list, want) << "threads " << t << " fine " << fine << " n " << n;
      }
  set_fine_grains(false);
}

// Every item copied to its own place, whatever the thread count and
// however the blocks fall (fine grains cut them to 4 items), into a vector
// longer or shorter than the source.
TEST_F(Parallel, CopyOnThreadsGivesAPlainCopy) {
  for (int t : {1, 2, 3})
    for (const bool fine : {false, true})
      for (const std::size_t n : {0u, 1u, 5u, 70000u}) {
        set_threads(t), set_fine_grains(fine);
        std::vector<double> from(n);
        for (std::size_t k = 0; k < n; ++k) from[k] = 0.5 * static_cast<double>(k) - 3;
        for (const std::size_t had : {std::size_t{0}, n + 9}) {
          std::vector<double> to(had, -1.0);
          copy_on_threads(std::span<const double>(from), to);
          ASSERT_EQ(to, from) << "threads " << t << " fine " << fine << " n " << n << " had " << had;
        }
      }
  set_fine_grains(false);
}

TEST_F(Parallel, ManyShortLoopsInARowNeitherLoseNorRepeatAnItem) {
  set_threads(2);
  std::vector<long> sums(200, 0);
  for (int loop = 0; loop < 2000; ++loop)
    for_each_index(sums.size(), [&](std::size_t k) { sums[k] += loop; }, 4);
  for (long s : sums) EXPECT_EQ(s, 1999L * 2000 / 2);
}

TEST_F(Parallel, AnItemsExceptionReachesTheCaller) {
  set_threads(2);
  EXPECT_THROW(for_each_index(1000, [](std::size_t k) { if (k == 777) throw std::runtime_error("item 777"); }, 8),
               std::runtime_error);
  // The pool is still usable after it.
  std::vector<int> hits(100, 0);
  for_each_index(hits.size(), [&](std::size_t k) { hits[k] = 1; }, 4);
  for (int h : hits) EXPECT_EQ(h, 1);
}

// A block of bodies integrated on one thread evaluates its forces through a
// loop of its own: that loop runs on the item's thread, every index once,
// and the pool takes the next outer loop as before.
TEST_F(Parallel, ALoopInsideAnItemRunsOnThatThread) {
  set_threads(2);
  constexpr std::size_t outer = 4, inner = 1000;
  std::vector<int> hits(outer * inner, 0);
  std::vector<char> same_thread(outer * inner, 0);
  for (int round = 0; round < 50; ++round) {
    std::fill(hits.begin(), hits.end(), 0);
    for_each_index(
        outer,
        [&](std::size_t k) {
          const auto me = std::this_thread::get_id();
          for_each_index(inner, [&](std::size_t i) {
            ++hits[k * inner + i];
            same_thread[k * inner + i] = std::this_thread::get_id() == me;
          });
        },
        1);
    for (std::size_t j = 0; j < hits.size(); ++j) ASSERT_EQ(hits[j], 1) << "round " << round << ", item " << j;
    for (std::size_t j = 0; j < hits.size(); ++j) ASSERT_TRUE(same_thread[j]) << "round " << round << ", item " << j;
  }
  std::vector<int> after(100, 0);
  for_each_index(after.size(), [&](std::size_t k) { after[k] = 1; }, 4);
  for (int h : after) EXPECT_EQ(h, 1);
}

TEST_F(Parallel, ThreadCountsOutsideOneTo256AreRefused) {
  EXPECT_THROW(set_threads(0), std::invalid_argument);
  EXPECT_THROW(set_threads(257), std::invalid_argument);
  EXPECT_EQ(threads(), 1);
}

}  // namespace
}  // namespace gacompare::core
