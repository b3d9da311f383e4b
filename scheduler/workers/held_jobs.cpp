#include "workers/held_jobs.hpp"

#include <chrono>

namespace railvsi::scheduler {

HeldJobs::HeldJobs(std::size_t threads) : jobs_of_thread_(threads) {}

void HeldJobs::hold(std::size_t thread, std::vector<std::string> job_ids) {
  {
    std::lock_guard lock(mutex_);
    jobs_of_thread_[thread] = std::move(job_ids);
    ++generation_;
  }
  changed_.notify_all();
}

std::vector<std::vector<std::string>> HeldJobs::snapshot() {
  std::lock_guard lock(mutex_);
  return jobs_of_thread_;
}

std::uint64_t HeldJobs::generation() {
  std::lock_guard lock(mutex_);
  return generation_;
}

bool HeldJobs::wait_for_change(std::uint64_t seen, double seconds) {
  std::unique_lock lock(mutex_);
  return changed_.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return generation_ != seen; });
}

}  // namespace railvsi::scheduler
