// Migrations upgrade a store in place. 8: the scenes and fidelity records
// of a version-7 store move out of the jobs rows, and every reader still
// sees them (view job_records), unchanged to the byte. 9: the envelopes are
// keyed by the job's number; view envelopes gives them by job id as before.
// 12: records and price rows take the schema's spelling of the load model.
// 13: the envelopes are stored by a small key of quantity and location;
// view job_envelopes gives (and takes) them as the table did. 14: the
// trains' static envelopes of a line study are stored; an older store gets
// them on its upgrade, the same rows a submission stores. 15: a scene
// is its part (shared by the jobs that differ in speed alone) and its
// speed's text, studies link their jobs and bridges by the store's numbers;
// views job_scenes, study_jobs and study_structures give the very rows, and
// vsi query the very bytes, of before. 16: the step's reason and the
// fidelity record are numbers of rows stored once; view job_records gives
// the very rows, vsi query and report the very bytes, of before.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/sha256.hpp"
#include "query/study_results.hpp"
#include "queue/job_queue.hpp"
#include "scheduler_test_support.hpp"
#include "store/scene_parts.hpp"
#include "store/store_check.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using namespace railvsi::scheduler;

class StoreMigration : public ServiceTest {};

// Every sqlite_schema entry (type, name, table, SQL text), the migrations
// recorded and the version: what tells two stores' schemas apart.
std::vector<std::string> schema_of(Database& db) {
  std::vector<std::string> entries;
  Statement s = db.prepare("SELECT type, name, tbl_name, coalesce(sql, '') FROM sqlite_schema ORDER BY type, name");
  while (s.step()) entries.push_back(s.text(0) + " " + s.text(1) + " on " + s.text(2) + ": " + s.text(3));
  Statement v = db.prepare("SELECT version, description FROM schema_version ORDER BY version");
  while (v.step()) entries.push_back("migration " + std::to_string(v.int64(0)) + ": " + v.text(1));
  entries.push_back("user_version " + std::to_string(count_rows(db, "PRAGMA user_version")));
  return entries;
}

// Claims and completes every queued job as done with `envelopes`; how many.
std::size_t complete_every_job(Database& db, const std::vector<EnvelopeRow>& envelopes) {
  JobQueue queue(db, "test:worker");
  std::size_t completed = 0;
  JobOutcome o;
  o.status = "ok";
  o.ok = true;
  o.fidelity = "{}";
  o.envelopes = envelopes;
  while (auto job = queue.claim()) {
    EXPECT_TRUE(queue.complete(*job, o));
    ++completed;
  }
  return completed;
}

// Jobs written as vsi wrote them from store version 9 to 14: the scene a
// row of the table job_scenes. Returns how many.
std::size_t insert_jobs_before_15(Database& db, const std::vector<JobSpec>& jobs) {
  Statement job = db.prepare(
      "INSERT INTO jobs (id, train, speed_kmh, irregularity, operator_key, dt_s, dt_reason, cutoff_hz, enqueued_at, "
      "rung, seq) VALUES (?, ?, ?, ?, ?, ?, ?, ?, 0, ?, (SELECT coalesce(max(seq), 0) + 1 FROM jobs))");
  Statement scene = db.prepare("INSERT INTO job_scenes (job_id, scene) VALUES (?, ?)");
  for (const JobSpec& j : jobs) {
    job.bind(1, j.id).bind(2, j.train).bind(3, j.speed_kmh).bind(4, j.irregularity).bind(5, j.operator_key);
    job.bind(6, j.dt_s).bind(7, j.dt_reason).bind(8, j.cutoff_hz);
    if (j.rung.empty()) job.bind_null(9); else job.bind(9, j.rung);
    job.run();
    scene.bind(1, j.id).bind(2, j.scene).run();
  }
  return jobs.size();
}

TEST_F(StoreMigration, ANewStoreGetsInOneStepTheSchemaOfEveryMigrationInTurn) {
  Database fresh((dir_ / "fresh.sqlite").string());
  migrate(fresh);
  Database stepwise((dir_ / "stepwise.sqlite").string());
  for (int v = 1; v <= kStoreSchemaVersion; ++v) migrate(stepwise, v);
  const std::vector<std::string> expected = schema_of(stepwise);
  EXPECT_EQ(schema_of(fresh), expected);
  if (HasFailure()) {
    // What fresh_store_schema.cpp must hold: the entries' SQL in order of creation.
    std::string sql;
    Statement s = stepwise.prepare("SELECT sql FROM sqlite_schema WHERE sql IS NOT NULL ORDER BY rowid");
    while (s.step()) sql += s.text(0) + ";\n";
    ADD_FAILURE() << "the schema of a new store after the last migration:\n" << sql;
  }
  EXPECT_EQ(count_rows(fresh, "SELECT count(*) FROM pragma_integrity_check WHERE integrity_check <> 'ok'"), 0);
  // A file that is not empty never takes the one-step path. One that holds
  // the migrations' table alone (a first migrate interrupted before any
  // migration ran, say) is migrated in turn, whose CREATE ... IF NOT EXISTS
  // takes it as it is (the one-step SQL would fail on it), to the same schema.
  Database started((dir_ / "started.sqlite").string());
  started.exec("CREATE TABLE schema_version (version INTEGER PRIMARY KEY, applied_at REAL NOT NULL, "
               "description TEXT NOT NULL)");
  migrate(started);
  EXPECT_EQ(schema_of(started), expected);
}

