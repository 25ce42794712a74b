#pragma once
// What a pair of bodies remembers from one detection to the next (the
// narrowphase's separating axis, core/collision/separating_axis.hpp SatHint). A
// detection of the whole world starts a new round (next()); a pair that no
// detection of the last round met (it left the broadphase) is forgotten, and
// one that comes back starts afresh. Detections of a part of the world (an
// island stepped alone) read and update what the round holds.
//
// An open-addressing hash table (linear probing, Fibonacci hashing, at most
// half full): a pair is found in one or two probes. Each entry carries the
// round that last met it, so forgetting costs nothing at the round's start:
// an entry older than the last round reads as new, and the table drops such
// entries when it grows, and every 32 rounds. (A binary search over the
// pairs, or lists kept by a pair's first body, where a wall's list holds
// hundreds of pairs, cost far more per lookup; so does rebuilding the table
// at every round.) The table keeps
// its storage, so a round allocates nothing once the number of pairs has
// settled.
#include <cstdint>
#include <vector>

namespace gacompare::collision {

template <class T>
class PairMemory {
 public:
  // A new round.
  void next() {
    ++round_;
    if (round_ % 32 == 0) rebuild(count_);
  }
  // The pair (i, j)'s value, to read and update in place: what it kept if a
  // detection of the last round or of this one met it, else T{} (the order of
  // i and j matters: a value may refer to "a" and "b"). The reference holds
  // until the next at() or next(). The pair counts as met in this round.
  T& at(int i, int j) {
    const std::uint64_t k = key(i, j);
    if (2 * (count_ + 1) > slots_.size()) rebuild(count_ + 1);
    std::size_t at = home(k);
    for (; slots_[at].used; at = (at + 1) & mask_) {
      Slot& s = slots_[at];
      if (s.key != k) continue;
      if (!live(s)) s.value = T{};
      s.round = round_;
      return s.value;
    }
    slots_[at] = {k, round_, T{}, true};
    ++count_;
    return slots_[at].value;
  }
  // The pair (i, j)'s value if a detection of the last round or of this one
  // met it, else nullptr; adds nothing. A pair found counts as met in this
  // round. The pointer holds until the next at() or next().
  T* find(int i, int j) {
    if (slots_.empty()) return nullptr;
    const std::uint64_t k = key(i, j);
    for (std::size_t at = home(k); slots_[at].used; at = (at + 1) & mask_) {
      Slot& s = slots_[at];
      if (s.key != k) continue;
      if (!live(s)) return nullptr;
      s.round = round_;
      return &s.value;
    }
    return nullptr;
  }
  // The pairs a detection of the last round or of this one met.
  std::size_t size() const {
    std::size_t n = 0;
    for (const Slot& s : slots_) n += s.used && live(s);
    return n;
  }

 private:
  struct Slot {
    std::uint64_t key = 0;
    std::uint64_t round = 0;  // the round that last met the pair
    T value{};
    bool used = false;
  };
  bool live(const Slot& s) const { return s.round + 1 >= round_; }
  static std::uint64_t key(int i, int j) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
  }
  std::size_t home(std::uint64_t k) const { return static_cast<std::size_t>((k * 0x9E3779B97F4A7C15ull) >> shift_); }
  // The live entries in a table of at least 16 slots and twice `least`, a power of two.
  void rebuild(std::size_t least) {
    std::size_t n = 16;
    unsigned bits = 4;
    while (n < 2 * least) n *= 2, ++bits;
    old_.swap(slots_);
    slots_.assign(n, Slot{});
    mask_ = n - 1;
    shift_ = 64 - bits;
    count_ = 0;
    for (const Slot& s : old_) {
      if (!s.used || !live(s)) continue;
      std::size_t at = home(s.key);
      while (slots_[at].used) at = (at + 1) & mask_;
      slots_[at] = s;
      ++count_;
    }
  }
  std::vector<Slot> slots_, old_;
  std::size_t mask_ = 0, count_ = 0;
  unsigned shift_ = 64;
  std::uint64_t round_ = 0;
};

}  // namespace gacompare::collision
