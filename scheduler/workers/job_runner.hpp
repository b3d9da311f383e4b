#pragma once
// One claimed job, or a batch of them, from scene text to what the
// database keeps: the scene is parsed, its planned rung run (the structure
// operator or the modal basis taken from the cache, or built), and its
// envelopes computed.
#include <vector>

#include "io/imported_structures.hpp"
#include "queue/job_queue.hpp"
#include "workers/factorization_cache.hpp"

namespace railvsi::scheduler {

// Deterministic failures (the scene cannot be set up, the run diverged or
// did not converge) come back as an outcome with ok = false; anything else
// (out of memory, a bug) is an exception for the caller to retry.
// An imported model is read through `imports` when given (a worker
// thread's own: the jobs of one operator key share one read).
JobOutcome run_job(const ClaimedJob& job, FactorizationCache& cache, ImportedStructures* imports = nullptr);

// A batch from JobQueue::claim_batch, one outcome per job in order. Jobs on
// the modal moving-force rung that differ only in speed share one pass: the
// scene parsed once, the modal basis (from the cache), the modal steps, the
// mode shapes on the rail elements and the code filter built once, one
// workspace; only envelopes are kept (no histories). A job's outcome has
// the same bits whether it runs alone or in a batch.
std::vector<JobOutcome> run_jobs(const std::vector<ClaimedJob>& jobs, FactorizationCache& cache,
                                 ImportedStructures* imports = nullptr);

}  // namespace railvsi::scheduler
