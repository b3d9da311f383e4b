#pragma once
// `vsi work`: worker threads, each with its own database connection, claim
// jobs until the database has none queued or running, and share one
// factorization cache. A heartbeat thread renews the lease of each job a
// thread holds (by job id and worker name), so that only the jobs of a dead
// worker return to the queue.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "queue/job_queue.hpp"
#include "queue/throughput.hpp"
#include "workers/factorization_cache.hpp"

namespace railvsi::scheduler {

struct WorkOptions {
  std::string db_file = "vsi-results.sqlite";
  int threads = 1;
  double lease_s = 60.0;
  std::size_t cache_budget_bytes = std::size_t{2} << 30;
  // How often the progress callback is called, s.
  double progress_interval_s = 0.5;
  // How long a thread keeps retrying a database that refuses its claims
  // (disk full, locked past the busy timeout) before the process gives up.
  double db_retry_s = 300.0;
  // Modal moving-force jobs of one structure, dt and train are claimed,
  // run and stored together, up to this many at a time (1: one by one).
  std::size_t max_batch_jobs = 256;
  // Names of this process's workers start with it (worker_name_prefix());
  // empty: run_workers makes one.
  std::string worker_prefix;
  // Set when the process stops on an interrupt: no claim takes a job after
  // it (checked inside the claim's write transaction). May be null.
  const std::atomic<bool>* stopping = nullptr;
};

struct WorkSummary {
  std::int64_t jobs_done = 0;     // by this process
  std::int64_t jobs_failed = 0;   // by this process
  std::int64_t lost_leases = 0;   // results dropped: the job was taken over or cancelled
  double wall_s = 0.0;
  CacheStats cache;
  // Why the workers stopped before the queue was empty (empty: they did
  // not); e.g. the database refused writes for longer than db_retry_s.
  std::string error;
};

// host:pid:start-nonce, new at every call: the names of a process's threads
// append :tN. A container restarted as PID 1 on the same host name gets a
// new name, so it never renews the leases of its dead predecessor.
std::string worker_name_prefix();

// What the progress of `vsi work` shows: the store's state counts and its
// throughput and ETA (recent_throughput over all studies, the function
// `vsi status` uses for one study), read at the same moment.
struct WorkProgress {
  StateCounts counts;
  Throughput throughput;
  double elapsed_s = 0.0;  // since run_workers started
};

// Reads the store's progress at now_s (unix time).
WorkProgress work_progress(Database& db, double now_s, double elapsed_s);

// Called from the calling thread while the workers run, then once at the end.
using ProgressCallback = std::function<void(const WorkProgress& progress, bool final)>;

// OPENBLAS_NUM_THREADS=1 and the BLAS itself single-threaded: parallelism
// is across jobs. Call before any BLAS call (vsi calls it in main).
void single_threaded_blas();

// Opens an existing database (NoSuchDatabase otherwise). The workers share
// a cache of options.cache_budget_bytes made for this call.
WorkSummary run_workers(const WorkOptions& options, const ProgressCallback& progress = {});
// The same on a cache the caller keeps, so that passes of one process (a
// study's refinement and verification runs) share what they computed; the
// summary counts this call's lookups only.
WorkSummary run_workers(const WorkOptions& options, FactorizationCache& cache, const ProgressCallback& progress = {});

}  // namespace railvsi::scheduler
