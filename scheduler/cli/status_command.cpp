#include <iostream>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/progress_display.hpp"
#include "cli/service_commands.hpp"
#include "cli/service_store.hpp"
#include "core/terminal_text.hpp"
#include "query/study_status.hpp"

namespace railvsi::cli {

int status_command(const ServiceArgs& args) {
  const auto db = open_store(args.db);
  std::vector<std::string> ids;
  if (!args.study_id.empty()) {
    const auto id = find_study(*db, args.study_id);
    if (!id) return kExitInvalidInput;
    ids.push_back(*id);
  } else {
    ids = scheduler::study_ids(*db);
  }
  if (ids.empty()) std::cout << "no studies in " << args.db << '\n';
  for (const std::string& id : ids) {
    const scheduler::StudyStatus s = scheduler::study_status(*db, id);
    const auto& c = s.counts;
    std::cout << fmt::format("study {} ({})\n", s.id, scheduler::terminal_safe(s.name));
    std::cout << fmt::format("  jobs: {} total, {} queued, {} running, {} done, {} failed, {} cancelled\n", c.total(),
                             c.queued, c.running, c.done, c.failed, c.cancelled);
    if (s.jobs_per_s)
      std::cout << fmt::format("  throughput: {:.2f} jobs/s{}\n", *s.jobs_per_s,
                               c.unfinished() > 0 ? ", ETA " + format_duration(*s.eta_s) : std::string());
    if (s.job_wall_s > 0.0)
      std::cout << fmt::format("  job time: {:.1f} s, of which {:.1f} s in time loops ({:.0f} %)\n", s.job_wall_s,
                               s.loop_s, 100.0 * s.loop_s / s.job_wall_s);
    std::cout << fmt::format("  factorization cache: {} factorizations ({:.2f} s), {} hits, {} evictions\n",
                             s.factorizations, s.factorization_s, s.cache_hits, s.evictions);
  }
  return kExitOk;
}

}  // namespace railvsi::cli
