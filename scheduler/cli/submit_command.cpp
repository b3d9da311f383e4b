#include <unistd.h>

#include <iostream>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli/commands.hpp"
#include "cli/interrupt_release.hpp"
#include "cli/line_study_output.hpp"
#include "core/input_error.hpp"
#include "cli/progress_display.hpp"
#include "cli/service_commands.hpp"
#include "cli/service_store.hpp"
#include "cli/verdict_exit.hpp"
#include "core/terminal_text.hpp"
#include "query/study_refinement.hpp"
#include "query/study_report.hpp"
#include "query/study_verification.hpp"
#include "queue/job_queue.hpp"
#include "study/study_cost.hpp"
#include "study/study_plan.hpp"
#include "study/structure_key.hpp"
#include "workers/cached_operator.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::cli {
namespace {

std::size_t cache_budget_bytes(const ServiceArgs& args) {
  return static_cast<std::size_t>(args.cache_mb * 1024.0 * 1024.0);
}

// Expands and validates the whole study first: when anything is wrong,
// InputError leaves here and nothing is enqueued.
struct Submitted {
  std::unique_ptr<scheduler::Database> db;
  scheduler::SubmitResult result;
};

// `cache`, when given, receives what the dry run builds (vsi run's workers
// use it next).
Submitted submit(const ServiceArgs& args, scheduler::FactorizationCache* cache = nullptr) {
  scheduler::ExpandOptions options;
  options.allow_large = args.allow_large;
  if (cache)
    options.operators = [cache](const Scene& scene, const std::string& key) {
      return scheduler::cached_operator(*cache, key, scheduler::structure_part(key), scene).op;
    };
  require_study_file(args.study_file);
  const scheduler::StudyPlan plan = scheduler::load_study(args.study_file, options);
  spdlog::info("study {}: {}", plan.id.substr(0, 12), scheduler::describe(scheduler::estimate_study_cost(plan)));
  Submitted s{open_store(args.db, scheduler::OpenMode::kCreate), {}};
  s.result = scheduler::submit_study(*s.db, plan, args.max_attempts);
  const scheduler::SubmitResult& r = s.result;
  if (r.differing_jobs > 0)
    throw InputError("",
                     fmt::format("{} holds this study (the same document, {}) with other jobs: {} of its {} stored "
                                 "jobs differ from the {} this vsi makes of it (vsi's planning changed since it was "
                                 "submitted, or files the study names moved or changed); nothing was added, its "
                                 "stored results stay as they are (vsi work --db finishes its stored jobs); run the "
                                 "study into a new database (--db) for this expansion's results",
                                 args.db, r.study_id.substr(0, 12), r.differing_jobs, r.stored_jobs, r.jobs),
                     args.study_file);
  fill_static_envelopes(*s.db, r.study_id);
  return s;
}

scheduler::WorkSummary work(const ServiceArgs& args, const WorkerIdentity* identity, scheduler::FactorizationCache& cache) {
  scheduler::WorkOptions options;
  options.db_file = args.db;
  options.threads = args.threads;
  options.lease_s = args.lease_s;
  options.db_retry_s = args.db_retry_s;
  options.max_batch_jobs = static_cast<std::size_t>(args.batch);
  options.worker_prefix = identity ? identity->prefix : scheduler::worker_name_prefix();
  ProgressDisplay display(::isatty(STDERR_FILENO) == 1);
  // Before the workers: they inherit its mask. A caller with an identity holds its own.
  std::optional<InterruptRelease> interrupts;
  if (!identity) interrupts.emplace(args.db, options.worker_prefix);
  options.stopping = identity ? identity->stopping : interrupts->stopping();
  const scheduler::WorkSummary s = scheduler::run_workers(
      options, cache, [&](const scheduler::WorkProgress& p, bool final) { display.update(p, final); });
  spdlog::info("this worker: {} jobs done, {} failed in {}; factorizations {} ({:.2f} s), cache lookups hit {}, evictions {}",
               s.jobs_done, s.jobs_failed, format_duration(s.wall_s), s.cache.factorizations, s.cache.factorization_s,
               s.cache.hits, s.cache.evictions);
  if (s.lost_leases > 0) spdlog::warn("{} results dropped: their jobs were taken over or cancelled", s.lost_leases);
  if (!s.error.empty()) std::cerr << "error: " << s.error << '\n';
  return s;
}

}  // namespace

scheduler::SubmitResult submit_study_file(const ServiceArgs& args) { return submit(args).result; }

int submit_command(const ServiceArgs& args) {
  const scheduler::SubmitResult r = submit(args).result;
  std::cout << "study " << r.study_id << ": " << r.jobs << " jobs, " << r.new_jobs << " new\n";
  return kExitOk;
}

