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
  // Natural cubic spline: tridiagonal system for the interior second
  // derivatives (Thomas algorithm; diagonally dominant).
  const std::size_t n = x_.size();
  spline_m_.assign(n, 0.0);
  if (n < 3) return;
  std::vector<double> diag(n, 1.0), rhs(n, 0.0), upper(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = x_[i] - x_[i - 1], h1 = x_[i + 1] - x_[i];
    const double lower = h0 / 6.0;
    diag[i] = (h0 + h1) / 3.0;
    upper[i] = h1 / 6.0;
    rhs[i] = (r_[i + 1] - r_[i]) / h1 - (r_[i] - r_[i - 1]) / h0;
    if (i > 1) {
      const double f = lower / diag[i - 1];
      diag[i] -= f * upper[i - 1];
      rhs[i] -= f * rhs[i - 1];
    }
  }
  for (std::size_t i = n - 2; i >= 1; --i) spline_m_[i] = (rhs[i] - upper[i] * spline_m_[i + 1]) / diag[i];
}

ProfilePoint Irregularity::smooth_at(double x) const {
  if (x < x_.front() || x > x_.back()) return {};
  const auto it = std::upper_bound(x_.begin(), x_.end(), x);
  std::size_t j = static_cast<std::size_t>(it - x_.begin());
  if (j >= x_.size()) j = x_.size() - 1;
  const std::size_t i = j - 1;
  const double h = x_[j] - x_[i], a = (x_[j] - x) / h, b = 1.0 - a;
  const double mi = spline_m_[i], mj = spline_m_[j];
  ProfilePoint p;
  p.r_m = a * r_[i] + b * r_[j] + ((a * a * a - a) * mi + (b * b * b - b) * mj) * h * h / 6.0;
  p.slope = (r_[j] - r_[i]) / h + ((1.0 - 3.0 * a * a) * mi + (3.0 * b * b - 1.0) * mj) * h / 6.0;
  p.curvature_per_m = a * mi + b * mj;
  return p;
}

double Irregularity::at(double x) const {
  if (x < x_.front() || x > x_.back()) return 0.0;
  return interpolated(static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin()), x);
}

double Irregularity::at(double x, std::size_t& hint) const {
  if (x < x_.front() || x > x_.back()) return 0.0;
  // j: the first sample past x (upper_bound's), found in the hint's
  // interval or the next one when x lies there.
  std::size_t j = x_.size();
  for (std::size_t k = hint; k < hint + 2 && k + 1 < x_.size(); ++k)
    if (x_[k] <= x && x < x_[k + 1]) j = k + 1;
  if (j == x_.size()) j = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin());
  if (j < x_.size()) hint = j - 1;
  return interpolated(j, x);
}

double Irregularity::interpolated(std::size_t j, double x) const {
  if (j >= x_.size()) return r_.back();
  const std::size_t i = j - 1;
  const double t = (x - x_[i]) / (x_[j] - x_[i]);
  return r_[i] + t * (r_[j] - r_[i]);
}

}  // namespace railvsi
