#pragma once
// What a pair of bodies remembers from one detection to the next (issue #14:
// the narrowphase's separating axis, core/separating_axis.hpp SatHint). A
// detection of the whole world starts a new round (next()); a pair that no
// detection of the last round met (it left the broadphase) is forgotten then,
// and one that comes back starts afresh. Detections of a part of the world
// (an island stepped alone) read and update what the round holds.
//
// One sorted flat array, not a hash map: a pair met again is found by one
// binary search and read and updated in place; a pair met for the first time
// waits in a second array until the next round merges it in. The arrays keep their
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
    merged_.resize(known_.size() + fresh_.size());
    std::merge(known_.begin(), known_.end(), fresh_.begin(), fresh_.end(), merged_.begin(),
               [](const Entry& x, const Entry& y) { return x.key < y.key; });
    known_.swap(merged_);
    fresh_.clear();
    ++round_;
  }
  // The pair (i, j)'s value from an earlier round, to read and update in
  // place (valid until next()), or nullptr for a pair met for the first time
  // (the order of i and j matters: a value may refer to "a" and "b"). Either
  // way the pair counts as met in this round.
  T* find(int i, int j) {
    const std::uint64_t k = key(i, j);
    const auto it = std::lower_bound(known_.begin(), known_.end(), k, [](const Entry& e, std::uint64_t x) { return e.key < x; });
    if (it == known_.end() || it->key != k) return nullptr;
    it->round = round_;
    return &it->value;
  }
  // A pair met for the first time: readable from the next round on.
  void add(int i, int j, const T& value) { fresh_.push_back({key(i, j), value, round_}); }
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
  std::vector<Entry> known_, fresh_, merged_;
  std::uint64_t round_ = 0;
};

}  // namespace gacompare::collision