TEST_F(StoreMigration, EightMovesScenesAndFidelityOutOfTheJobsRows) {
  const StudyPlan plan = expand_study(tiny_study(), dir_, (dir_ / "s.json").string());
  ASSERT_GE(plan.jobs.size(), 3u);
  const std::string record_a = R"({"model":"moving_forces","structure":"modal"})";
  const std::string record_b = R"({"model":"interaction","structure":"fe"})";
  {
    // A version-7 store as that vsi wrote it: scene and fidelity in the jobs rows.
    Database db((dir_ / "old.sqlite").string());
    migrate(db, 7);
    Statement insert = db.prepare(
        "INSERT INTO jobs (id, scene, train, speed_kmh, irregularity, operator_key, dt_s, dt_reason, cutoff_hz, "
        "enqueued_at, state, fidelity) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, 0, ?, ?)");
    for (std::size_t k = 0; k < plan.jobs.size(); ++k) {
      const JobSpec& j = plan.jobs[k];
      insert.bind(1, j.id).bind(2, j.scene).bind(3, j.train).bind(4, j.speed_kmh).bind(5, j.irregularity);
      insert.bind(6, j.operator_key).bind(7, j.dt_s).bind(8, j.dt_reason).bind(9, j.cutoff_hz);
      // Two jobs share record a, one has b, the others none yet (queued).
      if (k < 3) insert.bind(10, "done").bind(11, k < 2 ? record_a : record_b);
      else insert.bind(10, "queued").bind_null(11);
      insert.run();
    }
  }
  Database db((dir_ / "old.sqlite").string());
  migrate(db);
  EXPECT_EQ(count_rows(db, "PRAGMA user_version"), kStoreSchemaVersion);
  // The jobs rows hold neither text any more ...
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM pragma_table_info('jobs') WHERE name IN ('scene', 'fidelity')"), 0);
  // ... the scenes are in job_scenes, each record once in fidelity_records.
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM job_scenes"), static_cast<std::int64_t>(plan.jobs.size()));
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM fidelity_records"), 2);
  for (std::size_t k = 0; k < plan.jobs.size(); ++k) {
    Statement s = db.prepare("SELECT scene, fidelity, fidelity_id FROM job_records WHERE id = ?");
    ASSERT_TRUE(s.bind(1, plan.jobs[k].id).step());
    EXPECT_EQ(s.text(0), plan.jobs[k].scene);
    if (k < 3) {
      const std::string& record = k < 2 ? record_a : record_b;
      EXPECT_EQ(s.text(1), record);
      EXPECT_EQ(s.text(2), sha256_hex(record)) << "the record's id is the SHA-256 of its text, as vsi work stores it";
    } else {
      EXPECT_TRUE(s.is_null(1));
      EXPECT_TRUE(s.is_null(2));
    }
  }
  // The upgraded store works: the queued jobs are claimed with their scene,
  // and a completion stores its record once.
  JobQueue queue(db, "test:worker");
  std::vector<ClaimedJob> claimed;
  while (auto job = queue.claim()) claimed.push_back(std::move(*job));
  ASSERT_EQ(claimed.size(), plan.jobs.size() - 3);
  for (const ClaimedJob& c : claimed) {
    EXPECT_EQ(c.id, sha256_hex(c.scene)) << "the scene claimed is the job's own";
    JobOutcome o;
    o.status = "ok";
    o.fidelity = record_a;
    o.envelopes = {{"deck_acceleration_mps2", "", 1.0}};
    EXPECT_TRUE(queue.complete(c, o));
  }
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM fidelity_records"), 2);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM job_records WHERE fidelity IS NOT NULL"),
            static_cast<std::int64_t>(plan.jobs.size()));
  // fidelity_id has no foreign key (see migration 8): vsi check is what
  // finds a record gone missing. (This hand-made store has other problems:
  // its jobs are in no study; the deletion adds exactly one.)
  const std::vector<std::string> before = check_store(db).problems;
  for (const std::string& p : before) EXPECT_EQ(p.find("scene"), std::string::npos) << p;
  for (const std::string& p : before) EXPECT_EQ(p.find("fidelity"), std::string::npos) << p;
  db.exec("DELETE FROM fidelity_records WHERE record = '{\"model\":\"interaction\",\"structure\":\"fe\"}'");
  const std::vector<std::string> after = check_store(db).problems;
  ASSERT_EQ(after.size(), before.size() + 1);
  EXPECT_EQ(std::count_if(after.begin(), after.end(),
                          [](const std::string& p) { return p.find("fidelity record is missing") != std::string::npos; }),
            1);
}

