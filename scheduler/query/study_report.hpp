#pragma once
// The three outputs of `vsi query`:
// - table (80 columns, control characters escaped): one line per job, then
//   the envelope over speeds of every train (maximum and governing speed)
//   with the study's checks and a flag when it is at the edge of the speed
//   range, then, for random profiles with several seeds, the mean, standard
//   deviation and extreme over the seeds;
// - csv: one line per envelope value (train, irregularity, speed, quantity,
//   location, value, state) in full precision, and one line with empty
//   quantity, location and value for a job without values (cancelled,
//   failed, not yet run), so that no job silently drops out; two runs of
//   the same study give identical files. Wide: one line per job (train x
//   speed x profile), one column per quantity x location;
// - json: everything, timings, fidelity and the statistics over seeds per
//   train x speed (profile_statistics) included; the verdicts of the checks
//   (compliance_data) are added by format_checks_json.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compliance/check_verdict.hpp"
#include "envelopes/profile_statistics.hpp"
#include "envelopes/speed_envelope.hpp"
#include "query/study_results.hpp"

namespace railvsi::scheduler {

// The envelope over speeds (results/ envelope_over_speeds) of one quantity,
// trains in the order of the study.
std::vector<TrainEnvelope> study_envelope_over_speeds(const std::vector<JobResult>& jobs, const std::string& quantity);

// Mean, standard deviation (divisor n - 1) and extreme of one quantity over
// the seeds of each random profile, per train x speed.
std::vector<SampleStatistics> study_profile_statistics(const std::vector<JobResult>& jobs, const std::string& quantity);

// The governing value sits at the first or last speed the train runs (of at
// least three): a larger value may lie beyond the range.
bool at_edge_of_speed_range(const std::vector<JobResult>& jobs, const TrainEnvelope& envelope);

std::string format_table(const StudyInfo& study, const std::vector<JobResult>& jobs);
std::string format_csv(const std::vector<JobResult>& jobs);
// A CSV field: quoted when it holds a comma, quote or line break, and after
// a quote when a spreadsheet would read it as a formula.
std::string csv_field(const std::string& text);
// Columns: train, irregularity, speed_kmh, state, then per quantity (in the
// order of format_csv) the whole job's value named by the quantity
// ("deck_acceleration_mps2") and one column per location named
// "quantity@location" ("deck_acceleration_mps2@midspan"); a cell is empty
// where the job has no such value.
std::string format_wide_csv(const std::vector<JobResult>& jobs);
// Per check: its limit, clause, verdict, governing case (with its job id)
// and missing cases, overall and per train (README "vsi query --format json").
nlohmann::ordered_json format_checks_json(const std::vector<CheckResult>& checks, const std::vector<JobResult>& jobs);
// One line per check for the terminal: its verdict, governing value and limit.
std::string format_verdict_lines(const std::vector<CheckResult>& checks, Verdict overall);
nlohmann::ordered_json format_json(const StudyInfo& study, const std::vector<JobResult>& jobs);

}  // namespace railvsi::scheduler
