#pragma once
// Time histories of a run as CSV files (`vsi simulate --histories DIR`).
#include <filesystem>

#include "simulation/result.hpp"

namespace railvsi::cli {

// Creates `dir` and writes deck.csv (t_s, <point>_displacement_m,
// <point>_acceleration_mps2, ...), and when the train has wheels
// contact_forces.csv (t_s, <wheel>_N, ...) and carbody.csv (t_s,
// <body>_acceleration_mps2, ...). Each file appears complete or not at all.
// Throws std::runtime_error (or std::filesystem::filesystem_error).
void write_histories(const Histories& histories, const std::filesystem::path& dir);

}  // namespace railvsi::cli