TEST_F(StoreMigration, NineKeysTheEnvelopesByTheJobsNumberAndKeepsThemByJobId) {
  const StudyPlan plan = expand_study(tiny_study(), dir_, (dir_ / "s.json").string());
  ASSERT_GE(plan.jobs.size(), 3u);
  {
    // A version-8 store: envelopes keyed by job id, one of them verified.
    Database db((dir_ / "old.sqlite").string());
    migrate(db, 8);
    Statement insert = db.prepare(
        "INSERT INTO jobs (id, train, speed_kmh, irregularity, operator_key, dt_s, dt_reason, cutoff_hz, "
        "enqueued_at, state) VALUES (?, ?, ?, ?, ?, ?, ?, ?, 0, ?)");
    Statement envelope = db.prepare(
        "INSERT INTO envelopes (job_id, quantity, location, value, error_estimate) VALUES (?, ?, ?, ?, ?)");
    for (std::size_t k = 0; k < plan.jobs.size(); ++k) {
      const JobSpec& j = plan.jobs[k];
      insert.bind(1, j.id).bind(2, j.train).bind(3, j.speed_kmh).bind(4, j.irregularity).bind(5, j.operator_key);
      insert.bind(6, j.dt_s).bind(7, j.dt_reason).bind(8, j.cutoff_hz).bind(9, k < 2 ? "done" : "queued").run();
      db.prepare("INSERT INTO job_scenes (job_id, scene) VALUES (?, ?)").bind(1, j.id).bind(2, j.scene).run();
      if (k >= 2) continue;
      envelope.bind(1, j.id).bind(2, "deck_acceleration_mps2").bind(3, "").bind(4, 1.5 + k).bind(5, 0.25).run();
      envelope.bind(1, j.id).bind(2, "deck_acceleration_mps2").bind(3, "midspan").bind(4, 1.25 + k).bind_null(5).run();
      envelope.bind(1, j.id).bind(2, "deck_displacement_m").bind(3, "").bind_null(4).bind_null(5).run();
    }
  }
  Database db((dir_ / "old.sqlite").string());
  migrate(db);
  EXPECT_EQ(count_rows(db, "PRAGMA user_version"), kStoreSchemaVersion);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE seq IS NULL"), 0);
  EXPECT_EQ(count_rows(db, "SELECT count(DISTINCT seq) FROM jobs"), static_cast<std::int64_t>(plan.jobs.size()));
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM job_envelopes"), 6);
  // Every value (NULL included) and estimate by job id, as before.
  for (std::size_t k = 0; k < 2; ++k) {
    Statement s = db.prepare(
        "SELECT quantity, location, value, error_estimate FROM envelopes WHERE job_id = ? ORDER BY quantity, location");
    s.bind(1, plan.jobs[k].id);
    ASSERT_TRUE(s.step());
    EXPECT_EQ(s.text(1), "");
    EXPECT_EQ(s.real(2), 1.5 + static_cast<double>(k));
    EXPECT_EQ(s.real(3), 0.25);
    ASSERT_TRUE(s.step());
    EXPECT_EQ(s.text(1), "midspan");
    EXPECT_EQ(s.real(2), 1.25 + static_cast<double>(k));
    EXPECT_TRUE(s.is_null(3));
    ASSERT_TRUE(s.step());
    EXPECT_EQ(s.text(0), "deck_displacement_m");
    EXPECT_TRUE(s.is_null(2));
    EXPECT_FALSE(s.step());
  }
  // A job added after the upgrade gets the next number, and its completion
  // is found by job id.
  StudyPlan more = expand_study(tiny_study(), dir_, (dir_ / "s.json").string());
  more.jobs.front().id = sha256_hex("another scene");
  more.jobs.front().scene = "another scene";
  ASSERT_EQ(insert_jobs(db, {more.jobs.front()}, 3, 0.0), 1u);
  EXPECT_EQ(count_rows(db, "SELECT seq FROM jobs WHERE id = '" + more.jobs.front().id + "'"),
            static_cast<std::int64_t>(plan.jobs.size()) + 1);
  const std::size_t completed = complete_every_job(db, {{"deck_acceleration_mps2", "", 2.0}});
  EXPECT_EQ(completed, plan.jobs.size() - 2 + 1);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes WHERE job_id = '" + more.jobs.front().id + "' AND value = 2.0"), 1);
  const std::vector<std::string> before = check_store(db).problems;
  for (const std::string& p : before) {
    EXPECT_EQ(p.find("envelopes"), std::string::npos) << p;
    EXPECT_EQ(p.find("number"), std::string::npos) << p;
  }
  // A job that lost its number is what vsi check reports (its envelopes could not be stored).
  db.exec("DELETE FROM job_envelopes WHERE job_seq = (SELECT seq FROM jobs WHERE id = '" + more.jobs.front().id + "')");
  db.exec("UPDATE jobs SET seq = NULL WHERE id = '" + more.jobs.front().id + "'");
  const std::vector<std::string> after = check_store(db).problems;
  EXPECT_EQ(std::count_if(after.begin(), after.end(),
                          [](const std::string& p) { return p.find("jobs without a number") != std::string::npos; }),
            1);
}

TEST_F(StoreMigration, TwelveSpellsTheLoadModelAsTheSchemaDoesInRecordsAndPriceRows) {
  const StudyPlan plan = expand_study(tiny_study(), dir_, (dir_ / "s.json").string());
  ASSERT_GE(plan.jobs.size(), 3u);
  // Records as a version-11 vsi wrote them (nlohmann's dump, keys sorted).
  const std::string old_record = R"json({"model":"moving-forces","structure_backend":"modal (3 modes)"})json";
  const std::string other_record = R"json({"model":"interaction","structure_backend":"cholmod"})json";
  const std::string new_record = R"json({"model":"moving_forces","structure_backend":"modal (3 modes)"})json";
  {
    Database db((dir_ / "old.sqlite").string());
    migrate(db, 11);
    ASSERT_EQ(insert_jobs_before_15(db, plan.jobs), plan.jobs.size());
    for (const std::string& r : {old_record, other_record})
      db.prepare("INSERT INTO fidelity_records (id, record) VALUES (?, ?)").bind(1, sha256_hex(r)).bind(2, r).run();
    db.prepare("UPDATE jobs SET fidelity_id = ? WHERE id <> ?").bind(1, sha256_hex(old_record)).bind(2, plan.jobs[0].id).run();
    db.prepare("UPDATE jobs SET fidelity_id = ? WHERE id = ?").bind(1, sha256_hex(other_record)).bind(2, plan.jobs[0].id).run();
    db.exec("INSERT INTO studies (id, name, file, document, checks, job_count, submitted_at) VALUES ('s1', 's', 's.json', '{}', '{}', 0, 0)");
    for (const char* model : {"moving-forces", "interaction"})
      db.prepare("INSERT INTO price_rows (study_id, job_id, run, model, structure, contact_law, dt_s, status, cpu_s, "
                 "wall_s, reference, quantity, pareto, priced_at) VALUES ('s1', ?, ?, ?, 'fe', 'none', 0.001, 'ok', 1, "
                 "1, 0, 'deck_acceleration_mps2', 0, 0)")
          .bind(1, plan.jobs[0].id).bind(2, std::string(model) == "interaction" ? 1 : 0).bind(3, model).run();
  }
  Database db((dir_ / "old.sqlite").string());
  migrate(db);
  EXPECT_EQ(count_rows(db, "PRAGMA user_version"), kStoreSchemaVersion);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM fidelity_records WHERE instr(record, 'moving-forces') > 0"), 0);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM fidelity_records"), 2);
  // Each job's record by its key: the respelled one under its own SHA-256,
  // the other untouched; no job points to a record that is gone.
  Statement s = db.prepare("SELECT j.id, j.fidelity_id, f.record FROM job_records j LEFT JOIN fidelity_records f "
                           "ON f.id = j.fidelity_id ORDER BY j.id");
  int jobs = 0;
  while (s.step()) {
    ++jobs;
    const bool first = s.text(0) == plan.jobs[0].id;
    ASSERT_FALSE(s.is_null(2)) << s.text(0);
    EXPECT_EQ(s.text(2), first ? other_record : new_record);
    EXPECT_EQ(s.text(1), sha256_hex(first ? other_record : new_record));
  }
  EXPECT_EQ(jobs, static_cast<int>(plan.jobs.size()));
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM price_rows WHERE model = 'moving_forces'"), 1);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM price_rows WHERE model = 'interaction'"), 1);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM price_rows WHERE model = 'moving-forces'"), 0);
}

