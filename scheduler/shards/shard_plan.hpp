#pragma once
// How the jobs of a study are split into shards (self-contained stores
// worked on different machines). The cost of a job is estimated as its time
// steps times its model size (structure DOFs plus vehicle DOFs): the time
// loop dominates a job, and each step costs about one pass over the model.
//
// Balancing rule: jobs sharing an operator key (one structure
// factorization) form a group. Groups are placed largest first, each on the
// least loaded shard, whole when that shard then stays within
// kGroupSlack of the mean shard cost; otherwise the group is split: the
// least loaded shard takes the group's jobs, in study order, up to the
// mean, and the rest is placed again as a group of its own. Each split
// costs one more factorization on another shard. The largest shard stays
// within max(kGroupSlack x mean, mean + the costliest job).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace railvsi::scheduler {

inline constexpr double kGroupSlack = 1.05;

struct ShardJob {
  std::string id;
  std::string operator_key;
  double cost = 0.0;  // estimated: steps x model DOFs
};

struct ShardPlan {
  // Indices into the jobs given to balance_shards, in the order given.
  std::vector<std::vector<std::size_t>> shards;
  std::vector<double> costs;     // per shard
  std::size_t split_groups = 0;  // operator keys whose jobs went to more than one shard
  double mean_cost() const;
  double max_cost() const;
};

// shards >= 1; shards may be left empty when there are fewer jobs.
ShardPlan balance_shards(const std::vector<ShardJob>& jobs, int shards);

}  // namespace railvsi::scheduler
