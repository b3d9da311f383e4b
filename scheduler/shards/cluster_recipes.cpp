#include "shards/cluster_recipes.hpp"

#include <fmt/format.h>

#include "shards/shard_store.hpp"

namespace railvsi::scheduler {

using nlohmann::ordered_json;

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

namespace {

std::string short_id(const std::string& study_id) { return study_id.substr(0, 12); }

// The shebang, a comment naming the study (its name on one line: it comes
// from the user's document and must not end the comment) and the
// directives both scripts share.
std::string script_head(const SlurmOptions& o, const std::string& what, const std::string& job_name,
                        const std::string& log) {
  std::string name = o.study.study_name;
  for (char& c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  std::string s = fmt::format("#!/bin/bash\n# railvsi study {} ({}): {}\n", o.study.study_id, name, what);
  s += fmt::format("#SBATCH --job-name={}\n", job_name);
  if (!o.partition.empty()) s += fmt::format("#SBATCH --partition={}\n", o.partition);
  if (!o.time_limit.empty()) s += fmt::format("#SBATCH --time={}\n", o.time_limit);
  s += fmt::format("#SBATCH --output={}\n", (o.dir / "logs" / log).string());
  s += "#SBATCH --open-mode=append\n";
  return s;
}

}  // namespace

SlurmScripts slurm_scripts(const SlurmOptions& o) {
  const ClusterStudy& st = o.study;
  const std::string dir = shell_quote(o.dir.string());
  const std::string vsi = shell_quote(o.vsi.string());
  SlurmScripts out;
  out.array_script = fmt::format(
      "{head}"
      "#SBATCH --array=0-{last}\n"
      "#SBATCH --cpus-per-task={cpus}\n"
      "#SBATCH --requeue\n"
      "set -u\n"
      "export OPENBLAS_NUM_THREADS=1\n"
      "shard={dir}/shard-${{SLURM_ARRAY_TASK_ID}}.sqlite\n"
      "echo \"$(date -u +%FT%TZ) task ${{SLURM_ARRAY_JOB_ID}}_${{SLURM_ARRAY_TASK_ID}} on $(hostname), "
      "restart ${{SLURM_RESTART_COUNT:-0}}: $shard\"\n"
      "# A resumed shard keeps its finished jobs; the job a killed worker held\n"
      "# returns to the queue when its lease ({lease} s) expires.\n"
      "{vsi} work --db \"$shard\" --threads \"${{SLURM_CPUS_PER_TASK:-{cpus}}}\" --lease-s {lease}\n"
      "status=$?\n"
      "case $status in\n"
      "  0) exit 0 ;;\n"
      "  3) echo \"shard finished with failed jobs (deterministic: not retried); vsi merge lists them\"; exit 0 ;;\n"
      "esac\n"
      "# Anything else (the worker was killed, the node ran out of memory):\n"
      "# requeue this task; it resumes its shard.\n"
      "if [ \"${{SLURM_RESTART_COUNT:-0}}\" -lt {requeues} ]; then\n"
      "  echo \"$(date -u +%FT%TZ) vsi work exited with $status: requeueing the task\"\n"
      "  scontrol requeue \"${{SLURM_ARRAY_JOB_ID}}_${{SLURM_ARRAY_TASK_ID}}\"\n"
      "fi\n"
      "exit $status\n",
      fmt::arg("head", script_head(o, fmt::format("array task K works shard K of {} (written by vsi slurm)", st.shards),
                                   "vsi-" + short_id(st.study_id), "shard-%a.log")),
      fmt::arg("last", st.shards - 1), fmt::arg("cpus", st.cpus_per_task), fmt::arg("dir", dir),
      fmt::arg("vsi", vsi), fmt::arg("lease", st.lease_s), fmt::arg("requeues", o.max_requeues));
  out.merge_script = fmt::format(
      "{head}"
      "#SBATCH --cpus-per-task=1\n"
      "set -u\n"
      "exec {vsi} merge {dir}/shard-*.sqlite --into {into}\n",
      fmt::arg("head", script_head(o,
                                   fmt::format("merges the {} shards once every array task succeeded (submitted "
                                               "with --dependency=afterok:<array job id>)",
                                               st.shards),
                                   "vsi-merge-" + short_id(st.study_id), "merge.log")),
      fmt::arg("vsi", vsi), fmt::arg("dir", dir), fmt::arg("into", shell_quote((o.dir / "results.sqlite").string())));
  return out;
}

std::string k8s_shard_job_name(const std::string& study_id) { return "vsi-" + short_id(study_id); }
std::string k8s_merge_job_name(const std::string& study_id) { return "vsi-merge-" + short_id(study_id); }

namespace {

ordered_json labels(const std::string& study_id) {
  return {{"app.kubernetes.io/name", "railvsi"}, {"railvsi/study", short_id(study_id)}};
}

ordered_json shard_volume(const K8sOptions& o) {
  return ordered_json::array({{{"name", "shards"}, {"persistentVolumeClaim", {{"claimName", o.claim}}}}});
}

ordered_json container(const K8sOptions& o, const std::string& name, ordered_json args, int cpus) {
  const ordered_json amount = {{"cpu", std::to_string(cpus)}, {"memory", o.memory}};
  return {{"name", name},
          {"image", o.image},
          {"command", ordered_json::array({"vsi"})},
          {"args", std::move(args)},
          {"env", ordered_json::array({{{"name", "OPENBLAS_NUM_THREADS"}, {"value", "1"}}})},
          {"resources", {{"requests", amount}, {"limits", amount}}},
          {"volumeMounts", ordered_json::array({{{"name", "shards"}, {"mountPath", o.mount_path}}})}};
}

}  // namespace

ordered_json k8s_shard_job(const K8sOptions& o) {
  const ClusterStudy& st = o.study;
  ordered_json worker = container(
      o, "worker",
      ordered_json::array({"work", "--db", o.mount_path + "/shard-$(JOB_COMPLETION_INDEX).sqlite", "--threads",
                           std::to_string(st.cpus_per_task), "--lease-s", fmt::format("{}", st.lease_s)}),
      st.cpus_per_task);
  // The Job controller sets JOB_COMPLETION_INDEX too; declared here from the
  // same annotation so that $(JOB_COMPLETION_INDEX) in args is expanded.
  worker["env"].insert(
      worker["env"].begin(),
      ordered_json{{"name", "JOB_COMPLETION_INDEX"},
                   {"valueFrom",
                    {{"fieldRef", {{"fieldPath", "metadata.annotations['batch.kubernetes.io/job-completion-index']"}}}}}});
  return {
      {"apiVersion", "batch/v1"},
      {"kind", "Job"},
      {"metadata", {{"name", k8s_shard_job_name(st.study_id)}, {"labels", labels(st.study_id)}}},
      {"spec",
       {{"completionMode", "Indexed"},
        {"completions", st.shards},
        {"parallelism", st.shards},
        // A pod whose worker died is replaced and resumes its shard, up to
        // this many times per shard.
        {"backoffLimitPerIndex", o.backoff_limit_per_index},
        {"podFailurePolicy",
         {{"rules",
           ordered_json::array(
               {// exit 3: the shard finished with failed jobs (deterministic): no retry, vsi merge lists them
                {{"action", "FailIndex"},
                 {"onExitCodes", {{"containerName", "worker"}, {"operator", "In"}, {"values", {3}}}}},
                // preemption, eviction, node drain: not the shard's fault, not counted
                {{"action", "Ignore"},
                 {"onPodConditions", ordered_json::array({{{"type", "DisruptionTarget"}, {"status", "True"}}})}}})}}},
        {"template",
         {{"metadata", {{"labels", labels(st.study_id)}}},
          {"spec",
           {{"restartPolicy", "Never"},
            {"containers", ordered_json::array({worker})},
            {"volumes", shard_volume(o)}}}}}}}};
}

ordered_json k8s_merge_job(const K8sOptions& o) {
  const ClusterStudy& st = o.study;
  ordered_json args = ordered_json::array({"merge"});
  for (int k = 0; k < st.shards; ++k) args.push_back(o.mount_path + "/" + shard_file_name(k));
  args.push_back("--into");
  args.push_back(o.mount_path + "/results.sqlite");
  return {{"apiVersion", "batch/v1"},
          {"kind", "Job"},
          {"metadata", {{"name", k8s_merge_job_name(st.study_id)}, {"labels", labels(st.study_id)}}},
          {"spec",
           {{"backoffLimit", 2},
            {"template",
             {{"metadata", {{"labels", labels(st.study_id)}}},
              {"spec",
               {{"restartPolicy", "Never"},
                {"containers", ordered_json::array({container(o, "merge", std::move(args), 1)})},
                {"volumes", shard_volume(o)}}}}}}}};
}

}  // namespace railvsi::scheduler
