#pragma once
// Everything the compliance report shows, gathered from the study database
// alone: the checks (EN 1990 A2 / EN 1991-2) against the stored envelopes,
// response-against-speed plots, the governing cases re-simulated from their
// stored scenes, the static response of each train and of LM71 from the
// same structure, the model and the inputs.
#include <string>
#include <vector>

#include "query/study_results.hpp"
#include "report/compliance_report.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

struct ComplianceOptions {
  std::string version;  // vsi version for the report
  std::string date;     // the date line (the only text that changes between two reports of one store)
  bool histories = true;  // re-simulate the governing cases
  int max_governing_cases = 4;
  // The jobs to judge, already read (vsi query's, after its filters);
  // all of the study's jobs, read here, when null.
  const std::vector<JobResult>* jobs = nullptr;
  // Only the checks and the overall verdict (vsi query --line): no trains,
  // model, rungs, issues, prices, phi'dyn table, figures, modes or
  // histories. The checks are those of the whole report, to the bit.
  bool checks_only = false;
};

// Throws std::runtime_error when the study is not in the database, and
// InputError when a stored scene can no longer be loaded (e.g. a train
// library file removed since submission).
ComplianceReport build_compliance_report(Database& db, const std::string& study_id, const ComplianceOptions& options);

}  // namespace railvsi::scheduler
