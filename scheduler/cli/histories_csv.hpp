#pragma once
// Time histories of a run as CSV files (`vsi simulate --histories DIR`).
#include <filesystem>
#include <vector>

#include "simulation/result.hpp"

namespace railvsi::cli {

// Creates `dir` and writes deck.csv (t_s, <point>_displacement_m,
// <point>_acceleration_mps2, ...), and when the train has wheels
// contact_forces.csv (t_s, <wheel>_N, ...) and carbody.csv (t_s,
// <body>_acceleration_mps2, ...). Each file appears complete or not at all.
// Throws std::runtime_error (or std::filesystem::filesystem_error).
// extras (when given) add to deck.csv, after t_s, first_axle_x_m and
// in_window (1 inside the evaluation window, 0 outside), and per point
// <point>_acceleration_filtered_mps2 after its acceleration.
struct HistoryExtras {
  std::vector<double> first_axle_x_m;
  std::vector<double> in_window;
  std::vector<std::vector<double>> filtered_acceleration_mps2;  // [point][sample]; empty: not available
};
void write_histories(const Histories& histories, const std::filesystem::path& dir,
                     const HistoryExtras* extras = nullptr);

}  // namespace railvsi::cli
