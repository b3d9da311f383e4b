#pragma once
// Values over random track profiles: a study that runs every train and
// speed on several seeds of one spectrum gets, per train x speed, the mean,
// the standard deviation and the extreme of each quantity over the seeds,
// not only the extreme (the one seed that happened to be worst).
#include <optional>
#include <string>
#include <vector>

#include "envelopes/envelope_rows.hpp"

namespace railvsi {

// One job's value, with the profile family it belongs to (the spectrum
// profile without its seed); jobs of the same train, speed and family are
// samples of one random variable.
struct SeededValue {
  std::string train;
  double speed_kmh = 0.0;
  std::string family;
  std::optional<double> value;
};

struct SampleStatistics {
  std::string train;
  double speed_kmh = 0.0;
  std::string family;
  int samples = 0;        // jobs of the group, with or without a value
  int without_value = 0;  // failed or unproduced: the statistics miss them
  std::optional<double> mean;
  std::optional<double> std_dev;  // sample standard deviation (divisor n - 1); absent for n < 2
  std::optional<double> extreme;  // max (kMax) or min (kMin) over the samples
};

// One entry per (train, speed, family) with at least two samples, in the
// order of first appearance in rows.
std::vector<SampleStatistics> profile_statistics(const std::vector<SeededValue>& rows, Extreme extreme);

// Over speeds, per (train, family): the group whose mean governs and the
// group whose extreme governs (ties: the lowest speed).
struct StatisticsOverSpeeds {
  std::string train, family;
  std::optional<SampleStatistics> governing_mean;
  std::optional<SampleStatistics> governing_extreme;
};
std::vector<StatisticsOverSpeeds> statistics_over_speeds(const std::vector<SampleStatistics>& groups, Extreme extreme);

}  // namespace railvsi
