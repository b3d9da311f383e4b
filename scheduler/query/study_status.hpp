#pragma once
// Progress of a study for `vsi status`: jobs per state, throughput, ETA and
// the factorization cache statistics the workers stored.
#include <cstdint>
#include <optional>
#include <string>

#include "queue/job_queue.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

struct StudyStatus {
  std::string id, name;
  StateCounts counts;
  std::optional<double> jobs_per_s;  // finished jobs over the time since the first start
  std::optional<double> eta_s;       // unfinished jobs at that rate
  double job_wall_s = 0.0;           // sum over finished jobs
  double loop_s = 0.0;               // of which in time loops
  std::int64_t factorizations = 0, cache_hits = 0, evictions = 0;
  double factorization_s = 0.0;
};

StudyStatus study_status(Database& db, const std::string& study_id);

}  // namespace railvsi::scheduler
