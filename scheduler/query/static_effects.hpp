#pragma once
// The static response of each train of a study on the study's structure and
// the dynamic increment phi'dyn = max dyn / max static - 1 of every load
// effect (EN 1991-2 6.4.6.5): deck deflection at each output point, and on
// beam decks bending moment and shear there, support reactions and deck end
// rotations.
//
// The static envelope is computed on demand, not stored: it depends only on
// the structure and the train, both in the stored scenes, and the static
// influence-line pass (analysis/static_influence) is exact and costs one
// factorization of K plus one solve per load effect, far less than a run.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/static_influence.hpp"
#include "model/train.hpp"
#include "query/study_results.hpp"
#include "simulation/scene.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

struct DynamicIncrement {
  std::string train;
  std::string quantity;  // an envelope quantity (envelope_rows)
  std::string location;  // output point or support
  double static_value = 0.0;
  std::optional<double> dynamic_value;  // the largest over the train's jobs with a value
  double governing_speed_kmh = 0.0;
  int jobs_without_value = 0;
  // (speed_kmh, the largest dynamic value at that speed over its jobs, e.g.
  // the profiles), ascending in speed: dynamic_value is their largest.
  std::vector<std::pair<double, double>> dynamic_by_speed;
  // dynamic / static - 1; absent without a dynamic value or a static value > 0
  std::optional<double> phi_dyn() const;
  // (speed_kmh, phi'dyn at that speed) from dynamic_by_speed; empty without
  // a static value > 0.
  std::vector<std::pair<double, double>> phi_dyn_by_speed() const;
};

// A train's static envelopes on the jobs' structure, as the compliance
// checks computed them: phi'dyn takes them instead of computing them again.
struct TrainStatics {
  std::vector<double> max_deflection_m;  // per output point (train_envelope)
  StaticSectionEnvelope sections;        // section_envelope
};
struct KnownStatics {
  const StaticInfluence* influence = nullptr;  // on the structure every job shares
  std::map<std::string, TrainStatics> trains;  // by train name
};

// One entry per train x load effect x location, trains in the order of the
// jobs. `notes` gets why a load effect has no static value (e.g. section
// forces of a structure without a beam deck). Throws what loading a stored
// scene throws. `known` (optional): the influence of the structure all
// `jobs` share and the envelopes of some trains on it, used as they are.
std::vector<DynamicIncrement> dynamic_increments(Database& db, const std::vector<JobResult>& jobs,
                                                 std::vector<std::string>& notes, const KnownStatics* known = nullptr);

nlohmann::ordered_json dynamic_increments_json(const std::vector<DynamicIncrement>& increments,
                                               const std::vector<std::string>& notes);

}  // namespace railvsi::scheduler
