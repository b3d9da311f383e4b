#pragma once
// The jobs each worker thread of a process holds (one, or a batch): the
// heartbeat renews exactly these (by job id and worker name), nothing else
// the name might match; and a thread that finds nothing to claim while its
// siblings still run waits for one of them to take or let go of jobs,
// rather than sleep out its idle wait (a sweep's last batch then ended up
// to 0.2 s before the idle thread noticed: a whole `vsi run` of the
// 1,010-job HSLM sweep took 0.38 s of wall with two threads, 0.22 s with one).
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace railvsi::scheduler {

class HeldJobs {
 public:
  explicit HeldJobs(std::size_t threads);

  void hold(std::size_t thread, std::vector<std::string> job_ids);
  void drop(std::size_t thread) { hold(thread, {}); }
  // thread -> job ids; empty when it holds none.
  std::vector<std::vector<std::string>> snapshot();

  // Counts every hold and drop: read it before a claim, then wait on it.
  std::uint64_t generation();
  // Until a thread holds or drops jobs after `seen` (true), or `seconds`
  // have passed (false).
  bool wait_for_change(std::uint64_t seen, double seconds);

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<std::vector<std::string>> jobs_of_thread_;
  std::uint64_t generation_ = 0;
};

}  // namespace railvsi::scheduler
