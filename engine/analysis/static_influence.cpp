#include "analysis/static_influence.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>


#include "core/input_error.hpp"
#include "solver/cholmod_operator.hpp"

namespace railvsi {
namespace {

constexpr int kGridPerElement = 8;

// Maximum of f on [a, b] by golden-section search, started from the best
// sample of a grid search: f is piecewise cubic, so the sampled maximum is
// close and the search only polishes it.
std::pair<double, double> refine_maximum(const std::function<double(double)>& f, double a, double b) {
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 60 && b - a > 1e-9; ++it) {
    if (f1 < f2) {
      a = x1; x1 = x2; f1 = f2; x2 = a + g * (b - a); f2 = f(x2);
    } else {
      b = x2; x2 = x1; f2 = f1; x1 = b - g * (b - a); f1 = f(x1);
    }
  }
  return f1 > f2 ? std::pair{x1, f1} : std::pair{x2, f2};
}

// Grid search over [a, b] at `step`, then refinement around the best sample.
std::pair<double, double> maximize(const std::function<double(double)>& f, double a, double b, double step) {
  double best_x = a, best_f = -std::numeric_limits<double>::infinity();
  const long n = static_cast<long>(std::ceil((b - a) / step));
  for (long i = 0; i <= n; ++i) {
    const double x = std::min(b, a + static_cast<double>(i) * step);
    const double v = f(x);
    if (v > best_f) { best_f = v; best_x = x; }
  }
  const auto refined = refine_maximum(f, std::max(a, best_x - step), std::min(b, best_x + step));
  return refined.second > best_f ? refined : std::pair{best_x, best_f};
}

// Two-point Gauss integral of max(f, 0) on [a, b]: exact for the cubic
// pieces of an influence line that do not change sign inside [a, b].
double positive_gauss(const std::function<double(double)>& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a), s = h / std::sqrt(3.0);
  return h * (std::max(f(c - s), 0.0) + std::max(f(c + s), 0.0));
}

// The axles that may stand on the rails, [lo_m, hi_m], when the first is at
// front_x: for axles sorted by offset a range of them, found by bisection
// (a train is far longer than a short span). The others are off the
// modelled track and add an exact zero to every sum, so leaving them out
// changes no bit; unsorted axles are all taken.
class AxleWindow {
 public:
  AxleWindow(const std::vector<MovingForce>& axles, double lo_m, double hi_m)
      : axles_(axles), lo_m_(lo_m - kPad_m), hi_m_(hi_m + kPad_m),
        sorted_(std::is_sorted(axles.begin(), axles.end(),
                               [](const MovingForce& a, const MovingForce& b) { return a.offset_m < b.offset_m; })) {}
  std::pair<std::size_t, std::size_t> at(double front_x) const {
    if (!sorted_) return {0, axles_.size()};
    const auto first = std::lower_bound(axles_.begin(), axles_.end(), front_x - hi_m_,
                                        [](const MovingForce& a, double v) { return a.offset_m < v; });
    const auto last = std::upper_bound(first, axles_.end(), front_x - lo_m_,
                                       [](double v, const MovingForce& a) { return v < a.offset_m; });
    return {static_cast<std::size_t>(first - axles_.begin()), static_cast<std::size_t>(last - axles_.begin())};
  }

 private:
  // A margin against rounding at the ends: extra axles add zeros.
  static constexpr double kPad_m = 1.0;
  const std::vector<MovingForce>& axles_;
  double lo_m_, hi_m_;
  bool sorted_;
};

}  // namespace

StaticInfluence::StaticInfluence(const StructureModel& structure, std::vector<int> rail_lines)
    : structure_(structure), rail_lines_(std::move(rail_lines)) {
  if (rail_lines_.empty()) rail_lines_ = {0};
  CholmodOperatorOptions options;
  options.rail_flexibility = false;
  const CholmodOperator op(structure_, EffectiveMatrixFactors{0.0, 0.0, 1.0}, options);
  sections_.emplace(structure_, rail_lines_, op);  // checks the rail lines
  auto ws = op.make_workspace();
  for (const OutputPoint& p : structure_.outputs()) {
    Vector e = Vector::Zero(structure_.num_dofs());
    if (p.dof >= 0) e[p.dof] = 1.0;
    Vector g = Vector::Zero(structure_.num_dofs());
    const Status st = op.solve(e, g, *ws);
    if (!st.ok()) throw InputError("/structure", "static influence line: " + st.message());
    influence_.push_back(std::move(g));
  }

  // Grid for the cumulative positive area: each element of the first rail
  // line cut in kGridPerElement pieces.
  const RailLine& rail = structure_.rails()[static_cast<std::size_t>(rail_lines_.front())];
  for (std::size_t i = 0; i + 1 < rail.x_m.size(); ++i)
    for (int j = 0; j < kGridPerElement; ++j)
      grid_x_m_.push_back(rail.x_m[i] + (rail.x_m[i + 1] - rail.x_m[i]) * j / kGridPerElement);
  grid_x_m_.push_back(rail.x_m.back());
  for (int k = 0; k < num_points(); ++k) {
    const auto h = [&](double x) { return unit_deflection(k, x); };
    std::vector<double> area(grid_x_m_.size(), 0.0);
    for (std::size_t i = 1; i < grid_x_m_.size(); ++i)
      area[i] = area[i - 1] + positive_gauss(h, grid_x_m_[i - 1], grid_x_m_[i]);
    grid_area_.push_back(std::move(area));
  }
  for (std::size_t f = 0; f < section_forms().forms.size(); ++f) {
    const auto h = [&](double x) { return unit_form_value(static_cast<int>(f), x); };
    std::vector<double> area(grid_x_m_.size(), 0.0);
    for (std::size_t i = 1; i < grid_x_m_.size(); ++i)
      area[i] = area[i - 1] + positive_gauss(h, grid_x_m_[i - 1], grid_x_m_[i]);
    grid_form_area_.push_back(std::move(area));
  }
}