namespace {

// Studies that ask accuracy.verify, once complete: their verification jobs
// queued (once) and worked like any job, then the error estimates written
// (again at every call: idempotent, and a run killed before this point is
// finished by the next vsi work or vsi run).
void verify(const ServiceArgs& args, scheduler::Database& db, const std::vector<std::string>& studies,
            scheduler::WorkSummary& total, const WorkerIdentity* identity, scheduler::FactorizationCache& cache) {
  std::size_t added = 0;
  for (const std::string& id : studies) {
    const std::size_t n = scheduler::enqueue_verification(db, id, args.max_attempts);
    if (n > 0) spdlog::info("study {}: {} verification runs queued (accuracy.verify)", id.substr(0, 12), n);
    added += n;
  }
  if (added > 0 || scheduler::state_counts(db).unfinished() > 0) {
    const scheduler::WorkSummary s = work(args, identity, cache);
    // A verification run that fails is not a failed job of the study: its
    // job keeps no estimate (the report shows none), and the log says why.
    total.jobs_done += s.jobs_done;
    if (s.jobs_failed > 0) spdlog::warn("{} verification runs failed: their jobs get no error estimate", s.jobs_failed);
    if (!s.error.empty()) {
      total.error = s.error;
      return;
    }
  }
  for (const std::string& id : studies) {
    const std::size_t n = scheduler::store_error_estimates(db, id);
    if (n > 0) spdlog::info("study {}: error estimates of {} verified jobs stored", id.substr(0, 12), n);
  }
}

}  // namespace

// Work until the queue is empty; then studies that ask for refinement
// ("refine": true) get their next pass of speeds, which are worked in turn,
// until every peak is resolved (a bounded number of passes). Failed jobs are
// counted over all passes; an error of the workers ends the passes.
scheduler::WorkSummary work_and_refine(const ServiceArgs& args, scheduler::Database& db,
                                       const std::vector<std::string>& studies, const WorkerIdentity* identity,
                                       scheduler::FactorizationCache* given_cache) {
  constexpr int kMaxPasses = 12;  // 10 km/h to 1 km/h takes 4; a wide range of peaks a few more
  // One cache for every pass: a refinement's speeds and the dt/2
  // verification runs share the operators and reductions computed before.
  std::optional<scheduler::FactorizationCache> own_cache;
  if (!given_cache) own_cache.emplace(cache_budget_bytes(args));
  scheduler::FactorizationCache& cache = given_cache ? *given_cache : *own_cache;
  scheduler::WorkSummary total;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const scheduler::WorkSummary s = work(args, identity, cache);
    total.jobs_done += s.jobs_done;
    total.jobs_failed += s.jobs_failed;
    if (!s.error.empty()) {
      total.error = s.error;
      break;
    }
    std::size_t added = 0;
    for (const std::string& id : studies) {
      const std::size_t n = scheduler::refine_study(db, id, args.max_attempts);
      if (n > 0) spdlog::info("study {}: refinement pass {} adds {} jobs around the peaks", id.substr(0, 12), pass + 1, n);
      added += n;
    }
    if (added == 0) break;
  }
  if (total.error.empty()) verify(args, db, studies, total, identity, cache);
  return total;
}

int work_command(const ServiceArgs& args) {
  const auto db = open_store(args.db, scheduler::OpenMode::kExisting);  // migrate before the workers start; never create
  const scheduler::WorkSummary s = work_and_refine(args, *db, scheduler::study_ids(*db));
  if (!s.error.empty()) return kExitRuntimeFailure;
  return s.jobs_failed > 0 ? kExitStudyFailedJobs : kExitOk;
}

int run_command(const ServiceArgs& args) {
  // The submission's dry run and the workers share one cache: a
  // structure's setup is computed once.
  scheduler::FactorizationCache cache(cache_budget_bytes(args));
  const Submitted submitted = submit(args, &cache);
  const scheduler::SubmitResult& r = submitted.result;
  scheduler::Database& db = *submitted.db;
  // 12 digits, as the other log lines: the whole id wrapped the line at 80 columns.
  spdlog::info("study {}: {} jobs, {} new, in {}", r.study_id.substr(0, 12), r.jobs, r.new_jobs,
               scheduler::terminal_safe(args.db));
  if (!work_and_refine(args, db, {r.study_id}, nullptr, &cache).error.empty()) return kExitRuntimeFailure;
  // A line study ends with its line table: a row per bridge, read bridge by
  // bridge (its jobs' table is vsi query's).
  const bool line = !scheduler::study_structure_names(db, r.study_id).empty();
  std::optional<Verdict> line_verdict;
  std::vector<scheduler::JobResult> jobs;
  if (line) {
    line_verdict = write_line_table(db, r.study_id, std::cout);
  } else {
    jobs = scheduler::study_results(db, {r.study_id, {}, {}, {}, {}, {}});
    std::cout << scheduler::format_table(scheduler::study_info(db, r.study_id), jobs);
  }
  const scheduler::StateCounts c = scheduler::state_counts(db, r.study_id);
  int code = kExitOk;
  if (c.failed > 0) {
    std::cerr << "error: " << c.failed << " jobs of the study failed (vsi query --study " << r.study_id.substr(0, 12)
              << " --format json shows why; vsi retry queues them again)\n";
    code = kExitStudyFailedJobs;
  }
  if (args.fail_on_exceeded) {
    // A failed check wins over failed jobs (3), which win over incomplete (5).
    Verdict overall = Verdict::kNotEvaluated;
    if (line_verdict) {
      overall = *line_verdict;  // the line table shows each bridge's verdicts
    } else {
      const ComplianceReport judged = judge_jobs(db, r.study_id, jobs);
      std::cout << scheduler::format_verdict_lines(judged.checks, judged.overall);
      overall = judged.overall;
    }
    const int verdict = verdict_exit_code(overall);
    if (verdict == kExitCheckFailed || code == kExitOk) code = verdict;
  }
  return code;
}

}  // namespace railvsi::cli
