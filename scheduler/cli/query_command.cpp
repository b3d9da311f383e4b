#include <iostream>

#include "cli/commands.hpp"
#include "cli/service_commands.hpp"
#include "cli/service_store.hpp"
#include "query/study_report.hpp"
#include "queue/job_queue.hpp"

namespace railvsi::cli {

int query_command(const ServiceArgs& args) {
  const auto db = open_store(args.db);
  const auto id = find_study(*db, args.study_id);
  if (!id) return kExitInvalidInput;
  const scheduler::StudyInfo info = scheduler::study_info(*db, *id);
  const auto jobs = scheduler::study_results(
      *db, {*id, args.train, args.speed_min_kmh, args.speed_max_kmh, args.irregularity});
  if (args.format == "csv")
    std::cout << scheduler::format_csv(jobs);
  else if (args.format == "json")
    std::cout << scheduler::format_json(info, jobs).dump(2) << '\n';
  else
    std::cout << scheduler::format_table(info, jobs);
  return kExitOk;
}

int cancel_command(const ServiceArgs& args) {
  const auto db = open_store(args.db);
  const auto id = find_study(*db, args.study_id);
  if (!id) return kExitInvalidInput;
  std::cout << "study " << *id << ": " << scheduler::cancel_study(*db, *id) << " jobs cancelled\n";
  return kExitOk;
}

int retry_command(const ServiceArgs& args) {
  const auto db = open_store(args.db);
  const auto id = find_study(*db, args.study_id);
  if (!id) return kExitInvalidInput;
  std::cout << "study " << *id << ": " << scheduler::retry_study(*db, *id) << " jobs queued again\n";
  return kExitOk;
}

}  // namespace railvsi::cli