double StaticInfluence::unit_deflection(int k, double x_m) const {
  const Vector& g = influence_[static_cast<std::size_t>(k)];
  const double share = 1.0 / static_cast<double>(rail_lines_.size());
  double w = 0.0;
  for (int r : rail_lines_) {
    const auto row = structure_.rails()[static_cast<std::size_t>(r)].locate_weights(x_m);
    if (!row) continue;
    for (int i = 0; i < 4; ++i)
      if (row->dof[i] >= 0) w += share * row->weight[i] * g[row->dof[i]];
  }
  return w;
}

StaticSectionEnvelope StaticInfluence::section_envelope(const std::vector<MovingForce>& axles) const {
  StaticSectionEnvelope out;
  const SectionForms& forms = section_forms();
  if (!forms.available()) {
    out.unavailable = forms.unavailable;
    return out;
  }
  double length = 0.0;
  for (const MovingForce& a : axles) length = std::max(length, a.offset_m);
  // Every form at once for the train with its first axle at x.
  std::vector<double> values(forms.forms.size());
  const auto [start_m, end_m] = tracks_extent_m();
  const AxleWindow window(axles, start_m, end_m);
  const auto all_forms = [&](double front_x) -> const std::vector<double>& {
    std::fill(values.begin(), values.end(), 0.0);
    const double share = 1.0 / static_cast<double>(rail_lines_.size());
    const auto [first, last] = window.at(front_x);
    for (int r : rail_lines_)
      for (std::size_t i = first; i < last; ++i)
        sections_->add_form_values(r, front_x - axles[i].offset_m, share * axles[i].load_N, values);
    return values;
  };
  // The quantities: the larger magnitude of the two sides of a section,
  // the (signed) reaction, the larger end rotation at a support.
  struct Quantity {
    std::vector<int> forms;
    bool magnitude = true;
    double x_m = 0.0;
    double best = -std::numeric_limits<double>::infinity();
    double best_front_x = 0.0;
  };
  std::vector<Quantity> qs;
  for (std::size_t p = 0; p < forms.points.size(); ++p) {
    const SectionForms::Point& f = forms.points[p];
    if (f.moment_left < 0) continue;
    const double x = structure_.outputs()[p].x_m;
    qs.push_back({{f.moment_left, f.moment_right}, true, x});
    qs.push_back({{f.shear_left, f.shear_right}, true, x});
  }
  for (const SectionForms::Support& s : forms.supports) {
    qs.push_back({{s.reaction}, false, s.x_m});
    qs.push_back({s.rotations, true, s.x_m});
  }
  const auto measure = [](const Quantity& q, const std::vector<double>& v) {
    double m = -std::numeric_limits<double>::infinity();
    for (int f : q.forms) m = std::max(m, q.magnitude ? std::abs(v[static_cast<std::size_t>(f)]) : v[static_cast<std::size_t>(f)]);
    return m;
  };
  const auto consider = [&](double front_x) {
    const auto& v = all_forms(front_x);
    for (Quantity& q : qs) {
      const double m = measure(q, v);
      if (m > q.best) q.best = m, q.best_front_x = front_x;
    }
  };
  // Grid over every first-axle position (as train_envelope), then each
  // axle exactly on each section, then a golden-section polish per quantity.
  const double step = (grid_x_m_[1] - grid_x_m_[0]);
  const double a = rails_start_m(), b = rails_end_m() + length;
  const long n = static_cast<long>(std::ceil((b - a) / step));
  for (long i = 0; i <= n; ++i) consider(std::min(b, a + static_cast<double>(i) * step));
  for (const Quantity& q : std::vector<Quantity>(qs))
    for (const MovingForce& m : axles) consider(q.x_m + m.offset_m);
  for (Quantity& q : qs) {
    const auto f = [&](double front_x) { return measure(q, all_forms(front_x)); };
    const auto refined = refine_maximum(f, std::max(a, q.best_front_x - step), std::min(b, q.best_front_x + step));
    q.best = std::max(q.best, refined.second);
  }
  std::size_t k = 0;
  for (const SectionForms::Point& f : forms.points) {
    if (f.moment_left < 0) {
      out.max_abs_bending_moment_Nm.emplace_back();
      out.max_abs_shear_force_N.emplace_back();
      continue;
    }
    out.max_abs_bending_moment_Nm.push_back(qs[k++].best);
    out.max_abs_shear_force_N.push_back(qs[k++].best);
  }
  for (std::size_t s = 0; s < forms.supports.size(); ++s) {
    out.max_reaction_N.push_back(qs[k++].best);
    out.max_abs_rotation_rad.push_back(std::max(0.0, qs[k++].best));
  }
  return out;
}

