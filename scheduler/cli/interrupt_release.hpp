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
  explicit InterruptRelease(std::string db_file);
  ~InterruptRelease();
  InterruptRelease(const InterruptRelease&) = delete;
  InterruptRelease& operator=(const InterruptRelease&) = delete;

 private:
  void watch();
  std::string db_file_;
  sigset_t signals_{}, previous_mask_{};
  std::atomic<bool> stop_{false};
  std::thread watcher_;
};

}  // namespace railvsi::cli
