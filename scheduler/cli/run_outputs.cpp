#include "cli/run_outputs.hpp"

#include <cmath>

#include "cli/histories_csv.hpp"
#include "core/sampled_peak.hpp"
#include "summary/summary_json.hpp"
#include "envelopes/code_filter.hpp"
#include "simulation/simulation.hpp"
#include "planning/deck_frequencies.hpp"

namespace railvsi::cli {
namespace {

using nlohmann::ordered_json;

ordered_json number(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }

// Where |v| is largest: the sample's time and the first axle's x.
ordered_json where_max_abs(const std::vector<double>& v, const std::vector<double>& t_s, const RunFrame& frame) {
  std::size_t k_max = 0;
  for (std::size_t k = 1; k < v.size(); ++k)
    if (std::abs(v[k]) > std::abs(v[k_max])) k_max = k;
  if (v.empty() || k_max >= t_s.size()) return nullptr;
  return {{"value", number(std::abs(v[k_max]))},
          {"t_s", number(t_s[k_max])},
          {"first_axle_x_m", number(frame.first_axle_x_m(t_s[k_max]))}};
}

}  // namespace

bool RunFrame::in_window(double t_s) const {
  const double front = first_axle_x_m(t_s), rear = front - train_length_m;
  return front >= window_start_m && rear <= window_end_m;
}

RunFrame run_frame(const Scene& scene, std::optional<double> cutoff_hz) {
  RunFrame f;
  f.start_x_m = scene.start_x_m ? *scene.start_x_m : default_start_x_m(scene);
  f.speed_mps = scene.speed_mps;
  f.train_length_m = scene.train.length_m();
  const auto [b0, b1] = bridge_extent_m(*scene.structure);
  f.window_start_m = b0 - scene.analysis.evaluation_margin_m;
  f.window_end_m = b1 + scene.analysis.evaluation_margin_m;
  f.dt_s = scene.analysis.dt_s;
  f.history_stride = scene.analysis.history_stride;
  if (cutoff_hz) {
    f.cutoff_hz = *cutoff_hz;
  } else {
    const DeckFrequencies d = deck_frequencies(*scene.structure);
    f.cutoff_hz = code_cutoff_hz(d.f0_hz, d.f3_hz);
  }
  return f;
}

std::vector<std::vector<double>> filtered_deck_acceleration(const Histories& h, const RunFrame& frame) {
  std::vector<std::vector<double>> out;
  if (frame.history_stride != 1) return out;
  // At or above the Nyquist frequency nothing can be filtered: no value
  // rather than the raw one under the filtered name (filter_above_nyquist).
  if (!(frame.cutoff_hz < 0.5 / frame.dt_s)) return out;
  for (const auto& a : h.deck_acceleration_mps2) out.push_back(code_low_pass(a, frame.dt_s, frame.cutoff_hz));
  return out;
}

void write_run_histories(const Histories& h, const RunFrame& frame, const std::filesystem::path& dir) {
  HistoryExtras extras;
  for (double t : h.t_s) {
    extras.first_axle_x_m.push_back(frame.first_axle_x_m(t));
    extras.in_window.push_back(frame.in_window(t) ? 1.0 : 0.0);
  }
  extras.filtered_acceleration_mps2 = filtered_deck_acceleration(h, frame);
  write_histories(h, dir, &extras);
}

ordered_json run_summary_json(const Result& result, const Scene& scene, const RunFrame& frame) {
  ordered_json out = summary_json(result, scene.train.is_moving_forces());
  const Histories& h = result.histories;
  const auto filtered = filtered_deck_acceleration(h, frame);
  ordered_json& deck = out["deck"];
  double overall = 0.0;
  for (std::size_t p = 0; p < deck["points"].size() && p < h.deck_displacement_m.size(); ++p) {
    ordered_json& point = deck["points"][p];
    point["max_abs_acceleration_filtered_mps2"] = nullptr;
    if (!filtered.empty()) {
      // The peak as the stored envelope has it (CodeFilter::max_abs_filtered:
      // refined between samples); `at` gives the largest sample and its time.
      const ordered_json at = where_max_abs(filtered[p], h.t_s, frame);
      const double peak = refined_max_abs(filtered[p].data(), filtered[p].size());
      point["max_abs_acceleration_filtered_mps2"] = at.is_null() ? ordered_json(nullptr) : number(peak);
      if (!at.is_null() && std::isfinite(peak)) overall = std::max(overall, peak);
      point["at_max_acceleration_filtered"] = at;
    }
    point["at_max_displacement"] = where_max_abs(h.deck_displacement_m[p], h.t_s, frame);
    point["at_max_acceleration"] = where_max_abs(h.deck_acceleration_mps2[p], h.t_s, frame);
  }
  deck["max_abs_acceleration_filtered_mps2"] = filtered.empty() ? ordered_json(nullptr) : number(overall);
  deck["filter"] = code_filter_description(frame.dt_s, frame.cutoff_hz);
  deck["cutoff_hz"] = number(frame.cutoff_hz);
  if (frame.history_stride != 1)
    deck["note"] = "history_stride > 1: the filtered acceleration needs every step (decimation aliases), and the "
                   "times of the maxima are those of the stored samples";
  return out;
}

}  // namespace railvsi::cli
