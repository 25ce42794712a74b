#pragma once
// A test's threads for one scope: core::set_threads and core::set_fine_grains
// set on construction, and one thread with the stages' grains again when the
// scope ends, an assertion's early return or an exception included, so that
// no test leaves its setting to the next.
#include "core/parallel.hpp"

namespace gacompare::testing {

struct ScopedThreads {
  ScopedThreads(int threads, bool fine_grains) { core::set_threads(threads), core::set_fine_grains(fine_grains); }
  ~ScopedThreads() { core::set_threads(1), core::set_fine_grains(false); }
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;
};

}  // namespace gacompare::testing
