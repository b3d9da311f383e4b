#include "core/freed_memory.hpp"

#include <malloc.h>

#include <climits>

namespace railvsi {

bool keep_freed_memory(std::size_t bytes) {
  if (bytes == 0 || bytes > INT_MAX / 2) return false;
  const int threshold = static_cast<int>(bytes);
  // mallopt returns 1 on success. Setting either also stops glibc's own
  // adjustment of the two.
  const bool mmap_set = mallopt(M_MMAP_THRESHOLD, threshold) == 1;
  const bool trim_set = mallopt(M_TRIM_THRESHOLD, 2 * threshold) == 1;
  return mmap_set && trim_set;
}

bool one_heap_for_all_threads() { return mallopt(M_ARENA_MAX, 1) == 1; }

}  // namespace railvsi