TEST_F(StoreMigration, ThirteenKeepsEveryEnvelopeToTheBitAndTheViewWritesThrough) {
  const StudyPlan plan = expand_study(tiny_study(), dir_, (dir_ / "s.json").string());
  ASSERT_GE(plan.jobs.size(), 3u);
  // Values a run may store: signed zeros, integers, subnormals, the largest
  // double, NULL; each job a different order of quantities.
  const std::vector<std::optional<double>> values = {0.1, -0.0, 0.0, 3.0, 5e-324, std::numeric_limits<double>::max(),
                                                     -1.25e-7, std::nullopt, 123456789.123456789};
  struct Row {
    std::string job_id, quantity, location;
    std::optional<double> value, estimate;
  };
  std::vector<Row> written;
  {
    // A version-12 store: envelopes one row per quantity and location, one verified.
    Database db((dir_ / "old.sqlite").string());
    migrate(db, 12);
    ASSERT_EQ(insert_jobs_before_15(db, plan.jobs), plan.jobs.size());
    Statement e = db.prepare("INSERT INTO job_envelopes (job_seq, quantity, location, value, error_estimate) "
                             "VALUES ((SELECT seq FROM jobs WHERE id = ?), ?, ?, ?, ?)");
    const std::vector<std::pair<std::string, std::string>> names = {
        {"deck_acceleration_mps2", ""}, {"deck_acceleration_mps2", "x=7.5"}, {"shear_force_N", "x=7.5"},
        {"support_reaction_N", "support1"}, {"support_reaction_N", "support2"}, {"newton_iterations", ""}};
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t n = 0; n < names.size(); ++n) {
        const auto& [q, l] = names[(n + k) % names.size()];
        Row r{plan.jobs[k].id, q, l, values[(n + 2 * k) % values.size()], std::nullopt};
        if (k == 1 && n % 2 == 0) r.estimate = -0.0125 * static_cast<double>(n + 1);
        e.bind(1, r.job_id).bind(2, r.quantity).bind(3, r.location);
        if (r.value) e.bind(4, *r.value); else e.bind_null(4);
        if (r.estimate) e.bind(5, *r.estimate); else e.bind_null(5);
        e.run();
        written.push_back(r);
      }
    // What the version-12 store gives back (SQLite's own storage of a REAL,
    // e.g. of a negative zero) is what the upgrade must keep.
    Statement back = db.prepare("SELECT value, error_estimate FROM envelopes WHERE job_id = ? AND quantity = ? AND location = ?");
    for (Row& r : written) {
      back.bind(1, r.job_id).bind(2, r.quantity).bind(3, r.location);
      ASSERT_TRUE(back.step());
      r.value = back.optional_real(0);
      r.estimate = back.optional_real(1);
      back.reset();
    }
    for (std::size_t k = 0; k < 3; ++k)
      db.prepare("UPDATE jobs SET state = 'done' WHERE id = ?").bind(1, plan.jobs[k].id).run();
  }
  Database db((dir_ / "old.sqlite").string());
  migrate(db);
  EXPECT_EQ(count_rows(db, "PRAGMA user_version"), kStoreSchemaVersion);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelope_keys"), 6);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelope_values"), static_cast<std::int64_t>(written.size()));
  const auto bits = [](const std::optional<double>& v) {
    return v ? std::optional(std::bit_cast<std::uint64_t>(*v)) : std::nullopt;
  };
  // Every row by job id through the view envelopes, to the bit (the sign of
  // zero included), NULLs as NULL.
  Statement s = db.prepare("SELECT value, error_estimate FROM envelopes WHERE job_id = ? AND quantity = ? AND location = ?");
  for (const Row& r : written) {
    s.bind(1, r.job_id).bind(2, r.quantity).bind(3, r.location);
    ASSERT_TRUE(s.step()) << r.quantity << " " << r.location;
    EXPECT_EQ(bits(s.optional_real(0)), bits(r.value)) << r.quantity << " " << r.location;
    EXPECT_EQ(bits(s.optional_real(1)), bits(r.estimate)) << r.quantity << " " << r.location;
    EXPECT_FALSE(s.step());
    s.reset();
  }
  // The view takes writes as the table did: an estimate set, a row added
  // under a new key, a row deleted; a duplicate is refused.
  db.prepare("UPDATE job_envelopes SET error_estimate = 0.5 WHERE job_seq = (SELECT seq FROM jobs WHERE id = ?) "
             "AND quantity = 'shear_force_N' AND location = 'x=7.5'").bind(1, plan.jobs[2].id).run();
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes WHERE error_estimate = 0.5"), 1);
  db.prepare("INSERT INTO job_envelopes (job_seq, quantity, location, value) "
             "VALUES ((SELECT seq FROM jobs WHERE id = ?), 'bending_moment_Nm', 'x=7.5', 2.5)").bind(1, plan.jobs[2].id).run();
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelope_keys"), 7);
  EXPECT_THROW(db.prepare("INSERT INTO job_envelopes (job_seq, quantity, location, value) "
                          "VALUES ((SELECT seq FROM jobs WHERE id = ?), 'bending_moment_Nm', 'x=7.5', 3.5)")
                   .bind(1, plan.jobs[2].id).run(),
               SqliteError);
  db.prepare("DELETE FROM job_envelopes WHERE job_seq = (SELECT seq FROM jobs WHERE id = ?)").bind(1, plan.jobs[0].id).run();
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes WHERE job_id = '" + plan.jobs[0].id + "'"), 0);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelope_values"), static_cast<std::int64_t>(written.size()) - 6 + 1);
  // Job 0, its rows gone, runs again.
  db.prepare("UPDATE jobs SET state = 'queued' WHERE id = ?").bind(1, plan.jobs[0].id).run();
  // A completion after the upgrade stores its rows under the keys there are
  // and a new one; vsi check finds nothing amiss with them.
  const std::size_t completed = complete_every_job(
      db, {{"deck_acceleration_mps2", "", 0.1}, {"carbody_acceleration_mps2", "car1", std::nullopt}});
  ASSERT_GT(completed, 0u);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelope_keys"), 8);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes WHERE quantity = 'carbody_acceleration_mps2' AND value IS NULL"),
            static_cast<std::int64_t>(completed));
  Statement z = db.prepare("SELECT value FROM envelopes WHERE quantity = 'deck_acceleration_mps2' AND location = '' "
                           "AND job_id NOT IN (?, ?)");
  z.bind(1, plan.jobs[1].id).bind(2, plan.jobs[2].id);  // they keep their rows of before
  std::size_t zeros = 0;
  while (z.step()) {
    EXPECT_EQ(bits(z.optional_real(0)), bits(0.1));
    ++zeros;
  }
  EXPECT_EQ(zeros, completed);
  for (const std::string& p : check_store(db).problems) EXPECT_EQ(p.find("envelope"), std::string::npos) << p;
  // vsi's connections enforce the key; a row of another writer may lack it.
  EXPECT_THROW(db.exec("INSERT INTO envelope_values (job_seq, key, value) VALUES (1, 999, 1.0)"), SqliteError);
  db.exec("PRAGMA foreign_keys = OFF");
  db.exec("INSERT INTO envelope_values (job_seq, key, value) VALUES (1, 999, 1.0)");
  const std::vector<std::string> after = check_store(db).problems;
  EXPECT_EQ(std::count_if(after.begin(), after.end(),
                          [](const std::string& p) { return p.find("no known quantity") != std::string::npos; }),
            1);
}

