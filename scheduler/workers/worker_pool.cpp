#include "workers/worker_pool.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/terminal_text.hpp"
#include "core/unix_time.hpp"
#include "store/store_schema.hpp"
#include "workers/held_jobs.hpp"
#include "workers/job_runner.hpp"

namespace railvsi::scheduler {
namespace {

using Clock = std::chrono::steady_clock;

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "host";
  return name;
}

// What the worker threads report back; only atomics and the mutex-guarded
// error cross threads.
struct Tally {
  std::atomic<std::int64_t> done{0}, failed{0}, lost{0};
  std::mutex mutex;
  std::string error;  // the first thread that stopped early says why
  void stopped(const std::string& why) {
    std::lock_guard lock(mutex);
    if (error.empty()) error = why;
  }
};

// A stop flag the heartbeat and the progress loop can sleep on.
class StopSignal {
 public:
  void stop() {
    {
      std::lock_guard lock(mutex_);
      stopped_ = true;
    }
    cv_.notify_all();
  }
  // true when stopped during the wait.
  bool wait_for(double seconds) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return stopped_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stopped_ = false;
};

bool nothing_left(Database& db) { return state_counts(db).unfinished() == 0; }

// Claim retries after a database error: 0.2 s doubling to 10 s, until the
// errors have lasted options.db_retry_s.
class ClaimBackoff {
 public:
  explicit ClaimBackoff(double give_up_after_s) : give_up_after_s_(give_up_after_s) {}
  void succeeded() {
    failing_ = false;
    wait_s_ = kFirstWait_s;
  }
  // Sleeps before the next attempt; throws when the errors have lasted too
  // long, counted from the start of the first failed attempt (a locked
  // store fails only after the busy timeout).
  void failed(const std::string& name, const std::string& error, Clock::time_point attempt_started) {
    const auto now = Clock::now();
    if (!failing_) failing_since_ = attempt_started;
    failing_ = true;
    const double failing_s = std::chrono::duration<double>(now - failing_since_).count();
    if (failing_s >= give_up_after_s_)
      throw std::runtime_error(fmt::format(
          "the database refused claims for {:.0f} s (--db-retry-s {}), giving up: {}. Nothing is lost: queued jobs "
          "stay queued and a job in hand returns to the queue when its lease expires; free space (or the lock) and "
          "run vsi work again",
          failing_s, give_up_after_s_, error));
    const double wait_s = std::min(wait_s_, give_up_after_s_ - failing_s);
    spdlog::warn("{}: claim failed, retrying in {:.1f} s (giving up after {} s of failures): {}", name, wait_s,
                 give_up_after_s_, error);
    std::this_thread::sleep_for(std::chrono::duration<double>(wait_s));
    wait_s_ = std::min(2.0 * wait_s_, kMaxWait_s);
  }

 private:
  static constexpr double kFirstWait_s = 0.2, kMaxWait_s = 10.0;
  double give_up_after_s_;
  double wait_s_ = kFirstWait_s;
  bool failing_ = false;
  Clock::time_point failing_since_{};
};

void worker_loop(const WorkOptions& options, std::size_t thread, const std::string& name, FactorizationCache& cache,
                 HeldJobs& held, Tally& tally) {
  // A claim waits for a lock at most --db-retry-s (up to the usual 60 s)
  // before it counts as failed: with the 60 s timeout alone, --db-retry-s 1
  // gave up after about 120 s. Storing results keeps the 60 s: a short
  // wait there would throw computed results away.
  const int claim_timeout_ms = static_cast<int>(std::clamp(1000.0 * options.db_retry_s, 100.0, 60000.0));
  constexpr int kStoreTimeoutMs = 60000;
  Database db(options.db_file, OpenMode::kExisting, kStoreTimeoutMs);
  JobQueue queue(db, name, options.lease_s);
  ClaimBackoff backoff(options.db_retry_s);
  std::string last_key;
  // The last model this thread read (a study's trains share it).
  ImportedStructures imports(1);
  const double idle_wait_s = std::clamp(options.lease_s / 4.0, 0.02, 0.2);
  for (;;) {
    std::vector<ClaimedJob> batch;
    bool finished = false;
    const std::uint64_t seen = held.generation();  // before the claim: no change is missed
    const auto attempt_started = Clock::now();
    try {
      db.set_busy_timeout(claim_timeout_ms);
      batch = queue.claim_batch(last_key, std::max<std::size_t>(1, options.max_batch_jobs), options.stopping);
      // Read under the claim's timeout and retry path: a database error
      // here had ended the thread with the error instead of retrying.
      finished = batch.empty() && nothing_left(db);
      db.set_busy_timeout(kStoreTimeoutMs);
      backoff.succeeded();
    } catch (const SqliteError& e) {
      db.set_busy_timeout(kStoreTimeoutMs);
      backoff.failed(name, e.what(), attempt_started);
      continue;
    }
    if (batch.empty()) {
      // Jobs still running elsewhere may come back if their worker dies:
      // wait for them rather than leave them behind. A job this process
      // could not put back is no longer renewed, so its lease expires and
      // the next claim takes it: the wait ends. A sibling thread that
      // finishes or puts back its batch ends the wait at once.
      if ((options.stopping != nullptr && options.stopping->load()) || finished) return;
      held.wait_for_change(seen, idle_wait_s);
      continue;
    }
    std::vector<std::string> ids;
    for (const ClaimedJob& j : batch) ids.push_back(j.id);
    held.hold(thread, ids);
    last_key = batch.front().operator_key;
    try {
      const std::vector<JobOutcome> outcomes = run_jobs(batch, cache, &imports);
      // One transaction for the whole batch: all stored, or (a crash) none.
      const std::vector<bool> stored = queue.complete_batch(batch, outcomes);
      for (std::size_t i = 0; i < batch.size(); ++i) {
        const ClaimedJob& job = batch[i];
        if (!stored[i]) {
          ++tally.lost;
          spdlog::warn("{}: job {} was taken over or cancelled while running; its result is dropped", name,
                       job.id.substr(0, 12));
        } else if (outcomes[i].ok) {
          ++tally.done;
        } else {
          ++tally.failed;
          // Names and messages are user strings: escaped before they reach a terminal.
          spdlog::warn("job {} ({} at {} km/h, {}) failed: {}", job.id.substr(0, 12), terminal_safe(job.train),
                       job.speed_kmh, terminal_safe(job.irregularity), terminal_safe(outcomes[i].error));
        }
      }
    } catch (const std::exception& e) {
      for (const ClaimedJob& job : batch) {
        spdlog::error("{}: job {} attempt {}: {}", name, job.id.substr(0, 12), job.attempt, terminal_safe(e.what()));
        try {
          queue.release_after_error(job, e.what());
        } catch (const std::exception& e2) {
          spdlog::error("{}: could not put job {} back in the queue: {}; its lease is no longer renewed and it "
                        "returns to the queue when the lease expires",
                        name, job.id.substr(0, 12), e2.what());
        }
      }
    }
    held.drop(thread);
  }
}

void heartbeat_loop(const WorkOptions& options, const std::vector<std::string>& names, HeldJobs& held,
                    StopSignal& stop) {
  std::unique_ptr<Database> db;
  const double period_s = options.lease_s / 3.0;
  while (!stop.wait_for(period_s)) {
    try {
      if (!db) db = std::make_unique<Database>(options.db_file, OpenMode::kExisting);
      const std::vector<std::vector<std::string>> jobs = held.snapshot();
      for (std::size_t k = 0; k < names.size(); ++k)
        if (!jobs[k].empty()) JobQueue(*db, names[k], options.lease_s).renew(jobs[k]);
    } catch (const std::exception& e) {
      spdlog::warn("heartbeat failed (will retry): {}", e.what());
      db.reset();
    }
  }
}

}  // namespace

