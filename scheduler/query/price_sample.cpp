#include "query/price_sample.hpp"

#include <algorithm>
#include <stdexcept>

#include "envelopes/envelope_rows.hpp"
#include "price/price_analysis.hpp"
#include "query/study_report.hpp"

namespace railvsi::scheduler {

std::vector<SampledJob> price_sample(Database& db, const std::string& study_id, int jobs, bool every_train) {
  (void)study_info(db, study_id);  // throws for a study not in the database
  std::vector<JobResult> ok;
  for (JobResult& j : study_results(db, {study_id, {}, {}, {}, {}, {}}))
    if (j.state == "done" && j.status == "ok") ok.push_back(std::move(j));
  if (ok.empty()) throw std::runtime_error("study " + study_id + " has no job done with status ok to price");

  std::vector<SampledJob> out;
  const auto add = [&](const JobResult& j, const std::string& reason) {
    const auto it = std::find_if(out.begin(), out.end(), [&](const SampledJob& s) { return s.job.id == j.id; });
    if (it != out.end()) {
      it->reasons.push_back(reason);
    } else {
      out.push_back({j, {reason}});
    }
  };
  for (std::string_view qv : price_quantities()) {
    const std::string q(qv);
    const Extreme extreme = extreme_of(q).value_or(Extreme::kMax);
    const TrainEnvelope* best = nullptr;
    const auto add_case = [&](const TrainEnvelope& e, const std::string& reason) {
      const auto it = std::find_if(ok.begin(), ok.end(), [&](const JobResult& j) {
        return j.train == e.train && j.speed_kmh == e.governing_speed_kmh && j.irregularity == e.governing_irregularity;
      });
      if (it != ok.end()) add(*it, reason);
    };
    // The governing case over trains of the per-train governing cases.
    const std::vector<TrainEnvelope> per_train = study_envelope_over_speeds(ok, q);
    for (const TrainEnvelope& e : per_train) {
      if (!e.value) continue;
      if (every_train) add_case(e, "governing " + q + " of " + e.train);
      if (best == nullptr || (extreme == Extreme::kMax ? *e.value > *best->value : *e.value < *best->value)) best = &e;
    }
    if (best != nullptr && !every_train) add_case(*best, "governing " + q);
  }
  // Then evenly over the study: the k-th of n extra picks at (k + 1/2) n_ok / n.
  const int extra = jobs - static_cast<int>(out.size());
  for (int k = 0; k < extra; ++k) {
    std::size_t i = static_cast<std::size_t>((k + 0.5) * static_cast<double>(ok.size()) / extra);
    // The next job not yet taken, wrapping around.
    for (std::size_t tries = 0; tries < ok.size(); ++tries, i = (i + 1) % ok.size()) {
      const bool taken =
          std::any_of(out.begin(), out.end(), [&](const SampledJob& s) { return s.job.id == ok[i % ok.size()].id; });
      if (!taken) {
        add(ok[i % ok.size()], "sample");
        break;
      }
    }
  }
  return out;
}

}  // namespace railvsi::scheduler