// The rows of the store `now_db` written as a version-13 store holds them
// (tables job_scenes, study_jobs, study_structures keyed by SHA-256 texts;
// no static envelopes) into the new file `old_db`.
void write_as_version_13(const std::string& now_db, const std::string& old_db) {
  Database old(old_db);
  migrate(old, 13);
  old.exec("ATTACH '" + now_db + "' AS now");
  old.exec("INSERT INTO studies (id, name, file, document, checks, job_count, submitted_at) "
           "SELECT id, name, file, document, checks, job_count, submitted_at FROM now.studies");
  old.exec("INSERT INTO fidelity_records (id, record) SELECT id, record FROM now.fidelity_records");
  old.exec("INSERT INTO jobs (id, train, speed_kmh, irregularity, operator_key, dt_s, dt_reason, cutoff_hz, state, "
           "attempts, max_attempts, worker, lease_expires, error, status, steps, wall_s, loop_s, setup_s, "
           "factorization_s, enqueued_at, started_at, finished_at, warnings, rung, fidelity_id, seq, planned_modes) "
           "SELECT id, train, speed_kmh, irregularity, operator_key, dt_s, dt_reason, cutoff_hz, state, attempts, "
           "max_attempts, worker, lease_expires, error, status, steps, wall_s, loop_s, setup_s, factorization_s, "
           "enqueued_at, started_at, finished_at, warnings, rung, fidelity_id, seq, planned_modes FROM now.job_records "
           "ORDER BY seq");
  old.exec("INSERT INTO job_scenes (job_id, scene) SELECT job_id, scene FROM now.job_scenes");
  old.exec("INSERT INTO study_jobs SELECT study_id, job_id, position FROM now.study_jobs");
  old.exec("INSERT INTO study_structures SELECT study_id, job_id, structure, position FROM now.study_structures");
  old.exec("INSERT INTO cache_stats SELECT * FROM now.cache_stats");
  old.exec("INSERT INTO envelope_keys SELECT * FROM now.envelope_keys");
  old.exec("INSERT INTO envelope_values SELECT * FROM now.envelope_values");
}

