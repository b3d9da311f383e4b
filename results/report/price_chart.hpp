#pragma once
// The accuracy-price chart of the compliance report (inline SVG): for one
// quantity of one priced job, |error| against the reference run's value
// versus CPU time, both on log axes, one point per rung and time step, one
// colour per rung, the Pareto front joined and ringed, the reference run
// marked, and the 1 % and 5 % bands drawn.
//
// Log mapping (what a reader of the SVG can recompute): the x axis spans
// whole decades [10^floor(log10 min cpu), 10^ceil(log10 max cpu)], the
// y axis [y0, 10^ceil(log10 max(max |error|, 5 %))] with
// y0 = max(1e-6, 10^floor(log10 min non-zero |error|)); an error below y0
// (the reference's own 0 among them) is drawn on the bottom axis.
// Plot area: x from 70 to width - 215 px, y from 30 to height - 45 px.
#include <string>
#include <vector>

namespace railvsi {

struct PricePoint {
  std::string rung;  // series label: "moving_forces / fe / none"
  double dt_s = 0.0;
  double cpu_s = 0.0;   // > 0
  double error = 0.0;   // signed relative error, fraction
  bool pareto = false;
  bool reference = false;
};

struct PriceChart {
  std::string title;   // e.g. "deck_acceleration_mps2: HSLM-A1 at 300 km/h"
  std::vector<PricePoint> points;  // in ladder order (rung, then decreasing dt)
};

inline constexpr double kPriceChartMinError = 1e-6;

std::string render_price_chart(const PriceChart& chart, int width_px = 680, int height_px = 320);

}  // namespace railvsi
