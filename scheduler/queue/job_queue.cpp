#include "queue/job_queue.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/sha256.hpp"
#include "core/unix_time.hpp"
#include "store/scene_parts.hpp"
#include "store/step_reasons.hpp"

namespace railvsi::scheduler {

SubmitResult submit_study(Database& db, const StudyPlan& plan, int max_attempts) {
  SubmitResult result;
  result.study_id = plan.id;
  result.jobs = plan.jobs.size();
  const double now = unix_now_s();
  Transaction tx(db);
  db.prepare("INSERT OR IGNORE INTO studies (id, name, file, document, checks, job_count, submitted_at) "
             "VALUES (?, ?, ?, ?, ?, ?, ?)")
      .bind(1, plan.id)
      .bind(2, plan.name)
      .bind(3, plan.file)
      .bind(4, plan.document)
      .bind(5, plan.checks.dump())
      .bind(6, static_cast<std::int64_t>(plan.jobs.size()))
      .bind(7, now)
      .run();
  result.new_study = db.changes() > 0;
  if (!result.new_study) {
    // Each link keeps its job's position in the study's plan (a shard or a
    // partial merge holds some positions; refinement appends beyond the
    // plan). Another job at a position of this plan is another expansion
    // of the same document.
    Statement links = db.prepare("SELECT job_id, position FROM study_jobs WHERE study_id = ?");
    links.bind(1, plan.id);
    const auto planned = static_cast<std::int64_t>(plan.jobs.size());
    while (links.step()) {
      ++result.stored_jobs;
      const std::int64_t at = links.int64(1);
      if (at >= 0 && at < planned && links.text(0) != plan.jobs[static_cast<std::size_t>(at)].id)
        ++result.differing_jobs;
    }
    if (result.differing_jobs > 0) {
      tx.commit();  // nothing was written
      return result;
    }
  }
  db.prepare("INSERT OR IGNORE INTO cache_stats (study_id) VALUES (?)").bind(1, plan.id).run();
  result.new_jobs = insert_study_jobs(db, plan.id, plan.jobs, 0, max_attempts, now);
  if (!plan.structures.empty()) {
    // By the store's numbers of the study and the job (the view
    // study_structures gives the names and ids).
    const std::int64_t study = study_seq(db, plan.id);
    Statement bridge = db.prepare("INSERT OR IGNORE INTO study_bridges (study_seq, position, name) VALUES (?, ?, ?)");
    for (std::size_t k = 0; k < plan.structures.size(); ++k)
      bridge.bind(1, study).bind(2, static_cast<std::int64_t>(k)).bind(3, plan.structures[k]).run();
    Statement on = db.prepare("INSERT OR IGNORE INTO study_bridge_jobs (study_seq, job_seq, position) "
                              "VALUES (?, (SELECT seq FROM jobs WHERE id = ?), ?)");
    for (const JobSpec& j : plan.jobs)
      for (int k : j.structures) on.bind(1, study).bind(2, j.id).bind(3, k).run();
  }
  tx.commit();
  return result;
}

std::int64_t study_seq(Database& db, const std::string& study_id) {
  Statement s = db.prepare("SELECT seq FROM studies WHERE id = ?");
  if (!s.bind(1, study_id).step() || s.is_null(0))
    throw std::logic_error(fmt::format("study {} is not stored (or has no number)", study_id));
  return s.int64(0);
}

std::size_t insert_jobs(Database& db, const std::vector<JobSpec>& jobs, int max_attempts, double now) {
  std::size_t new_jobs = 0;
  // The scene as its part (stored once for the jobs that share it) and its
  // speed's text: the view job_scenes gives the very text back. The step's
  // reason by its number too (view job_records).
  Statement insert_job = db.prepare(
      "INSERT OR IGNORE INTO jobs (id, train, speed_kmh, irregularity, operator_key, dt_s, step_reason, "
      "cutoff_hz, max_attempts, enqueued_at, rung, planned_modes, scene_part, scene_speed, seq) VALUES (?, ?, ?, ?, ?, "
      "?, ?, ?, ?, ?, ?, ?, ?, ?, (SELECT coalesce(max(seq), 0) + 1 FROM jobs))");
  ScenePartCache parts(db);
  StepReasonCache reasons(db);
  for (const JobSpec& j : jobs) {
    const SceneSplit split = split_scene(j.scene);
    insert_job.bind(1, j.id)
        .bind(2, j.train)
        .bind(3, j.speed_kmh)
        .bind(4, j.irregularity)
        .bind(5, j.operator_key)
        .bind(6, j.dt_s)
        .bind(7, reasons.number(j.dt_reason))
        .bind(8, j.cutoff_hz)
        .bind(9, max_attempts)
        .bind(10, now)
        .bind(11, j.rung.empty() ? SqlValue(Null{}) : SqlValue(j.rung))
        .bind(12, j.modes > 0 ? SqlValue(static_cast<std::int64_t>(j.modes)) : SqlValue(Null{}))
        .bind(13, parts.part(split))
        .bind(14, split.speed)
        .run();
    new_jobs += static_cast<std::size_t>(db.changes());
  }
  return new_jobs;
}

std::size_t insert_study_jobs(Database& db, const std::string& study_id, const std::vector<JobSpec>& jobs,
                              std::int64_t first_position, int max_attempts, double now) {
  const std::size_t new_jobs = insert_jobs(db, jobs, max_attempts, now);
  const std::int64_t study = study_seq(db, study_id);
  Statement link = db.prepare("INSERT OR IGNORE INTO study_job_links (study_seq, job_seq, position) "
                              "VALUES (?, (SELECT seq FROM jobs WHERE id = ?), ?)");
  std::int64_t position = first_position;
  for (const JobSpec& j : jobs) link.bind(1, study).bind(2, j.id).bind(3, position++).run();
  return new_jobs;
}

JobQueue::JobQueue(Database& db, std::string worker, double lease_s)
    : db_(db), worker_(std::move(worker)), lease_s_(lease_s) {
  // A NaN lease is stored NULL and never expires: the job could never return.
  if (!std::isfinite(lease_s) || lease_s <= 0.0)
    throw std::invalid_argument(fmt::format("lease of {} s: it must be a positive number of seconds", lease_s));
}

std::optional<ClaimedJob> JobQueue::claim_row(const std::string& id, double now_s) {
  db_.prepare("UPDATE jobs SET state = 'running', attempts = attempts + 1, worker = ?, lease_expires = ?, "
              "started_at = ? WHERE id = ?")
      .bind(1, worker_)
      .bind(2, now_s + lease_s_)
      .bind(3, now_s)
      .bind(4, id)
      .run();
  Statement s = db_.prepare(
      "SELECT j.id, p.head || j.scene_speed || p.tail, j.operator_key, j.train, j.irregularity, j.speed_kmh, j.dt_s, "
      "j.cutoff_hz, j.attempts, coalesce(j.rung, ''), coalesce(j.planned_modes, -1) FROM jobs j "
      "JOIN scene_parts p ON p.part = j.scene_part WHERE j.id = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return ClaimedJob{s.text(0), s.text(1), s.text(2), s.text(3), s.text(4), s.real(5), s.real(6), s.real(7),
                    static_cast<int>(s.int64(8)), s.text(9), static_cast<int>(s.int64(10))};
}

std::vector<ClaimedJob> JobQueue::claim_batch(const std::string& preferred_key, std::size_t max_jobs,
                                              const std::atomic<bool>* stopping) {
  std::vector<ClaimedJob> batch;
  Transaction tx(db_);
  if (stopping != nullptr && stopping->load()) {
    tx.commit();
    return batch;
  }
  std::optional<ClaimedJob> first = claim_in_transaction(preferred_key);
  if (first) {
    // Modal moving-force jobs of the same structure and dt run in one
    // pass per train; every job of the batch is leased like a single claim.
    if (first->rung == kBatchedRung && max_jobs > 1) {
      // One statement claims the rest, as claim_row each: queued jobs and
      // those a dead worker held (lease expired, attempts left), so that a
      // resumed run stores them in batches as a fresh one does, not one
      // transaction (and its WAL pages) per job.
      const double now = unix_now_s();
      Statement s = db_.prepare(
          "UPDATE jobs SET state = 'running', attempts = attempts + 1, worker = ?, lease_expires = ?, started_at = ? "
          "WHERE id IN (SELECT id FROM jobs WHERE operator_key = ? AND rung = ? AND (state = 'queued' OR "
          "(state = 'running' AND lease_expires < ?3 AND attempts < max_attempts)) "
          "ORDER BY train, irregularity, speed_kmh LIMIT ?) RETURNING id, operator_key, train, irregularity, speed_kmh, dt_s, "
          "cutoff_hz, attempts, rung, coalesce(planned_modes, -1), scene_part, scene_speed");
      s.bind(1, worker_)
          .bind(2, now + lease_s_)
          .bind(3, now)
          .bind(4, first->operator_key)
          .bind(5, first->rung)
          .bind(6, static_cast<std::int64_t>(max_jobs - 1));
      batch.push_back(std::move(*first));
      // Each job's scene as job_scenes gives it (head || speed || tail),
      // the batch's few parts read once each instead of the view row by row.
      // A NULL speed makes the view's text NULL: an empty scene, as before.
      struct SceneRef {
        std::int64_t part = 0;
        std::optional<std::string> speed;
      };
      std::vector<SceneRef> speeds;
      while (s.step()) {
        if (s.is_null(10)) throw std::runtime_error(fmt::format("job {} has no scene in job_scenes", s.text(0)));
        batch.push_back(ClaimedJob{s.text(0), {}, s.text(1), s.text(2), s.text(3), s.real(4), s.real(5), s.real(6),
                                   static_cast<int>(s.int64(7)), s.text(8), static_cast<int>(s.int64(9))});
        speeds.push_back({s.int64(10), s.is_null(11) ? std::nullopt : std::optional(s.text(11))});
      }
      Statement part = db_.prepare("SELECT head, tail FROM scene_parts WHERE part = ?");
      std::map<std::int64_t, std::pair<std::string, std::string>> parts;
      for (std::size_t k = 1; k < batch.size(); ++k) {
        const auto& [number, speed] = speeds[k - 1];
        auto it = parts.find(number);
        if (it == parts.end()) {
          part.reset();
          if (!part.bind(1, number).step())
            throw std::runtime_error(fmt::format("job {} has no scene in job_scenes", batch[k].id));
          it = parts.emplace(number, std::pair(part.text(0), part.text(1))).first;
        }
        if (!speed) continue;
        std::string& scene = batch[k].scene;
        scene.reserve(it->second.first.size() + speed->size() + it->second.second.size());
        scene.append(it->second.first).append(*speed).append(it->second.second);
      }
      // RETURNING follows no order: the runner wants each train's speeds
      // together and in order (one pass per train, neighbouring speeds
      // side by side).
      std::stable_sort(batch.begin(), batch.end(), [](const ClaimedJob& a, const ClaimedJob& b) {
        return std::tie(a.train, a.irregularity, a.speed_kmh) < std::tie(b.train, b.irregularity, b.speed_kmh);
      });
    } else {
      batch.push_back(std::move(*first));
    }
  }
  tx.commit();
  return batch;
}

std::optional<ClaimedJob> JobQueue::claim(const std::string& preferred_key) {
  Transaction tx(db_);
  std::optional<ClaimedJob> job = claim_in_transaction(preferred_key);
  tx.commit();
  return job;
}

std::optional<ClaimedJob> JobQueue::claim_in_transaction(const std::string& preferred_key) {
  const double now = unix_now_s();
  std::string id;
  if (!preferred_key.empty()) {
    Statement s = db_.prepare("SELECT id FROM jobs WHERE state = 'queued' AND operator_key = ? LIMIT 1");
    if (s.bind(1, preferred_key).step()) id = s.text(0);
  }
  if (id.empty()) {
    // The claim index orders queued jobs by operator key: workers drain one
    // factorization's jobs before the next. Named: the planner would take
    // jobs_lease (state, of every job), and sort the queued jobs at each
    // claim for the ORDER BY.
    Statement s = db_.prepare(
        "SELECT id FROM jobs INDEXED BY jobs_claim WHERE state = 'queued' ORDER BY operator_key, rung, train LIMIT 1");
    if (s.step()) id = s.text(0);
  }
  while (id.empty()) {
    // A running job whose lease expired: its worker died (or hung).
    Statement s = db_.prepare(
        "SELECT id, attempts, max_attempts, worker FROM jobs WHERE state = 'running' AND lease_expires < ? LIMIT 1");
    if (!s.bind(1, now).step()) break;
    if (s.int64(1) < s.int64(2)) {
      id = s.text(0);
      break;
    }
    db_.prepare("UPDATE jobs SET state = 'failed', lease_expires = NULL, finished_at = ?, error = ? WHERE id = ?")
        .bind(1, now)
        .bind(2, fmt::format("the lease expired {} times: the worker died or hung (last: {})", s.int64(1), s.text(3)))
        .bind(3, s.text(0))
        .run();
  }
  std::optional<ClaimedJob> job;
  if (!id.empty()) job = claim_row(id, now);
  return job;
}

bool JobQueue::renew(const std::string& job_id) { return renew(std::vector<std::string>{job_id}) == 1; }

std::size_t JobQueue::renew(const std::vector<std::string>& job_ids) {
  const double now = unix_now_s();
  Transaction tx(db_);
  Statement update = db_.prepare("UPDATE jobs SET lease_expires = ? WHERE id = ? AND state = 'running' AND worker = ?");
  std::size_t held = 0;
  for (const std::string& id : job_ids) {
    update.bind(1, now + lease_s_).bind(2, id).bind(3, worker_).run();
    held += static_cast<std::size_t>(db_.changes());
  }
  tx.commit();
  return held;
}

namespace {

// The job's number in the store (jobs.seq) when `worker` still holds it.
std::optional<std::int64_t> still_ours(Database& db, const ClaimedJob& job, const std::string& worker) {
  Statement s = db.prepare("SELECT state, worker, seq FROM jobs WHERE id = ?");
  if (!s.bind(1, job.id).step()) return std::nullopt;
  if (s.text(0) != "running" || s.text(1) != worker) return std::nullopt;
  return s.int64(2);
}

// What completing a job runs, prepared once per transaction (a batch
// completes many jobs in one).
struct CompleteStatements {
  explicit CompleteStatements(Database& db)
      : db(db),
        fidelity(db.prepare("INSERT OR IGNORE INTO fidelity_records (id, record) VALUES (?, ?)")),
        // Only while `worker` still holds the job; its number in the store for the envelopes.
        update(db.prepare(
            "UPDATE jobs SET state = ?, status = ?, error = ?, "
            "fidelity_record = (SELECT number FROM fidelity_records WHERE id = ?), steps = ?, wall_s = ?, loop_s = ?, "
            "setup_s = ?, factorization_s = ?, lease_expires = NULL, finished_at = ?, warnings = ? "
            "WHERE id = ? AND state = 'running' AND worker = ? RETURNING seq")),
        // WHERE true: SQLite's upsert after INSERT ... SELECT needs a WHERE clause.
        stats(db.prepare(
            "INSERT INTO cache_stats (study_id, jobs, factorizations, hits, factorization_s, evictions) "
            "SELECT study_id, 1, ?, ?, ?, ? FROM study_jobs WHERE job_id = ? "
            "ON CONFLICT (study_id) DO UPDATE SET jobs = jobs + 1, "
            "factorizations = factorizations + excluded.factorizations, hits = hits + excluded.hits, "
            "factorization_s = factorization_s + excluded.factorization_s, evictions = evictions + excluded.evictions")) {}
  // A job's envelope rows go in one statement of as many rows (up to
  // kRowsPerInsert), prepared once per count: a statement per row cost a
  // third more (8,080 rows of the 1,010-job HSLM sweep: 14 ms against 10).
  // They go to envelope_values directly (the view job_envelopes' trigger
  // would look their key up row by row).
  static constexpr std::size_t kRowsPerInsert = 64;
  Statement& insert(std::size_t rows) {
    auto it = inserts.find(rows);
    if (it == inserts.end()) {
      std::string sql = "INSERT INTO envelope_values (job_seq, key, value) VALUES (?, ?, ?)";
      for (std::size_t r = 1; r < rows; ++r) sql += ", (?, ?, ?)";
      it = inserts.emplace(rows, db.prepare(sql)).first;
    }
    return it->second;
  }
  // The key of a quantity at a location (envelope_keys), added when new.
  // Known only within this transaction: a key added by one that rolls back
  // is gone, so the map dies with the transaction.
  std::int64_t key(const std::string& quantity, const std::string& location) {
    if (keys.empty()) {
      Statement all = db.prepare("SELECT key, quantity, location FROM envelope_keys");
      while (all.step()) keys.emplace(std::pair(all.text(1), all.text(2)), all.int64(0));
    }
    const auto it = keys.find(std::pair(quantity, location));
    if (it != keys.end()) return it->second;
    db.prepare("INSERT OR IGNORE INTO envelope_keys (quantity, location) VALUES (?, ?)").bind(1, quantity).bind(2, location).run();
    Statement s = db.prepare("SELECT key FROM envelope_keys WHERE quantity = ? AND location = ?");
    if (!s.bind(1, quantity).bind(2, location).step()) throw std::logic_error("envelope key not stored");
    return keys.emplace(std::pair(quantity, location), s.int64(0)).first->second;
  }
  // key() of a job's row-th envelope row: the jobs of a batch give the same
  // rows in the same order, so the last key at that row is compared (no
  // copy of the two names) before the map is searched.
  struct RecentKey {
    std::string quantity, location;
    std::int64_t key = 0;
  };
  std::int64_t key_at(std::size_t row, const std::string& quantity, const std::string& location) {
    if (row < recent.size() && recent[row].quantity == quantity && recent[row].location == location)
      return recent[row].key;
    const std::int64_t k = key(quantity, location);
    if (row >= recent.size()) recent.resize(row + 1);
    recent[row] = {quantity, location, k};
    return k;
  }
  Database& db;
  std::vector<RecentKey> recent;
  std::map<std::size_t, Statement> inserts;
  std::map<std::pair<std::string, std::string>, std::int64_t> keys;
  Statement fidelity, update, stats;
  // The last fidelity record stored and its id: the jobs of a batch share one.
  std::string fidelity_text, fidelity_id;
  // Jobs stored that neither factorized nor evicted (cache hits): counted in
  // cache_stats once per batch (count_cache_hits) rather than one by one.
  std::vector<std::int64_t> hits;  // by the jobs' numbers (jobs.seq)
};

// Adds the batch's cache hits to the statistics of every study that holds them.
// By the jobs' numbers: the links hold them, so no job id is looked up
// (the view study_jobs joined jobs by id: 2.3-3.6 ms a pass of the 1,010 S2
// jobs' stores, 1.1 ms this way).
void count_cache_hits(Database& db, const std::vector<std::int64_t>& job_seqs) {
  if (job_seqs.empty()) return;
  db.prepare("INSERT INTO cache_stats (study_id, jobs, factorizations, hits, factorization_s, evictions) "
             "SELECT s.id, count(*), 0, count(*), 0.0, 0 FROM study_job_links l JOIN studies s ON s.seq = l.study_seq "
             "WHERE l.job_seq IN (SELECT value FROM json_each(?)) GROUP BY s.id "
             "ON CONFLICT (study_id) DO UPDATE SET jobs = jobs + excluded.jobs, hits = hits + excluded.hits")
      .bind(1, nlohmann::json(job_seqs).dump())
      .run();
}

// complete() of one job with prepared statements; false when the job is no longer `worker`'s.
bool complete_one(const ClaimedJob& job, const JobOutcome& outcome, const std::string& worker, CompleteStatements& st);
}  // namespace

bool JobQueue::complete(const ClaimedJob& job, const JobOutcome& outcome) {
  Transaction tx(db_);
  const bool stored = complete_in_transaction(job, outcome);
  tx.commit();
  return stored;
}

std::vector<bool> JobQueue::complete_batch(const std::vector<ClaimedJob>& jobs, const std::vector<JobOutcome>& outcomes) {
  if (jobs.size() != outcomes.size()) throw std::logic_error("complete_batch: one outcome per job");
  Transaction tx(db_);
  CompleteStatements statements(db_);
  std::vector<bool> stored;
  for (std::size_t i = 0; i < jobs.size(); ++i) stored.push_back(complete_one(jobs[i], outcomes[i], worker_, statements));
  count_cache_hits(db_, statements.hits);
  tx.commit();
  return stored;
}

bool JobQueue::complete_in_transaction(const ClaimedJob& job, const JobOutcome& outcome) {
  CompleteStatements statements(db_);
  const bool stored = complete_one(job, outcome, worker_, statements);
  count_cache_hits(db_, statements.hits);
  return stored;
}

namespace {

bool complete_one(const ClaimedJob& job, const JobOutcome& outcome, const std::string& worker, CompleteStatements& st) {
  // Fidelity records are stored once, by content (SHA-256 of the text),
  // before the row that holds the record's number.
  const bool new_fidelity = st.fidelity_id.empty() || st.fidelity_text != outcome.fidelity;
  if (new_fidelity) {
    st.fidelity_text = outcome.fidelity;
    st.fidelity_id = sha256_hex(outcome.fidelity);
    st.fidelity.bind(1, st.fidelity_id).bind(2, st.fidelity_text).run();
  }
  st.update.bind(1, outcome.ok ? "done" : "failed")
      .bind(2, outcome.status)
      .bind(3, outcome.ok ? SqlValue(Null{}) : SqlValue(outcome.error))
      .bind(4, st.fidelity_id)
      .bind(5, static_cast<std::int64_t>(outcome.steps))
      .bind(6, outcome.wall_s)
      .bind(7, outcome.loop_s)
      .bind(8, outcome.setup_s)
      .bind(9, outcome.factorization_s)
      .bind(10, unix_now_s())
      .bind(11, outcome.warnings)
      .bind(12, job.id)
      .bind(13, worker);
  if (!st.update.step()) {
    // No longer this worker's (taken over or cancelled): nothing else is
    // written (the record, keyed by content, is any run's).
    st.update.reset();
    return false;
  }
  const std::int64_t seq = st.update.int64(0);
  st.update.run();  // to its end (one row: the id is the key), then reset
  if (outcome.ok) {
    const std::vector<EnvelopeRow>& rows = outcome.envelopes;
    for (std::size_t first = 0; first < rows.size(); first += CompleteStatements::kRowsPerInsert) {
      const std::size_t count = std::min(CompleteStatements::kRowsPerInsert, rows.size() - first);
      Statement& insert = st.insert(count);
      for (std::size_t r = 0; r < count; ++r) {
        const EnvelopeRow& e = rows[first + r];
        const int at = static_cast<int>(3 * r);
        insert.bind(at + 1, seq).bind(at + 2, st.key_at(first + r, e.quantity, e.location));
        if (e.value) insert.bind(at + 3, *e.value);
        else insert.bind_null(at + 3);
      }
      insert.run();
    }
  }
  if (!outcome.factorized && outcome.factorization_s == 0.0 && outcome.evictions == 0) {
    st.hits.push_back(seq);
    return true;
  }
  st.stats.bind(1, outcome.factorized ? 1 : 0)
      .bind(2, outcome.factorized ? 0 : 1)
      .bind(3, outcome.factorization_s)
      .bind(4, outcome.evictions)
      .bind(5, job.id)
      .run();
  return true;
}

}  // namespace

bool JobQueue::release_after_error(const ClaimedJob& job, const std::string& error) {
  Transaction tx(db_);
  if (!still_ours(db_, job, worker_)) return false;
  db_.prepare("UPDATE jobs SET state = CASE WHEN attempts >= max_attempts THEN 'failed' ELSE 'queued' END, "
              "error = ?, worker = NULL, lease_expires = NULL, finished_at = ? WHERE id = ?")
      .bind(1, error)
      .bind(2, unix_now_s())
      .bind(3, job.id)
      .run();
  tx.commit();
  return true;
}

StateCounts state_counts(Database& db, const std::string& study_id) {
  Statement s = study_id.empty()
                    ? db.prepare("SELECT state, count(*) FROM jobs GROUP BY state")
                    : db.prepare("SELECT j.state, count(*) FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq "
                                 "WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?) GROUP BY j.state");
  if (!study_id.empty()) s.bind(1, study_id);
  StateCounts c;
  while (s.step()) {
    const std::string state = s.text(0);
    const std::int64_t n = s.int64(1);
    if (state == "queued") c.queued = n;
    else if (state == "running") c.running = n;
    else if (state == "done") c.done = n;
    else if (state == "failed") c.failed = n;
    else if (state == "cancelled") c.cancelled = n;
  }
  return c;
}

std::vector<std::string> study_ids(Database& db) {
  Statement s = db.prepare("SELECT id FROM studies ORDER BY submitted_at, id");
  std::vector<std::string> ids;
  while (s.step()) ids.push_back(s.text(0));
  return ids;
}

namespace {

// One UPDATE of the jobs of a study: ?1 is the study id, ?2 the time now.
std::int64_t update_jobs_of_study(Database& db, std::string_view sql, const std::string& study_id) {
  Transaction tx(db);
  db.prepare(sql).bind(1, study_id).bind(2, unix_now_s()).run();
  const std::int64_t n = db.changes();
  tx.commit();
  return n;
}

}  // namespace

// A job another study still needs: that study has it and has not been
// cancelled itself (no job of it is 'cancelled'; retry_study clears that).
// Unfinished jobs of a study that has been cancelled are only those kept
// for others.
constexpr std::string_view kNeededElsewhere =
    "EXISTS (SELECT 1 FROM study_jobs o WHERE o.job_id = jobs.id AND o.study_id != ?1 AND NOT EXISTS "
    "(SELECT 1 FROM study_jobs oc JOIN jobs c ON c.id = oc.job_id WHERE oc.study_id = o.study_id AND "
    "c.state = 'cancelled'))";

CancelResult cancel_study(Database& db, const std::string& study_id) {
  Transaction tx(db);
  CancelResult r;
  db.prepare(fmt::format("UPDATE jobs SET state = 'cancelled', lease_expires = NULL, finished_at = ?2 "
                         "WHERE state IN ('queued', 'running') AND id IN (SELECT job_id FROM study_jobs WHERE "
                         "study_id = ?1) AND NOT {}",
                         kNeededElsewhere))
      .bind(1, study_id)
      .bind(2, unix_now_s())
      .run();
  r.cancelled = db.changes();
  Statement left = db.prepare(fmt::format("SELECT count(*) FROM jobs WHERE state IN ('queued', 'running') AND id IN "
                                          "(SELECT job_id FROM study_jobs WHERE study_id = ?1) AND {}",
                                          kNeededElsewhere));
  left.bind(1, study_id).step();
  r.left_for_other_studies = left.int64(0);
  tx.commit();
  return r;
}

std::int64_t retry_study(Database& db, const std::string& study_id) {
  return update_jobs_of_study(
      db,
      "UPDATE jobs SET state = 'queued', attempts = 0, worker = NULL, lease_expires = NULL, finished_at = NULL, "
      "enqueued_at = ?2 WHERE state IN ('failed', 'cancelled') AND id IN (SELECT job_id FROM study_jobs WHERE study_id = ?1)",
      study_id);
}

std::int64_t release_running_jobs(Database& db, const std::string& worker_prefix) {
  Transaction tx(db);
  db.prepare("UPDATE jobs SET state = 'queued', attempts = max(attempts - 1, 0), worker = NULL, lease_expires = NULL, "
             "started_at = NULL WHERE state = 'running' AND substr(worker, 1, ?1) = ?2")
      .bind(1, static_cast<std::int64_t>(worker_prefix.size()))
      .bind(2, worker_prefix)
      .run();
  const std::int64_t released = db.changes();
  tx.commit();
  return released;
}

std::string resolve_study_id(Database& db, const std::string& prefix) {
  if (prefix.size() < 6) return {};
  Statement s = db.prepare("SELECT id FROM studies WHERE substr(id, 1, ?) = ? LIMIT 2");
  s.bind(1, static_cast<std::int64_t>(prefix.size())).bind(2, prefix);
  std::string id;
  if (s.step()) id = s.text(0);
  if (s.step()) throw std::runtime_error(fmt::format("study id prefix {} is ambiguous: give more digits", prefix));
  return id;
}

}  // namespace railvsi::scheduler
