#include "simulation/deck_twist.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "simulation/scene.hpp"

namespace railvsi {

DeckTwistGauge make_deck_twist_gauge(const StructureModel& structure, const std::vector<int>& contact_rail_lines,
                                     double base_m, double spacing_m) {
  DeckTwistGauge g;
  g.base_m = base_m;
  const auto& rails = structure.rails();
  std::vector<int> named = contact_rail_lines;
  std::sort(named.begin(), named.end());
  named.erase(std::unique(named.begin(), named.end()), named.end());
  if (rails.size() < 2) {
    g.unavailable = "not applicable: a plane model has one rail line, so no cross level and no twist";
    return g;
  }
  if (named.size() == 2) {
    g.rail_a = named[0];
    g.rail_b = named[1];
  } else if (rails.size() == 2) {
    g.rail_a = 0;
    g.rail_b = 1;
  } else {
    g.unavailable = fmt::format("not evaluated: the structure has {} rail lines; name the two rails of the track in "
                                "analysis.contact.rail_lines",
                                rails.size());
    return g;
  }
  const RailLine& a = rails.at(static_cast<std::size_t>(g.rail_a));
  const RailLine& b = rails.at(static_cast<std::size_t>(g.rail_b));
  const auto [b0, b1] = bridge_extent_m(structure);
  const double start = std::max({b0, a.start_m(), b.start_m()});
  const double end = std::min({b1, a.end_m(), b.end_m()});
  if (!(end - start >= base_m)) {
    g.unavailable = fmt::format("not evaluated: both rails run together over {:.3g} m of the deck, less than the "
                                "{:g} m base of the twist",
                                std::max(0.0, end - start), base_m);
    return g;
  }
  const double room = end - start - base_m;
  const int intervals = room > 0.0 ? std::max(1, static_cast<int>(std::ceil(room / spacing_m - 1e-9))) : 0;
  std::map<int, int> index;  // DOF -> position in g.dofs
  for (int k = 0; k <= intervals; ++k) {
    const double x = intervals > 0 ? start + room * k / intervals : start;
    std::map<int, double> form;
    const auto add = [&](const RailLine& rail, double at, double sign) {
      const auto row = rail.locate(at);
      if (!row) return;
      for (int j = 0; j < 4; ++j)
        if (row->dof[j] >= 0 && row->weight[j] != 0.0) form[row->dof[j]] += sign * row->weight[j];
    };
    add(a, x + base_m, 1.0);
    add(b, x + base_m, -1.0);
    add(a, x, -1.0);
    add(b, x, 1.0);
    std::vector<std::pair<int, double>> terms;
    for (const auto& [dof, coef] : form) {
      if (coef == 0.0) continue;
      const auto [it, fresh] = index.try_emplace(dof, static_cast<int>(g.dofs.size()));
      if (fresh) g.dofs.push_back(dof);
      terms.emplace_back(it->second, coef);
    }
    g.x_m.push_back(x);
    g.forms.push_back(std::move(terms));
  }
  return g;
}

void read_twist_dofs(const DeckTwistGauge& g, const Vector& u, const StructureCoordinates& coords,
                     std::vector<double>& dof_values) {
  dof_values.resize(g.dofs.size());
  for (std::size_t i = 0; i < g.dofs.size(); ++i) dof_values[i] = coords.at(g.dofs[i], u);
}

double twist_m(const DeckTwistGauge& g, std::size_t sample, const std::vector<double>& dof_values) {
  double t = 0.0;
  for (const auto& [i, coef] : g.forms[sample]) t += coef * dof_values[static_cast<std::size_t>(i)];
  return t;
}

double max_abs_twist_m(const DeckTwistGauge& g, const Vector& u, const StructureCoordinates& coords,
                       std::vector<double>& scratch, double* at_x_m) {
  read_twist_dofs(g, u, coords, scratch);
  double worst = -1.0;
  for (std::size_t k = 0; k < g.forms.size(); ++k) {
    const double t = twist_m(g, k, scratch);
    if (std::abs(t) > worst) {
      worst = std::abs(t);
      if (at_x_m) *at_x_m = g.x_m[k];
    }
  }
  worst = std::max(worst, 0.0);
  return worst;
}

}  // namespace railvsi
