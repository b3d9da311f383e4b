#pragma once
// The universal dynamic trains HSLM-A and HSLM-B of EN 1991-2 (6.4.6.1.1,
// Annex E) as moving forces. The ten HSLM-A trains differ by four numbers
// (Table E.1), which the library files jobs/trains/HSLM-A<n>.json carry with
// their source; the axle layout is the rule of Figure E.2, coded here.
// HSLM-B is N equal point forces at a uniform spacing d.
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

struct HslmBOptions {
  int point_forces = 0;     // N
  double spacing_m = 0.0;   // d
  double axle_load_N = 170000.0;
  // The simply supported span the train is chosen for (0: not given).
  // HSLM-B is the universal train of spans L < 7 m (EN 1991-2 6.4.6.1.1):
  // a span of 7 m or more is refused. N and d are not derived from it:
  // EN 1991-2 reads them from L in a figure whose values are not built in
  // (not confirmed against the standard's text here).
  double span_m = 0.0;
};

// N forces of axle_load_N at 0, d, ..., (N - 1) d. The regular spacing d is
// the train's resonance length (coach_length_m): v = f0 d / i. Throws
// InputError with paths relative to the hslm_b JSON object.
Train make_hslm_b(const HslmBOptions& options, std::string name);

}  // namespace railvsi
