#include "workers/worker_pool.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/terminal_text.hpp"
#include "store/store_schema.hpp"
#include "workers/job_runner.hpp"

namespace railvsi::scheduler {
namespace {

using Clock = std::chrono::steady_clock;

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "host";
  return name;
}

// What the worker threads report back; only atomics cross threads.
struct Tally {
  std::atomic<std::int64_t> done{0}, failed{0}, lost{0};
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

void worker_loop(const WorkOptions& options, const std::string& name, FactorizationCache& cache, Tally& tally) {
  Database db(options.db_file);
  JobQueue queue(db, name, options.lease_s);
  std::string last_key;
  const double idle_wait_s = std::clamp(options.lease_s / 4.0, 0.02, 0.2);
  for (;;) {
    std::optional<ClaimedJob> job;
    try {
      job = queue.claim(last_key);
    } catch (const SqliteError& e) {
      spdlog::warn("{}: claim failed, retrying: {}", name, e.what());
      std::this_thread::sleep_for(std::chrono::duration<double>(idle_wait_s));
      continue;
    }
    if (!job) {
      // Jobs still running elsewhere may come back if their worker dies:
      // wait for them rather than leave them behind.
      if (nothing_left(db)) return;
      std::this_thread::sleep_for(std::chrono::duration<double>(idle_wait_s));
      continue;
    }
    last_key = job->operator_key;
    try {
      const JobOutcome outcome = run_job(*job, cache);
      if (!queue.complete(*job, outcome)) {
        ++tally.lost;
        spdlog::warn("{}: job {} was taken over or cancelled while running; its result is dropped", name,
                     job->id.substr(0, 12));
      } else if (outcome.ok) {
        ++tally.done;
      } else {
        ++tally.failed;
        // Names and messages are user strings: escaped before they reach a terminal.
        spdlog::warn("job {} ({} at {} km/h, {}) failed: {}", job->id.substr(0, 12), terminal_safe(job->train),
                     job->speed_kmh, terminal_safe(job->irregularity), terminal_safe(outcome.error));
      }
    } catch (const std::exception& e) {
      spdlog::error("{}: job {} attempt {}: {}", name, job->id.substr(0, 12), job->attempt, terminal_safe(e.what()));
      try {
        queue.release_after_error(*job, e.what());
      } catch (const std::exception& e2) {
        spdlog::error("{}: could not release job {}: {} (its lease will expire)", name, job->id.substr(0, 12), e2.what());
      }
    }
  }
}

void heartbeat_loop(const WorkOptions& options, const std::vector<std::string>& names, StopSignal& stop) {
  std::unique_ptr<Database> db;
  const double period_s = options.lease_s / 3.0;
  while (!stop.wait_for(period_s)) {
    try {
      if (!db) db = std::make_unique<Database>(options.db_file);
      for (const std::string& name : names) JobQueue(*db, name, options.lease_s).heartbeat();
    } catch (const std::exception& e) {
      spdlog::warn("heartbeat failed (will retry): {}", e.what());
      db.reset();
    }
  }
}

}  // namespace

void single_threaded_blas() {
  ::setenv("OPENBLAS_NUM_THREADS", "1", 1);
  // OpenBLAS reads the variable when it is loaded, before main: tell the
  // library itself too when it is the BLAS in use.
  using SetThreads = void (*)(int);
  if (auto* set = reinterpret_cast<SetThreads>(::dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
}

WorkSummary run_workers(const WorkOptions& options, const ProgressCallback& progress) {
  const auto start = Clock::now();
  {
    Database db(options.db_file);
    migrate(db);
  }
  FactorizationCache cache(options.cache_budget_bytes);
  Tally tally;
  const int threads = std::max(1, options.threads);
  std::vector<std::string> names;
  const std::string prefix = fmt::format("{}:{}", host_name(), ::getpid());
  for (int k = 0; k < threads; ++k) names.push_back(fmt::format("{}:t{}", prefix, k));

  std::unique_ptr<Database> monitor;
  const auto report = [&](bool final) {
    if (!progress) return;
    try {
      if (!monitor) monitor = std::make_unique<Database>(options.db_file);
      progress(state_counts(*monitor), std::chrono::duration<double>(Clock::now() - start).count(), final);
    } catch (const SqliteError& e) {
      spdlog::warn("progress: {}", e.what());
    }
  };
  report(false);  // the state before this process starts: the baseline of its rate

  StopSignal stop_heartbeat, workers_finished;
  std::thread heartbeat([&] { heartbeat_loop(options, names, stop_heartbeat); });
  std::atomic<int> running{threads};
  std::vector<std::thread> workers;
  for (const std::string& name : names)
    workers.emplace_back([&, name] {
      try {
        worker_loop(options, name, cache, tally);
      } catch (const std::exception& e) {
        spdlog::error("{}: stopped: {}", name, e.what());
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
  summary.cache = cache.stats();
  summary.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace railvsi::scheduler
