#include "model/irregularity.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {

Irregularity::Irregularity(std::vector<double> x_m, std::vector<double> r_m, std::string source)
    : x_(std::move(x_m)), r_(std::move(r_m)), source_(std::move(source)) {
  if (x_.size() != r_.size()) throw InputError("/r_m", "x_m and r_m must have the same length");
  if (x_.size() < 2) throw InputError("/x_m", "a profile needs at least two samples");
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (!std::isfinite(x_[i]) || !std::isfinite(r_[i]))
      throw InputError(fmt::format("/x_m/{}", i), "profile values must be finite numbers");
    if (i > 0 && !(x_[i] > x_[i - 1]))
      throw InputError(fmt::format("/x_m/{}", i), "profile x must increase strictly");
  }
}

double Irregularity::at(double x) const {
  if (x < x_.front() || x > x_.back()) return 0.0;
  const auto it = std::upper_bound(x_.begin(), x_.end(), x);
  std::size_t j = static_cast<std::size_t>(it - x_.begin());
  if (j >= x_.size()) return r_.back();
  const std::size_t i = j - 1;
  const double t = (x - x_[i]) / (x_[j] - x_[i]);
  return r_[i] + t * (r_[j] - r_[i]);
}

}  // namespace railvsi
