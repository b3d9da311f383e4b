#include "query/study_refinement.hpp"

#include <map>

#include <nlohmann/json.hpp>

#include "core/unix_time.hpp"
#include "query/study_results.hpp"
#include "queue/job_queue.hpp"
#include "study/study_plan.hpp"

namespace railvsi::scheduler {

std::size_t refine_study(Database& db, const std::string& study_id, int max_attempts, const RefineOptions& options) {
  Statement s = db.prepare("SELECT document, file FROM studies WHERE id = ?");
  if (!s.bind(1, study_id).step()) return 0;
  nlohmann::json doc = nlohmann::json::parse(s.text(0));
  const std::filesystem::path file = s.text(1);
  if (!doc.value("refine", false)) return 0;
  if (state_counts(db, study_id).unfinished() > 0) return 0;

  // The governing value per train and speed: the largest over the profiles,
  // absent when any profile has none there.
  std::map<std::string, std::map<double, std::optional<double>>> curves;
  for (const JobResult& j : study_results(db, {study_id, {}, {}, {}, {}, {}})) {
    const std::optional<double> v = j.overall("deck_acceleration_mps2");
    auto [it, fresh] = curves[j.train].try_emplace(j.speed_kmh, v);
    if (!fresh && it->second) it->second = v ? std::optional(std::max(*it->second, *v)) : std::nullopt;
  }

  std::vector<JobSpec> jobs;
  const nlohmann::json trains = doc.at("trains");
  for (const nlohmann::json& train : trains) {
    const auto curve = curves.find(study_train_label(train));
    if (curve == curves.end()) continue;
    std::vector<SpeedValue> values;
    for (const auto& [speed, value] : curve->second) values.push_back({speed, value});
    const std::vector<double> speeds = refinement_speeds(values, options);
    if (speeds.empty()) continue;
    nlohmann::json part = doc;
    part["trains"] = nlohmann::json::array({train});
    part["speeds_kmh"] = speeds;
    for (const char* key : {"line_speed_kmh", "speed_min_kmh", "speed_step_kmh"}) part.erase(key);
    ExpandOptions expand;
    expand.allow_large = true;
    StudyPlan plan = expand_study(part, file.parent_path(), file.string(), expand);
    for (JobSpec& j : plan.jobs) jobs.push_back(std::move(j));
  }
  if (jobs.empty()) return 0;

  Transaction tx(db);
  Statement last = db.prepare("SELECT coalesce(max(position), -1) FROM study_jobs WHERE study_id = ?");
  last.bind(1, study_id).step();
  // Every speed is new to the study; a job another study already ran is linked, not run again.
  insert_study_jobs(db, study_id, jobs, last.int64(0) + 1, max_attempts, unix_now_s());
  db.prepare("UPDATE studies SET job_count = (SELECT count(*) FROM study_jobs WHERE study_id = ?1) WHERE id = ?1")
      .bind(1, study_id)
      .run();
  tx.commit();
  return jobs.size();
}

}  // namespace railvsi::scheduler
