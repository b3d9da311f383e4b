#pragma once
// The three outputs of `vsi query`:
// - table: one line per job, then the envelope over speeds of every train
//   (maximum and governing speed) with the study's checks;
// - csv: one line per envelope value (train, irregularity, speed, quantity,
//   location, value), values only, in full precision: two runs of the same
//   study give identical files;
// - json: everything, timings and fidelity included.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "envelopes/speed_envelope.hpp"
#include "query/study_results.hpp"

namespace railvsi::scheduler {

// The envelope over speeds (results/ envelope_over_speeds) of one quantity,
// trains in the order of the study.
std::vector<TrainEnvelope> study_envelope_over_speeds(const std::vector<JobResult>& jobs, const std::string& quantity);

std::string format_table(const StudyInfo& study, const std::vector<JobResult>& jobs);
std::string format_csv(const std::vector<JobResult>& jobs);
nlohmann::ordered_json format_json(const StudyInfo& study, const std::vector<JobResult>& jobs);

}  // namespace railvsi::scheduler
