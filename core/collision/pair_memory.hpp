#pragma once
// What a pair of bodies remembers from one detection to the next (its
// separating axis and kept-contacts state, core/collision/collisions.hpp
// PairRecord; its kept manifold, core/collision/kept_contacts.hpp). A
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
//
// A reference or pointer into a table holds only until the next insertion,
// which can rebuild it. The narrowphase's step 4 once wrote pairs' records
// through pointers taken before it inserted new pairs: only the 10,000-body
// box's hash showed it, since a growth rarely falls in the same detection as
// such a write. So the determinism check also runs with every insertion
// moving every entry (set_move_pair_tables), where any such write lands in
// the wrong place and changes the run's hash.
#include <cstdint>
#include <utility>
#include <vector>

namespace gacompare::collision {

// For the determinism check (gacompare-state-hash --move-pair-tables): every
// insertion into a PairMemory rebuilds its table with a new hash salt, so that
// each entry moves. What a table answers is unchanged; where its entries lie
// is not. Set before a run, never during one; never faster.
namespace detail {
inline bool g_move_pair_tables = false;
}
inline void set_move_pair_tables(bool on) { detail::g_move_pair_tables = on; }
inline bool move_pair_tables() { return detail::g_move_pair_tables; }

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
    if (2 * (count_ + 1) > keys_.size()) rebuild(count_ + 1);
    std::size_t at = home(k);
    for (; keys_[at].key != kEmpty; at = (at + 1) & mask_) {
      Key& s = keys_[at];
      if (s.key != k) continue;
      if (!live(s)) values_[at] = T{};
      s.round = round_;
      return values_[at];
    }
    if (move_pair_tables()) {
      salt_ += 0x9E3779B97F4A7C15ull;
      rebuild(count_ + 1);
      for (at = home(k); keys_[at].key != kEmpty;) at = (at + 1) & mask_;
    }
    keys_[at] = {k, round_};
    values_[at] = T{};
    ++count_;
    return values_[at];
  }
  // Asks the cache for the place where the pair (i, j)'s lookup starts: its
  // key and its value, read a few pairs later by find().
  void prefetch(int i, int j) const {
    if (keys_.empty()) return;
    const std::size_t at = home(key(i, j));
    __builtin_prefetch(&keys_[at]);
    __builtin_prefetch(&values_[at]);
  }
  // The pair (i, j)'s value if a detection of the last round or of this one
  // met it, else nullptr; adds nothing. A pair found counts as met in this
  // round. The pointer holds until the next at() or next(). Safe on several
  // threads at once for distinct pairs, with no at() or next() meanwhile: a
  // lookup writes only its own pair's entry (its round), and reads of the
  // other entries it probes stop at their keys.
  T* find(int i, int j) {
    if (keys_.empty()) return nullptr;
    const std::uint64_t k = key(i, j);
    for (std::size_t at = home(k); keys_[at].key != kEmpty; at = (at + 1) & mask_) {
      Key& s = keys_[at];
      if (s.key != k) continue;
      if (!live(s)) return nullptr;
      s.round = round_;
      return &values_[at];
    }
    return nullptr;
  }
  // The pairs a detection of the last round or of this one met.
  std::size_t size() const {
    std::size_t n = 0;
    for (const Key& s : keys_) n += s.key != kEmpty && live(s);
    return n;
  }

 private:
  // The probes read only the keys: 16 bytes a slot, four to a cache line.
  // The values lie apart, at the same index, and are read on a hit only. (With
  // each value beside its key, a kept manifold's 328-byte slot put every probe
  // on a line of its own, and the kept contacts' table, probed for every pair,
  // took a tenth of the 10,000-body box's run in cache misses.)
  struct Key {
    std::uint64_t key = kEmpty;
    std::uint64_t round = 0;  // the round that last met the pair
  };
  // No pair's key: i and j are body indices, never both −1.
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  bool live(const Key& s) const { return s.round + 1 >= round_; }
  static std::uint64_t key(int i, int j) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
  }
  std::size_t home(std::uint64_t k) const {
    return static_cast<std::size_t>(((k ^ salt_) * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  // The live entries in a table of at least 16 slots and twice `least`, a power of two.
  void rebuild(std::size_t least) {
    std::size_t n = 16;
    unsigned bits = 4;
    while (n < 2 * least) n *= 2, ++bits;
    old_keys_.swap(keys_), old_values_.swap(values_);
    keys_.assign(n, Key{});
    values_.resize(n);  // a value is written before it is read (at())
    mask_ = n - 1;
    shift_ = 64 - bits;
    count_ = 0;
    for (std::size_t s = 0; s < old_keys_.size(); ++s) {
      if (old_keys_[s].key == kEmpty || !live(old_keys_[s])) continue;
      std::size_t at = home(old_keys_[s].key);
      while (keys_[at].key != kEmpty) at = (at + 1) & mask_;
      keys_[at] = old_keys_[s];
      values_[at] = std::move(old_values_[s]);
      ++count_;
    }
  }
  std::vector<Key> keys_, old_keys_;
  std::vector<T> values_, old_values_;
  std::size_t mask_ = 0, count_ = 0;
  unsigned shift_ = 64;
  std::uint64_t round_ = 0;
  std::uint64_t salt_ = 0;  // 0 but under set_move_pair_tables
};

}  // namespace gacompare::collision
