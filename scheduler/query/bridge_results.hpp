#pragma once
// A line study's jobs read bridge by bridge: each bridge's jobs as
// study_results gives them for `--structure NAME`, in the study's order,
// one bridge in memory at a time (the line table and the line report).
#include <memory>
#include <string>
#include <vector>

#include "query/study_results.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

enum class BridgeFields {
  kAll,  // every field study_results reads
  // What the checks' verdicts read (ComplianceOptions::checks_only): the
  // job's labels, state and step (not why it was chosen), its bound of the structure and whether
  // its train is axle forces (read from one scene per train and operator
  // key, not per job), and only the envelope values the checks judge. No
  // fidelity record, warnings, timings or profile family.
  kVerdicts,
  // kVerdicts without the envelope values: which jobs a bridge has, for
  // the static envelopes stored at submission (stored_statics.hpp).
  kLabels,
};

class BridgeReader {
 public:
  BridgeReader(Database& db, const std::string& study_id, BridgeFields fields);
  ~BridgeReader();
  BridgeReader(const BridgeReader&) = delete;
  BridgeReader& operator=(const BridgeReader&) = delete;
  // The next bridge's name and jobs; false after the last one.
  bool next(std::string& name, std::vector<JobResult>& jobs);

 private:
  struct Statements;
  std::unique_ptr<Statements> s_;
};

}  // namespace railvsi::scheduler
