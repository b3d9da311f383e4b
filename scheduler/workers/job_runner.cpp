#include "workers/job_runner.hpp"

#include <chrono>
#include <cstdlib>
#include <optional>
#include <string_view>

#include <fmt/format.h>

#include "analysis/modal_moving_forces.hpp"
#include "analysis/modal_run_warnings.hpp"
#include "analysis/modal_sweep.hpp"
#include "core/input_error.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "simulation/run_monitor.hpp"
#include "simulation/simulation.hpp"
#include "envelopes/code_filter.hpp"
#include "envelopes/envelope_rows.hpp"
#include "envelopes/job_envelopes.hpp"
#include "planning/time_step_warnings.hpp"
#include "planning/run_planning_warnings.hpp"
#include "study/structure_key.hpp"
#include "workers/cached_operator.hpp"
#include "summary/summary_json.hpp"
#include "planning/rung_runner.hpp"

namespace railvsi::scheduler {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string job_name(const ClaimedJob& job) { return "job " + job.id.substr(0, 12); }

// File names in a job are absolute (made so at submission). An imported
// model is shared between the jobs whose operator keys have the same
// structure part (the hash of the matrices the study read at submission),
// whatever their dt.
Scene parse_job_scene(const ClaimedJob& job, ImportedStructures* imports) {
  const std::string name = job_name(job);
  return parse_scene(parse_json_text(job.scene, name), "/", name, imports, structure_part(job.operator_key));
}

// The outcome's record of a run and its envelopes; fidelity_text: the
// fidelity record's JSON when the caller has it already.
void store_run(const RunSummary& s, const JobEnvelopes& envelopes, const std::string& run_message, JobOutcome& out,
               const std::string* fidelity_text = nullptr) {
  out.warnings = warnings_json(s.warnings).dump();
  out.fidelity = fidelity_text ? *fidelity_text : fidelity_json(s.fidelity).dump();
  out.steps = s.steps;
  // The envelopes may find what the run did not report (a non-finite value).
  out.status = envelopes.status;
  if (!envelopes.ok()) {
    out.ok = false;
    out.error = envelopes.message.empty() ? run_message : envelopes.message;
  } else {
    out.envelopes = envelope_rows(envelopes);
  }
}

void invalid_input(const InputError& e, JobOutcome& out) {
  // The job was validated at submission; a library file edited since, or
  // a setup the dry run did not meet (another speed), ends here.
  out.ok = false;
  out.status = "invalid_input";
  out.error = e.describe();
}

// The canonical scene text around its speed: jobs whose texts agree outside
// the number run the same scene at another speed. Empty when the text has
// no single top-level "speed_kmh".
struct SpeedSplit {
  std::string_view before, after;
  std::string_view number;
};
std::optional<SpeedSplit> split_at_speed(std::string_view text) {
  static constexpr std::string_view kKey = "\"speed_kmh\":";
  const std::size_t at = text.find(kKey);
  if (at == std::string_view::npos || text.find(kKey, at + 1) != std::string_view::npos) return std::nullopt;
  const std::size_t start = at + kKey.size();
  const std::size_t end = text.find_first_of(",}", start);
  if (end == std::string_view::npos) return std::nullopt;
  return SpeedSplit{text.substr(0, start), text.substr(end), text.substr(start, end - start)};
}

// What the modal jobs of one batch share.
struct ModalPass {
  std::string scene_text;  // of the job that built it
  std::optional<SpeedSplit> split;
  Scene scene;
  ScenePlan plan;
  std::shared_ptr<const ModalBasis> basis;
  std::unique_ptr<ModalSweep> sweep;
  std::unique_ptr<CodeFilter> filter;
  std::string obstacle;  // why no filtered acceleration, "" when there is one
  // The fidelity record's JSON: the same for every job of the pass (rung,
  // plan, modes, dt, what it ignores), written once.
  std::string fidelity_text;
};

// The scene of `job` on `pass` (same text but the speed), else nullopt.
std::optional<Scene> same_scene_at_speed(const ModalPass& pass, const ClaimedJob& job) {
  if (!pass.split) return std::nullopt;
  const auto split = split_at_speed(job.scene);
  if (!split || split->before != pass.split->before || split->after != pass.split->after) return std::nullopt;
  // The number as the parser reads it (shortest round-trip form): the speed column.
  const std::string number(split->number);
  char* end = nullptr;
  const double speed_kmh = std::strtod(number.c_str(), &end);
  if (end != number.c_str() + number.size() || speed_kmh != job.speed_kmh) return std::nullopt;
  Scene scene = pass.scene;
  scene.speed_mps = speed_kmh / 3.6;  // as the scene loader
  return scene;
}

std::unique_ptr<ModalPass> make_modal_pass(const ClaimedJob& job, Scene scene, ScenePlan plan, FactorizationCache& cache,
                                           JobOutcome& out) {
  auto pass = std::make_unique<ModalPass>();
  pass->scene_text = job.scene;
  pass->split = split_at_speed(pass->scene_text);
  pass->scene = std::move(scene);
  pass->plan = std::move(plan);
  const auto& rails = pass->scene.analysis.contact.rail_lines;
  const BasisLookup lookup = cache.get_basis(job.operator_key, [&] {
    ModalBasisOptions o;
    o.max_frequency_hz = pass->plan.modal_cutoff_hz;
    ModalModel m;
    m.basis = std::make_shared<const ModalBasis>(pass->scene.structure, o);
    m.sections = modal_section_forces(*m.basis, rails);
    return m;
  });
  out.factorized = lookup.built;
  out.factorization_s = lookup.build_s;
  out.evictions = lookup.evictions;
  // The cached basis may have been computed on another job's structure
  // object: the modal key (modal_operator_key) covers everything the sweep
  // reads of it (matrices, rail lines, output points), so it is this one's.
  pass->basis = lookup.basis;
  const Scene& s = pass->scene;
  pass->sweep = std::make_unique<ModalSweep>(*pass->basis, s.train, rails, s.analysis.dt_s,
                                             scene_asks(s).section_forces ? lookup.sections : nullptr,
                                             deck_output_correction(s));
  if (0.5 / s.analysis.dt_s < job.cutoff_hz)
    pass->obstacle = fmt::format("the Nyquist frequency 1/(2 dt) = {:.3g} Hz is below the code cut-off {:.3g} Hz",
                                 0.5 / s.analysis.dt_s, job.cutoff_hz);
  else
    pass->filter = std::make_unique<CodeFilter>(s.analysis.dt_s, job.cutoff_hz);
  return pass;
}

// Modal jobs of one pass run together, up to kSweepLanes speeds in one
// group: the run of each (the same bits as alone), its maxima and filtered
// acceleration from the workspace, its envelopes.
static_assert(CodeFilter::kLanes >= kSweepLanes, "a group's signals are filtered together");

struct GroupMember {
  std::size_t job = 0;  // index in the batch
  Scene scene;
  long n_steps = 0;
};

void run_group_on_pass(ModalPass& pass, const std::vector<GroupMember>& group, const std::vector<ClaimedJob>& jobs,
                       ModalSweepWorkspace& ws, CodeFilter::LaneWorkspace& filter_ws, std::vector<JobOutcome>& outcomes) {
  const auto start = Clock::now();
  std::vector<SweepLane> lanes;
  for (const GroupMember& m : group) lanes.push_back({modal_run_start_x_m(m.scene), m.scene.speed_mps, m.n_steps});
  const std::vector<ModalSweepRun> runs = pass.sweep->run_group(lanes, ws);
  // The filtered acceleration of each output point, the group's signals
  // filtered side by side; a run that stopped early filters what it computed.
  std::vector<std::vector<double>> filtered(group.size());
  if (pass.filter) {
    const std::size_t points = ws.acceleration[0].size();
    for (std::size_t g = 0; g < group.size(); ++g)
      for (auto& a : ws.acceleration[g]) a.resize(static_cast<std::size_t>(runs[g].steps) + 1);
    std::vector<const std::vector<double>*> signals(group.size());
    std::vector<double> maxima(group.size());
    for (std::size_t i = 0; i < points; ++i) {
      for (std::size_t g = 0; g < group.size(); ++g) signals[g] = &ws.acceleration[g][i];
      pass.filter->max_abs_filtered(signals, maxima.data(), filter_ws);
      for (std::size_t g = 0; g < group.size(); ++g) filtered[g].push_back(maxima[g]);
    }
  }
  // The group's time, shared by its jobs in proportion to their steps.
  const double loop_s = seconds_since(start);
  double total_steps = 0.0;
  for (const GroupMember& m : group) total_steps += static_cast<double>(std::max(1L, m.n_steps));
  for (std::size_t g = 0; g < group.size(); ++g) {
    const auto job_start = Clock::now();
    const Scene& scene = group[g].scene;
    const ClaimedJob& job = jobs[group[g].job];
    JobOutcome& out = outcomes[group[g].job];
    const ModalSweepRun& run = runs[g];
    RunSummary summary;
    fill_modal_summary(*pass.sweep, run, summary);
    summary.warnings = modal_run_warnings(scene);
    for (RunWarning& w : modal_time_step_warnings(scene, job.cutoff_hz)) summary.warnings.push_back(std::move(w));
    if (pass.fidelity_text.empty()) {
      record_rung(scene, pass.plan, pass.plan.rung, summary);
      pass.fidelity_text = fidelity_json(summary.fidelity).dump();
    }
    out.loop_s = loop_s * static_cast<double>(std::max(1L, group[g].n_steps)) / total_steps;
    summary.wall_s = out.loop_s + seconds_since(job_start);
    const JobEnvelopes envelopes = compute_envelopes(run.status, summary, scene.analysis.dt_s, job.cutoff_hz,
                                                     pass.filter ? &filtered[g] : nullptr, pass.obstacle);
    store_run(summary, envelopes, run.status.message(), out, &pass.fidelity_text);
    out.wall_s += summary.wall_s;
  }
}

std::vector<JobOutcome> run_modal_jobs(const std::vector<ClaimedJob>& jobs, FactorizationCache& cache,
                                       std::optional<std::pair<Scene, ScenePlan>> first, ImportedStructures* imports) {
  std::vector<JobOutcome> outcomes(jobs.size());
  std::unique_ptr<ModalPass> pass;
  ModalSweepWorkspace ws;
  CodeFilter::LaneWorkspace filter_ws;
  for (std::size_t i = 0; i < jobs.size();) {
    const auto start = Clock::now();
    JobOutcome& out = outcomes[i];
    try {
      std::optional<Scene> scene;
      if (pass) scene = same_scene_at_speed(*pass, jobs[i]);
      if (!scene) {
        // A new pass: this job's scene, parsed (or as the caller parsed it).
        std::pair<Scene, ScenePlan> parsed = first && i == 0 ? std::move(*first) : [&] {
          Scene s = parse_job_scene(jobs[i], imports);
          ScenePlan p = plan_scene(s, DeckFrequencies{});
          return std::make_pair(std::move(s), std::move(p));
        }();
        if (parsed.second.rung.name() != kBatchedRung) {
          out = run_job(jobs[i], cache, imports);  // not modal after all (an edited scene): alone
          ++i;
          continue;
        }
        pass.reset();
        pass = make_modal_pass(jobs[i], std::move(parsed.first), std::move(parsed.second), cache, out);
        scene = pass->scene;
        out.setup_s = seconds_since(start);
        out.wall_s = out.setup_s;
      }
      // This job and the next ones on the same pass, one per lane; a job
      // whose own setup fails ends the group and then fails alone.
      std::vector<GroupMember> group;
      group.push_back({i, std::move(*scene), 0});
      group.back().n_steps = modal_run_steps(group.back().scene);
      for (std::size_t j = i + 1; j < jobs.size() && group.size() < static_cast<std::size_t>(kSweepLanes); ++j) {
        std::optional<Scene> next = same_scene_at_speed(*pass, jobs[j]);
        if (!next) break;
        long n_steps = 0;
        try {
          n_steps = modal_run_steps(*next);
        } catch (const InputError&) {
          break;
        }
        group.push_back({j, std::move(*next), n_steps});
      }
      run_group_on_pass(*pass, group, jobs, ws, filter_ws, outcomes);
      i = group.back().job + 1;
    } catch (const InputError& e) {
      invalid_input(e, out);
      out.wall_s = seconds_since(start);
      pass.reset();
      ++i;
    }
  }
  return outcomes;
}

}  // namespace

