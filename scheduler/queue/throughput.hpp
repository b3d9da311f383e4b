#pragma once
// How fast the jobs of a store (or of one study) finish and when the rest
// will be done, computed one way for everyone who shows it: `vsi status`,
// the HTTP API and dashboard, and the progress line and log of `vsi work`
// and `vsi run`. Read at the same second from the same store, they agree.
#include <optional>
#include <string>

#include "queue/job_queue.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

inline constexpr double kThroughputWindow_s = 60.0;

struct Throughput {
  // Jobs done or failed in the recent window (kThroughputWindow_s up to
  // now, or up to the last finish when nothing is left) over the time from
  // the window's start, or the earliest start of those jobs if later, to
  // its end: pauses before the window and cancelled jobs do not count.
  // None before any job has finished.
  std::optional<double> jobs_per_s;
  // The unfinished jobs at that rate; none when the rate is 0 or unknown.
  std::optional<double> eta_s;
};

// Of the study `study_id`, or of every job in the store when it is empty;
// `counts` are that study's (or the store's) state counts read with it.
Throughput recent_throughput(Database& db, const std::string& study_id, const StateCounts& counts, double now_s);

}  // namespace railvsi::scheduler
