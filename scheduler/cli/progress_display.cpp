#include "cli/progress_display.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace railvsi::cli {

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60) : fmt::format("{}:{:02}", s / 60, s % 60);
}

ProgressDisplay::ProgressDisplay(bool terminal, double log_interval_s)
    : terminal_(terminal), log_interval_s_(log_interval_s) {}

void ProgressDisplay::update(const scheduler::StateCounts& c, double elapsed_s, bool final) {
  const std::int64_t finished = c.done + c.failed + c.cancelled;
  if (finished_at_start_ < 0) finished_at_start_ = finished;
  // The rate of this process's session: jobs finished since it started.
  const double rate = elapsed_s > 0.0 ? static_cast<double>(finished - finished_at_start_) / elapsed_s : 0.0;
  const std::string eta = rate > 0.0 ? format_duration(static_cast<double>(c.unfinished()) / rate) : "?";
  const std::int64_t total = std::max<std::int64_t>(c.total(), 1);
  if (terminal_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(kWidth * finished / total);
    std::fputs(fmt::format("\r[{}{}] {}/{} done, {} failed, {} running, {:.1f} jobs/s, ETA {}   ",
                           std::string(static_cast<std::size_t>(filled), '#'),
                           std::string(static_cast<std::size_t>(kWidth - filled), '.'), c.done, c.total(), c.failed,
                           c.running, rate, eta)
                   .c_str(),
               stderr);
    if (final) std::fputs("\n", stderr);
    std::fflush(stderr);
    return;
  }
  if (!final && elapsed_s - last_log_s_ < log_interval_s_) return;
  last_log_s_ = elapsed_s;
  spdlog::info("{}/{} jobs done, {} failed, {} queued, {} running; {:.2f} jobs/s, ETA {}", c.done, c.total(), c.failed,
               c.queued, c.running, rate, eta);
}

}  // namespace railvsi::cli
