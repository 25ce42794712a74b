#pragma once
// The stages' second core: a loop over independent items split across the
// run's threads (gacompare --threads N; 1 unless set, so that timings compare
// algebras on one core).
//
// Bit-identical for any number of threads, by construction rather than by
// luck: for_each_index hands out item indices, never a reduction. The caller
// gives each item its own output slot (a body's derivative, a pair's hit) and
// combines the slots afterwards in index order on one thread, so no sum's
// order, and no result, depends on which thread ran which item.
//
// The pool: threads − 1 workers, started on first use and kept. A loop is
// cut into chunks of `grain` items taken in turn from an atomic counter by
// the caller and the workers; the caller returns once every chunk is done. An
// exception thrown by an item is rethrown in the caller (the first one;
// items after it may still run). A loop of fewer than two chunks runs on the
// caller alone: waking a worker costs more than a few items save.
#include <algorithm>
#include <cstddef>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace gacompare::core {

// How many threads the stages may use, the caller's included (≥ 1).
void set_threads(int n);
int threads();

namespace detail {
// Runs call(context, begin, end) over [0, n) in chunks of `grain` on the pool.
void run_chunks(std::size_t n, std::size_t grain, void* context, void (*call)(void*, std::size_t, std::size_t));
// Whether this thread is running an item of a loop: a loop inside an item (a
// body's forces within a block of bodies integrated on one thread) then runs
// on that thread alone, since the pool runs one loop at a time.
bool in_item();
}  // namespace detail

// The stages' grains: a chunk must hold some 100 µs of work, or moving its
// items' data between the cores' caches (read next by a stage on one
// thread) costs more than the second core saves. Measured on the scale
// boxes (docs/results/scale.md): with a grain of 32 bodies and 8 pairs, two
// threads ran the 1,000-body box at 0.8x one thread's speed, the
// narrowphase alone at 0.6x.
inline constexpr std::size_t kGrainLight = 8192;  // ~20 ns items: a body's pose, reach or forces, a box test
inline constexpr std::size_t kGrainPair = 512;    // a pair's lookups, placing and narrowphase test, 200 ns and up
// Loops over a world's bodies whose items cost some 20 to 100 ns (a body's
// reach, its fat box test, its sphere placed in the broadphase's frame):
// with kGrainLight a 10,000-body world's such loops, fewer than two chunks,
// ran on one thread, each a share of the run's own thread.
inline constexpr std::size_t kGrainBody = 2048;
// The push-out's detections (core/collision/push_out_step.hpp: a few hundred
// pairs each, about 800 in the 10,000-body box's pile, most of them in
// contact) take a finer grain: left to kGrainPair, which splits from 1,024
// pairs, they all ran on one thread. On the 10,000-body box without a search (two
// threads, three interleaved runs) 32 took the run from 23.6 s to 22.8 s. An
// island's searched sub-steps keep kGrainPair: at 32 the searched
// 1,000-body box went from 17.3 s to 18.0 s.
inline constexpr std::size_t kGrainPushOutPair = 32;
// A time-of-impact search's depth tests at a trial time (Collider::depth_at):
// a pile's searches test tens of pairs at a time, up to a hundred and more,
// a few microseconds each with their bodies placed.
inline constexpr std::size_t kGrainDepthPair = 32;

// For the determinism check (gacompare-state-hash --fine-grains): every
// loop is cut into chunks of at most 4 items, so that a scene small enough
// to check in seconds still runs every parallel path. Never faster.
void set_fine_grains(bool on);
bool fine_grains();
inline std::size_t grain_of(std::size_t grain) { return fine_grains() && grain > 4 ? 4 : grain; }

// Whether for_each_index(n, f, grain) splits its items across threads.
inline bool runs_parallel(std::size_t n, std::size_t grain) {
  return threads() > 1 && n >= 2 * grain_of(grain) && !detail::in_item();
}

// f(k) for every k in [0, n); f must write only what item k owns.
template <class F>
void for_each_index(std::size_t n, F&& f, std::size_t grain = 32) {
  if (!runs_parallel(n, grain)) {
    for (std::size_t k = 0; k < n; ++k) f(k);
    return;
  }
  grain = grain_of(grain);
  detail::run_chunks(n, grain, &f, [](void* context, std::size_t begin, std::size_t end) {
    F& g = *static_cast<std::remove_reference_t<F>*>(context);
    for (std::size_t k = begin; k < end; ++k) g(k);
  });
}

// [0, n) cut into blocks of `grain` items (the last one shorter), and
// f(b, begin, end) for every block b on the run's threads: for loops whose
// blocks each fill a slot of their own (a count, a maximum, a list), to be
// combined in block order afterwards.
inline std::size_t blocks_of(std::size_t n, std::size_t grain) { return (n + grain_of(grain) - 1) / grain_of(grain); }
template <class F>
void for_each_block(std::size_t n, std::size_t grain, F&& f) {
  const std::size_t g = grain_of(grain);
  for_each_index(blocks_of(n, grain), [&](std::size_t b) { f(b, b * g, std::min(n, (b + 1) * g)); }, 1);
}

