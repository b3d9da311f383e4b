#pragma once
// `vsi merge`: the shard stores of one study into one store that answers
// query exactly as a single-machine run (same jobs, same positions, same
// envelope values). Idempotent: a job already done in the target is left
// as it is, so merging the same shards again adds nothing; a job not yet
// finished in the target is replaced when its shard has finished it, so
// merging again after more work completes the store.
#include <filesystem>
#include <string>
#include <vector>

#include "queue/job_queue.hpp"

namespace railvsi::scheduler {

struct MergedShard {
  std::filesystem::path file;
  int index = 0;
  StateCounts counts;        // the shard's jobs per state
  std::int64_t new_jobs = 0;  // jobs added to or completed in the target by this merge
};

struct MergeSummary {
  std::string study_id;
  std::string study_name;
  int shard_count = 0;
  std::vector<MergedShard> shards;  // by index
  std::vector<int> missing;         // indices of the study's shards not given
  std::int64_t new_jobs = 0;
  StateCounts target;               // the study's jobs per state in the target after the merge
  bool complete() const { return missing.empty() && target.unfinished() == 0; }
};

// Checks every file before writing anything: each must be a shard store
// (table `shard`), of this vsi's store schema version, all of one study and
// one shard count, no index twice. Throws InputError naming the file
// otherwise. The shards are only read. Each shard is merged in one
// transaction of the target (created when missing).
MergeSummary merge_shards(const std::vector<std::filesystem::path>& shard_files, const std::filesystem::path& into);

}  // namespace railvsi::scheduler
