#include "shards/shard_store.hpp"

#include <unistd.h>

#include <map>
#include <utility>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/unix_time.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "shards/attached_store.hpp"
#include "simulation/simulation.hpp"
#include "store/store_schema.hpp"

namespace railvsi::scheduler {

std::optional<ShardMarker> shard_marker(Database& db) {
  Statement s = db.prepare("SELECT study_id, shard_index, shard_count, estimated_cost FROM shard LIMIT 1");
  if (!s.step()) return std::nullopt;
  return ShardMarker{s.text(0), static_cast<int>(s.int64(1)), static_cast<int>(s.int64(2)), s.real(3)};
}

int store_schema_version(Database& db) {
  Statement s = db.prepare("PRAGMA user_version");
  s.step();
  return static_cast<int>(s.int64(0));
}

namespace {

int model_dofs(const Scene& scene) {
  int dofs = scene.structure->num_dofs();
  for (const TrainVehicle& v : scene.train.vehicles) dofs += v.model->num_dofs();
  return dofs;
}

}  // namespace

std::vector<ShardJob> estimate_study_jobs(Database& db, const std::string& study_id) {
  Statement s = db.prepare(
      "SELECT j.id, j.operator_key, j.train, j.speed_kmh, j.scene FROM study_job_links sj "
      "JOIN job_records j ON j.seq = sj.job_seq WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?) "
      "ORDER BY sj.position");
  s.bind(1, study_id);
  std::map<std::pair<std::string, std::string>, Scene> scenes;  // (operator key, train) -> a scene of the group
  std::vector<ShardJob> jobs;
  while (s.step()) {
    ShardJob job{s.text(0), s.text(1), 0.0};
    auto [it, fresh] = scenes.try_emplace({job.operator_key, s.text(2)});
    const std::string name = "job " + job.id.substr(0, 12);
    // File names in a job are absolute (made so at submission).
    if (fresh) it->second = parse_scene(parse_json_text(s.text(4), name), "/", name);
    Scene at_speed = it->second;
    at_speed.speed_mps = s.real(3) / 3.6;
    job.cost = static_cast<double>(planned_steps(at_speed)) * model_dofs(at_speed);
    jobs.push_back(std::move(job));
  }
  return jobs;
}

std::string shard_file_name(int index) { return fmt::format("shard-{}.sqlite", index); }

namespace {

bool holds_shards(const std::filesystem::path& dir) {
  if (!std::filesystem::is_directory(dir)) return false;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("shard-") && name.ends_with(".sqlite")) return true;
  }
  return false;
}

// A store file with its WAL side files, moved together.
void move_store(const std::filesystem::path& from, const std::filesystem::path& to) {
  for (const char* suffix : {"-wal", "-shm"}) {
    const std::filesystem::path side = from.string() + suffix;
    if (std::filesystem::exists(side)) std::filesystem::rename(side, to.string() + suffix);
  }
  std::filesystem::rename(from, to);
}

