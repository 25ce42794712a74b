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
#include <cstddef>
#include <type_traits>
#include <utility>

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

// f(k) for every k in [0, n); f must write only what item k owns.
template <class F>
void for_each_index(std::size_t n, F&& f, std::size_t grain = 32) {
  if (threads() == 1 || n < 2 * grain || detail::in_item()) {
    for (std::size_t k = 0; k < n; ++k) f(k);
    return;
  }
  detail::run_chunks(n, grain, &f, [](void* context, std::size_t begin, std::size_t end) {
    F& g = *static_cast<std::remove_reference_t<F>*>(context);
    for (std::size_t k = begin; k < end; ++k) g(k);
  });
}

}  // namespace gacompare::core
