#pragma once
// The shortest feature of a track profile, for the time-step policy's track
// bound: a wheel must cross it in enough steps for the integrator to see its
// shape (a short dip or a step excites the wheel on the Hertz spring far
// above the structure's frequencies; the energy residual cannot see a Δt
// error there).
//
// Read from the samples themselves (linear interpolation, as the wheels see
// them), so a CSV profile, a spectrum and the defects added to them are
// judged alike. In each window of window_m around a sample interval, with
// dr the rise of each interval and ds the change of slope at each sample,
//   lambda = 2 pi sqrt(sum dr^2 / sum ds^2)
// is the wavelength of a sinusoid (exact for a sampled sine or a cosine dip
// of length L: lambda = L), and 4.4 h for a rise over one interval h (a step:
// its shortness is the interval's). The shortest lambda over the windows
// centred on a bend (a change of slope at least half the window's largest)
// whose peak-to-peak height is at least min_height_m is the feature.
#include <string>

#include "model/irregularity.hpp"

namespace railvsi {

struct TrackFeature {
  double wavelength_m = 0.0;  // 0: no feature (a flat or linear profile)
  double x_m = 0.0;           // centre of its window
  double height_m = 0.0;      // peak to peak within the window
  // Largest curvature within the window, 1/m: each sample's change of slope
  // over the shorter of its two intervals (a step's kinks count in full).
  double max_curvature_per_m = 0.0;
  // "a feature 0.50 m long, 30.0 mm peak to peak, at x = 10.25 m"
  std::string describe() const;
};

TrackFeature shortest_track_feature(const Irregularity& profile, double window_m = 2.0,
                                    double min_height_m = 1e-4);

}  // namespace railvsi
