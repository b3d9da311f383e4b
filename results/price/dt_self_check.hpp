#pragma once
// The time-step self-check of one run (vsi simulate --verify): the run's key
// quantities (price_quantities) against the same scene at dt/2. A value
// whose relative change exceeds the tolerance is not converged in dt: its
// row is flagged, and the run carries a "dt_self_check" warning per such
// value. A study does the same for its governing cases (accuracy.verify,
// scheduler/query/study_verification). Pure functions: no runs here.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "envelopes/job_envelopes.hpp"
#include "simulation/result.hpp"

namespace railvsi {

// The overall envelope values of price_quantities(), by name.
std::map<std::string, std::optional<double>> key_quantity_values(const JobEnvelopes& e);

struct DtCheckRow {
  std::string quantity;
  std::optional<double> value, half_dt_value;
  // (value - half_dt_value) / half_dt_value, as a study's error_estimate;
  // absent when either value is absent or half_dt_value is 0 and value is not.
  std::optional<double> relative_change;
  // |relative_change| > tolerance; also when one run has the value and the
  // other has none, or the reference is 0 and the value is not (no
  // relative change, but the step changes the answer).
  bool above_tolerance = false;
};

struct DtSelfCheck {
  double dt_s = 0.0, half_dt_s = 0.0, tolerance = 0.0;
  std::vector<DtCheckRow> rows;  // in price_quantities() order; quantities absent from both runs left out
  bool any_above() const;
};

// dt_s, half_dt_s: the steps the two runs ran at (an escalated run's, when
// the rung repeated it at a finer step).
DtSelfCheck dt_self_check(const JobEnvelopes& at_dt, const JobEnvelopes& at_half_dt, double dt_s, double half_dt_s,
                          double tolerance);

// One "dt_self_check" warning per row above the tolerance, naming the
// quantity, both values and both steps.
std::vector<RunWarning> dt_self_check_warnings(const DtSelfCheck& check);

// The "dt_self_check" object of vsi simulate --verify's summary:
// {dt_s, half_dt_s, tolerance, converged, quantities: [{quantity, value,
// half_dt_value, relative_change, above_tolerance}]}; absent values null.
nlohmann::ordered_json dt_self_check_json(const DtSelfCheck& check);

}  // namespace railvsi
