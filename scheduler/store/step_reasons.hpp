#pragma once
// A job's step reason (why its dt_s is what it is: the planner's words, the
// same for every job of a structure) is stored once in step_reasons and the
// job's row holds its number (jobs.step_reason); the view job_records gives
// the text back as dt_reason.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "store/sqlite.hpp"

namespace railvsi::scheduler {

// The reasons of one transaction's jobs: looked up or added once each (a
// reason added by a transaction that rolls back is gone, so the map dies with it).
class StepReasonCache {
 public:
  explicit StepReasonCache(Database& db);
  // The number of the reason (step_reasons.number), added when new.
  std::int64_t number(std::string_view reason);

 private:
  Statement insert_, find_;
  std::map<std::string, std::int64_t, std::less<>> numbers_;
};

}  // namespace railvsi::scheduler
