#include "cli/progress_display.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include "core/terminal_text.hpp"

namespace railvsi::cli {

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60) : fmt::format("{}:{:02}", s / 60, s % 60);
}

std::string progress_line(const scheduler::StateCounts& c, double rate, const std::string& eta, int width) {
  const std::int64_t finished = c.done + c.failed + c.cancelled;
  const std::int64_t total = std::max<std::int64_t>(c.total(), 1);
  std::string text = fmt::format("{}/{} done, {} failed, {} running, {:.1f} jobs/s, ETA {}", c.done, c.total(),
                                 c.failed, c.running, rate, eta);
  if (static_cast<int>(text.size()) > width) text = fmt::format("{}/{} done, ETA {}", c.done, c.total(), eta);
  // A bar of up to 30 cells in front when at least 10 fit.
  const int bar = std::min(30, width - static_cast<int>(text.size()) - 3);
  if (bar >= 10) {
    const auto filled = static_cast<std::size_t>(bar * finished / total);
    text = fmt::format("[{}{}] {}", std::string(filled, '#'), std::string(static_cast<std::size_t>(bar) - filled, '.'),
                       text);
  }
  if (static_cast<int>(text.size()) > width) text.resize(static_cast<std::size_t>(std::max(0, width)));
  return text;
}

ProgressDisplay::ProgressDisplay(bool terminal, double log_interval_s)
    : terminal_(terminal), log_interval_s_(log_interval_s) {}

std::string eta_text(const scheduler::Throughput& throughput) {
  return throughput.eta_s ? format_duration(*throughput.eta_s) : std::string("?");
}

void ProgressDisplay::update(const scheduler::WorkProgress& progress, bool final) {
  // The store's recent rate and ETA, as `vsi status` computes them (not this
  // session's own average, which disagreed with status in the same second).
  const scheduler::StateCounts& c = progress.counts;
  const double rate = progress.throughput.jobs_per_s.value_or(0.0);
  const std::string eta = eta_text(progress.throughput);
  if (terminal_) {
    // One line rewritten in place: never wider than the terminal (less one
    // column, so that the cursor does not wrap), padded to erase the last one.
    const int width = std::max(1, scheduler::terminal_columns(STDERR_FILENO) - 1);
    std::string line = progress_line(c, rate, eta, width);
    line.resize(static_cast<std::size_t>(width), ' ');
    std::fputs("\r", stderr);
    std::fputs(line.c_str(), stderr);
    if (final) std::fputs("\n", stderr);
    std::fflush(stderr);
    return;
  }
  if (!final && progress.elapsed_s - last_log_s_ < log_interval_s_) return;
  last_log_s_ = progress.elapsed_s;
  spdlog::info("{}/{} jobs done, {} failed, {} queued, {} running; {:.2f} jobs/s, ETA {}", c.done, c.total(), c.failed,
               c.queued, c.running, rate, eta);
}

}  // namespace railvsi::cli