TEST_F(StoreMigration, FourteenStoresTheStaticEnvelopesOfAnOldStoresLineOnItsUpgradeAsASubmissionDoes) {
  json doc = tiny_study();
  json a = doc["structure"], b = doc["structure"];
  b["spans_m"] = {12};
  doc.erase("structure");
  doc["structures"] = json::array({{{"name", "A"}, {"structure", a}}, {{"name", "B"}, {"structure", b}}});
  const auto file = write_json("line.json", doc);
  const std::string old_db = (dir_ / "old.sqlite").string(), new_db = (dir_ / "new.sqlite").string();
  const VsiResult submitted = vsi({"submit", file.string(), "--db", new_db}, "submit");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  // A version-13 store of the same line: the submission's rows as vsi 13
  // held them, without the static envelopes (its schema has no such table).
  write_as_version_13(new_db, old_db);
  {
    Database db(old_db);
    EXPECT_EQ(count_rows(db, "SELECT count(*) FROM sqlite_schema WHERE name = 'static_envelopes'"), 0);
  }
  const VsiResult upgrade = vsi({"work", "--db", old_db, "--threads", "1"}, "upgrade");
  ASSERT_EQ(upgrade.exit_code, 0) << upgrade.err;
  EXPECT_NE(upgrade.err.find("the static envelopes of 4 trains stored"), std::string::npos) << upgrade.err;
  // Every row, its value's bits included: (structure job, train job,
  // quantity, place, location, bits or NULL).
  const auto rows = [](const std::string& file) {
    Database db(file, OpenMode::kReadOnly);
    EXPECT_EQ(count_rows(db, "PRAGMA user_version"), kStoreSchemaVersion);
    std::vector<std::string> out;
    Statement s = db.prepare("SELECT structure_job, train_job, quantity, place, location, value FROM static_envelopes "
                             "ORDER BY structure_job, train_job, quantity, place");
    while (s.step()) {
      const std::optional<double> v = s.optional_real(5);
      out.push_back(s.text(0) + " " + s.text(1) + " " + s.text(2) + " " + std::to_string(s.int64(3)) + " " +
                    s.text(4) + " " + (v ? std::to_string(std::bit_cast<std::uint64_t>(*v)) : "NULL"));
    }
    return out;
  };
  const std::vector<std::string> upgraded = rows(old_db);
  // 2 bridges x 2 trains x (2 output points x deflection, moment and shear
  // + 2 supports x reaction and rotation).
  EXPECT_EQ(upgraded.size(), 2u * 2u * (2u * 3u + 2u * 2u));
  EXPECT_EQ(rows(new_db), upgraded);
  // The upgrade is done once: the next writer finds the current schema and stores nothing.
  const VsiResult again = vsi({"work", "--db", old_db, "--threads", "1"}, "again");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(again.err.find("static envelopes"), std::string::npos) << again.err;
}


// Every row of a query as text ('|' between columns, NULL as \N), sorted:
// what a table and the view that replaces it must both give.
std::vector<std::string> rows_of(Database& db, const std::string& sql) {
  std::vector<std::string> rows;
  Statement s = db.prepare(sql);
  while (s.step()) {
    std::string row;
    for (int c = 0; c < s.columns(); ++c) {
      if (c > 0) row += '|';
      row += s.is_null(c) ? std::string("\\N") : s.text(c);
    }
    rows.push_back(row);
  }
  std::sort(rows.begin(), rows.end());
  return rows;
}

TEST_F(StoreMigration, SceneSplitGivesBackEveryTextToTheByte) {
  // Speeds as canonical JSON writes them, a scene without one, text after
  // the number up to '}' only, UTF-8 before the key, a key in a string.
  for (const std::string& scene :
       {std::string(R"({"analysis":{"dt_s":0.001},"speed_kmh":103.5,"train":"HSLM-A1"})"), std::string(R"({"speed_kmh":100})"),
        std::string(R"({"train":"x"})"), std::string(R"({"name":"Brücke \"speed_kmh\":1","speed_kmh":2e2,"z":0})"),
        std::string(R"({"speed_kmh":)"), std::string()}) {
    const SceneSplit s = split_scene(scene);
    EXPECT_EQ(std::string(s.head) + std::string(s.speed) + std::string(s.tail), scene);
  }
  const SceneSplit s = split_scene(R"({"analysis":{},"speed_kmh":103.5,"train":"A"})");
  EXPECT_EQ(s.head, R"({"analysis":{},"speed_kmh":)");
  EXPECT_EQ(s.speed, "103.5");
  EXPECT_EQ(s.tail, R"(,"train":"A"})");
}

// A line study of three bridges (A and C one structure, "Brücke B" another).
nlohmann::json three_bridge_line() {
  nlohmann::json doc = tiny_study();
  nlohmann::json span12 = doc["structure"];
  span12["spans_m"] = {12.0};
  doc["structures"] = json::array({{{"name", "A"}, {"structure", doc["structure"]}},
                                   {{"name", "Brücke B"}, {"structure", span12}},
                                   {{"name", "C"}, {"structure", doc["structure"]}}});
  doc.erase("structure");
  return doc;
}

