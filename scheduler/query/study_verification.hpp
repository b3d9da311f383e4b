#pragma once
// A study with "accuracy": {"verify": "governing" | fraction} gets an error
// estimate next to its envelope values. Once every job of the study has
// finished, its governing cases (price_sample: per key quantity and train
// the job of the governing value, as query and report show it) and, for a
// fraction, evenly spread jobs up to that fraction of its ok jobs are
// re-run one rung up: the same scene at dt/2 (refinement 1) and, where the
// job runs on a cheaper rung than the full model, at dt/2 on next_rung()
// (refinement 2). The re-runs are ordinary queued jobs (content-hashed ids,
// leases, the worker pool and its cache) linked to the study's job in
// verification_jobs, not to the study: query, report and the envelopes
// over speeds never see them. When they are done, each envelope value of a
// verified job gets error_estimate = (value - verified) / verified from its
// most refined verification run that ended ok; value itself is never
// written. Both steps are idempotent: a second call adds nothing and
// writes the same estimates.
#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "store/sqlite.hpp"

namespace railvsi::scheduler {

// "governing", or the fraction of the study's jobs; nullopt when the study
// document asks no verification ("verify": false), or leaves it out and
// `by_default` is false.
struct VerifyRequest {
  bool governing_only = true;
  double fraction = 0.0;  // (0, 1] when !governing_only
  // The default's time-step self-check: dt/2 on the job's own rung only,
  // not the next rung (which a "verify" given also runs).
  bool dt_only = false;
};
std::optional<VerifyRequest> verify_request(const nlohmann::json& study_document, bool by_default = false);

// The default of accuracy.verify: "governing" for an interaction study on a
// track with irregularities - some job of the study runs on an interaction
// rung over a profile or defects (its irregularity is not "none"), where a
// time step the policy accepts can still be too coarse for the track's
// shortest features (issue 33): its governing cases re-run at dt/2 on
// their own rung (VerifyRequest::dt_only); no verification otherwise.
bool verifies_by_default(Database& db, const std::string& study_id);

// How many jobs a request verifies among n_ok jobs done with status ok:
// 0 for "governing" (price_sample: the governing cases alone), else
// ceil(fraction x n_ok) (the governing cases first, then spread).
int verify_sample_size(const VerifyRequest& request, std::size_t n_ok);

// Queues the verification jobs of a study and links them in
// verification_jobs (the governing cases: price_sample's, of every train);
// returns how many links it added (0 when the study asks
// none, has unfinished jobs, was verified already, has no ok job, or the
// store is a shard: the merged store verifies the whole study).
std::size_t enqueue_verification(Database& db, const std::string& study_id, int max_attempts = 3);

// Writes envelopes.error_estimate of every verified job of the study whose
// verification has a run done with status ok; returns how many jobs.
std::size_t store_error_estimates(Database& db, const std::string& study_id);

}  // namespace railvsi::scheduler
