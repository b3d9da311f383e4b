#include "generators/spectrum_profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/split_mix64.hpp"
#include "generators/turn_trig.hpp"

namespace railvsi {
namespace {

constexpr double kTwoPi = 6.283185307179586;  // correctly rounded
constexpr std::int64_t kBlock = 256;          // samples between exact restarts of the recurrence
constexpr double kMaxTerms = 4e10;            // samples x components (about a minute)

void check(const TrackSpectrum& spectrum, const SpectrumSampling& s, TrackRange range) {
  if (!(std::isfinite(range.start_m) && std::isfinite(range.end_m) && range.end_m > range.start_m))
    throw std::invalid_argument("spectrum_profile: the track range must be finite and not empty");
  if (!(s.wavelength_min_m > 0.0)) throw InputError("/wavelength_min_m", "must be > 0");
  if (!(s.wavelength_max_m > s.wavelength_min_m))
    throw InputError("/wavelength_min_m", fmt::format("the band is empty: wavelength_min_m ({} m) must be below "
                                                      "wavelength_max_m ({} m)",
                                                      s.wavelength_min_m, s.wavelength_max_m));
  if (spectrum.valid_wavelength_min_m && s.wavelength_min_m < *spectrum.valid_wavelength_min_m)
    throw InputError("/wavelength_min_m", fmt::format("{} is published for wavelengths {}-{} m only", spectrum.name,
                                                      *spectrum.valid_wavelength_min_m, *spectrum.valid_wavelength_max_m));
  if (spectrum.valid_wavelength_max_m && s.wavelength_max_m > *spectrum.valid_wavelength_max_m)
    throw InputError("/wavelength_max_m", fmt::format("{} is published for wavelengths {}-{} m only", spectrum.name,
                                                      *spectrum.valid_wavelength_min_m, *spectrum.valid_wavelength_max_m));
  if (s.components < 1) throw InputError("/components", "must be >= 1");
  const double h = s.spacing_m();
  if (!(h > 0.0)) throw InputError("/sample_spacing_m", "must be > 0");
  if (h > 0.5 * s.wavelength_min_m)
    throw InputError("/sample_spacing_m", fmt::format("{} m would alias the shortest wavelength ({} m): at most half of it",
                                                      h, s.wavelength_min_m));
  const double samples = (range.end_m - range.start_m) / h + 3.0;
  if (samples * s.components > kMaxTerms)
    throw InputError("/sample_spacing_m",
                     fmt::format("{:.0f} m of track every {} m with {} components is too much work ({:.3g} terms, "
                                 "at most {:.0e}): use a coarser spacing or fewer components",
                                 range.end_m - range.start_m, h, s.components, samples * s.components, kMaxTerms));
}

struct Component {
  double amplitude_m;  // sqrt(2 G dW)
  double cycles_per_m;  // W / (2 pi)
  double phase_turns;   // phi / (2 pi), in [0, 1)
};

std::vector<Component> components(const TrackSpectrum& spectrum, const SpectrumSampling& s) {
  const double f_min = 1.0 / s.wavelength_max_m, f_max = 1.0 / s.wavelength_min_m;
  const double df = (f_max - f_min) / s.components;
  const double dw = kTwoPi * df;
  SplitMix64 rng(s.seed);
  std::vector<Component> out(static_cast<std::size_t>(s.components));
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double f = f_min + (static_cast<double>(k) + 0.5) * df;
    out[k] = {std::sqrt(2.0 * spectrum.psd(kTwoPi * f) * dw), f, rng.next_unit()};
  }
  return out;
}

// Adds components comps[0, G) to the samples i0 <= i < last of one block:
// per sample the G products, in order of k, are summed first, then added to
// the sample. The G rotations are independent, so they run side by side.
template <int G>
void add_group(const Component* comps, double h, std::int64_t block, std::int64_t last, std::int64_t i0,
               std::vector<double>& r) {
  double a[G], c[G], s[G], dc[G], ds[G];
  for (int g = 0; g < G; ++g) {
    const CosSin step = cos_sin_turns(comps[g].cycles_per_m * h);
    const CosSin z = cos_sin_turns(comps[g].cycles_per_m * (static_cast<double>(block) * h) + comps[g].phase_turns);
    a[g] = comps[g].amplitude_m;
    c[g] = z.cos, s[g] = z.sin, dc[g] = step.cos, ds[g] = step.sin;
  }
  for (std::int64_t i = block; i < last; ++i) {
    if (i >= i0) {
      double sum = a[0] * c[0];
      for (int g = 1; g < G; ++g) sum += a[g] * c[g];
      r[static_cast<std::size_t>(i - i0)] += sum;
    }
    for (int g = 0; g < G; ++g) {
      const double c_next = c[g] * dc[g] - s[g] * ds[g];
      s[g] = s[g] * dc[g] + c[g] * ds[g];
      c[g] = c_next;
    }
  }
}

// Adds every component to r at x_i = i*h, i = i0 .. i0 + r.size() - 1,
// components in groups of kGroup in order of k. Within a block of kBlock
// global indices each cosine advances by a rotation; every block restarts
// from the exact angle, so a sample's value depends on its index alone.
void add_components(const std::vector<Component>& comps, double h, std::int64_t i0, std::vector<double>& r) {
  constexpr std::size_t kGroup = 8;
  const std::int64_t i_end = i0 + static_cast<std::int64_t>(r.size());
  std::int64_t block = i0 >= 0 ? i0 / kBlock * kBlock : -((-i0 + kBlock - 1) / kBlock) * kBlock;
  for (; block < i_end; block += kBlock) {
    const std::int64_t last = std::min(block + kBlock, i_end);
    std::size_t k = 0;
    for (; k + kGroup <= comps.size(); k += kGroup) add_group<kGroup>(&comps[k], h, block, last, i0, r);
    for (; k < comps.size(); ++k) add_group<1>(&comps[k], h, block, last, i0, r);
  }
}

}  // namespace

Irregularity spectrum_profile(const TrackSpectrum& spectrum, const SpectrumSampling& s, TrackRange range) {
  check(spectrum, s, range);
  const double h = s.spacing_m();
  const auto i0 = static_cast<std::int64_t>(std::floor(range.start_m / h)) - 1;
  const auto i1 = static_cast<std::int64_t>(std::ceil(range.end_m / h)) + 1;
  std::vector<double> x(static_cast<std::size_t>(i1 - i0 + 1)), r(x.size(), 0.0);
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = static_cast<double>(i0 + static_cast<std::int64_t>(j)) * h;
  add_components(components(spectrum, s), h, i0, r);
  return Irregularity(std::move(x), std::move(r),
                      fmt::format("{}, seed {}, wavelengths {:g}-{:g} m, {} components, sampled every {:g} m",
                                  spectrum.describe(), s.seed, s.wavelength_min_m, s.wavelength_max_m, s.components, h));
}

}  // namespace railvsi
