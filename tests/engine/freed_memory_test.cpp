// keep_freed_memory: a block below the threshold comes from the heap (not a
// mapping of its own that free() unmaps), so a worker's buffers stay mapped
// from one job to the next. Each check runs in a child process: it starts
// from glibc's defaults (which earlier frees in this process may have
// raised) and leaves no setting behind.
#include <gtest/gtest.h>
#include <malloc.h>

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <thread>

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

// Exits 0 when every expectation holds, else with the number of the first that fails.
[[noreturn]] void check_thresholds() {
  const std::size_t before = mallinfo2().hblks;
  // glibc's default in a fresh process: a 1 MiB block is mapped on its own.
  if (own_mappings_while_holding(std::size_t{1} << 20) != before + 1) std::_Exit(1);
  if (!keep_freed_memory(std::size_t{32} << 20)) std::_Exit(2);
  if (own_mappings_while_holding(std::size_t{1} << 20) != before) std::_Exit(3);
  // Above the threshold a block is still mapped on its own (and unmapped when freed).
  if (own_mappings_while_holding(std::size_t{40} << 20) != before + 1) std::_Exit(4);
  std::_Exit(0);
}

TEST(FreedMemory, BlocksBelowTheThresholdComeFromTheHeap) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // a fresh process: glibc's defaults
  EXPECT_EXIT(check_thresholds(), ::testing::ExitedWithCode(0), "");
}

// Whether a block a new thread allocates (while the main thread holds one)
// lies in the main heap, below the program break, rather than in an arena
// mapped for the thread. Exits 0 when it is where `one_heap` says.
[[noreturn]] void check_thread_block(bool one_heap) {
  if (one_heap && !one_heap_for_all_threads()) std::_Exit(1);
  void* held = std::malloc(64);
  bool in_main_heap = false;
  std::thread t([&] {
    void* p = std::malloc(std::size_t{64} << 10);
    std::memset(p, 1, std::size_t{64} << 10);
    in_main_heap = static_cast<char*>(p) < static_cast<char*>(::sbrk(0));
    std::free(p);
  });
  t.join();
  std::free(held);
  std::_Exit(in_main_heap == one_heap ? 0 : 2);
}

TEST(FreedMemory, ThreadsAllocateFromTheMainHeapWhenAskedElseFromAnArenaOfTheirOwn) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // a fresh process: glibc's defaults
  EXPECT_EXIT(check_thread_block(false), ::testing::ExitedWithCode(0), "");
  EXPECT_EXIT(check_thread_block(true), ::testing::ExitedWithCode(0), "");
}

TEST(FreedMemory, RefusesAThresholdGlibcCannotHold) {
  EXPECT_FALSE(keep_freed_memory(0));
  EXPECT_FALSE(keep_freed_memory(std::size_t{1} << 40));
}

}  // namespace
}  // namespace railvsi
