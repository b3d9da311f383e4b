#pragma once
// What `vsi query` reads from the database: the jobs of a study with their
// envelope values, filtered, in the order of the study (trains, speeds,
// profiles).
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "simulation/scene.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

struct QueryFilter {
  std::string study_id;
  std::optional<std::string> train;
  std::optional<double> speed_min_kmh, speed_max_kmh;
  std::optional<std::string> irregularity;
  std::optional<std::string> structure;  // a bridge of a line study (its name)
};

struct JobResult {
  std::string id;
  std::string train;
  double speed_kmh = 0.0;
  std::string irregularity;
  std::string variant = "nominal";  // bound of the structure, from the scene's structure.variant
  // The bridge of a line study ("structures") the row is for; empty in a
  // study of one structure. A job listed under two names is two rows.
  std::string structure;
  std::string state;
  std::string status;  // engine status, empty before a run
  std::string error;
  double dt_s = 0.0;  // planned (jobs.dt_s), and why
  std::string dt_reason;
  // The step the answer ran at (its fidelity record's): an escalated job
  // re-ran at a fraction of the planned step. The planned one before a run.
  double ran_dt_s = 0.0;
  double cutoff_hz = 0.0;
  // Its train is axle forces (a load model, or a train given "as" forces):
  // no wheel or car-body quantity exists for it. Absent when its train can
  // no longer be read.
  std::optional<bool> axle_forces;
  std::optional<double> wall_s, loop_s;
  std::string fidelity;  // JSON, empty before a run
  // A random profile (a spectrum with a seed): its profile without the seed
  // (canonical JSON, the key that groups the seeds of one spectrum) and the
  // spectrum's name. Both empty for other profiles.
  std::string profile_family, family_label;
  std::string warnings;  // JSON array of the run's warnings, empty before a run
  bool has_warnings() const { return !warnings.empty() && warnings != "[]"; }
  // quantity -> location ("" for the whole job) -> value (nullopt: not produced)
  std::map<std::string, std::map<std::string, std::optional<double>>> envelopes;
  // The stored value of quantity at location ("" overall), if any.
  std::optional<double> value(const std::string& quantity, const std::string& location) const;
  std::optional<double> overall(const std::string& quantity) const;
  // quantity -> location -> error estimate of the value (study_verification);
  // only values that have one.
  std::map<std::string, std::map<std::string, double>> error_estimates;
  std::optional<double> error_estimate(const std::string& quantity, const std::string& location = "") const;
};

// The jobs whose train has vehicles (or can no longer be read): those that
// wheel and car-body quantities concern. Trains of axle forces have none.
std::vector<JobResult> jobs_with_vehicles(const std::vector<JobResult>& jobs);

struct StudyInfo {
  std::string id, name, file;
  nlohmann::json checks = nlohmann::json::object();
  std::int64_t job_count = 0;
  double tolerance = 0.01;  // accuracy.tolerance: an error estimate beyond it is flagged
};

// Throws std::runtime_error when the study is not in the database.
StudyInfo study_info(Database& db, const std::string& study_id);
// The names of a line study's structures in its order; empty for a study
// of one structure.
std::vector<std::string> study_structure_names(Database& db, const std::string& study_id);
std::vector<JobResult> study_results(Database& db, const QueryFilter& filter);

// Whether a scene's train (json_type and text of its "train") is axle
// forces, parsed once per train; nullopt when it can no longer be read.
class TrainKinds {
 public:
  std::optional<bool> operator()(const std::string& type, const std::string& text);

 private:
  std::map<std::string, std::optional<bool>> known_;
};
// The columns study_results reads of a job (alias j of jobs, with its scene,
// step reason and fidelity record given as SQL expressions), kJobResultColumns
// of them, and the JobResult of a row that starts with them (no envelopes, no structure).
constexpr int kJobResultColumns = 20;
std::string job_result_columns(std::string_view scene, std::string_view dt_reason, std::string_view fidelity);
JobResult read_job_result(Statement& s, TrainKinds& axle_forces);
// A stored job's scene, loaded as the worker loaded it (job_scenes.scene).
// Throws std::runtime_error when the job is not in the database.
Scene load_job_scene(Database& db, const std::string& job_id);

// Why a filter cannot mean what the user asked (nullopt when it can): a
// train or profile the study does not have (with the list of those it has),
// --speed-min above --speed-max, or a speed range outside the study's. A
// silent "0 jobs shown" would read as "no result".
std::optional<std::string> filter_error(Database& db, const QueryFilter& filter);

}  // namespace railvsi::scheduler
