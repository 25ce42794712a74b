#include "core/memory.hpp"

#include <malloc.h>

namespace gacompare::core {

void keep_freed_memory() {
  // Either call may fail (a C library other than glibc's ignores them); the
  // run is then as fast as the allocator makes it, never wrong.
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
}

}  // namespace gacompare::core
