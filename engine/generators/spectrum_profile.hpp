#pragma once
// A random vertical track profile of a given spectrum (spectral
// representation, Shinozuka & Jan 1972, J. Sound Vib. 25): with the one-sided PSD G of track_spectrum.hpp,
//   r(x) = sum_k sqrt(2 * G(W_k) * dW) * cos(W_k * x + phi_k),
// so that the variance of r is sum_k G(W_k) dW, the midpoint rule for the
// integral of G over the band.
//
// Frequencies: `components` band centres spaced uniformly in W over
// [2*pi/lambda_max, 2*pi/lambda_min]. Uniform (not logarithmic) spacing
// keeps every component's weight a plain midpoint rule and makes the profile
// repeat only after 2*pi/dW (6.3 km for the defaults, 3-70 m and 2000
// components: longer than any bridge model); a logarithmic spacing would put
// few, widely spaced components at the short wavelengths and repeat there
// much sooner.
// Phases: phi_k = 2*pi*u_k with u_k the k-th draw of SplitMix64(seed)
// (core/split_mix64.hpp), k = 0, 1, ... in order of increasing W.
// Samples: at x_i = i * sample_spacing_m for every integer i with x_i in the
// requested range, widened by one sample on each side. Neither x_i nor r_i
// depends on the range, so two tracks with the same seed and parameters have
// bit-identical profiles where they overlap.
// Bit-identical on every machine: integer RNG, exact conversions, and a fixed
// order of IEEE double +, -, *, /, sqrt and floor; cosines through
// turn_trig.hpp and a rotation recurrence restarted from the exact angle at
// every multiple of 256 samples of the global grid; no
// libm transcendental functions; compiled with -ffp-contract=off.
#include <cstdint>
#include <optional>

#include "generators/track_spectrum.hpp"
#include "model/irregularity.hpp"

namespace railvsi {

struct SpectrumSampling {
  std::uint64_t seed = 0;
  // Default band: EN 13848 D1 + D2, 3-70 m.
  double wavelength_min_m = 3.0;
  double wavelength_max_m = 70.0;
  int components = 2000;
  // Default wavelength_min_m / 30 (0.1 m for the default band): linear
  // interpolation between samples then loses at most 0.6 % of the shortest
  // wave's amplitude. At most wavelength_min_m / 2 (no aliasing).
  std::optional<double> sample_spacing_m;

  double spacing_m() const { return sample_spacing_m.value_or(wavelength_min_m / 30.0); }
};

// Part of the track x the profile must cover, m.
struct TrackRange {
  double start_m = 0.0;
  double end_m = 0.0;
};

// Throws InputError with paths of the irregularity JSON object
// ("/wavelength_min_m", "/sample_spacing_m", ...) for a band outside the
// spectrum's validity, an empty band, or a sampling too fine for the range;
// std::invalid_argument for an empty or non-finite range. The profile's
// source() records spectrum, A_v, seed, band, components and spacing.
Irregularity spectrum_profile(const TrackSpectrum& spectrum, const SpectrumSampling& sampling, TrackRange range);

}  // namespace railvsi
