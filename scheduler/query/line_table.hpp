#pragma once
// The line table of a line study (its "structures"): one row per bridge
// with the verdict of each check of vsi report, its governing value and
// the train and speed that govern it. Each bridge is judged over its own
// jobs exactly as a study of that bridge alone would be.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "query/bridge_results.hpp"
#include "query/compliance_data.hpp"
#include "query/study_results.hpp"
#include "report/line_summary.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

// The bridges of `jobs` (study_results of a line study) in the study's
// order, each with the compliance report of its jobs; `options.jobs` is
// ignored. Empty when no job names a bridge. Takes the jobs, and lets each
// bridge's go once it is judged.
std::vector<LineBridge> line_bridges(Database& db, const std::string& study_id, std::vector<JobResult> jobs,
                                     ComplianceOptions options);
// The same over all of the study's jobs, read bridge by bridge
// (BridgeReader): one bridge's jobs in memory at a time. With
// options.checks_only each bridge's report holds its checks and verdict
// only, read from what they judge (BridgeFields::kVerdicts).
std::vector<LineBridge> line_bridges(Database& db, const std::string& study_id, ComplianceOptions options);

// vsi query --line: a text table, a CSV (one line per bridge and check:
// structure,check,verdict,value,limit,unit,train,speed_kmh,location) and
// JSON (one object per bridge).
std::string format_line_table(const std::vector<LineBridge>& bridges);
std::string format_line_csv(const std::vector<LineBridge>& bridges);
nlohmann::ordered_json format_line_json(const std::vector<LineBridge>& bridges);

}  // namespace railvsi::scheduler
