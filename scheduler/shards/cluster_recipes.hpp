#pragma once
// What `vsi slurm` and `vsi k8s` write beside the shards: a Slurm job array
// (task K works shard K) with a dependent merge job, and a Kubernetes
// Indexed Job (completion index K works shard K) with a merge Job. Only
// the shard directory is shared between the tasks; each shard file is
// opened by one task at a time.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace railvsi::scheduler {

struct ClusterStudy {
  std::string study_id;
  std::string study_name;
  int shards = 1;
  int cpus_per_task = 1;  // worker threads of each task
  double lease_s = 60.0;  // vsi work --lease-s: how long a resumed task waits for a killed worker's job
};

struct SlurmOptions {
  ClusterStudy study;
  std::filesystem::path dir;     // the shard directory, absolute, the same path on every node
  std::filesystem::path vsi;     // the vsi binary, absolute, the same path on every node
  std::string partition;         // empty: the cluster's default
  std::string time_limit;        // empty: the partition's default
  int max_requeues = 3;          // requeues of a task whose worker died, before it fails
};

struct SlurmScripts {
  std::string array_script;  // slurm-array.sh
  std::string merge_script;  // slurm-merge.sh
};

SlurmScripts slurm_scripts(const SlurmOptions& options);

struct K8sOptions {
  ClusterStudy study;
  std::string image;                      // the docker/ image (vsi on PATH)
  std::string claim = "railvsi-shards";   // PersistentVolumeClaim holding the shard directory
  std::string mount_path = "/shards";
  std::string memory = "2Gi";
  int backoff_limit_per_index = 3;
};

// The Indexed Job (one completion per shard) and the merge Job, as JSON
// manifests (kubectl apply -f takes JSON as it takes YAML).
nlohmann::ordered_json k8s_shard_job(const K8sOptions& options);
nlohmann::ordered_json k8s_merge_job(const K8sOptions& options);
// Kubernetes object names of the two Jobs.
std::string k8s_shard_job_name(const std::string& study_id);
std::string k8s_merge_job_name(const std::string& study_id);

// A word for a POSIX shell: single-quoted, embedded quotes escaped.
std::string shell_quote(const std::string& text);

}  // namespace railvsi::scheduler
