#include "envelopes/profile_statistics.hpp"

#include <cmath>
#include <map>
#include <tuple>

namespace railvsi {
namespace {

bool governs(double candidate, double current, Extreme extreme) {
  return extreme == Extreme::kMax ? candidate > current : candidate < current;
}

}  // namespace

std::vector<SampleStatistics> profile_statistics(const std::vector<SeededValue>& rows, Extreme extreme) {
  std::map<std::tuple<std::string, double, std::string>, std::size_t> index;
  std::vector<SampleStatistics> groups;
  std::vector<std::vector<double>> values;
  for (const SeededValue& r : rows) {
    const auto [it, fresh] = index.try_emplace({r.train, r.speed_kmh, r.family}, groups.size());
    if (fresh) {
      groups.push_back({r.train, r.speed_kmh, r.family, 0, 0, {}, {}, {}});
      values.emplace_back();
    }
    SampleStatistics& g = groups[it->second];
    ++g.samples;
    if (r.value) values[it->second].push_back(*r.value);
    else ++g.without_value;
  }
  std::vector<SampleStatistics> out;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    SampleStatistics g = groups[k];
    if (g.samples < 2) continue;
    const std::vector<double>& v = values[k];
    if (!v.empty()) {
      double sum = 0.0, best = v.front();
      for (double x : v) {
        sum += x;
        if (governs(x, best, extreme)) best = x;
      }
      const double mean = sum / static_cast<double>(v.size());
      g.mean = mean;
      g.extreme = best;
      if (v.size() >= 2) {
        double squares = 0.0;  // two-pass: no cancellation for values far from zero
        for (double x : v) squares += (x - mean) * (x - mean);
        g.std_dev = std::sqrt(squares / static_cast<double>(v.size() - 1));
      }
    }
    out.push_back(std::move(g));
  }
  return out;
}

std::vector<StatisticsOverSpeeds> statistics_over_speeds(const std::vector<SampleStatistics>& groups, Extreme extreme) {
  std::map<std::pair<std::string, std::string>, std::size_t> index;
  std::vector<StatisticsOverSpeeds> out;
  const auto better = [&](const std::optional<SampleStatistics>& current, const SampleStatistics& g,
                          std::optional<double> SampleStatistics::*field) {
    if (!(g.*field)) return false;
    if (!current) return true;
    const double a = *(g.*field), b = *((*current).*field);
    return governs(a, b, extreme) || (a == b && g.speed_kmh < current->speed_kmh);
  };
  for (const SampleStatistics& g : groups) {
    const auto [it, fresh] = index.try_emplace({g.train, g.family}, out.size());
    if (fresh) out.push_back({g.train, g.family, {}, {}});
    StatisticsOverSpeeds& s = out[it->second];
    if (better(s.governing_mean, g, &SampleStatistics::mean)) s.governing_mean = g;
    if (better(s.governing_extreme, g, &SampleStatistics::extreme)) s.governing_extreme = g;
  }
  return out;
}

}  // namespace railvsi
