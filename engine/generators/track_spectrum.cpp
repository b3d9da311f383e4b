#include "generators/track_spectrum.hpp"

#include <array>

#include <fmt/format.h>

namespace railvsi {
namespace {

constexpr double kGermanOmegaC = 0.8246, kGermanOmegaR = 0.0206;  // rad/m
constexpr double kFraK = 0.25, kFraOmegaC = 0.8245;                 // -, rad/m
constexpr double kCm2ToM2 = 1e-4;
constexpr double kFraLambdaMin = 1.524, kFraLambdaMax = 304.8;  // m (5 and 1000 ft)

constexpr TrackSpectrum german(std::string_view name, double A_v) {
  return {name, SpectrumFamily::kGerman, A_v, std::nullopt, std::nullopt};
}
constexpr TrackSpectrum fra(std::string_view name, double A_v) {
  return {name, SpectrumFamily::kFra, A_v, kFraLambdaMin, kFraLambdaMax};
}

const std::array<TrackSpectrum, 8> kSpectra{{
    german("german-low", 4.032e-7),
    german("german-high", 1.080e-6),
    fra("fra-1", 1.2107),
    fra("fra-2", 1.0181),
    fra("fra-3", 0.6816),
    fra("fra-4", 0.5376),
    fra("fra-5", 0.2095),
    fra("fra-6", 0.0339),
}};

}  // namespace

double TrackSpectrum::psd(double w) const {
  const double w2 = w * w;
  if (family == SpectrumFamily::kGerman) {
    const double c2 = kGermanOmegaC * kGermanOmegaC, r2 = kGermanOmegaR * kGermanOmegaR;
    return A_v * c2 / ((w2 + r2) * (w2 + c2));
  }
  const double c2 = kFraOmegaC * kFraOmegaC;
  return kCm2ToM2 * kFraK * A_v * c2 / (w2 * (w2 + c2));
}

std::string TrackSpectrum::describe() const {
  return family == SpectrumFamily::kGerman ? fmt::format("{} (A_v = {:.3e} m*rad)", name, A_v)
                                           : fmt::format("{} (A_v = {:.4g} cm^2*rad/m)", name, A_v);
}

std::span<const TrackSpectrum> track_spectra() { return kSpectra; }

const TrackSpectrum* find_track_spectrum(std::string_view name) {
  for (const TrackSpectrum& s : kSpectra)
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace railvsi
