#pragma once
// Progress of `vsi work` / `vsi run`: a bar with the ETA redrawn on stderr
// when it is a terminal, else a plain log line every few seconds.
#include "queue/job_queue.hpp"

namespace railvsi::cli {

class ProgressDisplay {
 public:
  explicit ProgressDisplay(bool terminal, double log_interval_s = 10.0);
  void update(const scheduler::StateCounts& counts, double elapsed_s, bool final);

 private:
  bool terminal_;
  double log_interval_s_;
  double last_log_s_ = -1e9;
  std::int64_t finished_at_start_ = -1;
};

// "1:02:03", "4:05"
std::string format_duration(double seconds);

}  // namespace railvsi::cli
