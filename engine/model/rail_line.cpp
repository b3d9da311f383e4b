#include "model/rail_line.hpp"

#include <algorithm>

namespace railvsi {

std::array<double, 4> hermite_weights(double xi, double h) {
  const double xi2 = xi * xi;
  const double xi3 = xi2 * xi;
  return {1.0 - 3.0 * xi2 + 2.0 * xi3, h * (xi - 2.0 * xi2 + xi3), 3.0 * xi2 - 2.0 * xi3,
          h * (xi3 - xi2)};
}

std::array<double, 4> hermite_slopes(double xi, double h) {
  const double xi2 = xi * xi;
  return {6.0 * (xi2 - xi) / h, 1.0 - 4.0 * xi + 3.0 * xi2, 6.0 * (xi - xi2) / h, 3.0 * xi2 - 2.0 * xi};
}

std::array<double, 4> hermite_curvatures(double xi, double h) {
  return {(12.0 * xi - 6.0) / (h * h), (6.0 * xi - 4.0) / h, (6.0 - 12.0 * xi) / (h * h), (6.0 * xi - 2.0) / h};
}

RailLine RailLine::from_nodes(std::string name, std::vector<double> x_m,
                              const std::vector<int>& dof_v, const std::vector<int>& dof_rot) {
  RailLine line;
  line.name = std::move(name);
  line.x_m = std::move(x_m);
  const std::size_t n = std::min({line.x_m.size(), dof_v.size(), dof_rot.size()});
  for (std::size_t i = 0; i + 1 < n; ++i)
    line.element_dofs.push_back({dof_v[i], dof_rot[i], dof_v[i + 1], dof_rot[i + 1]});
  return line;
}

std::optional<RailContactRow> RailLine::locate(double x) const { return locate(x, true); }

std::optional<RailContactRow> RailLine::locate_weights(double x) const { return locate(x, false); }

std::optional<RailContactRow> RailLine::locate(double x, bool derivatives) const {
  if (x_m.size() < 2 || !covers(x)) return std::nullopt;
  // First node strictly greater than x; the element starts one before it.
  const auto it = std::upper_bound(x_m.begin(), x_m.end(), x);
  std::size_t j = static_cast<std::size_t>(it - x_m.begin());
  if (j >= x_m.size()) j = x_m.size() - 1;  // x == end: last element
  const std::size_t i = j - 1;
  const double h = x_m[j] - x_m[i];
  const double xi = (x - x_m[i]) / h;
  const auto w = hermite_weights(xi, h);
  RailContactRow row;
  row.element = static_cast<int>(i);
  row.dof = element_dofs[i];
  for (int k = 0; k < 4; ++k)
    if (row.dof[k] >= 0) row.weight[k] = w[k];
  if (!derivatives) return row;
  const auto w1 = hermite_slopes(xi, h);
  const auto w2 = hermite_curvatures(xi, h);
  for (int k = 0; k < 4; ++k) {
    if (row.dof[k] < 0) continue;
    row.slope[k] = w1[k];
    row.curvature[k] = w2[k];
  }
  return row;
}

}  // namespace railvsi
