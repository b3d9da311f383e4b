#pragma once
// A study (schemas/study.schema.json) expanded into jobs: structures (a
// line's bridges) x structure variants x trains x speeds x irregularity
// profiles (x seeds). Each job is one canonical scene; its id is
// the SHA-256 of that text, so the same job submitted twice is one job.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace railvsi {
struct Scene;
class StructureOperator;
}  // namespace railvsi

namespace railvsi::scheduler {

struct JobSpec {
  std::string id;            // SHA-256 of scene
  std::string scene;         // canonical scene JSON, file names absolute
  std::string train;         // label of the train (its name)
  double speed_kmh = 0.0;
  std::string irregularity;  // label of the profile, "none" for a perfect track
  std::string variant = "nominal";  // bound of the structure (study "variants"), in the scene too
  // Jobs with the same key share one structure factorization: SHA-256 of the
  // structure model's matrices and rail DOFs, dt, the HHT parameters and
  // whether the rail flexibility is needed.
  std::string operator_key;
  double dt_s = 0.0;
  std::string dt_reason;
  double cutoff_hz = 0.0;  // deck acceleration low-pass cut-off of the code
  std::string rung;        // the planned rung (Rung::name()), e.g. "moving_forces/modal"
  // The exact modal rung: the modes its dry run kept, all up to the cut-off
  // (0 otherwise, and for a job read back from a store); stored as
  // jobs.planned_modes.
  int modes = 0;
  // The hybrid rung: the bridge modes the dry run's hybrid structure kept,
  // for the cost estimate (not stored; 0 for a job read back).
  int hybrid_modes = 0;
  // The bridges of a line study (StudyPlan::structures) this job runs for,
  // by index: one, or several when the same structure is listed under
  // several names. Empty for a study of one structure.
  std::vector<int> structures;
};

struct StudyPlan {
  std::string id;        // SHA-256 of the canonical study document
  std::string name;
  std::string file;
  std::string document;  // canonical study JSON
  nlohmann::json checks = nlohmann::json::object();
  std::vector<JobSpec> jobs;
  // The names of a line study's structures ("structures"), in its order;
  // empty for a study of one structure.
  std::vector<std::string> structures;
};

// The dry run's operator for a scene and its operator key: empty, built
// for the dry run alone; vsi run gives its workers' cache, so that what the
// dry run computed (a factor, the hybrid structure's reduction) is not
// computed again by the jobs.
using DryRunOperators =
    std::function<std::shared_ptr<const StructureOperator>(const Scene& scene, const std::string& operator_key)>;

struct ExpandOptions {
  std::size_t max_jobs = 100000;  // more is refused unless allow_large
  bool allow_large = false;
  DryRunOperators operators;
};

// Validates the whole study before anything is returned: the schema, every
// train, every profile, and a dry run of the engine's setup (factorization,
// static equilibrium) for every train. Throws InputError naming the study
// file (or the library file at fault) and the JSON path in the study, e.g.
// /trains/2/vehicles/0/primary/k_N_per_m. File names in the study are
// relative to study_dir (itself relative to the working directory or
// absolute); the scenes of the jobs hold them absolute.
StudyPlan expand_study(const nlohmann::json& doc, const std::filesystem::path& study_dir, const std::string& file,
                       const ExpandOptions& options = {});
// The label of a study's train as jobs carry it: its library name ("X as
// Y" for a renamed library train) or its name.
std::string study_train_label(const nlohmann::json& train);

StudyPlan load_study(const std::filesystem::path& file, const ExpandOptions& options = {});

}  // namespace railvsi::scheduler
