#pragma once
// What a pair of bodies remembers from one detection to the next (issue #14:
// the narrowphase's separating axis, core/separating_axis.hpp SatHint). A
// detection of the whole world starts a new round (next()); a pair that no
// detection of the last round met (it left the broadphase) is forgotten then,
// and one that comes back starts afresh. Detections of a part of the world
// (an island stepped alone) read and update what the round holds.
//
// One sorted flat array, not a hash map: a pair met again is found by binary
// search and updated in place; a pair met for the first time waits in a
// second array until the next round merges it in. The arrays keep their
// storage, so a round allocates nothing once the number of pairs has settled.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace gacompare::collision {

template <class T>
class PairMemory {
 public:
  // A new round: the pairs met in the last one are kept, the others dropped.
  void next() {
    std::erase_if(known_, [&](const Entry& e) { return e.round != round_; });
    std::stable_sort(fresh_.begin(), fresh_.end(), [](const Entry& x, const Entry& y) { return x.key < y.key; });
    // A pair met twice while new: its last value wins.
    const auto last = std::unique(fresh_.rbegin(), fresh_.rend(), [](const Entry& x, const Entry& y) { return x.key == y.key; });
    fresh_.erase(fresh_.begin(), last.base());
    const std::size_t old = known_.size();
    known_.insert(known_.end(), fresh_.begin(), fresh_.end());
    std::inplace_merge(known_.begin(), known_.begin() + static_cast<long>(old), known_.end(),
                       [](const Entry& x, const Entry& y) { return x.key < y.key; });
    fresh_.clear();
    ++round_;
  }
  // What the pair (i, j) kept last, or T{} (the order of i and j matters: a
  // value may refer to "a" and "b").
  T recall(int i, int j) const {
    const auto it = find(known_, key(i, j));
    return it != known_.end() ? it->value : T{};
  }
  void keep(int i, int j, const T& value) {
    const std::uint64_t k = key(i, j);
    const auto it = find(known_, k);
    if (it != known_.end()) *it = {k, value, round_};
    else fresh_.push_back({k, value, round_});
  }
  std::size_t size() const { return known_.size(); }

 private:
  struct Entry {
    std::uint64_t key;
    T value;
    std::uint64_t round;  // the round that last met the pair
  };
  static std::uint64_t key(int i, int j) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
  }
  template <class V>
  static auto find(V& entries, std::uint64_t k) {
    const auto it = std::lower_bound(entries.begin(), entries.end(), k, [](const Entry& e, std::uint64_t x) { return e.key < x; });
    return it != entries.end() && it->key == k ? it : entries.end();
  }
  std::vector<Entry> known_, fresh_;
  std::uint64_t round_ = 0;
};

}  // namespace gacompare::collision
