#include "cli/service_commands.hpp"

#include <thread>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "workers/worker_pool.hpp"

namespace railvsi::cli {
namespace {

void add_db_option(CLI::App* command, ServiceArgs& a) {
  command->add_option("--db", a.db, "Study database (SQLite file; created if needed)")->capture_default_str();
}

void add_work_options(CLI::App* command, ServiceArgs& a) {
  command->add_option("--threads", a.threads, "Worker threads (default: one per core)")->check(CLI::NonNegativeNumber);
  command->add_option("--lease-s", a.lease_s, "Lease of a claimed job in s; a job whose worker stops renewing it "
                                              "returns to the queue when it expires")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--cache-mb", a.cache_mb, "Memory budget of the factorization cache in MB")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
}

void add_submit_options(CLI::App* command, ServiceArgs& a) {
  command->add_option("study", a.study_file, "Study file (JSON, schemas/study.schema.json)")->required();
  command->add_flag("--allow-large", a.allow_large, "Accept a study of more than 100,000 jobs");
  command->add_option("--max-attempts", a.max_attempts,
                      "Attempts of a job before it ends failed (a worker that died counts as one)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
}

void add_study_id(CLI::App* command, ServiceArgs& a, bool required) {
  auto* option = command->add_option("--study", a.study_id, "Study id (or a unique prefix of at least 6 digits)");
  if (required) option->required();
}

}  // namespace

ServiceCommands::ServiceCommands(CLI::App& app) {
  submit_ = app.add_subcommand("submit", "Expand a study into jobs and queue them; prints the study id and job count");
  add_submit_options(submit_, args_);
  add_db_option(submit_, args_);

  work_ = app.add_subcommand("work", "Run queued jobs until none is left (several processes may share a database)");
  add_db_option(work_, args_);
  add_work_options(work_, args_);

  run_ = app.add_subcommand("run", "Submit a study, work until the queue is empty, print the study's envelope table");
  add_submit_options(run_, args_);
  add_db_option(run_, args_);
  add_work_options(run_, args_);

  status_ = app.add_subcommand("status", "Jobs per state, throughput, ETA and factorization cache of each study");
  add_db_option(status_, args_);
  add_study_id(status_, args_, false);

  query_ = app.add_subcommand("query", "Envelopes of a study: per job and per train over speeds");
  add_db_option(query_, args_);
  add_study_id(query_, args_, true);
  query_->add_option("--format", args_.format, "table, csv (envelope values only) or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"table", "csv", "json"}));
  query_->add_option("--train", args_.train, "Only this train (its name as shown)");
  query_->add_option("--speed-min", args_.speed_min_kmh, "Only speeds >= this, km/h");
  query_->add_option("--speed-max", args_.speed_max_kmh, "Only speeds <= this, km/h");
  query_->add_option("--irregularity", args_.irregularity, "Only this irregularity profile (its label as shown)");

  cancel_ = app.add_subcommand("cancel", "Cancel the queued and running jobs of a study");
  add_db_option(cancel_, args_);
  add_study_id(cancel_, args_, true);

  retry_ = app.add_subcommand("retry", "Queue the failed and cancelled jobs of a study again");
  add_db_option(retry_, args_);
  add_study_id(retry_, args_, true);
}

std::optional<int> ServiceCommands::run_parsed() const {
  const std::pair<CLI::App*, int (*)(const ServiceArgs&)> commands[] = {
      {submit_, submit_command}, {work_, work_command},     {run_, run_command},    {status_, status_command},
      {query_, query_command},   {cancel_, cancel_command}, {retry_, retry_command}};
  for (const auto& [command, run] : commands) {
    if (!command->parsed()) continue;
    // Logs go to stderr: stdout carries the results.
    spdlog::set_default_logger(spdlog::stderr_color_mt("vsi"));
    scheduler::single_threaded_blas();
    ServiceArgs args = args_;
    if (args.threads == 0) args.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    return run(args);
  }
  return std::nullopt;
}

}  // namespace railvsi::cli
