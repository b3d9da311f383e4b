#pragma once
// Shard stores: `vsi shard` splits a study into N self-contained study
// databases, each an ordinary store (vsi work runs and resumes it, vsi
// status reads it) holding the study row (same study id), its share of the
// jobs with their study_jobs rows (positions of the whole study) and one
// row of the table `shard` saying which shard of how many it is.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shards/shard_plan.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

struct ShardMarker {
  std::string study_id;
  int index = 0;
  int count = 0;
  double estimated_cost = 0.0;
};

// The `shard` row of a store; nullopt for a store that is not a shard.
std::optional<ShardMarker> shard_marker(Database& db);

// PRAGMA user_version of an open store (its schema version).
int store_schema_version(Database& db);

// The jobs of a study in study order with their estimated cost: time steps
// (engine planned_steps) x model DOFs (structure + vehicles). One scene per
// operator key and train is built; the other jobs differ only in speed and
// profile, which change the step count, not the model.
std::vector<ShardJob> estimate_study_jobs(Database& db, const std::string& study_id);

// "shard-K.sqlite".
std::string shard_file_name(int index);

struct WrittenShards {
  std::vector<std::filesystem::path> files;
  ShardPlan plan;
};

// Writes dir/shard-0.sqlite .. shard-(N-1).sqlite from the study in
// `source` (which is only read). Every job is written queued. The files are
// built in a temporary directory inside dir and moved in place at the end,
// so an error leaves no shard behind. Throws InputError (file = dir) when
// dir already holds shard stores: they may hold results.
WrittenShards write_shards(Database& source, const std::string& study_id, int shards, const std::filesystem::path& dir);

}  // namespace railvsi::scheduler
