#pragma once
// The durable job queue in the study database. Every change of a job's state
// is one SQLite transaction taken with BEGIN IMMEDIATE, so that any number
// of threads (each with its own connection) and processes may share a file:
// - claim: the next queued job (or one whose lease expired: its worker died)
//   becomes 'running' under a lease owned by the worker;
// - renew: a live worker renews the lease of each job it holds, by job id
//   and worker name (a reused name never renews someone else's job);
// - complete: the envelopes are stored and the job marked 'done' in one
//   transaction, only if the worker still holds the job (a result is never
//   lost nor stored twice).
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "envelopes/envelope_rows.hpp"
#include "store/sqlite.hpp"
#include "study/study_plan.hpp"

namespace railvsi::scheduler {

struct SubmitResult {
  std::string study_id;
  std::size_t jobs = 0;        // jobs of the study
  std::size_t new_jobs = 0;    // jobs not in the database before
  bool new_study = false;
  // The study was there already (the same document): of the `stored_jobs`
  // it holds, this many are other jobs than this plan's at their position
  // in it (another vsi planned it, or files it names moved or changed).
  // Then nothing is written: one study never mixes two expansions. A store
  // that holds only some of the plan's jobs (a shard, a partial merge) is
  // completed as usual.
  std::size_t differing_jobs = 0;
  std::size_t stored_jobs = 0;
};

// Inserts the study and its jobs in one transaction; what is there already
// stays as it is (re-submitting adds nothing, and a study stored with other
// jobs gets none of the plan's: differing_jobs).
SubmitResult submit_study(Database& db, const StudyPlan& plan, int max_attempts = 3);

// The store's number of a stored study (studies.seq: what its links hold).
std::int64_t study_seq(Database& db, const std::string& study_id);

// Inserts jobs (INSERT OR IGNORE: a job already stored stays as it is) in
// no study; returns the number of new jobs. Inside the caller's transaction.
std::size_t insert_jobs(Database& db, const std::vector<JobSpec>& jobs, int max_attempts, double now);
// Inserts jobs (INSERT OR IGNORE: a job already stored stays as it is) and
// links them to the study at positions first_position, +1, ...; returns the
// number of new jobs. Inside the caller's transaction.
std::size_t insert_study_jobs(Database& db, const std::string& study_id, const std::vector<JobSpec>& jobs,
                              std::int64_t first_position, int max_attempts, double now);

struct ClaimedJob {
  std::string id;
  std::string scene;
  std::string operator_key;
  std::string train;
  std::string irregularity;
  double speed_kmh = 0.0;
  double dt_s = 0.0;
  double cutoff_hz = 0.0;
  int attempt = 0;  // 1 for the first claim
  std::string rung;  // planned at submission; empty for older jobs
  // The modal moving-force rung: the modes counted up to the cut-off at
  // submission; -1 when not known.
  int planned_modes = -1;
};

// Jobs on this rung are claimed and run in batches (claim_batch).
inline constexpr const char* kBatchedRung = "moving_forces/modal";

// What a finished run leaves in the database.
struct JobOutcome {
  bool ok = true;               // false: a deterministic failure (the run's status, a setup error)
  std::string status;           // engine status name
  std::string error;            // for a failure
  std::string fidelity;         // JSON
  std::string warnings = "[]";  // JSON array of the run's warnings (RunWarning), also for a failure
  long steps = 0;
  double wall_s = 0.0, loop_s = 0.0, setup_s = 0.0, factorization_s = 0.0;
  bool factorized = false;      // the factorization cache missed and factorized for this job
  int evictions = 0;            // entries the cache dropped to make room for it
  std::vector<EnvelopeRow> envelopes;  // results/ envelope_rows(): quantity, location, value
};

struct StateCounts {
  std::int64_t queued = 0, running = 0, done = 0, failed = 0, cancelled = 0;
  std::int64_t total() const { return queued + running + done + failed + cancelled; }
  std::int64_t unfinished() const { return queued + running; }
};

class JobQueue {
 public:
  // `worker` names the claimant in the jobs table (host:pid:start:thread).
  // Throws std::invalid_argument unless lease_s is finite and positive.
  JobQueue(Database& db, std::string worker, double lease_s = 60.0);

  // A job whose lease has expired more than max_attempts times ends
  // 'failed'. Prefers jobs with preferred_key (their factor is cached).
  std::optional<ClaimedJob> claim(const std::string& preferred_key = {});
  // One claim as above and, when that job is on kBatchedRung, up to
  // max_jobs - 1 more queued jobs of the same operator key (structure, dt)
  // and rung, all in one transaction, each leased as a single claim, in
  // order of train, profile and speed:
  // complete_batch stores them in one transaction; a worker that dies
  // leaves them all to expire and return.
  // stopping (may be null): once set, claims take nothing; read inside the
  // claim's write transaction, so no claim passes a release that set it.
  std::vector<ClaimedJob> claim_batch(const std::string& preferred_key, std::size_t max_jobs,
                                      const std::atomic<bool>* stopping = nullptr);
  // Renews the lease of the job if this worker still holds it; false when
  // it does not (taken over after an expired lease, or cancelled).
  bool renew(const std::string& job_id);
  // The same for several jobs in one transaction; returns how many are still held.
  std::size_t renew(const std::vector<std::string>& job_ids);
  // false (and nothing stored) when the job is no longer this worker's:
  // its lease expired and another worker took it, or it was cancelled.
  bool complete(const ClaimedJob& job, const JobOutcome& outcome);
  // complete() of each job (outcomes[i] for jobs[i]) in one transaction;
  // per job, whether it was stored.
  std::vector<bool> complete_batch(const std::vector<ClaimedJob>& jobs, const std::vector<JobOutcome>& outcomes);
  // A transient failure (an exception that is not the scene's fault): the
  // job returns to the queue while it has attempts left, else ends 'failed'.
  bool release_after_error(const ClaimedJob& job, const std::string& error);

  const std::string& worker() const { return worker_; }

 private:
  std::optional<ClaimedJob> claim_row(const std::string& id, double now_s);
  std::optional<ClaimedJob> claim_in_transaction(const std::string& preferred_key);
  bool complete_in_transaction(const ClaimedJob& job, const JobOutcome& outcome);
  Database& db_;
  std::string worker_;
  double lease_s_;
};

// Counts per state, for one study or (empty id) the whole database.
StateCounts state_counts(Database& db, const std::string& study_id = {});
// Study ids known to the database, oldest first.
std::vector<std::string> study_ids(Database& db);
struct CancelResult {
  std::int64_t cancelled = 0;
  std::int64_t left_for_other_studies = 0;  // queued or running, needed by another unfinished study
};
// Cancels the queued and running jobs of a study that no other unfinished
// study needs.
CancelResult cancel_study(Database& db, const std::string& study_id);
// Failed and cancelled jobs of a study go back to the queue with their
// attempts reset; returns how many.
std::int64_t retry_study(Database& db, const std::string& study_id);
// Running jobs whose worker name starts with `worker_prefix` (one run's
// worker_name_prefix()) go back to the queue, their attempt not counted: a
// process its user interrupts gives its leases back instead of leaving them
// to expire. Returns how many.
std::int64_t release_running_jobs(Database& db, const std::string& worker_prefix);
// Full id from a unique prefix (at least 6 hex digits); empty if none.
// Throws std::runtime_error when the prefix is ambiguous.
std::string resolve_study_id(Database& db, const std::string& prefix);

}  // namespace railvsi::scheduler
