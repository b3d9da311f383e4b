#include "simulation/section_forms.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "generators/beam_element.hpp"
#include "simulation/result.hpp"

namespace railvsi {
namespace {

constexpr double kNodeTol_m = 1e-9;

// Node of the deck line at x, or -1.
int node_at(const RailLine& deck, double x_m) {
  const auto it = std::lower_bound(deck.x_m.begin(), deck.x_m.end(), x_m - kNodeTol_m);
  if (it == deck.x_m.end() || std::abs(*it - x_m) > kNodeTol_m) return -1;
  return static_cast<int>(it - deck.x_m.begin());
}

void add(std::vector<std::pair<int, double>>& into, int dof, double c) {
  if (dof >= 0 && c != 0.0) into.emplace_back(dof, c);
}

// Builds sign * S_e[slot] as a form.
class ElementRows {
 public:
  ElementRows(const RailLine& deck, const DeckBeam& beam) : deck_(deck), beam_(beam) {
    for (const DeckLink& l : beam.links) {
      const DeckPoint at = deck_point(deck, l.x_m);
      if (at.element >= 0) links_[at.element].push_back({&l, at.w});
    }
  }

  void add_row(LinearForm& f, int e, int slot, double sign, bool skip_at_start = false) const {
    const auto& dofs = deck_.element_dofs[static_cast<std::size_t>(e)];
    const double h = deck_.x_m[static_cast<std::size_t>(e) + 1] - deck_.x_m[static_cast<std::size_t>(e)];
    const Matrix4 K = beam_stiffness(beam_.EI_Nm2, h);
    const Matrix4 M = beam_consistent_mass(beam_.mass_kg_per_m, h);
    for (int t = 0; t < 4; ++t) {
      add(f.u, dofs[t], sign * K(slot, t));
      add(f.v, dofs[t], sign * (beam_.rayleigh_a0_per_s * M(slot, t) + beam_.rayleigh_a1_s * K(slot, t)));
      add(f.a, dofs[t], sign * M(slot, t));
    }
    // Ballast springs inside the element: their force is a load on it.
    const auto it = links_.find(e);
    if (it != links_.end())
      for (const auto& [link, w] : it->second) {
        add(f.u, link->dof, -sign * w[slot] * link->k_N_per_m);
        add(f.v, link->dof, -sign * w[slot] * link->c_Ns_per_m);
        for (int t = 0; t < 4; ++t) {
          add(f.u, dofs[t], sign * w[slot] * link->k_N_per_m * w[t]);
          add(f.v, dofs[t], sign * w[slot] * link->c_Ns_per_m * w[t]);
        }
      }
    LinearForm::Direct d;
    d.element = e;
    d.coef[static_cast<std::size_t>(slot)] = sign;  // S_e = ... - f_e, f_e = -w down_N
    d.skip_at_start = skip_at_start;
    f.direct.push_back(d);
  }

