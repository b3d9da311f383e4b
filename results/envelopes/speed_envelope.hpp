#pragma once
// The envelope over speeds (and irregularity profiles) per train: the
// governing value of one quantity and the case that gives it, as `vsi
// query` and the compliance report show it.
#include <optional>
#include <string>
#include <vector>

#include "envelopes/envelope_rows.hpp"

namespace railvsi {

// One job's value of the quantity; absent when the job has none (failed,
// or the value could not be produced).
struct CaseValue {
  std::string train;
  double speed_kmh = 0.0;
  std::string irregularity;  // profile label, "none" for a perfect track
  std::optional<double> value;
  std::string variant = "nominal";  // bound of the structure (EN 1991-2 6.4.6.3)
};

struct TrainEnvelope {
  std::string train;
  std::optional<double> value;  // absent when no case of the train has one
  double governing_speed_kmh = 0.0;
  std::string governing_irregularity;
  std::string governing_variant = "nominal";
  int cases = 0;
  int cases_without_value = 0;  // a hole the user must see: the envelope may miss it
};

// One entry per train, ordered by train name, whatever the order of the
// rows. The governing case is the largest value (kMax) or the smallest
// (kMin); equal values are broken by the lowest speed, then by the
// irregularity label, then by the variant label, so the answer never
// depends on row order.
std::vector<TrainEnvelope> envelope_over_speeds(const std::vector<CaseValue>& rows, Extreme extreme = Extreme::kMax);

}  // namespace railvsi