// Appends item(k) to `out` for every k in [0, n) with pick(k), in index
// order: the same list for any number of threads. On several, each block of
// `grain` items counts its picks, a running sum of the counts (on this
// thread) gives each block its place, and the blocks write there. pick runs
// twice per item, so it should be a lookup, not a test.
template <class T, class Pick, class Item>
void append_picked(std::vector<T>& out, std::size_t n, Pick&& pick, Item&& item, std::size_t grain) {
  if (!runs_parallel(n, grain)) {
    for (std::size_t k = 0; k < n; ++k)
      if (pick(k)) out.push_back(item(k));
    return;
  }
  const std::size_t blocks = blocks_of(n, grain);
  std::vector<std::size_t> at(blocks + 1, 0);
  for_each_block(n, grain, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::size_t c = 0;
    for (std::size_t k = begin; k < end; ++k) c += pick(k) ? 1 : 0;
    at[b + 1] = c;
  });
  at[0] = out.size();
  for (std::size_t b = 0; b < blocks; ++b) at[b + 1] += at[b];
  out.resize(at[blocks]);
  for_each_block(n, grain, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::size_t w = at[b];
    for (std::size_t k = begin; k < end; ++k)
      if (pick(k)) out[w++] = item(k);
  });
}

// `list` without the items whose `drop` flag is set, the rest in order
// (append_picked into a fresh list): the same list for any number of threads.
template <class T>
void erase_flagged(std::vector<T>& list, const std::vector<char>& drop, std::size_t grain) {
  std::vector<T> left;
  append_picked(left, list.size(), [&](std::size_t k) { return !drop[k]; }, [&](std::size_t k) { return list[k]; }, grain);
  list.swap(left);
}

// to = from, copied in blocks on the run's threads: a 10,000-body world's
// state (a megabyte) copied at every step was half a percent of the run's
// own thread.
inline constexpr std::size_t kGrainCopy = std::size_t{1} << 15;  // doubles: some 10 µs a block
template <class T>
void copy_on_threads(std::span<const T> from, std::vector<T>& to) {
  to.resize(from.size());
  for_each_block(from.size(), kGrainCopy, [&](std::size_t, std::size_t begin, std::size_t end) {
    std::copy(from.begin() + static_cast<std::ptrdiff_t>(begin), from.begin() + static_cast<std::ptrdiff_t>(end),
              to.begin() + static_cast<std::ptrdiff_t>(begin));
  });
}

// out = std::merge(a, b) (stable: of equal items, a's first), its parts
// merged on the run's threads: the longer list cut into chunks of `grain`
// items, each chunk with the part of the other list that sorts among it
// (found by a binary search), written where the two parts' starts add up
// to. The same list for any number of threads.
template <class T>
void merge_sorted(const std::vector<T>& a, const std::vector<T>& b, std::vector<T>& out, std::size_t grain) {
  const std::size_t n = a.size() + b.size();
  out.resize(n);
  if (!runs_parallel(n, grain) || a.empty() || b.empty()) {
    std::merge(a.begin(), a.end(), b.begin(), b.end(), out.begin());
    return;
  }
  const bool by_a = a.size() >= b.size();
  const std::vector<T>& cut = by_a ? a : b;
  const std::size_t parts = blocks_of(cut.size(), grain);
  // Part p: a[ia[p], ia[p + 1]) and b[ib[p], ib[p + 1]).
  std::vector<std::size_t> ia(parts + 1), ib(parts + 1);
  for (std::size_t p = 0; p <= parts; ++p) {
    const std::size_t at = p * cut.size() / parts;
    if (p == 0 || p == parts) {
      ia[p] = p == 0 ? 0 : a.size(), ib[p] = p == 0 ? 0 : b.size();
    } else if (by_a) {  // b's items equal to a[at] after it
      ia[p] = at, ib[p] = static_cast<std::size_t>(std::lower_bound(b.begin(), b.end(), a[at]) - b.begin());
    } else {  // a's items equal to b[at] before it
      ib[p] = at, ia[p] = static_cast<std::size_t>(std::upper_bound(a.begin(), a.end(), b[at]) - a.begin());
    }
  }
  for_each_index(parts, [&](std::size_t p) {
    std::merge(a.begin() + static_cast<long>(ia[p]), a.begin() + static_cast<long>(ia[p + 1]),
               b.begin() + static_cast<long>(ib[p]), b.begin() + static_cast<long>(ib[p + 1]),
               out.begin() + static_cast<long>(ia[p] + ib[p]));
  }, 1);
}

}  // namespace gacompare::core
