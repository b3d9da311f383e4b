#pragma once
// The study service's subcommands of vsi: submit, work, run, status, query,
// cancel, retry, check. They share one database option, default
// ./vsi-results.sqlite; only submit and run create it.
#include <atomic>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/command_group.hpp"
#include "queue/job_queue.hpp"
#include "store/sqlite.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::cli {

struct ServiceArgs {
  std::string db = "vsi-results.sqlite";
  std::string study_file;
  std::string study_id;
  int threads = 0;  // 0: one per core
  double lease_s = 60.0;
  int max_attempts = 3;
  double cache_mb = 2048.0;
  double db_retry_s = 300.0;
  int batch = 256;  // modal jobs claimed, run and stored together
  bool allow_large = false;
  std::string format = "table";
  bool wide = false;              // query --format csv --wide
  bool fail_on_exceeded = false;  // query, run: exit 4 / 5 on the checks' verdict
  std::optional<std::string> train, irregularity, structure;  // query filters
  bool line = false;  // query --line: one row per bridge of a line study
  std::optional<double> speed_min_kmh, speed_max_kmh;
};

class ServiceCommands final : public CommandGroup {
 public:
  // Adds the subcommands to app.
  explicit ServiceCommands(CLI::App& app);
  // After app.parse(): the exit code of the subcommand that was parsed,
  // nullopt when none of these was.
  std::optional<int> run_parsed() const override;

 private:
  ServiceArgs args_;
  CLI::App *submit_ = nullptr, *work_ = nullptr, *run_ = nullptr, *status_ = nullptr, *query_ = nullptr,
           *cancel_ = nullptr, *retry_ = nullptr, *check_ = nullptr;
};

int submit_command(const ServiceArgs& args);
int work_command(const ServiceArgs& args);
int run_command(const ServiceArgs& args);
int status_command(const ServiceArgs& args);
int query_command(const ServiceArgs& args);
int cancel_command(const ServiceArgs& args);
int retry_command(const ServiceArgs& args);
int check_command(const ServiceArgs& args);

// The bodies the commands share with vsi serve (one implementation each).
// vsi submit without its output line: expands and validates args.study_file
// (InputError when anything is wrong: nothing is enqueued), then queues it.
scheduler::SubmitResult submit_study_file(const ServiceArgs& args);
// vsi query: what it prints on stdout to `out`, its errors and warnings to
// `err`; returns its exit code. args.study_id must name a study.
int write_query(const ServiceArgs& args, std::ostream& out, std::ostream& err);
// A caller that takes SIGINT and SIGTERM itself (vsi serve holds one
// InterruptRelease for its whole life): its workers' name prefix and stop flag.
struct WorkerIdentity {
  std::string prefix;
  const std::atomic<bool>* stopping = nullptr;
};
// vsi work's loop: work until the queue is empty, then the studies'
// refinement passes and verification runs. Without `identity`, the call
// holds its own InterruptRelease, as vsi work does.
// The passes share one cache: `cache` when given (vsi run's, which its
// submission filled), else one of args.cache_mb made for this call.
scheduler::WorkSummary work_and_refine(const ServiceArgs& args, scheduler::Database& db,
                                       const std::vector<std::string>& studies,
                                       const WorkerIdentity* identity = nullptr,
                                       scheduler::FactorizationCache* cache = nullptr);

}  // namespace railvsi::cli
