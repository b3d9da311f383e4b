#pragma once
// One claimed job from its scene text to what the database keeps: the scene
// is parsed, the structure operator taken from the cache (or built), the
// simulation run and its envelopes computed.
#include "queue/job_queue.hpp"
#include "workers/factorization_cache.hpp"

namespace railvsi::scheduler {

// Deterministic failures (the scene cannot be set up, the run diverged or
// did not converge) come back as an outcome with ok = false; anything else
// (out of memory, a bug) is an exception for the caller to retry.
JobOutcome run_job(const ClaimedJob& job, FactorizationCache& cache);

}  // namespace railvsi::scheduler
