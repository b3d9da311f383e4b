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
  // Of counts.running: jobs whose lease has expired. Their worker died or
  // hung; the next claim returns them to work.
  std::int64_t stale_leases = 0;
  // Jobs done or failed in the recent window (kThroughputWindow_s up to now,
  // or up to the last finish when nothing is left) over the time from the
  // window's start, or the earliest start of those jobs if later, to its
  // end: pauses before the window and cancelled jobs do not count.
  std::optional<double> jobs_per_s;
  std::optional<double> eta_s;       // unfinished jobs at that rate; none when the rate is 0
  double job_wall_s = 0.0;           // sum over finished jobs
  double loop_s = 0.0;               // of which in time loops
  std::int64_t factorizations = 0, cache_hits = 0, evictions = 0;
  double factorization_s = 0.0;
};

inline constexpr double kThroughputWindow_s = 60.0;

StudyStatus study_status(Database& db, const std::string& study_id);

}  // namespace railvsi::scheduler