TEST_F(StoreMigration, FifteenKeepsEverySceneAndLinkToTheByteAndVsiQueryGivesTheSameBytes) {
  // A line study (bridges A and C one structure, B another) run on this
  // vsi's schema ...
  const std::string now_db = (dir_ / "now.sqlite").string(), old_db = (dir_ / "old.sqlite").string();
  ASSERT_EQ(vsi({"run", write_json("line.json", three_bridge_line()).string(), "--db", now_db}, "run").exit_code, 0);
  // ... and the same rows written as a version-13 store holds them (tables
  // job_scenes, study_jobs, study_structures keyed by SHA-256 texts).
  write_as_version_13(now_db, old_db);
  Database old(old_db);
  const std::vector<std::string> scenes = rows_of(old, "SELECT job_id, scene FROM job_scenes");
  const std::vector<std::string> links = rows_of(old, "SELECT * FROM study_jobs");
  const std::vector<std::string> bridges = rows_of(old, "SELECT * FROM study_structures");
  const std::vector<std::string> records = rows_of(old, "SELECT * FROM job_records");
  ASSERT_EQ(scenes.size(), 20u);   // 2 structures x 2 trains x 5 speeds
  ASSERT_EQ(bridges.size(), 30u);  // A and C share their 10 jobs
  migrate(old);
  EXPECT_EQ(count_rows(old, "PRAGMA user_version"), kStoreSchemaVersion);
  // The views give the very rows: scenes to the byte (SHA-256 of each is its id).
  EXPECT_EQ(rows_of(old, "SELECT job_id, scene FROM job_scenes"), scenes);
  EXPECT_EQ(count_rows(old, "SELECT count(*) FROM job_scenes WHERE vsi_sha256(scene) != job_id"), 0);
  EXPECT_EQ(rows_of(old, "SELECT * FROM study_jobs"), links);
  EXPECT_EQ(rows_of(old, "SELECT * FROM study_structures"), bridges);
  // job_records as before, with the two new columns of jobs at the end.
  std::vector<std::string> upgraded_records = rows_of(
      old, "SELECT id, train, speed_kmh, irregularity, operator_key, dt_s, dt_reason, cutoff_hz, state, attempts, "
           "max_attempts, worker, lease_expires, error, status, steps, wall_s, loop_s, setup_s, factorization_s, "
           "enqueued_at, started_at, finished_at, warnings, rung, fidelity_id, seq, planned_modes, scene, fidelity "
           "FROM job_records");
  EXPECT_EQ(upgraded_records, records);
  // One part per structure and train: the 5 speeds of each share it.
  EXPECT_EQ(count_rows(old, "SELECT count(*) FROM scene_parts"), 4);
  // The claim index holds the queued jobs alone: none after the run.
  EXPECT_EQ(count_rows(old, "SELECT count(*) FROM jobs INDEXED BY jobs_claim WHERE state = 'queued'"), 0);
  for (const std::string& p : check_store(old).problems) ADD_FAILURE() << p;

  // vsi query reads the upgraded store to the byte as the store run on
  // this schema: the table, CSV, JSON and the line table.
  const std::string study = rows_of(old, "SELECT id FROM studies").at(0);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{}, {"--format", "csv"}, {"--format", "json"}, {"--line"}, {"--line", "--format", "csv"},
        {"--structure", "Brücke B", "--format", "json"}}) {
    std::vector<std::string> on_old = {"query", "--db", old_db, "--study", study}, on_now = on_old;
    on_now[2] = now_db;
    on_old.insert(on_old.end(), args.begin(), args.end());
    on_now.insert(on_now.end(), args.begin(), args.end());
    const VsiResult a = vsi(on_old, "q-old"), b = vsi(on_now, "q-now");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_EQ(a.out, b.out) << args.size();
    EXPECT_GT(a.out.size(), 200u) << "an output to compare";
  }

  // The views take writes as the tables did: a job added with its scene
  // and link; a duplicate link refused, OR IGNORE ignored; a link deleted.
  const std::string scene = R"({"speed_kmh":777,"train":"Zug ü"})";
  const std::string id = sha256_hex(scene);
  old.prepare("INSERT INTO jobs (id, train, speed_kmh, irregularity, operator_key, dt_s, cutoff_hz, "
              "enqueued_at, seq) VALUES (?, 'Zug ü', 777, 'none', 'k', 0.001, 30, 0, 1000)")
      .bind(1, id)
      .run();
  old.prepare("INSERT INTO job_scenes (job_id, scene) VALUES (?, ?)").bind(1, id).bind(2, scene).run();
  EXPECT_EQ(rows_of(old, "SELECT scene FROM job_scenes WHERE job_id = '" + id + "'"), std::vector<std::string>{scene});
  old.prepare("INSERT INTO study_jobs (study_id, job_id, position) VALUES (?, ?, 99)").bind(1, study).bind(2, id).run();
  EXPECT_EQ(count_rows(old, "SELECT count(*) FROM study_jobs WHERE position = 99 AND job_id = '" + id + "'"), 1);
  EXPECT_THROW(old.prepare("INSERT INTO study_jobs (study_id, job_id, position) VALUES (?, ?, 98)")
                   .bind(1, study).bind(2, id).run(),
               SqliteError);
  old.prepare("INSERT OR IGNORE INTO study_jobs (study_id, job_id, position) VALUES (?, ?, 98)").bind(1, study).bind(2, id).run();
  EXPECT_THROW(old.prepare("INSERT INTO study_jobs (study_id, job_id, position) VALUES (?, 'no such job', 97)")
                   .bind(1, study).run(),
               SqliteError);
  old.prepare("INSERT INTO study_structures (study_id, job_id, structure, position) VALUES (?, ?, 'Brücke B', 1)")
      .bind(1, study).bind(2, id).run();
  EXPECT_EQ(count_rows(old, "SELECT count(*) FROM study_structures WHERE structure = 'Brücke B'"), 11);
  old.prepare("DELETE FROM study_jobs WHERE job_id = ?").bind(1, id).run();
  EXPECT_EQ(count_rows(old, "SELECT count(*) FROM study_jobs"), 20);
}

