#include "cli/service_commands.hpp"

#include <cmath>
#include <iostream>
#include <thread>

#include <fmt/format.h>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "cli/verdict_exit.hpp"
#include "store/sqlite.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::cli {
namespace {

void add_db_option(CLI::App* command, ServiceArgs& a, bool creates) {
  command->add_option("--db", a.db, creates ? "Study database (SQLite file; created if needed)"
                                            : "Study database (SQLite file; must exist)")
      ->capture_default_str();
}

void add_work_options(CLI::App* command, ServiceArgs& a) {
  command->add_option("--threads", a.threads, "Worker threads (default: one per core)")->check(CLI::Range(1, 256));
  command->add_option("--lease-s", a.lease_s, "Lease of a claimed job in s; a job whose worker stops renewing it "
                                              "returns to the queue when it expires")
      ->capture_default_str()
      ->check(finite_in(kLeaseMinS, kLeaseMaxS));
  command->add_option("--cache-mb", a.cache_mb, "Memory budget of the factorization cache in MB")
      ->capture_default_str()
      ->check(finite_in(1.0, 1.0e7));
  command->add_option("--db-retry-s", a.db_retry_s,
                      "How long to retry a database that refuses claims (disk full, locked) before exiting 1")
      ->capture_default_str()
      ->check(finite_in(1.0, 86400.0));
  command->add_option("--batch", a.batch,
                      "Modal moving-force jobs of one structure (and time step) claimed, run and stored together "
                      "(1: one by one; the results are the same bits)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
}

void add_submit_options(CLI::App* command, ServiceArgs& a) {
  command->add_option("study", a.study_file, "Study file (JSON, schemas/study.schema.json)")->required();
  command->add_flag("--allow-large", a.allow_large, "Accept a study of more than 100,000 jobs");
  command->add_option("--max-attempts", a.max_attempts,
                      "Attempts of a job before it ends failed (a worker that died counts as one)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
}

void add_study_id(CLI::App* command, ServiceArgs& a, bool required) {
  auto* option = command->add_option("--study", a.study_id, "Study id (or a unique prefix of at least 6 digits)");
  if (required) option->required();
}

}  // namespace

ServiceCommands::ServiceCommands(CLI::App& app) {
  submit_ = app.add_subcommand("submit", "Expand a study into jobs and queue them; prints the study id and job count");
  add_submit_options(submit_, args_);
  add_db_option(submit_, args_, true);

  work_ = app.add_subcommand("work", "Run queued jobs until none is left (several processes may share a database)");
  add_db_option(work_, args_, false);
  add_work_options(work_, args_);

  run_ = app.add_subcommand("run", "Submit a study, work until the queue is empty, print the study's envelope table (a line study's: its line table, a row per bridge)");
  add_submit_options(run_, args_);
  add_db_option(run_, args_, true);
  add_work_options(run_, args_);
  run_->add_flag("--fail-on-exceeded", args_.fail_on_exceeded, kFailOnExceededHelp);
  run_->footer(verdict_exit_footer(true));

  status_ = app.add_subcommand("status", "Jobs per state, throughput, ETA and factorization cache of each study");
  add_db_option(status_, args_, false);
  add_study_id(status_, args_, false);

  query_ = app.add_subcommand("query", "Envelopes of a study: per job and per train over speeds");
  add_db_option(query_, args_, false);
  add_study_id(query_, args_, true);
  query_->add_option("--format", args_.format,
                     "table, csv (one line per envelope value, and per job without values, with its state) or json "
                     "(with the checks' verdicts)")
      ->capture_default_str()
      ->check(CLI::IsMember({"table", "csv", "json"}));
  query_->add_flag("--wide", args_.wide,
                   "With --format csv: one line per train x speed x profile, one column per quantity x location");
  query_->add_flag("--fail-on-exceeded", args_.fail_on_exceeded, kFailOnExceededHelp);
  query_->footer(verdict_exit_footer(false));
  query_->add_option("--train", args_.train, "Only this train (its name as shown)");
  query_->add_option("--speed-min", args_.speed_min_kmh, "Only speeds >= this, km/h")->check(finite_in(0.0, 1.0e4));
  query_->add_option("--speed-max", args_.speed_max_kmh, "Only speeds <= this, km/h")->check(finite_in(0.0, 1.0e4));
  query_->add_option("--irregularity", args_.irregularity, "Only this irregularity profile (its label as shown)");
  query_->add_option("--structure", args_.structure, "Only this bridge of a line study (its name in \"structures\")");
  query_->add_flag("--line", args_.line,
                   "The line table of a line study: one row per bridge with the verdict of each check, its governing "
                   "value, train and speed (csv: one line per bridge and check; json: one object per bridge)");

  cancel_ = app.add_subcommand("cancel", "Cancel the queued and running jobs of a study");
  add_db_option(cancel_, args_, false);
  add_study_id(cancel_, args_, true);

  retry_ = app.add_subcommand("retry", "Queue the failed and cancelled jobs of a study again");
  add_db_option(retry_, args_, false);
  add_study_id(retry_, args_, true);

  check_ = app.add_subcommand("check", "Check a study database: SQLite integrity, foreign keys and the queue's "
                                       "invariants; exit 0 when sound, 1 when not");
  add_db_option(check_, args_, false);
}

std::optional<int> ServiceCommands::run_parsed() const {
  const std::pair<CLI::App*, int (*)(const ServiceArgs&)> commands[] = {
      {submit_, submit_command}, {work_, work_command},     {run_, run_command},    {status_, status_command},
      {query_, query_command},   {cancel_, cancel_command}, {retry_, retry_command},  {check_, check_command}};
  for (const auto& [command, run] : commands) {
    if (!command->parsed()) continue;
    // Logs go to stderr: stdout carries the results.
    spdlog::set_default_logger(spdlog::stderr_color_mt("vsi"));
    scheduler::single_threaded_blas();
    ServiceArgs args = args_;
    if (args.threads == 0) args.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    try {
      return run(args);
    } catch (const scheduler::NoSuchDatabase& e) {  // a typo in --db must not become an empty database
      std::cerr << "error: " << e.what() << '\n';
      return kExitInvalidInput;
    }
  }
  return std::nullopt;
}

}  // namespace railvsi::cli
