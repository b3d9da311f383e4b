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

}  // namespace railvsi::scheduler
