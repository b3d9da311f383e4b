// The balancing rule of vsi shard (scheduler/shards/shard_plan.hpp) on
// jobs with given costs: groups that fit stay whole, a group too large for
// one shard is split, every job lands in exactly one shard.
#include <algorithm>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "shards/shard_plan.hpp"

namespace railvsi::scheduler {
namespace {

std::vector<ShardJob> jobs_of(const std::vector<std::pair<std::string, double>>& key_cost) {
  std::vector<ShardJob> jobs;
  for (std::size_t i = 0; i < key_cost.size(); ++i)
    jobs.push_back({"job" + std::to_string(i), key_cost[i].first, key_cost[i].second});
  return jobs;
}

void expect_each_job_once(const ShardPlan& plan, std::size_t jobs) {
  std::multiset<std::size_t> seen;
  for (const auto& s : plan.shards) seen.insert(s.begin(), s.end());
  ASSERT_EQ(seen.size(), jobs);
  for (std::size_t j = 0; j < jobs; ++j) EXPECT_EQ(seen.count(j), 1u) << "job " << j;
}

TEST(ShardPlan, EqualGroupsStayWholeOnePerShard) {
  std::vector<std::pair<std::string, double>> kc;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j) kc.push_back({"key" + std::to_string(k), 10.0 + j});
  const auto jobs = jobs_of(kc);
  const ShardPlan plan = balance_shards(jobs, 4);
  expect_each_job_once(plan, jobs.size());
  EXPECT_EQ(plan.split_groups, 0u);
  for (const auto& s : plan.shards) {
    std::set<std::string> keys;
    for (std::size_t j : s) keys.insert(jobs[j].operator_key);
    EXPECT_EQ(keys.size(), 1u);
  }
  EXPECT_DOUBLE_EQ(plan.max_cost(), plan.mean_cost());
}

TEST(ShardPlan, OneLargeGroupIsSplitEvenly) {
  std::vector<std::pair<std::string, double>> kc;
  for (int j = 0; j < 40; ++j) kc.push_back({"only", 1.0 + (j % 7)});
  const auto jobs = jobs_of(kc);
  const ShardPlan plan = balance_shards(jobs, 4);
  expect_each_job_once(plan, jobs.size());
  EXPECT_EQ(plan.split_groups, 1u);
  // Each shard is filled up to the mean, so the largest exceeds it by less
  // than the costliest job (7).
  EXPECT_LT(plan.max_cost(), plan.mean_cost() + 7.0);
  for (const auto& s : plan.shards) EXPECT_FALSE(s.empty());
}

TEST(ShardPlan, SmallGroupsAreNotSplitWhenWholeGroupsBalance) {
  // 8 groups of cost 10 on 4 shards: two whole groups per shard.
  std::vector<std::pair<std::string, double>> kc;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 2; ++j) kc.push_back({"key" + std::to_string(k), 5.0});
  const auto jobs = jobs_of(kc);
  const ShardPlan plan = balance_shards(jobs, 4);
  expect_each_job_once(plan, jobs.size());
  EXPECT_EQ(plan.split_groups, 0u);
  EXPECT_DOUBLE_EQ(plan.max_cost(), 20.0);
}

TEST(ShardPlan, MoreShardsThanJobsLeavesShardsEmpty) {
  const auto jobs = jobs_of({{"a", 1.0}, {"b", 2.0}});
  const ShardPlan plan = balance_shards(jobs, 3);
  expect_each_job_once(plan, jobs.size());
  EXPECT_EQ(std::count_if(plan.shards.begin(), plan.shards.end(), [](const auto& s) { return s.empty(); }), 1);
}

}  // namespace
}  // namespace railvsi::scheduler
