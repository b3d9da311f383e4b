// The factorization cache: one build per key however many threads ask at
// once, least recently used entries dropped to stay within the budget.
#include <atomic>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "workers/factorization_cache.hpp"

namespace railvsi::scheduler {
namespace {

// An operator of n DOFs that solves nothing: the cache only holds it.
class FakeOperator final : public StructureOperator {
 public:
  explicit FakeOperator(int n) : n_(n) {}
  int num_dofs() const override { return n_; }
  std::unique_ptr<SolveWorkspace> make_workspace() const override { return std::make_unique<SolveWorkspace>(); }
  Status solve(const Vector& b, Vector& x, SolveWorkspace&) const override {
    x = b;
    return Status::Ok();
  }
  std::string backend_name() const override { return "fake"; }
  DenseMatrix inverse_block(const std::vector<int>&, const std::vector<int>&, SolveWorkspace&) const override {
    return {};
  }
  StructureCoordinates coordinates(const StructureModel& model) const override {
    return StructureCoordinates(model);
  }
  std::shared_ptr<const StructureOperator> static_operator(const StructureModel&) const override {
    return std::make_shared<const FakeOperator>(n_);
  }
  std::size_t memory_bytes() const override { return static_cast<std::size_t>(n_) * sizeof(double); }

 private:
  int n_;
};

std::shared_ptr<const StructureOperator> fake(int n) { return std::make_shared<const FakeOperator>(n); }

TEST(FactorizationCache, ConcurrentRequestsForOneKeyBuildOnce) {
  FactorizationCache cache;
  std::atomic<int> builds{0};
  std::vector<std::thread> threads;
  std::vector<std::shared_ptr<const StructureOperator>> got(8);
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&, t] {
      got[static_cast<std::size_t>(t)] = cache
                                             .get("key",
                                                  [&] {
                                                    ++builds;
                                                    std::this_thread::sleep_for(std::chrono::milliseconds(50));
                                                    return fake(10);
                                                  })
                                             .op;
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(builds.load(), 1);
  for (const auto& op : got) EXPECT_EQ(op.get(), got[0].get());
  const CacheStats s = cache.stats();
  EXPECT_EQ(s.factorizations, 1);
  EXPECT_EQ(s.hits, 7);
}

// Defect (issue 35): a model larger than the whole budget emptied the cache
// first and was then not kept: every later job refactorized what had been
// cached. Now it is used without touching the entries.
TEST(FactorizationCache, AModelOverTheWholeBudgetEvictsNothing) {
  FactorizationCache cache(2000);  // two 800-byte operators fit
  int builds = 0;
  const auto build = [&] {
    ++builds;
    return fake(100);
  };
  cache.get("A", build);
  cache.get("B", build);
  const CacheLookup huge = cache.get("huge", [] { return fake(1000); });  // 8,000 bytes
  EXPECT_TRUE(huge.factorized);
  EXPECT_EQ(huge.evictions, 0);
  EXPECT_FALSE(cache.get("A", build).factorized);
  EXPECT_FALSE(cache.get("B", build).factorized);
  EXPECT_EQ(builds, 2);
  EXPECT_EQ(cache.stats().evictions, 0);
}

TEST(FactorizationCache, LeastRecentlyUsedIsEvictedFirst) {
  // Each fake operator of 100 DOFs is estimated at 800 bytes: two fit.
  ASSERT_EQ(FactorizationCache::estimated_bytes(FakeOperator(100)), 800u);
  FactorizationCache cache(2000);
  int builds = 0;
  const auto build = [&] {
    ++builds;
    return fake(100);
  };
  EXPECT_TRUE(cache.get("A", build).factorized);
  EXPECT_TRUE(cache.get("B", build).factorized);
  EXPECT_FALSE(cache.get("A", build).factorized);  // A is now the most recent
  const CacheLookup c = cache.get("C", build);     // evicts B
  EXPECT_TRUE(c.factorized);
  EXPECT_EQ(c.evictions, 1);
  EXPECT_FALSE(cache.get("A", build).factorized);
  EXPECT_TRUE(cache.get("B", build).factorized) << "B was evicted";
  EXPECT_EQ(builds, 4);
  EXPECT_EQ(cache.stats().evictions, 2);  // B made room for C, then C (least recent) for B
}

TEST(FactorizationCache, OperatorLargerThanTheBudgetIsUsedButNotKept) {
  FactorizationCache cache(100);
  int builds = 0;
  const auto build = [&] {
    ++builds;
    return fake(100);
  };
  EXPECT_NE(cache.get("big", build).op, nullptr);
  EXPECT_TRUE(cache.get("big", build).factorized);
  EXPECT_EQ(builds, 2);
}

TEST(FactorizationCache, FailedBuildLetsTheNextCallerTry) {
  FactorizationCache cache;
  EXPECT_THROW(cache.get("k", []() -> std::shared_ptr<const StructureOperator> { throw std::runtime_error("no"); }),
               std::runtime_error);
  EXPECT_TRUE(cache.get("k", [] { return fake(5); }).factorized);
}

}  // namespace
}  // namespace railvsi::scheduler