// Removes the temporary directory unless released.
class TemporaryDirectory {
 public:
  explicit TemporaryDirectory(std::filesystem::path path) : path_(std::move(path)) {
    std::filesystem::create_directories(path_);
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

void copy_shard(Database& source, const std::string& study_id, const std::vector<std::string>& job_ids,
                const ShardMarker& marker, const std::filesystem::path& file) {
  {
    Database shard(file.string());
    migrate(shard);
  }  // closed: the WAL is checkpointed into the file
  source.exec("CREATE TEMP TABLE IF NOT EXISTS shard_job_ids (id TEXT PRIMARY KEY)");
  source.exec("DELETE FROM temp.shard_job_ids");
  AttachedStore attached(source, file, "dst");
  DeferredTransaction tx(source);
  Statement add = source.prepare("INSERT INTO temp.shard_job_ids (id) VALUES (?)");
  for (const std::string& id : job_ids) add.bind(1, id).run();
  source.prepare("INSERT INTO dst.studies (id, name, file, document, checks, job_count, submitted_at) "
                 "SELECT id, name, file, document, checks, job_count, submitted_at FROM main.studies WHERE id = ?")
      .bind(1, study_id)
      .run();
  source.prepare("INSERT INTO dst.cache_stats (study_id) VALUES (?)").bind(1, study_id).run();
  // The definition of each job; its state starts afresh (queued).
  // seq: the source's numbers are unique, so they serve the new store.
  // With its planned rung and modes: a worker batches the modal moving-force
  // jobs of one key only when they carry their rung.
  // Their scenes' parts under the source's numbers too (the new store has none).
  // And their step reasons.
  source.exec("INSERT INTO dst.scene_parts (part, head, tail) SELECT part, head, tail FROM main.scene_parts "
              "WHERE part IN (SELECT scene_part FROM main.jobs WHERE id IN temp.shard_job_ids)");
  source.exec("INSERT INTO dst.step_reasons (number, text) SELECT number, text FROM main.step_reasons "
              "WHERE number IN (SELECT step_reason FROM main.jobs WHERE id IN temp.shard_job_ids)");
  source.prepare("INSERT INTO dst.jobs (id, train, speed_kmh, irregularity, operator_key, dt_s, step_reason, "
                 "cutoff_hz, max_attempts, enqueued_at, seq, rung, planned_modes, scene_part, scene_speed) SELECT id, "
                 "train, speed_kmh, irregularity, operator_key, dt_s, step_reason, cutoff_hz, max_attempts, ?, seq, rung, "
                 "planned_modes, scene_part, scene_speed FROM main.jobs WHERE id IN temp.shard_job_ids")
      .bind(1, unix_now_s())
      .run();
  source.prepare("INSERT INTO dst.study_jobs (study_id, job_id, position) SELECT study_id, job_id, position "
                 "FROM main.study_jobs WHERE study_id = ? AND job_id IN temp.shard_job_ids")
      .bind(1, study_id)
      .run();
  source.prepare("INSERT INTO dst.study_structures (study_id, job_id, structure, position) SELECT study_id, job_id, "
                 "structure, position FROM main.study_structures WHERE study_id = ? AND job_id IN temp.shard_job_ids")
      .bind(1, study_id)
      .run();
  source.prepare("INSERT INTO dst.shard (study_id, shard_index, shard_count, estimated_cost, created_at) "
                 "VALUES (?, ?, ?, ?, ?)")
      .bind(1, study_id)
      .bind(2, marker.index)
      .bind(3, marker.count)
      .bind(4, marker.estimated_cost)
      .bind(5, unix_now_s())
      .run();
  tx.commit();
}

}  // namespace

WrittenShards write_shards(Database& source, const std::string& study_id, int shards, const std::filesystem::path& dir) {
  if (shards < 1) throw InputError("", "--shards must be at least 1", dir.string());
  if (holds_shards(dir))
    throw InputError("", "the directory already holds shard stores (they may hold results): choose another --out or "
                         "remove them first", dir.string());
  WrittenShards out;
  const std::vector<ShardJob> jobs = estimate_study_jobs(source, study_id);
  out.plan = balance_shards(jobs, shards);

  std::filesystem::create_directories(dir);
  const TemporaryDirectory tmp(dir / fmt::format(".vsi-shard-{}", ::getpid()));
  for (int k = 0; k < shards; ++k) {
    const auto& members = out.plan.shards[static_cast<std::size_t>(k)];
    std::vector<std::string> ids;
    for (std::size_t j : members) ids.push_back(jobs[j].id);
    copy_shard(source, study_id, ids, {study_id, k, shards, out.plan.costs[static_cast<std::size_t>(k)]},
               tmp.path() / shard_file_name(k));
  }
  for (int k = 0; k < shards; ++k) {
    out.files.push_back(dir / shard_file_name(k));
    move_store(tmp.path() / shard_file_name(k), out.files.back());
  }
  return out;
}

}  // namespace railvsi::scheduler
