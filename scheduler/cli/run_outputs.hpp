#pragma once
// What `vsi simulate` and `vsi replay` add to a run so that its histories
// reconcile with the envelopes of a study: where the train is at each
// sample, which samples the evaluation window holds, and the deck
// acceleration through the code filter (results/ code_low_pass, the filter
// the study's envelopes use), with the time and train position of each
// maximum.
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi::cli {

struct RunFrame {
  double start_x_m = 0.0;    // first axle at t = 0
  double speed_mps = 0.0;
  double train_length_m = 0.0;
  double window_start_m = 0.0, window_end_m = 0.0;  // bridge -/+ evaluation_margin_m
  double dt_s = 0.0;
  int history_stride = 1;
  double cutoff_hz = 0.0;  // EN 1990 A2.4.4.2.1 code frequency max(30 Hz, 1.5 f0, f3)

  double first_axle_x_m(double t_s) const { return start_x_m + speed_mps * t_s; }
  // An axle of the train is within the evaluation window: the wheel and
  // car-body envelopes count these samples only (the deck envelopes count
  // every sample of the run, which by default ends as the last axle leaves
  // the window).
  bool in_window(double t_s) const;
};

// cutoff_hz: the job's stored cut-off; absent: from the structure's f0 and f3.
RunFrame run_frame(const Scene& scene, std::optional<double> cutoff_hz = std::nullopt);

// The filtered deck acceleration per output point, or empty when the
// histories are not sampled at every step (decimation aliases; see
// results/envelopes/job_envelopes.hpp).
std::vector<std::vector<double>> filtered_deck_acceleration(const Histories& h, const RunFrame& frame);

// deck.csv (t_s, first_axle_x_m, in_window, per point displacement,
// acceleration and filtered acceleration), contact_forces.csv and
// carbody.csv; all appear together or not at all.
void write_run_histories(const Histories& h, const RunFrame& frame, const std::filesystem::path& dir);

// The summary JSON of the run, with the filtered deck acceleration and
// the time and first-axle position of each deck maximum added.
nlohmann::ordered_json run_summary_json(const Result& result, const Scene& scene, const RunFrame& frame);

}  // namespace railvsi::cli
