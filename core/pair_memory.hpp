#pragma once
// What a pair of bodies remembers from one detection to the next (issue #14:
// the narrowphase's separating axis, core/separating_axis.hpp SatHint). Only
// the pairs of the last detection are kept: a pair that leaves the broadphase
// is forgotten, and one that comes back starts afresh.
//
// Two flat arrays, not a hash map: the pairs of a detection are appended as
// they are met, sorted once when the next detection starts, and looked up by
// binary search; the arrays keep their storage, so a detection allocates
// nothing once the number of pairs has settled.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace gacompare::collision {

template <class T>
class PairMemory {
 public:
  // A new detection: what keep() stored in the last one is what recall() reads.
  void next() {
    std::sort(current_.begin(), current_.end(), [](const Entry& x, const Entry& y) { return x.first < y.first; });
    previous_.swap(current_);
    current_.clear();
  }
  // The value the pair (i, j) kept at the last detection, or T{} (the order
  // of i and j matters: a value may refer to "a" and "b").
  T recall(int i, int j) const {
    const std::uint64_t k = key(i, j);
    const auto it = std::lower_bound(previous_.begin(), previous_.end(), k,
                                     [](const Entry& e, std::uint64_t x) { return e.first < x; });
    return it != previous_.end() && it->first == k ? it->second : T{};
  }
  void keep(int i, int j, const T& value) { current_.emplace_back(key(i, j), value); }
  void clear() { previous_.clear(), current_.clear(); }

 private:
  using Entry = std::pair<std::uint64_t, T>;
  static std::uint64_t key(int i, int j) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
  }
  std::vector<Entry> previous_, current_;
};

}  // namespace gacompare::collision
