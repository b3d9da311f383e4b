// keep_freed_memory: a block below the threshold comes from the heap (not a
// mapping of its own that free() unmaps), so a worker's buffers stay mapped
// from one job to the next.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>
#include <cstring>

#include "core/freed_memory.hpp"

namespace railvsi {
namespace {

// Blocks mapped on their own (mallinfo2().hblks) while a block of `bytes` is held.
std::size_t own_mappings_while_holding(std::size_t bytes) {
  void* p = std::malloc(bytes);
  std::memset(p, 1, bytes);
  asm volatile("" : : "g"(p) : "memory");  // the block is used: the compiler may not elide it
  const std::size_t mapped = mallinfo2().hblks;
  std::free(p);
  return mapped;
}

TEST(FreedMemory, BlocksBelowTheThresholdComeFromTheHeap) {
  const std::size_t before = mallinfo2().hblks;
  // glibc's default: a 1 MiB block is mapped on its own.
  ASSERT_EQ(own_mappings_while_holding(std::size_t{1} << 20), before + 1);
  ASSERT_TRUE(keep_freed_memory(std::size_t{32} << 20));
  EXPECT_EQ(own_mappings_while_holding(std::size_t{1} << 20), before);
  // Above the threshold a block is still mapped on its own (and unmapped when freed).
  EXPECT_EQ(own_mappings_while_holding(std::size_t{40} << 20), before + 1);
}

TEST(FreedMemory, RefusesAThresholdGlibcCannotHold) {
  EXPECT_FALSE(keep_freed_memory(0));
  EXPECT_FALSE(keep_freed_memory(std::size_t{1} << 40));
}

}  // namespace
}  // namespace railvsi
