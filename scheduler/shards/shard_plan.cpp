#include "shards/shard_plan.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>

namespace railvsi::scheduler {

double ShardPlan::mean_cost() const {
  return costs.empty() ? 0.0 : std::accumulate(costs.begin(), costs.end(), 0.0) / static_cast<double>(costs.size());
}

double ShardPlan::max_cost() const { return costs.empty() ? 0.0 : *std::max_element(costs.begin(), costs.end()); }

namespace {

struct Group {
  std::vector<std::size_t> jobs;  // in study order
  double cost = 0.0;
  std::size_t first = 0;          // tie-break: the earlier group first, so the plan is deterministic
};

std::size_t least_loaded(const std::vector<double>& costs) {
  return static_cast<std::size_t>(std::min_element(costs.begin(), costs.end()) - costs.begin());
}

}  // namespace

ShardPlan balance_shards(const std::vector<ShardJob>& jobs, int shards) {
  if (shards < 1) throw std::invalid_argument("balance_shards: at least one shard");
  ShardPlan plan;
  plan.shards.resize(static_cast<std::size_t>(shards));
  plan.costs.assign(static_cast<std::size_t>(shards), 0.0);

  std::map<std::string, Group> by_key;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    auto [it, fresh] = by_key.try_emplace(jobs[i].operator_key);
    if (fresh) it->second.first = i;
    it->second.jobs.push_back(i);
    it->second.cost += jobs[i].cost;
  }
  const double total = std::accumulate(jobs.begin(), jobs.end(), 0.0, [](double s, const ShardJob& j) { return s + j.cost; });
  const double mean = total / shards;

  const auto larger = [](const Group& a, const Group& b) { return a.cost != b.cost ? a.cost > b.cost : a.first < b.first; };
  std::vector<Group> pending;
  for (auto& [key, g] : by_key) pending.push_back(std::move(g));
  std::set<std::string> split_keys;

  while (!pending.empty()) {
    std::sort(pending.begin(), pending.end(), larger);
    Group g = std::move(pending.front());
    pending.erase(pending.begin());
    const std::size_t s = least_loaded(plan.costs);
    if (plan.costs[s] + g.cost <= kGroupSlack * mean || g.jobs.size() == 1) {
      for (std::size_t j : g.jobs) plan.shards[s].push_back(j);
      plan.costs[s] += g.cost;
      continue;
    }
    // Split: fill shard s up to the mean (at least one job), the rest waits.
    Group rest;
    rest.first = g.first;
    bool took_one = false;
    for (std::size_t j : g.jobs) {
      const double c = jobs[j].cost;
      if (rest.jobs.empty() && (!took_one || plan.costs[s] + c <= mean)) {
        plan.shards[s].push_back(j);
        plan.costs[s] += c;
        took_one = true;
      } else {
        rest.jobs.push_back(j);
        rest.cost += c;
      }
    }
    if (rest.jobs.empty()) continue;
    split_keys.insert(jobs[g.jobs.front()].operator_key);
    pending.push_back(std::move(rest));
  }
  for (auto& shard : plan.shards) std::sort(shard.begin(), shard.end());
  plan.split_groups = split_keys.size();
  return plan;
}

}  // namespace railvsi::scheduler
