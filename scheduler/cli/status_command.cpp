#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/progress_display.hpp"
#include "cli/service_commands.hpp"
#include "cli/service_store.hpp"
#include "core/terminal_text.hpp"
#include "query/study_status.hpp"
#include "store/store_check.hpp"

namespace railvsi::cli {

int status_command(const ServiceArgs& args) {
  const auto db = open_store(args.db, scheduler::OpenMode::kReadOnly);
  std::vector<std::string> ids;
  if (!args.study_id.empty()) {
    const auto id = find_study(*db, args.study_id);
    if (!id) return kExitInvalidInput;
    ids.push_back(*id);
  } else {
    ids = scheduler::study_ids(*db);
  }
  // Printed only once every read succeeded: an error is never a partial report.
  std::ostringstream out;
  if (ids.empty()) out << "no studies in " << args.db << '\n';
  for (const std::string& id : ids) {
    scheduler::require_consistent_study(*db, id);
    const scheduler::StudyStatus s = scheduler::study_status(*db, id);
    const auto& c = s.counts;
    out << fmt::format("study {} ({})\n", s.id, scheduler::terminal_safe(s.name));
    out << fmt::format("  jobs: {} total, {} queued, {} running, ", c.total(), c.queued, c.running - s.stale_leases);
    if (s.stale_leases > 0) out << fmt::format("{} running (lease expired), ", s.stale_leases);
    out << fmt::format("{} done, {} failed, {} cancelled\n", c.done, c.failed, c.cancelled);
    if (s.jobs_per_s) {
      out << fmt::format("  throughput: {:.2f} jobs/s over the last {:.0f} s of work", *s.jobs_per_s,
                         scheduler::kThroughputWindow_s);
      if (c.unfinished() > 0)
        out << (s.eta_s ? ", ETA " + eta_text({s.jobs_per_s, s.eta_s})  // as vsi work shows it
                        : std::string(", no job finished recently: no ETA"));
      out << '\n';
    }
    if (s.job_wall_s > 0.0)
      out << fmt::format("  job time: {:.1f} s, of which {:.1f} s in time loops ({:.0f} %)\n", s.job_wall_s, s.loop_s,
                         100.0 * s.loop_s / s.job_wall_s);
    out << fmt::format("  factorization cache: {} factorizations ({:.2f} s), {} jobs reused one (hits), {} evictions\n",
                       s.factorizations, s.factorization_s, s.cache_hits, s.evictions);
  }
  std::cout << out.str();
  return kExitOk;
}

int check_command(const ServiceArgs& args) {
  // Read-only, without the schema check: a damaged file must still be examined.
  scheduler::StoreCheck check;
  try {
    scheduler::Database db(args.db, scheduler::OpenMode::kReadOnly);
    check = scheduler::check_store(db);
  } catch (const scheduler::SqliteError& e) {  // damage where opening reads (the schema)
    check.problems.push_back(fmt::format("cannot be read: {}", e.what()));
  }
  for (const std::string& problem : check.problems) std::cout << "problem: " << problem << '\n';
  if (check.problems.empty()) {
    std::cout << fmt::format("ok: {}: {} studies, {} jobs; integrity, foreign keys and queue consistent\n", args.db,
                             check.studies, check.jobs);
    return kExitOk;
  }
  std::cerr << fmt::format("error: {}: {} problems (above)\n", args.db, check.problems.size());
  return kExitRuntimeFailure;
}

}  // namespace railvsi::cli
