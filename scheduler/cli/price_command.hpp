#pragma once
// `vsi price`: what accuracy costs in time, for a scene or for a sample of
// a study's jobs (results/planning/accuracy_price.hpp does the work).
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command_group.hpp"

namespace railvsi::cli {

struct PriceArgs {
  std::string scene_file;  // or db + study
  std::string db;
  std::string study_id;
  int jobs = 0;  // study: governing cases, plus spread jobs up to this many
  std::string format = "table";
  int threads = 1;
};

class PriceCommand final : public CommandGroup {
 public:
  explicit PriceCommand(CLI::App& app);
  std::optional<int> run_parsed() const override;

 private:
  PriceArgs args_;
  CLI::App* price_ = nullptr;
};

// Exit 0 when the reference run is ok, 1 when none of its runs is, 2 for
// bad input or usage.
int price_command(const PriceArgs& args);

}  // namespace railvsi::cli
