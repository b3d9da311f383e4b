#pragma once
// Vertical track irregularity spectra, all as ONE-SIDED power spectral densities G(Omega) in m^2/(rad/m)
// of the spatial angular frequency Omega = 2*pi/lambda in rad/m, normalised
// so that the variance of r(x) over a band is the integral of G dOmega over
// that band. Sources differ by factors of 2 and 2*pi (two-sided spectra,
// spectra in cycles/m) and some public code swaps the German low/high labels:
// here the larger A_v is always the worse track.
//
// German high-speed spectra ("low interference" / "high interference"):
//   G = A_v * Wc^2 / ((W^2 + Wr^2) * (W^2 + Wc^2)),  Wc = 0.8246, Wr = 0.0206 rad/m,
//   A_v = 4.032e-7 (low) or 1.080e-6 (high) m*rad.
// As widely cited from the DB / ORE B176 high-speed spectrum in the
// train-track-bridge literature (Zhai and co-workers and others).
// UNVERIFIED: as cited in that literature, not checked against the ORE B176
// report; in particular whether the published formula is one-sided in rad/m.
// No validity band is stated there, so none is enforced.
//
// US FRA track classes 1-6 (class 6 the best track):
//   G = k * A_v * Wc^2 / (W^2 * (W^2 + Wc^2)) in cm^2/(rad/m), k = 0.25,
//   Wc = 0.8245 rad/m, A_v = 1.2107, 1.0181, 0.6816, 0.5376, 0.2095, 0.0339
//   cm^2*rad/m, valid for wavelengths 1.524-304.8 m (5-1000 ft);
//   converted here to m^2/(rad/m) (x 1e-4).
// As cited from the FRA track classes by Hamid & Yang and later papers.
// UNVERIFIED: as cited in that literature, not checked against the FRA
// report.
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace railvsi {

enum class SpectrumFamily { kGerman, kFra };

struct TrackSpectrum {
  std::string_view name;  // as written in a scene: "german-high", "fra-6"
  SpectrumFamily family = SpectrumFamily::kGerman;
  double A_v = 0.0;  // German: m*rad; FRA: cm^2*rad/m, as published
  // Wavelengths the published formula is valid for, m; absent when no band
  // is stated.
  std::optional<double> valid_wavelength_min_m, valid_wavelength_max_m;

  // One-sided PSD in m^2/(rad/m) at Omega > 0 in rad/m.
  double psd(double omega_rad_per_m) const;
  // "german-high (A_v = 1.080e-06 m*rad)", for the record of a profile.
  std::string describe() const;
};

// All spectra, in the order of the schema's list.
std::span<const TrackSpectrum> track_spectra();
// Null when there is no spectrum of that name.
const TrackSpectrum* find_track_spectrum(std::string_view name);

}  // namespace railvsi
