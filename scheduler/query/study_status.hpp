#pragma once
// Progress of a study for `vsi status`: jobs per state, throughput, ETA and
// the factorization cache statistics the workers stored.
#include <cstdint>
#include <optional>
#include <string>

#include "queue/job_queue.hpp"
#include "queue/throughput.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

struct StudyStatus {
  std::string id, name;
  StateCounts counts;
  // Of counts.running: jobs whose lease has expired. Their worker died or
  // hung; the next claim returns them to work.
  std::int64_t stale_leases = 0;
  // recent_throughput (queue/throughput.hpp), as the workers' progress shows it.
  std::optional<double> jobs_per_s;
  std::optional<double> eta_s;
  double job_wall_s = 0.0;           // sum over finished jobs
  double loop_s = 0.0;               // of which in time loops
  std::int64_t factorizations = 0, cache_hits = 0, evictions = 0;
  double factorization_s = 0.0;
};

// At now_s (unix time; now by default).
StudyStatus study_status(Database& db, const std::string& study_id);
StudyStatus study_status(Database& db, const std::string& study_id, double now_s);

}  // namespace railvsi::scheduler
