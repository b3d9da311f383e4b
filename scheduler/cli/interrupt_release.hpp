#pragma once
// Ctrl-C (SIGINT) or SIGTERM while this process works a store: the jobs its
// workers are running go back to the queue at once (their attempt not
// counted) and the process exits 128 + the signal. Before, they stayed
// `running` until their lease expired, and the next `vsi run` waited for it
// (61 s for one Eurostar job in a user trial).
//
// While an InterruptRelease lives, SIGINT and SIGTERM are blocked in the
// thread that made it and in every thread started after (the workers), and
// one thread of its own takes them with sigtimedwait.
#include <atomic>
#include <csignal>
#include <string>
#include <thread>

namespace railvsi::cli {

class InterruptRelease {
 public:
  // worker_prefix: the run's worker_name_prefix(), given to run_workers too
  // (WorkOptions::worker_prefix): only this run's jobs are given back, not
  // those of another process with the same host name and PID (containers).
  InterruptRelease(std::string db_file, std::string worker_prefix);
  ~InterruptRelease();
  InterruptRelease(const InterruptRelease&) = delete;
  InterruptRelease& operator=(const InterruptRelease&) = delete;

  // Set before the jobs are given back: WorkOptions::stopping, so that no
  // worker claims a job after the release.
  const std::atomic<bool>* stopping() const { return &stopping_; }

 private:
  void watch();
  std::string db_file_, worker_prefix_;
  sigset_t signals_{}, previous_mask_{};
  std::atomic<bool> done_{false}, stopping_{false};
  std::thread watcher_;
};

}  // namespace railvsi::cli