JobOutcome run_job(const ClaimedJob& job, FactorizationCache& cache, ImportedStructures* imports) {
  const auto start = Clock::now();
  JobOutcome out;
  try {
    Scene scene = parse_job_scene(job, imports);
    // Job scenes carry their rung (pinned at submission) or none (the
    // analysis as given): no frequencies needed.
    ScenePlan plan = plan_scene(scene, DeckFrequencies{});
    if (plan.rung.name() == kBatchedRung)
      return run_modal_jobs({job}, cache, std::make_pair(std::move(scene), std::move(plan)), imports).front();
    CacheLookup lookup;
    RungModels models;
    std::optional<StructureBackend> first_backend;
    models.fe_operator = [&](const Scene& s, std::shared_ptr<const HybridBasis> reuse) {
      // An escalation at a finer dt (wheel quantities) needs its own K_bar,
      // and a run repeated on FE after an impact on the hybrid structure
      // the FE operator.
      if (!first_backend) first_backend = s.analysis.structure_backend;
      std::string key = s.analysis.dt_s == scene.analysis.dt_s
                            ? job.operator_key
                            : fmt::format("{}/dt={:.17g}", job.operator_key, s.analysis.dt_s);
      if (s.analysis.structure_backend != *first_backend)
        key += fmt::format("/{}", structure_backend_name(s.analysis.structure_backend));
      const CacheLookup before = lookup;  // the first run's, counted with the escalation's
      lookup = cached_operator(cache, key, structure_part(job.operator_key), s, std::move(reuse));
      lookup.factorized = lookup.factorized || before.factorized;
      lookup.factorization_s += before.factorization_s;
      lookup.evictions += before.evictions;
      return lookup.op;
    };
    Result result = run_at_rung(scene, plan, models);
    out.factorized = lookup.factorized;
    out.factorization_s = lookup.factorization_s;
    out.evictions = lookup.evictions;
    const Scene ran = scene_as_run(scene, result.summary);
    for (RunWarning& w : run_planning_warnings(ran, result.summary, job.cutoff_hz))
      result.summary.warnings.push_back(std::move(w));
    const RunSummary& s = result.summary;
    out.setup_s = s.setup_s + lookup.factorization_s;
    out.loop_s = s.wall_s - s.setup_s;
    const JobEnvelopes envelopes =
        compute_envelopes(result, s.dt_s, scene.analysis.history_stride, job.cutoff_hz);  // the dt it ran at
    store_run(s, envelopes, result.status.message(), out);
  } catch (const InputError& e) {
    invalid_input(e, out);
  }
  out.wall_s = seconds_since(start);
  return out;
}

std::vector<JobOutcome> run_jobs(const std::vector<ClaimedJob>& jobs, FactorizationCache& cache,
                                 ImportedStructures* imports) {
  if (jobs.size() == 1 && jobs.front().rung != kBatchedRung) return {run_job(jobs.front(), cache, imports)};
  return run_modal_jobs(jobs, cache, std::nullopt, imports);
}

}  // namespace railvsi::scheduler
