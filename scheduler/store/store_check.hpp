#pragma once
// `vsi check`: is the study database sound? SQLite's own integrity and
// foreign-key checks, then the queue's invariants (a running job has a
// lease, a done job has its envelopes, a study has all its jobs...).
#include <cstdint>
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
void require_consistent_study(Database& db, const std::string& study_id);

}  // namespace railvsi::scheduler
