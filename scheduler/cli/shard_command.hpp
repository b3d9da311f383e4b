#pragma once
// Beyond one machine: vsi shard, merge, slurm and k8s (README "Running a
// study on a cluster").
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/command_group.hpp"

namespace railvsi::cli {

struct ClusterArgs {
  std::string study_file;  // a study document, or:
  std::string db;          // a store holding the study
  std::string study_id;    //   and its id
  int shards = 0;
  std::string out;
  bool allow_large = false;
  // merge
  std::vector<std::string> shard_files;
  std::string into;
  // slurm and k8s
  int cpus_per_task = 1;
  double lease_s = 60.0;
  std::string partition, time_limit, vsi_binary;
  int max_requeues = 3;
  bool submit = false;
  std::string image, claim = "railvsi-shards", memory = "2Gi";
  int backoff_limit_per_index = 3;
};

class ClusterCommands final : public CommandGroup {
 public:
  explicit ClusterCommands(CLI::App& app);
  // After app.parse(): the exit code of the subcommand parsed, nullopt when
  // none of these was.
  std::optional<int> run_parsed() const override;

 private:
  ClusterArgs args_;
  CLI::App *shard_ = nullptr, *merge_ = nullptr, *slurm_ = nullptr, *k8s_ = nullptr;
};

int shard_command(const ClusterArgs& args);
int merge_command(const ClusterArgs& args);
int slurm_command(const ClusterArgs& args);
int k8s_command(const ClusterArgs& args);

}  // namespace railvsi::cli
