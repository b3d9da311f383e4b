#pragma once
// `vsi serve`: the study service over HTTP (http/study_api.hpp) with a
// worker pool that runs the store's queue as `vsi work` does.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command_group.hpp"
#include "cli/service_commands.hpp"

namespace railvsi::cli {

struct ServeArgs {
  ServiceArgs service;  // --db, --threads (0: accept only) and the work options
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port (the one taken is printed)
  std::string token;  // else RAILVSI_TOKEN
  double max_body_mb = 16.0;
};

class ServeCommand final : public CommandGroup {
 public:
  explicit ServeCommand(CLI::App& app);
  std::optional<int> run_parsed() const override;

 private:
  ServeArgs args_;
  CLI::App* serve_ = nullptr;
};

// Exit 2 for bad options (a non-loopback address without a token); 1 when the
// address cannot be bound; SIGINT/SIGTERM exit 128 + the signal, the running
// jobs given back to the queue.
int serve_command(const ServeArgs& args);

}  // namespace railvsi::cli
