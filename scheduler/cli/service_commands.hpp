#pragma once
// The study service's subcommands of vsi: submit, work, run, status, query,
// cancel, retry, check. They share one database option, default
// ./vsi-results.sqlite; only submit and run create it.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

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

class ServiceCommands {
 public:
  // Adds the subcommands to app.
  explicit ServiceCommands(CLI::App& app);
  // After app.parse(): the exit code of the subcommand that was parsed,
  // nullopt when none of these was.
  std::optional<int> run_parsed() const;

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

}  // namespace railvsi::cli
