#pragma once
// `vsi check`: is the study database sound? SQLite's own integrity and
// foreign-key checks, then the queue's invariants (a running job has a
// lease, a done job has its envelopes, a study has all its jobs...).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "store/sqlite.hpp"

namespace railvsi::scheduler {

struct StoreCheck {
  std::vector<std::string> problems;  // empty: sound
  std::int64_t studies = 0, jobs = 0;
};

// Never throws for a damaged file: what cannot be read is a problem.
StoreCheck check_store(Database& db);

// PRAGMA quick_check (the b-trees, not the indexes against their tables):
// throws std::runtime_error naming the first problem. A damaged page that
// still looks like a page (e.g. a copy of another) is read by queries
// without any error, as fewer rows: the read commands run this first, so
// that they never print a partial table with exit 0. It reads the whole
// file once (0.7 s for 88 MB from the page cache).
void require_sound(Database& db);

// What quick_check cannot see (a page replaced by a copy of another reads as
// a sound page with other rows): the study's jobs counted through three
// different b-trees (its links, the links' job index, the jobs), no more
// than its job count, and its done jobs all with envelopes. Throws std::runtime_error when they disagree. Rows missing
// inside one job's envelopes remain for vsi check to find.
// kLinks: the links alone (three counts over the links' b-trees and the
// jobs' id index, no table row read): for a caller that reads every job of
// the study with its envelope values anyway (the line table and the line
// report, BridgeReader) and refuses a done job without any
// (done_job_without_envelopes) before it prints anything. The done jobs'
// envelopes are what made this check cost about as much as the line table's
// own reads (303,000 jobs: 2.2 s CPU of 10.5).
enum class StudyCheck { kAll, kLinks };
void require_consistent_study(Database& db, const std::string& study_id, StudyCheck what = StudyCheck::kAll);

// The error require_consistent_study throws for done jobs without envelopes
// (`count` of them), for a reader that finds one as it reads.
std::runtime_error done_jobs_without_envelopes(Database& db, const std::string& study_id, std::int64_t count);

}  // namespace railvsi::scheduler
