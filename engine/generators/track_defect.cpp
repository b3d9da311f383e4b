#include "generators/track_defect.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "generators/turn_trig.hpp"

namespace railvsi {
namespace {

void check(const TrackDefect& d, std::size_t k, const Irregularity* base) {
  const std::string path = fmt::format("/defects/{}", k);
  if (!std::isfinite(d.x_m)) throw InputError(path + "/x_m", "must be a finite number");
  if (!(d.length_m > 0.0) || !std::isfinite(d.length_m)) throw InputError(path + "/length_m", "must be > 0");
  if (!(d.depth_m > 0.0) || !std::isfinite(d.depth_m))
    throw InputError(path + "/depth_m", "must be > 0 (the type, dip or bump, gives the sign)");
  if (base && (d.x_m < base->x_m().front() || d.x_m + d.length_m > base->x_m().back()))
    throw InputError(path + "/x_m", fmt::format("the defect ({}-{} m) reaches outside the profile it is added to "
                                                "({}-{} m)",
                                                d.x_m, d.x_m + d.length_m, base->x_m().front(), base->x_m().back()));
}

}  // namespace

double TrackDefect::at(double x) const {
  if (!(x >= x_m && x <= x_m + length_m)) return 0.0;
  const double half = 0.5 * depth_m * (1.0 - cos_sin_turns((x - x_m) / length_m).cos);
  return shape == DefectShape::kDip ? -half : half;
}

std::string TrackDefect::describe() const {
  return fmt::format("{} {:g} m deep, {:g} m long at x = {:g} m", shape == DefectShape::kDip ? "dip" : "bump", depth_m,
                     length_m, x_m);
}

Irregularity with_defects(const Irregularity* base, const std::vector<TrackDefect>& defects) {
  for (std::size_t k = 0; k < defects.size(); ++k) check(defects[k], k, base);
  std::vector<double> x = base ? base->x_m() : std::vector<double>{};
  for (const TrackDefect& d : defects)
    for (int j = 0; j <= kDefectIntervals; ++j) x.push_back(d.x_m + d.length_m * (static_cast<double>(j) / kDefectIntervals));
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  std::vector<double> r(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    r[i] = base ? base->at(x[i]) : 0.0;
    for (const TrackDefect& d : defects) r[i] += d.at(x[i]);
  }
  std::string source = base ? base->source() : std::string("perfect track");
  for (const TrackDefect& d : defects) source += "; " + d.describe();
  return Irregularity(std::move(x), std::move(r), std::move(source));
}

}  // namespace railvsi
