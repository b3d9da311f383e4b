#include "query/study_verification.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "core/sha256.hpp"
#include "core/unix_time.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "planning/effects_planner.hpp"
#include "price/price_analysis.hpp"
#include "query/price_sample.hpp"
#include "queue/job_queue.hpp"
#include "study/canonical_json.hpp"
#include "planning/scene_plan.hpp"
#include "study/structure_key.hpp"

namespace railvsi::scheduler {
namespace {

using nlohmann::json;

struct StoredJob {
  std::string scene, train, irregularity, rung;
  double speed_kmh = 0.0, dt_s = 0.0, cutoff_hz = 0.0;
};

StoredJob stored_job(Database& db, const std::string& id) {
  Statement s = db.prepare(
      "SELECT scene, train, irregularity, coalesce(rung, ''), speed_kmh, dt_s, cutoff_hz FROM job_records WHERE id = ?");
  if (!s.bind(1, id).step()) throw std::runtime_error("job " + id + " is not in the database");
  return {s.text(0), s.text(1), s.text(2), s.text(3), s.real(4), s.real(5), s.real(6)};
}

// The job of a verification scene document: its id, rung and operator key
// as a study's job gets them (study_expansion), the labels and code cut-off
// of the job it verifies.
JobSpec verification_job(const json& doc, const StoredJob& of, const std::string& reason) {
  JobSpec j;
  j.scene = canonical_text(doc);
  j.id = sha256_hex(j.scene);
  const std::string name = "verification job " + j.id.substr(0, 12);
  const Scene scene = parse_scene(doc, "/", name);
  const ScenePlan plan = plan_scene(scene, DeckFrequencies{});
  const std::string hash = structure_model_hash(*scene.structure);
  if (plan.rung.exact_modal()) {
    j.operator_key = modal_operator_key(hash, *scene.structure, plan.modal_cutoff_hz, scene.analysis.dt_s);
  } else {
    AnalysisOptions analysis = scene.analysis;
    apply_rung_structure(plan, analysis);
    j.operator_key = operator_key(hash, analysis, !scene.train.is_moving_forces());
  }
  j.train = of.train;
  j.speed_kmh = of.speed_kmh;
  j.irregularity = of.irregularity;
  j.dt_s = scene.analysis.dt_s;
  j.dt_reason = reason;
  j.cutoff_hz = of.cutoff_hz;
  j.rung = plan.rung.name();
  return j;
}

// The verification runs of one job, least refined first: dt/2 on its rung,
// then dt/2 on the next rung when its rung is not the full model's (not
// for dt_only: the default's time-step self-check).
std::vector<JobSpec> verification_jobs(const std::string& job_id, const StoredJob& of, bool dt_only) {
  const std::string short_id = job_id.substr(0, 12);
  json doc = parse_json_text(of.scene, "job " + short_id);
  const double dt_s = 0.5 * of.dt_s;
  doc["analysis"]["dt_s"] = dt_s;
  std::vector<JobSpec> out;
  out.push_back(verification_job(doc, of, fmt::format("verification of job {}: its dt {:.4g} s halved", short_id, of.dt_s)));
  // Only where a rung was pinned (by the planner or the study): a scene run
  // as its analysis gives has no rung to climb.
  if (dt_only || !doc.contains("fidelity")) return out;
  const Scene scene = parse_scene(doc, "/", "job " + short_id);
  const ScenePlan plan = plan_scene(scene, DeckFrequencies{});
  const std::optional<Rung> next = next_rung(plan.rung);
  if (!next) return out;
  // A modal job on the planner's step for refined deck peaks has about
  // three times the sampled rule's step; the next rung (FE) takes the
  // largest sample, so it runs at half the sampled rule's step instead. (A
  // step the study gave is halved as it is.)
  if (plan.rung.exact_modal() && of.cutoff_hz > 0.0 &&
      (of.dt_s == modal_time_step_s(of.cutoff_hz, scene.fidelity.tolerance, ModalPeaks::kRefined) ||
       of.dt_s == modal_time_step_s(of.cutoff_hz, scene.fidelity.tolerance, ModalPeaks::kRefinedWithSections))) {
    const double sampled_dt_s = modal_time_step_s(of.cutoff_hz, scene.fidelity.tolerance, ModalPeaks::kSampled);
    doc["analysis"]["dt_s"] = std::min(dt_s, 0.5 * sampled_dt_s);
  }
  const double up_dt_s = doc["analysis"]["dt_s"].get<double>();
  EffectsPlan up;
  up.rung = *next;
  up.reasons = {fmt::format("verification of job {} one rung up: {} -> {}", short_id, plan.rung.name() + " " +
                                                                                        plan.rung.contact_law,
                            next->name() + " " + next->contact_law)};
  doc["fidelity"] = pinned_fidelity_json(up);
  out.push_back(verification_job(doc, of,
                                 up_dt_s == dt_s ? fmt::format("verification of job {}: its dt {:.4g} s halved, on the next rung",
                                                               short_id, of.dt_s)
                                                 : fmt::format("verification of job {} on the next rung at dt {:.4g} s "
                                                               "(its dt {:.4g} s refines the deck's peaks; the next "
                                                               "rung samples them)",
                                                               short_id, up_dt_s, of.dt_s)));
  return out;
}

}  // namespace

std::optional<VerifyRequest> verify_request(const json& study_document, bool by_default) {
  const auto accuracy = study_document.find("accuracy");
  if (accuracy == study_document.end() || !accuracy->contains("verify"))
    return by_default ? std::optional<VerifyRequest>(VerifyRequest{true, 0.0, true}) : std::nullopt;
  const json& v = accuracy->at("verify");
  if (v.is_boolean() && !v.get<bool>()) return std::nullopt;
  VerifyRequest r;
  if (v.is_number()) {
    r.governing_only = false;
    r.fraction = v.get<double>();
  }
  return r;
}

bool verifies_by_default(Database& db, const std::string& study_id) {
  Statement s = db.prepare(
      "SELECT EXISTS (SELECT 1 FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?) "
      "AND j.rung LIKE 'interaction/%' AND j.irregularity != 'none')");
  s.bind(1, study_id).step();
  return s.int64(0) != 0;
}

int verify_sample_size(const VerifyRequest& request, std::size_t n_ok) {
  if (request.governing_only) return 0;
  return static_cast<int>(std::ceil(request.fraction * static_cast<double>(n_ok)));
}

std::size_t enqueue_verification(Database& db, const std::string& study_id, int max_attempts) {
  Statement s = db.prepare("SELECT document FROM studies WHERE id = ?");
  if (!s.bind(1, study_id).step()) return 0;
  const std::optional<VerifyRequest> request = verify_request(json::parse(s.text(0)), verifies_by_default(db, study_id));
  if (!request) return 0;
  if (state_counts(db, study_id).unfinished() > 0) return 0;
  // Verified once; and not in a shard store, whose governing cases are not
  // the study's (the merged store verifies).
  Statement done = db.prepare(
      "SELECT (SELECT count(*) FROM verification_jobs WHERE study_id = ?1) + (SELECT count(*) FROM shard WHERE study_id = ?1)");
  done.bind(1, study_id).step();
  if (done.int64(0) > 0) return 0;
  Statement ok = db.prepare(
      "SELECT count(*) FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq "
      "WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?) AND j.state = 'done' AND j.status = 'ok'");
  ok.bind(1, study_id).step();
  if (ok.int64(0) == 0) return 0;

  struct Link {
    std::string job_id, verify_job_id, why;
    int refinement = 0;
  };
  std::vector<JobSpec> jobs;
  std::vector<Link> links;
  for (const SampledJob& sampled : price_sample(db, study_id, verify_sample_size(*request, static_cast<std::size_t>(ok.int64(0))), true)) {
    std::string why;
    for (const std::string& r : sampled.reasons) why += (why.empty() ? "" : ", ") + r;
    int refinement = 0;
    for (JobSpec& j : verification_jobs(sampled.job.id, stored_job(db, sampled.job.id), request->dt_only)) {
      links.push_back({sampled.job.id, j.id, why, ++refinement});
      jobs.push_back(std::move(j));
    }
  }
  Transaction tx(db);
  insert_jobs(db, jobs, max_attempts, unix_now_s());
  Statement link = db.prepare(
      "INSERT OR IGNORE INTO verification_jobs (study_id, job_id, verify_job_id, refinement, why) VALUES (?, ?, ?, ?, ?)");
  std::size_t added = 0;
  for (const Link& l : links) {
    link.bind(1, study_id).bind(2, l.job_id).bind(3, l.verify_job_id).bind(4, l.refinement).bind(5, l.why).run();
    added += static_cast<std::size_t>(db.changes());
  }
  tx.commit();
  return added;
}

std::size_t store_error_estimates(Database& db, const std::string& study_id) {
  // Per verified job, its most refined verification run that ended ok.
  std::map<std::string, std::string> reference_of;
  Statement v = db.prepare(
      "SELECT v.job_id, v.verify_job_id FROM verification_jobs v JOIN jobs j ON j.id = v.verify_job_id "
      "WHERE v.study_id = ? AND j.state = 'done' AND j.status = 'ok' ORDER BY v.job_id, v.refinement DESC");
  v.bind(1, study_id);
  while (v.step()) reference_of.try_emplace(v.text(0), v.text(1));
  if (reference_of.empty()) return 0;

  Transaction tx(db);
  Statement rows = db.prepare(
      "SELECT e.quantity, e.location, e.value, r.value FROM envelopes e LEFT JOIN envelopes r "
      "ON r.job_id = ?2 AND r.quantity = e.quantity AND r.location = e.location WHERE e.job_id = ?1");
  Statement update = db.prepare(
      "UPDATE job_envelopes SET error_estimate = ? WHERE job_seq = (SELECT seq FROM jobs WHERE id = ?) "
      "AND quantity = ? AND location = ?");
  for (const auto& [job, reference] : reference_of) {
    struct Estimate {
      std::string quantity, location;
      std::optional<double> value;
    };
    std::vector<Estimate> estimates;
    rows.bind(1, job).bind(2, reference);
    while (rows.step())
      estimates.push_back({rows.text(0), rows.text(1), relative_error(rows.optional_real(2), rows.optional_real(3))});
    rows.reset();
    for (const Estimate& e : estimates) {
      update.bind(1, e.value ? SqlValue(*e.value) : SqlValue(Null{})).bind(2, job).bind(3, e.quantity).bind(4, e.location).run();
    }
  }
  tx.commit();
  return reference_of.size();
}

}  // namespace railvsi::scheduler
