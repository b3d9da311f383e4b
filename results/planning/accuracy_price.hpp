#pragma once
// The accuracy price of one scene (`vsi price`): every rung of the
// fidelity ladder that applies to the scene, each at every step of the dt
// ladder (the time-step policy's dt x 4, x 2, x 1, / 2, / 4), run on a pool
// of threads; the CPU and wall time of each run; the key quantities of each
// against the reference run (price_analysis). Each run goes through the
// rung runner (run_at_rung, on fidelity_ladder's ladder_plan), as a worker
// runs a job. The FE structure operator
// (factor of K_bar and rail flexibility) is built once per dt and shared by
// the rungs; the modal basis once per price.
#include <string>
#include <vector>

#include "planning/time_step_policy.hpp"
#include "price/price_analysis.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

struct PriceOptions {
  // The structure's first bending and third deck frequencies (0: unknown),
  // for the time-step policy and the code filter's cut-off.
  double f0_hz = 0.0, f3_hz = 0.0;
  int threads = 1;
  std::vector<double> dt_factors{4.0, 2.0, 1.0, 0.5, 0.25};
  // The dt the factors multiply; 0: the time-step policy's (a stored job's
  // own dt prices the rung and dt it ran at).
  double base_dt_s = 0.0;
  // Modal rungs keep the modes up to this multiple of the code cut-off
  // max(30 Hz, 1.5 f0, f3) (the margin of the modal sweep benchmark).
  double modal_cutoff_factor = 1.2;
  TimeStepPolicy policy;
};

struct PriceReport {
  double policy_dt_s = 0.0;
  std::string policy_reason;
  double cutoff_hz = 0.0;
  std::vector<PriceRow> rows;  // by rung (ladder order), then by decreasing dt
  PriceReference reference;
  std::map<std::string, std::vector<std::size_t>> pareto;  // by quantity
  std::map<std::string, std::optional<std::size_t>> cheapest_1pct, cheapest_5pct;
  double wall_s = 0.0;  // the whole price, all threads
  int threads = 1;
};

// Throws InputError for a scene none of whose rungs can be set up (every
// run refused, the first refusal's message).
PriceReport price_scene(const Scene& scene, const PriceOptions& options);

}  // namespace railvsi