// The rows of the store `now_db` written as a version-15 store holds them
// (the step's reason and the fidelity record's id as texts in each job's
// row) into the new file `old_db`.
void write_as_version_15(const std::string& now_db, const std::string& old_db) {
  Database old(old_db);
  migrate(old, 15);
  old.exec("ATTACH '" + now_db + "' AS now");
  old.exec("INSERT INTO studies (id, name, file, document, checks, job_count, submitted_at, seq) "
           "SELECT id, name, file, document, checks, job_count, submitted_at, seq FROM now.studies");
  old.exec("INSERT INTO fidelity_records (id, record) SELECT id, record FROM now.fidelity_records");
  old.exec("INSERT INTO scene_parts SELECT * FROM now.scene_parts");
  old.exec("INSERT INTO jobs (id, train, speed_kmh, irregularity, operator_key, dt_s, dt_reason, cutoff_hz, state, "
           "attempts, max_attempts, worker, lease_expires, error, status, steps, wall_s, loop_s, setup_s, "
           "factorization_s, enqueued_at, started_at, finished_at, warnings, rung, fidelity_id, seq, planned_modes, "
           "scene_part, scene_speed) SELECT id, train, speed_kmh, irregularity, operator_key, dt_s, dt_reason, "
           "cutoff_hz, state, attempts, max_attempts, worker, lease_expires, error, status, steps, wall_s, loop_s, "
           "setup_s, factorization_s, enqueued_at, started_at, finished_at, warnings, rung, fidelity_id, seq, "
           "planned_modes, scene_part, scene_speed FROM now.job_records ORDER BY seq");
  for (const char* table : {"study_job_links", "study_bridges", "study_bridge_jobs", "cache_stats", "envelope_keys",
                            "envelope_values", "static_envelopes"})
    old.exec(fmt::format("INSERT INTO {0} SELECT * FROM now.{0}", table));
}

TEST_F(StoreMigration, SixteenNumbersTheStepReasonsAndFidelityRecordsAndVsiQueryAndReportGiveTheSameBytes) {
  // The line study of the test above (two structures, three bridges), run
  // on this vsi's schema ...
  const std::string now_db = (dir_ / "now.sqlite").string(), old_db = (dir_ / "old.sqlite").string();
  ASSERT_EQ(vsi({"run", write_json("line.json", three_bridge_line()).string(), "--db", now_db}, "run").exit_code, 0);
  // ... and as a version-15 store holds it.
  write_as_version_15(now_db, old_db);
  std::vector<std::string> records;
  std::int64_t reasons = 0, fidelities = 0;
  {
    Database old(old_db);
    records = rows_of(old, "SELECT * FROM job_records");
    reasons = count_rows(old, "SELECT count(DISTINCT dt_reason) FROM jobs");
    fidelities = count_rows(old, "SELECT count(DISTINCT fidelity_id) FROM jobs");
    ASSERT_EQ(records.size(), 20u);  // 2 structures x 2 trains x 5 speeds
    ASSERT_GE(reasons, 1);
    ASSERT_GE(fidelities, 1);
  }
  // A writing command upgrades it.
  const VsiResult upgrade = vsi({"work", "--db", old_db, "--threads", "1"}, "upgrade");
  ASSERT_EQ(upgrade.exit_code, 0) << upgrade.err;
  {
    Database old(old_db);
    EXPECT_EQ(count_rows(old, "PRAGMA user_version"), kStoreSchemaVersion);
    // job_records gives every row and column of before, to the byte, and
    // the store run on this schema the same rows.
    EXPECT_EQ(rows_of(old, "SELECT * FROM job_records"), records);
    Database now(now_db, OpenMode::kReadOnly);
    EXPECT_EQ(rows_of(now, "SELECT * FROM job_records"), records);
    // Each text once; the rows hold their numbers, not the texts.
    EXPECT_EQ(count_rows(old, "SELECT count(*) FROM step_reasons"), reasons);
    EXPECT_EQ(count_rows(old, "SELECT count(*) FROM fidelity_records"), fidelities);
    EXPECT_EQ(count_rows(old, "SELECT count(*) FROM pragma_table_info('jobs') WHERE name IN ('dt_reason', 'fidelity_id')"), 0);
    EXPECT_EQ(count_rows(old, "SELECT count(*) FROM jobs WHERE step_reason IS NULL OR fidelity_record IS NULL"), 0);
    for (const std::string& p : check_store(old).problems) ADD_FAILURE() << p;
  }
  // vsi query and the report read the upgraded store to the byte as the
  // store run on this schema.
  std::string study;
  {
    Database old(old_db, OpenMode::kReadOnly);
    study = rows_of(old, "SELECT id FROM studies").at(0);
  }
  ::setenv("SOURCE_DATE_EPOCH", "1800000000", 1);  // the report's date (the child inherits it)
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"query"}, {"query", "--format", "csv"}, {"query", "--format", "json"},
        {"query", "--line"}, {"query", "--line", "--format", "csv"}, {"query", "--line", "--format", "json"},
        {"query", "--structure", "Brücke B", "--format", "json"},
        {"report", "--no-histories", "--format", "json"}}) {
    std::vector<std::string> on_old = args;
    on_old.insert(on_old.begin() + 1, {"--db", old_db, "--study", study});
    std::vector<std::string> on_now = on_old;
    on_now[2] = now_db;
    const VsiResult a = vsi(on_old, "old"), b = vsi(on_now, "now");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_EQ(a.out, b.out) << args.back();
    EXPECT_GT(a.out.size(), 200u) << "an output to compare";
  }
  ::unsetenv("SOURCE_DATE_EPOCH");
}
}  // namespace
}  // namespace railvsi::test
