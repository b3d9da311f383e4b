#pragma once
// The universal dynamic trains HSLM-A of EN 1991-2 Annex E as moving forces.
// The ten trains differ by four numbers (Table E.1), which the library files
// jobs/trains/HSLM-A<n>.json carry with their source; the axle layout is the
// rule of Figure E.2, coded here.
#include <string>

#include "model/train.hpp"

namespace railvsi {

struct HslmAOptions {
  int intermediate_coaches = 0;       // N
  double coach_length_m = 0.0;        // D
  double bogie_axle_spacing_m = 0.0;  // d
  double axle_load_N = 0.0;           // P
};

// Axles from the first one, each carrying P downward: power car 0, 3, 14,
// 17 m; end coach +3.525 m and +d; N+1 articulated bogies D apart; the rear
// end coach and power car mirror the front. 2N + 14 axles, (N + 2) D +
// 37.525 m from first to last. Throws InputError with paths relative to the
// hslm_a JSON object.
Train make_hslm_a(const HslmAOptions& options, std::string name);

}  // namespace railvsi
