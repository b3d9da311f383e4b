#include "generators/hslm.hpp"

#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {

Train make_hslm_a(const HslmAOptions& o, std::string name) {
  if (o.intermediate_coaches < 1)
    throw InputError("/intermediate_coaches", fmt::format("must be >= 1 (got {})", o.intermediate_coaches));
  const std::pair<const char*, double> positive[] = {{"/coach_length_m", o.coach_length_m},
                                                     {"/bogie_axle_spacing_m", o.bogie_axle_spacing_m},
                                                     {"/axle_load_N", o.axle_load_N}};
  for (const auto& [path, value] : positive)
    if (!(value > 0.0)) throw InputError(path, fmt::format("must be > 0 (got {})", value));
  const double D = o.coach_length_m, d = o.bogie_axle_spacing_m;
  // EN 1991-2 Figure E.2: distance from an end coach's inner axle to the
  // nearest articulated bogie's axle.
  const double end_coach_gap_m = D - 1.5 * d - 1.7625;
  if (!(end_coach_gap_m > 0.0))
    throw InputError("/coach_length_m",
                     fmt::format("must exceed 1.5 * bogie_axle_spacing_m + 1.7625 m = {} m, or the end coach's "
                                 "axles would overlap the articulated bogie's",
                                 1.5 * d + 1.7625));

  std::vector<double> x{0.0, 3.0, 14.0, 17.0, 20.525, 20.525 + d};  // power car, end coach
  const double first_articulated_m = x.back() + end_coach_gap_m;
  for (int k = 0; k <= o.intermediate_coaches; ++k) {
    x.push_back(first_articulated_m + k * D);
    x.push_back(first_articulated_m + k * D + d);
  }
  x.push_back(x.back() + end_coach_gap_m);  // rear end coach
  x.push_back(x.back() + d);
  for (double step_m : {3.525, 3.0, 11.0, 3.0}) x.push_back(x.back() + step_m);  // rear power car

  Train t;
  t.name = std::move(name);
  t.coach_length_m = o.coach_length_m;
  for (double offset_m : x) t.moving_forces.push_back({offset_m, o.axle_load_N});
  return t;
}

Train make_hslm_b(const HslmBOptions& o, std::string name) {
  if (o.span_m != 0.0 && !(o.span_m > 0.0 && o.span_m < 7.0))
    throw InputError("/span_m", fmt::format("HSLM-B is the universal train of simply supported spans L < 7 m "
                                            "(EN 1991-2 6.4.6.1.1); got L = {} m: use HSLM-A",
                                            o.span_m));
  if (o.point_forces < 1)
    throw InputError("/point_forces", fmt::format("must be >= 1 (got {})", o.point_forces));
  if (!(o.spacing_m > 0.0)) throw InputError("/spacing_m", fmt::format("must be > 0 (got {})", o.spacing_m));
  if (!(o.axle_load_N > 0.0)) throw InputError("/axle_load_N", fmt::format("must be > 0 (got {})", o.axle_load_N));
  Train t;
  t.name = std::move(name);
  t.coach_length_m = o.spacing_m;
  for (int k = 0; k < o.point_forces; ++k) t.moving_forces.push_back({k * o.spacing_m, o.axle_load_N});
  return t;
}

}  // namespace railvsi