std::pair<double, double> StaticInfluence::tracks_extent_m() const {
  double start_m = std::numeric_limits<double>::infinity(), end_m = -start_m;
  for (int r : rail_lines_)
    if (const auto& rail = structure_.rails()[static_cast<std::size_t>(r)]; rail.x_m.size() >= 2) {
      start_m = std::min(start_m, rail.x_m.front());
      end_m = std::max(end_m, rail.x_m.back());
    }
  return {start_m, end_m};
}

double StaticInfluence::rails_start_m() const { return grid_x_m_.front(); }
double StaticInfluence::rails_end_m() const { return grid_x_m_.back(); }

double StaticInfluence::positive_area_to(int k, double x_m) const {
  return positive_area_to([&](double x) { return unit_deflection(k, x); }, grid_area_[static_cast<std::size_t>(k)],
                          x_m);
}

double StaticInfluence::positive_area_to(const std::function<double(double)>& h, const std::vector<double>& area,
                                         double x_m) const {
  if (x_m <= grid_x_m_.front()) return 0.0;
  if (x_m >= grid_x_m_.back()) return area.back();
  const auto it = std::upper_bound(grid_x_m_.begin(), grid_x_m_.end(), x_m);
  const std::size_t i = static_cast<std::size_t>(it - grid_x_m_.begin()) - 1;
  return area[i] + positive_gauss(h, grid_x_m_[i], x_m);
}

StaticEnvelope StaticInfluence::train_envelope(int k, const std::vector<MovingForce>& axles) const {
  double length = 0.0;
  for (const MovingForce& a : axles) length = std::max(length, a.offset_m);
  const auto [start_m, end_m] = tracks_extent_m();
  const AxleWindow window(axles, start_m, end_m);
  const auto magnitude = [&](double front_x) {
    double w = 0.0;
    const auto [first, last] = window.at(front_x);
    for (std::size_t i = first; i < last; ++i) w += axles[i].load_N * unit_deflection(k, front_x - axles[i].offset_m);
    return std::abs(w);
  };
  const double step = (grid_x_m_[1] - grid_x_m_[0]);
  const auto [x, value] = maximize(magnitude, rails_start_m(), rails_end_m() + length, step);
  return {value, x};
}

LoadModel71Result StaticInfluence::lm71(int k, const LoadModel71& lm) const {
  return lm71_of([&](double x) { return unit_deflection(k, x); }, grid_area_[static_cast<std::size_t>(k)], lm);
}

LoadModel71Result StaticInfluence::lm71_form(int form, const LoadModel71& lm) const {
  return lm71_of([&](double x) { return unit_form_value(form, x); }, grid_form_area_[static_cast<std::size_t>(form)],
                 lm);
}

LoadModel71Result StaticInfluence::lm71_of(const std::function<double(double)>& h, const std::vector<double>& area,
                                           const LoadModel71& lm) const {
  const double group_m = lm.point_spacing_m * (lm.point_loads - 1);
  const double total_area = area.back();
  const auto effect = [&](double a) {
    double w = 0.0;
    for (int j = 0; j < lm.point_loads; ++j) w += lm.point_load_N * h(a + j * lm.point_spacing_m);
    const double window = positive_area_to(h, area, a + group_m + lm.clear_distance_m) -
                          positive_area_to(h, area, a - lm.clear_distance_m);
    return w + lm.distributed_N_per_m * (total_area - window);
  };
  const double step = (grid_x_m_[1] - grid_x_m_[0]);
  const auto [a, value] = maximize(effect, rails_start_m() - group_m, rails_end_m(), step);
  return {value, a};
}

}  // namespace railvsi
