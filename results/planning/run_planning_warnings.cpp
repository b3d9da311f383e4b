#include "planning/run_planning_warnings.hpp"

#include "planning/time_step_warnings.hpp"
#include "planning/wheel_value_warnings.hpp"

namespace railvsi {

std::vector<RunWarning> run_planning_warnings(const Scene& ran, const RunSummary& summary, double cutoff_hz) {
  // The FE rungs' policy bounds HHT's period error; the exact modal rung's
  // step only samples the load and the output: its own rule.
  std::vector<RunWarning> out = summary.fidelity.solver_path != "modal-exact"
                                    ? time_step_warnings(ran, cutoff_hz)
                                    : modal_time_step_warnings(ran, cutoff_hz);
  for (RunWarning& w : wheel_value_warnings(ran, summary, cutoff_hz)) out.push_back(std::move(w));
  return out;
}

}  // namespace railvsi
