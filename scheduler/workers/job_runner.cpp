#include "workers/job_runner.hpp"

#include <chrono>

#include "core/input_error.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"
#include "envelopes/envelope_rows.hpp"
#include "envelopes/job_envelopes.hpp"
#include "planning/time_step_warnings.hpp"
#include "summary/summary_json.hpp"

namespace railvsi::scheduler {

JobOutcome run_job(const ClaimedJob& job, FactorizationCache& cache) {
  const auto start = std::chrono::steady_clock::now();
  JobOutcome out;
  const std::string name = "job " + job.id.substr(0, 12);
  try {
    // File names in a job are absolute (made so at submission).
    const Scene scene = parse_scene(parse_json_text(job.scene, name), "/", name);
    const CacheLookup lookup = cache.get(job.operator_key, [&] { return make_structure_operator(scene); });
    out.factorized = lookup.factorized;
    out.factorization_s = lookup.factorization_s;
    out.evictions = lookup.evictions;
    const Simulation simulation(scene, lookup.op);
    Result result = simulation.run();
    for (RunWarning& w : time_step_warnings(scene, job.cutoff_hz)) result.summary.warnings.push_back(std::move(w));
    out.warnings = warnings_json(result.summary.warnings).dump();
    const RunSummary& s = result.summary;
    out.fidelity = fidelity_json(s.fidelity).dump();
    out.steps = s.steps;
    out.setup_s = s.setup_s + lookup.factorization_s;
    out.loop_s = s.wall_s - s.setup_s;
    const JobEnvelopes envelopes =
        compute_envelopes(result, scene.analysis.dt_s, scene.analysis.history_stride, job.cutoff_hz);
    // The envelopes may find what the run did not report (a non-finite value).
    out.status = envelopes.status;
    if (!envelopes.ok()) {
      out.ok = false;
      out.error = envelopes.message.empty() ? result.status.message() : envelopes.message;
    } else {
      out.envelopes = envelope_rows(envelopes);
    }
  } catch (const InputError& e) {
    // The job was validated at submission; a library file edited since, or
    // a setup the dry run did not meet (another speed), ends here.
    out.ok = false;
    out.status = "invalid_input";
    out.error = e.describe();
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace railvsi::scheduler
