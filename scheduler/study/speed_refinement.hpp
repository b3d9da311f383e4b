#pragma once
// Refinement of a speed sweep around its peaks ("refine": true in a study).
// A resonance peak of the deck acceleration is a few km/h wide: a sweep in
// steps of 10 km/h can step over it (HSLM-A1 on a 25 m span: 1.8 m/s^2 at
// 180 km/h where 184 km/h gives 3.0). After a pass, every local maximum of
// the governing value over speeds (the largest over the profiles at each
// speed) that reaches at least min_fraction_of_max of the train's largest
// value gets the midpoints between it and its neighbours; the next pass does
// the same with the new speeds, until every such maximum has both
// neighbours within tolerance_kmh. The peak's speed is then known to within
// tolerance_kmh. A maximum at the first or last speed is refined inwards
// only (and flagged by vsi query: the peak may lie outside the range).
#include <optional>
#include <vector>

namespace railvsi::scheduler {

struct RefineOptions {
  double tolerance_kmh = 1.0;
  double min_fraction_of_max = 0.5;
};

struct SpeedValue {
  double speed_kmh = 0.0;
  std::optional<double> value;  // absent: the job failed or has no value
};

// Speeds to add for one train (sorted, none already in curve); empty when
// the peaks are resolved. Values missing at a speed leave its neighbours
// unrefined (no peak is claimed next to a hole).
std::vector<double> refinement_speeds(std::vector<SpeedValue> curve, const RefineOptions& options = {});

}  // namespace railvsi::scheduler