 private:
  const RailLine& deck_;
  const DeckBeam& beam_;
  std::map<int, std::vector<std::pair<const DeckLink*, std::array<double, 4>>>> links_;
};

}  // namespace

SectionForms forms_in_coordinates(SectionForms forms, const StructureCoordinates& coords) {
  Vector acc = Vector::Zero(coords.size());
  const auto convert = [&](std::vector<std::pair<int, double>>& terms) {
    acc.setZero();
    for (const auto& [d, c] : terms) coords.add(d, c, acc);
    terms.clear();
    for (Eigen::Index i = 0; i < acc.size(); ++i)
      if (acc[i] != 0.0) terms.emplace_back(static_cast<int>(i), acc[i]);
  };
  for (LinearForm& f : forms.forms) {
    convert(f.u);
    convert(f.v);
    convert(f.a);
  }
  return forms;
}

double LinearForm::state_value(const Vector& u_s, const Vector& v_s, const Vector& a_s) const {
  double s = 0.0;
  for (const auto& [d, c] : u) s += c * u_s[d];
  for (const auto& [d, c] : v) s += c * v_s[d];
  for (const auto& [d, c] : a) s += c * a_s[d];
  return s;
}

DeckPoint deck_point(const RailLine& deck, double x_m) {
  const auto row = deck.locate_weights(x_m);  // its element alone: no slopes or curvatures
  if (!row) return {};
  const auto e = static_cast<std::size_t>(row->element);
  const double h = deck.x_m[e + 1] - deck.x_m[e];
  return {row->element, hermite_weights((x_m - deck.x_m[e]) / h, h)};
}

double LinearForm::unit_load_value(const RailLine& deck, double x_m) const {
  return direct.empty() ? 0.0 : unit_load_value(deck_point(deck, x_m));
}

double LinearForm::unit_load_value(const DeckPoint& at) const {
  double s = 0.0;
  const bool at_start = at.w[0] == 1.0 && at.w[2] == 0.0;
  for (const Direct& d : direct)
    if (d.element == at.element && !(d.skip_at_start && at_start))
      for (int k = 0; k < 4; ++k) s += d.coef[static_cast<std::size_t>(k)] * at.w[static_cast<std::size_t>(k)];
  return s;
}

double LinearForm::load_value(const RailLine& deck, const std::vector<DeckLoad>& loads) const {
  double s = 0.0;
  if (direct.empty()) return s;
  for (const DeckLoad& l : loads) s += l.down_N * unit_load_value(deck, l.x_m);
  return s;
}

SectionForms make_section_forms(const StructureModel& structure) {
  SectionForms out;
  const StructureInfo& info = structure.info();
  const RailLine& deck = info.deck_line;
  if (!info.deck_beam || deck.x_m.size() < 2 || info.support_x_m.size() < 2) {
    out.unavailable = fmt::format("section forces are defined for beam decks (bridge-2d) only; this structure ({}) "
                                  "has no beam deck",
                                  info.source.empty() ? "unknown" : info.source);
    return out;
  }
  for (const RailLine& r : structure.rails()) out.rail_is_deck.push_back(r.element_dofs == deck.element_dofs);
  const ElementRows rows(deck, *info.deck_beam);
  const int last = static_cast<int>(deck.x_m.size()) - 1;
  const auto new_form = [&](double x_m) {
    out.forms.emplace_back();
    out.forms.back().x_m = x_m;
    return static_cast<int>(out.forms.size()) - 1;
  };
  for (const OutputPoint& p : structure.outputs()) {
    const int j = node_at(deck, p.x_m);
    SectionForms::Point pf;
    if (j > 0 && j < last) {
      // Left element ends at node j (its slots 2, 3), right one starts there (0, 1).
      pf.moment_left = new_form(p.x_m);
      rows.add_row(out.forms.back(), j - 1, 3, 1.0);
      pf.moment_right = new_form(p.x_m);
      rows.add_row(out.forms.back(), j, 1, -1.0);
      pf.shear_left = new_form(p.x_m);
      rows.add_row(out.forms.back(), j - 1, 2, -1.0);
      pf.shear_right = new_form(p.x_m);
      rows.add_row(out.forms.back(), j, 0, 1.0, /*skip_at_start=*/true);
    }
    out.points.push_back(pf);
  }
  for (std::size_t i = 0; i < info.support_x_m.size(); ++i) {
    SectionForms::Support s;
    s.name = fmt::format("support{}", i + 1);
    s.x_m = info.support_x_m[i];
    const int j = node_at(deck, s.x_m);
    if (j < 0) {
      out = SectionForms{};
      out.unavailable = fmt::format("support at x = {} m is not a node of the deck line", s.x_m);
      return out;
    }
    s.reaction = new_form(s.x_m);
    std::vector<int> rot;
    if (j > 0) {
      rows.add_row(out.forms[static_cast<std::size_t>(s.reaction)], j - 1, 2, 1.0);
      rot.push_back(deck.element_dofs[static_cast<std::size_t>(j) - 1][3]);
    }
    if (j < last) {
      rows.add_row(out.forms[static_cast<std::size_t>(s.reaction)], j, 0, 1.0);
      rot.push_back(deck.element_dofs[static_cast<std::size_t>(j)][1]);
    }
    std::sort(rot.begin(), rot.end());
    rot.erase(std::unique(rot.begin(), rot.end()), rot.end());
    for (int d : rot) {
      if (d < 0) continue;
      s.rotations.push_back(new_form(s.x_m));
      out.forms.back().u.emplace_back(d, 1.0);
    }
    out.supports.push_back(std::move(s));
  }
  return out;
}

SectionEnvelope::SectionEnvelope(const SectionForms& forms)
    : forms_(forms), moment_(forms.points.size(), 0.0), shear_(forms.points.size(), 0.0),
      reaction_(forms.supports.size(), -std::numeric_limits<double>::infinity()),
      rotation_(forms.supports.size(), 0.0) {}

void SectionEnvelope::update(const std::vector<double>& v) {
  seen_ = true;
  const auto at = [&](int i) { return i < 0 ? 0.0 : std::abs(v[static_cast<std::size_t>(i)]); };
  for (std::size_t p = 0; p < forms_.points.size(); ++p) {
    const SectionForms::Point& f = forms_.points[p];
    moment_[p] = std::max({moment_[p], at(f.moment_left), at(f.moment_right)});
    shear_[p] = std::max({shear_[p], at(f.shear_left), at(f.shear_right)});
  }
  for (std::size_t s = 0; s < forms_.supports.size(); ++s) {
    const SectionForms::Support& f = forms_.supports[s];
    reaction_[s] = std::max(reaction_[s], v[static_cast<std::size_t>(f.reaction)]);
    for (int r : f.rotations) rotation_[s] = std::max(rotation_[s], at(r));
  }
}

void SectionEnvelope::summarize(RunSummary& sum) const {
  if (!forms_.available()) {
    sum.section_forces_note = forms_.unavailable;
    return;
  }
  if (!seen_) {
    sum.section_forces_note = "no step was recorded";
    return;
  }
  for (std::size_t p = 0; p < forms_.points.size() && p < sum.points.size(); ++p) {
    if (forms_.points[p].moment_left < 0) continue;  // a point not inside the deck line
    sum.points[p].max_abs_bending_moment_Nm = moment_[p];
    sum.points[p].max_abs_shear_force_N = shear_[p];
  }
  sum.supports.clear();
  for (std::size_t s = 0; s < forms_.supports.size(); ++s)
    sum.supports.push_back({forms_.supports[s].name, forms_.supports[s].x_m, reaction_[s], rotation_[s]});
}

}  // namespace railvsi
