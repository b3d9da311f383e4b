#pragma once
// Progress of `vsi work` / `vsi run`: on a terminal, one line redrawn with
// \r on stderr, fitted to the terminal's width (TIOCGWINSZ, else $COLUMNS,
// else 80); otherwise a plain log line every log_interval_s.
#include <string>

#include "workers/worker_pool.hpp"

namespace railvsi::cli {

class ProgressDisplay {
 public:
  explicit ProgressDisplay(bool terminal, double log_interval_s = 10.0);
  void update(const scheduler::WorkProgress& progress, bool final);

 private:
  bool terminal_;
  double log_interval_s_;
  double last_log_s_ = -1e9;
};

// The ETA as progress lines and `vsi status` print it: "4:05", "?" when
// there is none (no job finished in the throughput window).
std::string eta_text(const scheduler::Throughput& throughput);

// The progress text of a terminal, at most `width` columns: a bar when it
// fits, the counts, rate and ETA (shortened when they do not fit); `eta`
// from eta_text.
std::string progress_line(const scheduler::StateCounts& counts, double rate, const std::string& eta, int width);

// "1:02:03", "4:05"
std::string format_duration(double seconds);

}  // namespace railvsi::cli
