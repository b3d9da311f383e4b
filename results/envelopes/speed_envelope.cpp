#include "envelopes/speed_envelope.hpp"

#include <cmath>
#include <map>
#include <tuple>

namespace railvsi {

std::vector<TrainEnvelope> envelope_over_speeds(const std::vector<CaseValue>& rows, Extreme extreme) {
  // Does case a govern over the current choice g?
  const auto governs = [extreme](const CaseValue& a, const TrainEnvelope& g) {
    if (*a.value != *g.value) return extreme == Extreme::kMax ? *a.value > *g.value : *a.value < *g.value;
    return std::tie(a.speed_kmh, a.irregularity, a.variant) <
           std::tie(g.governing_speed_kmh, g.governing_irregularity, g.governing_variant);
  };
  std::map<std::string, TrainEnvelope> by_train;  // ordered by name
  for (const CaseValue& c : rows) {
    TrainEnvelope& t = by_train[c.train];
    t.train = c.train;
    ++t.cases;
    if (!c.value || !std::isfinite(*c.value)) {
      ++t.cases_without_value;
      continue;
    }
    if (!t.value || governs(c, t)) {
      t.value = c.value;
      t.governing_speed_kmh = c.speed_kmh;
      t.governing_irregularity = c.irregularity;
      t.governing_variant = c.variant;
    }
  }
  std::vector<TrainEnvelope> out;
  for (auto& [name, t] : by_train) out.push_back(std::move(t));
  return out;
}

}  // namespace railvsi
