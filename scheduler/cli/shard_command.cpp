#include "cli/shard_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "cli/service_store.hpp"
#include "queue/job_queue.hpp"
#include "shards/cluster_recipes.hpp"
#include "shards/shard_merge.hpp"
#include "shards/shard_store.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::cli {
namespace {

namespace fs = std::filesystem;

void add_source_options(CLI::App* c, ClusterArgs& a) {
  c->add_option("study", a.study_file, "Study file (JSON); or give --db and --study");
  c->add_option("--db", a.db, "A study database holding the study (only read)");
  c->add_option("--study", a.study_id, "Id of the study in --db (or a unique prefix of at least 6 digits)");
  c->add_option("--shards", a.shards, "Number of shards")->required()->check(CLI::Range(1, 100000));
  c->add_option("--out", a.out, "Directory for the shard stores (created; must not hold shards already)")->required();
  c->add_flag("--allow-large", a.allow_large, "Accept a study of more than 100,000 jobs");
}

void add_task_options(CLI::App* c, ClusterArgs& a) {
  c->add_option("--cpus-per-task", a.cpus_per_task, "CPUs of each task, and its worker threads")
      ->capture_default_str()
      ->check(CLI::Range(1, 4096));
  c->add_option("--lease-s", a.lease_s,
                "Lease of a claimed job in s: a resumed task waits this long for the job its killed worker held")
      ->capture_default_str()
      ->check(finite_in(kLeaseMinS, kLeaseMaxS));  // what vsi work accepts
}

// The study to shard: expanded from a file into a temporary in-memory
// store, or found in an existing store, which is only read.
struct Source {
  std::unique_ptr<scheduler::Database> db;
  std::string study_id;
  std::string study_name;
};

std::optional<Source> open_source(const ClusterArgs& a) {
  const bool from_file = !a.study_file.empty(), from_db = !a.db.empty() || !a.study_id.empty();
  if (from_file == from_db) {
    std::cerr << "error: give either a study file or --db F --study ID\n";
    return std::nullopt;
  }
  Source s;
  if (from_file) {
    scheduler::ExpandOptions options;
    options.allow_large = a.allow_large;
    const scheduler::StudyPlan plan = scheduler::load_study(a.study_file, options);
    s.db = std::make_unique<scheduler::Database>(":memory:");
    scheduler::migrate(*s.db);
    scheduler::submit_study(*s.db, plan);
    s.study_id = plan.id;
  } else {
    if (a.db.empty() || a.study_id.empty()) {
      std::cerr << "error: --db and --study go together\n";
      return std::nullopt;
    }
    if (!fs::is_regular_file(a.db)) {
      std::cerr << "error: " << a.db << ": no such study database\n";
      return std::nullopt;
    }
    s.db = std::make_unique<scheduler::Database>(a.db);
    if (const int v = scheduler::store_schema_version(*s.db); v != scheduler::kStoreSchemaVersion) {
      std::cerr << fmt::format("error: {}: store schema version {}, this vsi's is {}\n", a.db, v,
                               scheduler::kStoreSchemaVersion);
      return std::nullopt;
    }
    const auto id = find_study(*s.db, a.study_id);
    if (!id) return std::nullopt;
    s.study_id = *id;
  }
  scheduler::Statement name = s.db->prepare("SELECT name FROM studies WHERE id = ?");
  if (name.bind(1, s.study_id).step()) s.study_name = name.text(0);
  return s;
}

// Shards written, with a line per shard on stdout; nullopt (nothing
// written, the reason on stderr) when there are more shards than jobs.
std::optional<scheduler::WrittenShards> make_shards(const ClusterArgs& a, Source& source) {
  const fs::path dir = fs::absolute(a.out);
  if (const std::int64_t jobs = scheduler::state_counts(*source.db, source.study_id).total(); a.shards > jobs) {
    std::cerr << fmt::format("error: --shards {}: the study has {} jobs; give at most {} shards (an empty shard "
                             "is a task with nothing to do)\n",
                             a.shards, jobs, jobs);
    return std::nullopt;
  }
  scheduler::WrittenShards w = scheduler::write_shards(*source.db, source.study_id, a.shards, dir);
  const auto& p = w.plan;
  std::cout << fmt::format("study {} ({}): {} shards in {}\n", source.study_id, source.study_name, a.shards,
                           dir.string());
  for (std::size_t k = 0; k < w.files.size(); ++k)
    std::cout << fmt::format("  {}: {} jobs, estimated cost {:.4g} (steps x DOFs)\n", w.files[k].filename().string(),
                             p.shards[k].size(), p.costs[k]);
  std::cout << fmt::format("largest shard {:.1f} % above the mean; {} factorization groups split across shards\n",
                           p.mean_cost() > 0 ? 100.0 * (p.max_cost() / p.mean_cost() - 1.0) : 0.0, p.split_groups);
  return w;
}

scheduler::ClusterStudy cluster_study(const ClusterArgs& a, const Source& s) {
  return {s.study_id, s.study_name, a.shards, a.cpus_per_task, a.lease_s};
}

void write_text(const fs::path& file, const std::string& text, bool executable) {
  {
    std::ofstream out(file, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write", file.string()));
  }
  if (executable)
    fs::permissions(file, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
}

fs::path this_binary() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path("vsi") : self;
}

// Runs a command through the shell; its standard output, or nullopt when it failed.
std::optional<std::string> run_capture(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(command.c_str(), "r"), ::pclose);
  if (!pipe) return std::nullopt;
  std::string out;
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe.get()) != nullptr) out += buffer;
  const int status = ::pclose(pipe.release());
  if (status != 0) return std::nullopt;
  return out;
}

