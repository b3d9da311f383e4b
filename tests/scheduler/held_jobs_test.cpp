// HeldJobs: what each worker thread holds (the heartbeat's list), and the
// wait of an idle thread, which a sibling's hold or drop ends.
#include <gtest/gtest.h>

#include <thread>

#include "workers/held_jobs.hpp"

namespace railvsi::test {
namespace {

using scheduler::HeldJobs;

TEST(HeldJobs, SnapshotListsEachThreadsJobsAndNothingOnceDropped) {
  HeldJobs held(2);
  held.hold(1, {"a", "b"});
  EXPECT_EQ(held.snapshot(), (std::vector<std::vector<std::string>>{{}, {"a", "b"}}));
  held.drop(1);
  EXPECT_EQ(held.snapshot(), (std::vector<std::vector<std::string>>{{}, {}}));
}

TEST(HeldJobs, AWaitEndsWhenASiblingDropsItsBatchAndAChangeBeforeTheWaitIsNotMissed) {
  HeldJobs held(2);
  held.hold(1, {"a"});
  const std::uint64_t seen = held.generation();
  // The sibling lets go from another thread; the wait (a minute at most)
  // returns true because it changed, not because the time passed.
  std::thread sibling([&] { held.drop(1); });
  EXPECT_TRUE(held.wait_for_change(seen, 60.0));
  sibling.join();
  // A change made before the wait starts (between the claim and the wait)
  // ends it at once.
  const std::uint64_t before = held.generation();
  held.hold(0, {"b"});
  EXPECT_TRUE(held.wait_for_change(before, 60.0));
  // No change: the wait runs out and says so.
  EXPECT_FALSE(held.wait_for_change(held.generation(), 0.01));
}

}  // namespace
}  // namespace railvsi::test
