#pragma once
// What `vsi price` makes of its runs: the error of each key quantity
// against the reference run, a Richardson estimate of the reference's own
// error, the Pareto front of error against CPU time, and the cheapest run
// within a tolerance. Pure functions of the rows: no runs here.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace railvsi {

// The quantities priced, named as the result store's envelope quantities
// (results/envelopes/envelope_rows), overall values (location "").
const std::vector<std::string_view>& price_quantities();

struct PriceRow {
  std::string model, structure, contact_law;  // the rung (fidelity_ladder)
  int rung = 0;                               // index in fidelity_ladder()
  std::optional<int> modes;                   // modal rungs: modes kept
  double dt_s = 0.0;
  std::string status = "ok";  // the run's status, or "refused" when the rung cannot run the scene
  std::string message;
  long steps = 0;
  // Thread CPU and wall time of what a run of this row alone costs: its
  // setup and time loop plus the factorization (FE) or modal basis (modal)
  // it shares with the other rows of its dt or rung; setup_cpu_s is that
  // shared part.
  double cpu_s = 0.0, wall_s = 0.0, setup_cpu_s = 0.0;
  std::optional<double> cpu_predicted_s;  // cost_model, before the run
  std::vector<std::string> warnings;      // the run's health warning codes (run.warnings), each once
  std::map<std::string, std::optional<double>> values;  // by price_quantities(); absent: none
  std::map<std::string, std::optional<double>> errors;  // signed relative to the reference, fractions
  bool ok() const { return status == "ok"; }
};

// Richardson extrapolation on the reference rung's three finest steps
// h, 2h, 4h (values v1, v2, v4): d1 = v2 - v1, d2 = v4 - v2, r = d2 / d1.
// In the asymptotic range v(h) = v* + C h^p, r = 2^p and the reference's
// own error v1 - v* = d1 / (r - 1). Criterion: d1 and d2 of one sign and
// r in [2, 8], i.e. an observed order p in [1, 3] around the HHT's 2 (peak
// values sampled on the time grid converge at the same order); otherwise
// the estimate is withheld. Both differences below 1e-12 |v1|: converged to
// round-off, error 0.
struct RichardsonEstimate {
  bool asymptotic = false;
  std::optional<double> order;           // observed p = log2(r), when d1 d2 > 0
  std::optional<double> error;           // (v1 - v*) / v*, when asymptotic
  std::optional<double> last_change;     // (v2 - v1) / v1: always, when both exist
};
inline constexpr double kRichardsonMinRatio = 2.0, kRichardsonMaxRatio = 8.0;
RichardsonEstimate richardson_estimate(std::optional<double> v1, std::optional<double> v2, std::optional<double> v4);

struct PriceReference {
  std::optional<std::size_t> row;  // none when no run of the reference rung is ok
  std::vector<std::size_t> richardson_rows;  // h, 2h, 4h when all three are ok
  std::map<std::string, RichardsonEstimate> richardson;  // by quantity
};

// (v - v_ref) / v_ref, signed, as a fraction; absent when either value is
// absent, and when v_ref = 0 unless v = 0 too (then 0).
std::optional<double> relative_error(std::optional<double> v, std::optional<double> v_ref);

// The reference: the finest ok run of the most complete rung (the highest
// rung index with an ok run). Fills every row's errors against it:
// (v - v_ref) / v_ref; absent when either value is absent or the row is not
// ok; when v_ref = 0, 0 for v = 0 and absent otherwise (no relative error).
PriceReference price_errors(std::vector<PriceRow>& rows);

// Per quantity, the rows on the Pareto front of |error| against cpu_s: no
// other row is at most as costly and at most as wrong, one of them
// strictly. In increasing cpu_s. A row with a smaller |error| than a finer
// dt of its own rung (error not monotone in dt: a lucky step) is never on
// the front.
std::map<std::string, std::vector<std::size_t>> pareto_fronts(const std::vector<PriceRow>& rows);

// Per quantity, the cheapest row (cpu_s) with |error| <= tolerance, lucky
// steps (see pareto_fronts) left out.
std::map<std::string, std::optional<std::size_t>> cheapest_within(const std::vector<PriceRow>& rows,
                                                                   double tolerance);

}  // namespace railvsi