// "12345" from sbatch --parsable ("12345" or "12345;cluster").
std::string parsable_job_id(const std::string& out) {
  std::string id;
  for (char c : out) {
    if (c == ';' || c == '\n') break;
    id += c;
  }
  return id;
}

}  // namespace

ClusterCommands::ClusterCommands(CLI::App& app) {
  shard_ = app.add_subcommand("shard", "Split a study into N self-contained shard databases, balanced by estimated "
                                       "cost (steps x DOFs), jobs sharing a factorization kept together");
  add_source_options(shard_, args_);

  merge_ = app.add_subcommand("merge", "Merge the shard databases of a study into one (idempotent)");
  merge_->add_option("shards", args_.shard_files, "Shard databases (DIR/shard-*.sqlite)")->required();
  merge_->add_option("--into", args_.into, "The merged study database (created if needed)")->required();

  slurm_ = app.add_subcommand("slurm", "Shards plus a Slurm job array (task K works shard K, --requeue) and a "
                                       "dependent merge job");
  add_source_options(slurm_, args_);
  add_task_options(slurm_, args_);
  // Written into #SBATCH lines: one word each.
  slurm_->add_option("--partition", args_.partition, "Slurm partition (default: the cluster's)")->check(one_word());
  slurm_->add_option("--time", args_.time_limit, "Time limit of a task (Slurm --time, e.g. 4:00:00)")
      ->check(one_word());
  slurm_->add_option("--max-requeues", args_.max_requeues, "Requeues of a task whose worker died")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  slurm_->add_option("--vsi", args_.vsi_binary, "vsi binary on the nodes (default: this one's absolute path)");
  slurm_->add_flag("--submit", args_.submit, "Submit both with sbatch (the merge with --dependency=afterok)");

  k8s_ = app.add_subcommand("k8s", "Shards plus a Kubernetes Indexed Job (completion index K works shard K) and a "
                                   "merge Job");
  add_source_options(k8s_, args_);
  add_task_options(k8s_, args_);
  k8s_->add_option("--image", args_.image, "Worker image (built from docker/)")->required()->check(one_word());
  k8s_->add_option("--claim", args_.claim, "PersistentVolumeClaim holding the shard directory")
      ->capture_default_str()
      ->check(kubernetes_name());
  k8s_->add_option("--memory", args_.memory, "Memory of each pod (Kubernetes quantity)")
      ->capture_default_str()
      ->check(kubernetes_quantity());
  k8s_->add_option("--backoff-limit-per-index", args_.backoff_limit_per_index,
                   "Pods of one shard that may fail before the shard counts as failed")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

std::optional<int> ClusterCommands::run_parsed() const {
  const std::pair<CLI::App*, int (*)(const ClusterArgs&)> commands[] = {
      {shard_, shard_command}, {merge_, merge_command}, {slurm_, slurm_command}, {k8s_, k8s_command}};
  for (const auto& [command, run] : commands) {
    if (!command->parsed()) continue;
    spdlog::set_default_logger(spdlog::stderr_color_mt("vsi"));
    scheduler::single_threaded_blas();
    return run(args_);
  }
  return std::nullopt;
}

int shard_command(const ClusterArgs& args) {
  auto source = open_source(args);
  if (!source) return kExitInvalidInput;
  return make_shards(args, *source) ? kExitOk : kExitInvalidInput;
}

int merge_command(const ClusterArgs& args) {
  std::vector<fs::path> files(args.shard_files.begin(), args.shard_files.end());
  const scheduler::MergeSummary m = scheduler::merge_shards(files, args.into);
  std::cout << fmt::format("study {} ({}): merged {} of {} shards into {}, {} jobs new or completed\n", m.study_id,
                           m.study_name, m.shards.size(), m.shard_count, args.into, m.new_jobs);
  for (const auto& s : m.shards)
    std::cout << fmt::format("  shard {}: {} jobs, {} done, {} failed, {} cancelled, {} unfinished\n", s.index,
                             s.counts.total(), s.counts.done, s.counts.failed, s.counts.cancelled,
                             s.counts.unfinished());
  const auto& t = m.target;
  std::cout << fmt::format("merged study: {} jobs, {} done, {} failed, {} cancelled, {} unfinished\n", t.total(),
                           t.done, t.failed, t.cancelled, t.unfinished());
  int code = kExitOk;
  if (!m.missing.empty()) {
    std::string list;
    for (int k : m.missing) list += (list.empty() ? "" : ", ") + std::to_string(k);
    std::cerr << fmt::format("error: missing shards: {} (of {}); merge them when they are there\n", list, m.shard_count);
    code = kExitRuntimeFailure;
  }
  for (const auto& s : m.shards)
    if (s.counts.unfinished() > 0) {
      std::cerr << fmt::format("error: shard {} has {} unfinished jobs: work it (vsi work --db {}) and merge again\n",
                               s.index, s.counts.unfinished(), s.file.string());
      code = kExitRuntimeFailure;
    }
  if (code == kExitOk && t.failed > 0) {
    std::cerr << fmt::format("error: {} jobs of the study failed (vsi query --db {} --study {} --format json shows "
                             "why)\n",
                             t.failed, args.into, m.study_id.substr(0, 12));
    code = kExitStudyFailedJobs;
  }
  return code;
}

int slurm_command(const ClusterArgs& args) {
  auto source = open_source(args);
  if (!source) return kExitInvalidInput;
  const fs::path dir = fs::absolute(args.out);
  if (!make_shards(args, *source)) return kExitInvalidInput;
  scheduler::SlurmOptions o;
  o.study = cluster_study(args, *source);
  o.dir = dir;
  o.vsi = args.vsi_binary.empty() ? this_binary() : fs::path(args.vsi_binary);
  o.partition = args.partition;
  o.time_limit = args.time_limit;
  o.max_requeues = args.max_requeues;
  const scheduler::SlurmScripts scripts = scheduler::slurm_scripts(o);
  fs::create_directories(dir / "logs");
  write_text(dir / "slurm-array.sh", scripts.array_script, true);
  write_text(dir / "slurm-merge.sh", scripts.merge_script, true);
  const std::string array = scheduler::shell_quote((dir / "slurm-array.sh").string());
  const std::string merge = scheduler::shell_quote((dir / "slurm-merge.sh").string());
  if (!args.submit) {
    std::cout << fmt::format("submit with:\n  array=$(sbatch --parsable {})\n  sbatch --dependency=afterok:$array {}\n",
                             array, merge);
    return kExitOk;
  }
  const auto array_out = run_capture("sbatch --parsable " + array);
  if (!array_out) {
    std::cerr << "error: sbatch of the job array failed (see above); the shards and scripts are in " << dir << '\n';
    return kExitRuntimeFailure;
  }
  const std::string array_id = parsable_job_id(*array_out);
  const auto merge_out = run_capture(fmt::format("sbatch --parsable --dependency=afterok:{} {}", array_id, merge));
  if (!merge_out) {
    std::cerr << "error: sbatch of the merge job failed; the array " << array_id << " runs; submit the merge with: "
              << fmt::format("sbatch --dependency=afterok:{} {}", array_id, merge) << '\n';
    return kExitRuntimeFailure;
  }
  std::cout << fmt::format("submitted array job {} ({} tasks) and merge job {} (afterok:{})\n", array_id, args.shards,
                           parsable_job_id(*merge_out), array_id);
  return kExitOk;
}

int k8s_command(const ClusterArgs& args) {
  auto source = open_source(args);
  if (!source) return kExitInvalidInput;
  const fs::path dir = fs::absolute(args.out);
  if (!make_shards(args, *source)) return kExitInvalidInput;
  scheduler::K8sOptions o;
  o.study = cluster_study(args, *source);
  o.image = args.image;
  o.claim = args.claim;
  o.memory = args.memory;
  o.backoff_limit_per_index = args.backoff_limit_per_index;
  write_text(dir / "k8s-shards-job.json", scheduler::k8s_shard_job(o).dump(2) + "\n", false);
  write_text(dir / "k8s-merge-job.json", scheduler::k8s_merge_job(o).dump(2) + "\n", false);
  std::cout << fmt::format(
      "copy {0} to the volume of claim {1}, then:\n"
      "  kubectl apply -f {0}/k8s-shards-job.json\n"
      "  kubectl wait --for=condition=complete --timeout=-1s job/{2}\n"
      "  kubectl apply -f {0}/k8s-merge-job.json\n",
      dir.string(), args.claim, scheduler::k8s_shard_job_name(source->study_id));
  return kExitOk;
}

}  // namespace railvsi::cli
