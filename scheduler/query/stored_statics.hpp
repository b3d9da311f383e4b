#pragma once
// The static envelopes of a train on a structure (static_effects.hpp's
// TrainStatics: the deflection at each output point, the section forces
// and support values of a beam deck), kept in the store's
// static_envelopes: computed once when a study is submitted (or when an
// older store is upgraded), then read by the line table and the report
// instead of running the static influence lines over every train again.
// A row holds the REAL the computation gave, so a read value is the
// computed one to the bit. Missing or incomplete rows: the caller computes.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/static_influence.hpp"
#include "model/train.hpp"
#include "query/static_effects.hpp"
#include "query/study_results.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

// The jobs whose scenes the compliance checks of `jobs` load: per train its
// first job of the nominal structure (else its first job), in the order of
// `jobs`; the structure is that of the first train by name.
struct StaticSceneJobs {
  std::map<std::string, std::string> train_job;  // train -> job id
  std::string structure_job;                     // empty without jobs
};
StaticSceneJobs static_scene_jobs(const std::vector<JobResult>& jobs);

// A train's envelopes on `influence`'s structure (no stored rows involved).
TrainStatics compute_train_statics(const StaticInfluence& influence, const std::vector<MovingForce>& axles);

// The stored envelopes of the train of `train_job`'s scene on the structure
// of `structure_job`'s scene, shaped by `influence` (built from that
// structure); nullopt unless every value of them is stored.
std::optional<TrainStatics> read_train_statics(Database& db, const std::string& structure_job,
                                               const std::string& train_job, const StaticInfluence& influence);
void write_train_statics(Database& db, const std::string& structure_job, const std::string& train_job,
                         const StaticInfluence& influence, const TrainStatics& statics);

// Stores what the study's line table and report read and the store lacks:
// for each bridge of a line study (each over its own jobs), else for the
// study's jobs. Returns how many trains' envelopes it computed. A structure
// whose influence lines cannot be computed (a mechanism) is left out: the
// report says why when it reads it.
std::size_t store_static_envelopes(Database& db, const std::string& study_id);
// The same for every study of the store (an upgrade from schema 13).
std::size_t store_missing_static_envelopes(Database& db);

}  // namespace railvsi::scheduler