std::string worker_name_prefix() {
  // The start time alone could repeat within a second (a restart loop);
  // 32 random bits make a collision negligible.
  std::random_device random;
  const auto start_s = static_cast<std::int64_t>(unix_now_s());
  return fmt::format("{}:{}:{}-{:08x}", host_name(), ::getpid(), start_s, random());
}

WorkProgress work_progress(Database& db, double now_s, double elapsed_s) {
  WorkProgress p;
  p.counts = state_counts(db);
  p.throughput = recent_throughput(db, {}, p.counts, now_s);
  p.elapsed_s = elapsed_s;
  return p;
}

void single_threaded_blas() {
  ::setenv("OPENBLAS_NUM_THREADS", "1", 1);
  // OpenBLAS reads the variable when it is loaded, before main: tell the
  // library itself too when it is the BLAS in use.
  using SetThreads = void (*)(int);
  if (auto* set = reinterpret_cast<SetThreads>(::dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
}

WorkSummary run_workers(const WorkOptions& options, const ProgressCallback& progress) {
  FactorizationCache cache(options.cache_budget_bytes);
  return run_workers(options, cache, progress);
}

WorkSummary run_workers(const WorkOptions& options, FactorizationCache& cache, const ProgressCallback& progress) {
  const auto start = Clock::now();
  {
    Database db(options.db_file, OpenMode::kExisting);
    migrate(db);
  }
  const CacheStats cache_before = cache.stats();
  Tally tally;
  const int threads = std::max(1, options.threads);
  std::vector<std::string> names;
  const std::string prefix = options.worker_prefix.empty() ? worker_name_prefix() : options.worker_prefix;
  for (int k = 0; k < threads; ++k) names.push_back(fmt::format("{}:t{}", prefix, k));
  HeldJobs held(names.size());

  std::unique_ptr<Database> monitor;
  const auto report = [&](bool final) {
    if (!progress) return;
    try {
      if (!monitor) monitor = std::make_unique<Database>(options.db_file, OpenMode::kExisting);
      progress(work_progress(*monitor, unix_now_s(), std::chrono::duration<double>(Clock::now() - start).count()),
               final);
    } catch (const SqliteError& e) {
      spdlog::warn("progress: {}", e.what());
    }
  };
  report(false);  // the state before this process starts

  StopSignal stop_heartbeat, workers_finished;
  std::thread heartbeat([&] { heartbeat_loop(options, names, held, stop_heartbeat); });
  std::atomic<int> running{threads};
  std::vector<std::thread> workers;
  for (std::size_t k = 0; k < names.size(); ++k)
    workers.emplace_back([&, k] {
      try {
        worker_loop(options, k, names[k], cache, held, tally);
      } catch (const std::exception& e) {
        spdlog::error("{}: stopped: {}", names[k], e.what());
        tally.stopped(e.what());
      }
      if (--running == 0) workers_finished.stop();
    });

  while (!workers_finished.wait_for(options.progress_interval_s)) report(false);
  for (auto& w : workers) w.join();
  stop_heartbeat.stop();
  heartbeat.join();
  report(true);

  WorkSummary summary;
  summary.jobs_done = tally.done;
  summary.jobs_failed = tally.failed;
  summary.lost_leases = tally.lost;
  summary.cache = cache.stats() - cache_before;
  summary.error = tally.error;
  summary.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace railvsi::scheduler
