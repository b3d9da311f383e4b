#pragma once
// The jobs of a study `vsi price --db F --study ID` prices: its governing
// cases (for each priced quantity, the job of the governing value of the
// envelope over speeds that query and report show), then, up to the
// number asked, jobs spread evenly over the study's order.
#include <string>
#include <vector>

#include "query/study_results.hpp"

namespace railvsi::scheduler {

struct SampledJob {
  JobResult job;
  std::vector<std::string> reasons;  // "governing deck_acceleration_mps2", "sample"
};

// Only jobs done with status ok. jobs <= 0 or fewer than the governing
// cases: the governing cases alone. every_train: the governing case of
// each train (each line of query's envelope over speeds), not only the
// one over trains. Throws std::runtime_error when the study is not in the
// database or has no ok job.
std::vector<SampledJob> price_sample(Database& db, const std::string& study_id, int jobs, bool every_train = false);

}  // namespace railvsi::scheduler
