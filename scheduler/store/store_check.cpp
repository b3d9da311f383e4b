#include "store/store_check.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "store/store_schema.hpp"

namespace railvsi::scheduler {
namespace {

// A query whose rows each describe one problem (its first column).
void collect(Database& db, std::string_view sql, std::vector<std::string>& problems) {
  Statement s = db.prepare(sql);
  while (s.step()) problems.push_back(s.text(0));
}

// A count that must be zero, with what a non-zero count means.
struct Invariant {
  const char* sql;
  const char* meaning;
};

const Invariant kInvariants[] = {
    {"SELECT count(*) FROM jobs WHERE state = 'running' AND (lease_expires IS NULL OR worker IS NULL)",
     "running jobs without a lease or a worker (they would never return to the queue)"},
    {"SELECT count(*) FROM jobs WHERE state != 'running' AND lease_expires IS NOT NULL",
     "jobs under a lease that are not running"},
    {"SELECT count(*) FROM jobs WHERE state IN ('done', 'failed', 'cancelled') AND finished_at IS NULL",
     "finished jobs without a finish time"},
    {"SELECT count(*) FROM jobs j WHERE state = 'done' AND NOT EXISTS (SELECT 1 FROM job_envelopes e WHERE e.job_seq = j.seq)",
     "done jobs without envelopes"},
    {"SELECT count(*) FROM (SELECT DISTINCT e.job_seq FROM job_envelopes e JOIN jobs j ON j.seq = e.job_seq "
     "WHERE j.state != 'done')",
     "jobs with envelopes that are not done"},
    {"SELECT count(*) FROM jobs WHERE seq IS NULL", "jobs without a number (jobs.seq: their envelopes could not be stored)"},
    {"SELECT count(*) FROM envelope_values v WHERE NOT EXISTS (SELECT 1 FROM envelope_keys k WHERE k.key = v.key)",
     "envelope values of no known quantity and location (envelope_keys)"},
    {"SELECT count(*) FROM jobs j WHERE NOT EXISTS (SELECT 1 FROM study_job_links sj WHERE sj.job_seq = j.seq) "
     "AND NOT EXISTS (SELECT 1 FROM verification_jobs v WHERE v.verify_job_id = j.id)",
     "jobs of no study (nor verifying one)"},
    // A shard store links part of its study's jobs: fewer is not a problem.
    {"SELECT count(*) FROM studies s WHERE job_count < (SELECT count(*) FROM study_job_links sj WHERE sj.study_seq = s.seq)",
     "studies with more jobs linked than they have"},
    {"SELECT count(*) FROM jobs WHERE attempts > max_attempts OR attempts < 0",
     "jobs with more attempts than allowed"},
    {"SELECT count(*) FROM jobs j WHERE NOT EXISTS (SELECT 1 FROM scene_parts p WHERE p.part = j.scene_part) "
     "OR j.scene_speed IS NULL",
     "jobs without a scene"},
    {"SELECT count(*) FROM studies WHERE seq IS NULL", "studies without a number (studies.seq: their jobs cannot be linked)"},
    {"SELECT count(*) FROM jobs j WHERE fidelity_record IS NOT NULL "
     "AND NOT EXISTS (SELECT 1 FROM fidelity_records f WHERE f.number = j.fidelity_record)",
     "jobs whose fidelity record is missing"},
    {"SELECT count(*) FROM jobs j WHERE NOT EXISTS (SELECT 1 FROM step_reasons r WHERE r.number = j.step_reason)",
     "jobs without a step reason"},
};

}  // namespace

StoreCheck check_store(Database& db) {
  StoreCheck check;
  auto& problems = check.problems;
  try {
    std::vector<std::string> integrity;
    collect(db, "PRAGMA integrity_check(100)", integrity);
    if (!(integrity.size() == 1 && integrity.front() == "ok"))
      for (const std::string& line : integrity) problems.push_back("integrity: " + line);
  } catch (const SqliteError& e) {
    problems.push_back(fmt::format("integrity check could not run: {}", e.what()));
    return check;  // the file is not readable enough for the rest
  }
  try {
    Statement s = db.prepare("PRAGMA user_version");
    s.step();
    if (s.int64(0) != kStoreSchemaVersion)
      problems.push_back(fmt::format("schema version {}, this vsi's is {}", s.int64(0), kStoreSchemaVersion));
    collect(db,
            "SELECT 'foreign key: ' || fk.\"table\" || ' refers to a missing row of ' || fk.parent "
            "FROM pragma_foreign_key_check AS fk LIMIT 100",
            problems);
    for (const Invariant& inv : kInvariants) {
      Statement c = db.prepare(inv.sql);
      c.step();
      if (const std::int64_t n = c.int64(0); n > 0) problems.push_back(fmt::format("{} {}", n, inv.meaning));
    }
    Statement counts = db.prepare("SELECT (SELECT count(*) FROM studies), (SELECT count(*) FROM jobs)");
    counts.step();
    check.studies = counts.int64(0);
    check.jobs = counts.int64(1);
  } catch (const SqliteError& e) {
    problems.push_back(fmt::format("queue check could not run: {}", e.what()));
  }
  return check;
}

void require_sound(Database& db) {
  Statement s = db.prepare("PRAGMA quick_check(1)");
  std::string first;
  if (s.step()) first = s.text(0);
  if (first != "ok")
    throw std::runtime_error(fmt::format("{} is damaged (PRAGMA quick_check: {}); vsi check --db {} lists the problems",
                                         db.file(), first, db.file()));
}

namespace {

std::runtime_error inconsistent(Database& db, const std::string& study_id, const std::string& why) {
  return std::runtime_error(fmt::format("{} is damaged or inconsistent: study {}: {}; vsi check --db {} lists the problems",
                                        db.file(), study_id.substr(0, 12), why, db.file()));
}

}  // namespace

std::runtime_error done_jobs_without_envelopes(Database& db, const std::string& study_id, std::int64_t count) {
  return inconsistent(db, study_id, fmt::format("{} done jobs have no envelopes", count));
}

void require_consistent_study(Database& db, const std::string& study_id, StudyCheck what) {
  // A shard store holds part of a study: job_count bounds the links, it
  // need not equal them. The join to jobs reads their number index alone.
  Statement s = db.prepare(
      "SELECT (SELECT job_count FROM studies WHERE id = ?1), "
      "(SELECT count(*) FROM study_job_links WHERE study_seq = (SELECT seq FROM studies WHERE id = ?1)), "
      "(SELECT count(*) FROM study_job_links INDEXED BY study_job_links_job "
      "WHERE study_seq = (SELECT seq FROM studies WHERE id = ?1)), "
      "(SELECT count(*) FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq "
      "WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?1))");
  s.bind(1, study_id).step();
  const std::int64_t listed = s.int64(0), linked = s.int64(1), indexed = s.int64(2), found = s.int64(3);
  if (linked != indexed || linked != found || linked > listed)
    throw inconsistent(db, study_id,
                       fmt::format("the study lists {} jobs; {} are linked to it, {} through the job index and {} found",
                                   listed, linked, indexed, found));
  if (what == StudyCheck::kLinks) return;
  Statement b = db.prepare(
      "SELECT count(*) FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq "
      "WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?1) AND j.state = 'done' "
      "AND NOT EXISTS (SELECT 1 FROM job_envelopes e WHERE e.job_seq = j.seq)");
  b.bind(1, study_id).step();
  if (const std::int64_t bare = b.int64(0); bare > 0) throw done_jobs_without_envelopes(db, study_id, bare);
}

}  // namespace railvsi::scheduler
