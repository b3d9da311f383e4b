#include "report/governing_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/sampled_peak.hpp"
#include "envelopes/code_filter.hpp"
#include "simulation/evaluation_window.hpp"
#include "simulation/simulation.hpp"
#include "simulation/train_layout.hpp"

namespace railvsi {
namespace {

// Samples i of the run (a mask over the histories' samples).
using Mask = std::vector<bool>;

// Which samples of wheel c the run's envelopes counted: its position inside
// the evaluation window, computed as RunState::record computes it.
Mask wheel_mask(const Scene& scene, const std::vector<double>& t_s, const ContactSpec& c) {
  const EvaluationWindow window = EvaluationWindow::of(scene);
  const double x0 = scene.start_x_m.value_or(default_start_x_m(scene));
  Mask m(t_s.size());
  for (std::size_t i = 0; i < t_s.size(); ++i)
    m[i] = window.contains(TrainLayout::position_m(x0 + scene.speed_mps * t_s[i], c.offset_m));
  return m;
}

std::pair<double, double> mask_span(const std::vector<double>& t_s, const Mask& m) {
  const auto first = std::find(m.begin(), m.end(), true);
  if (first == m.end()) return {0.0, 0.0};
  const auto last = std::find(m.rbegin(), m.rend(), true);
  return {t_s[static_cast<std::size_t>(first - m.begin())], t_s[m.size() - 1 - static_cast<std::size_t>(last - m.rbegin())]};
}

struct Series {
  std::vector<double> t, y;
};

Series masked(const std::vector<double>& t_s, const std::vector<double>& y, const Mask* m) {
  Series s;
  for (std::size_t i = 0; i < y.size() && i < t_s.size(); ++i)
    if (!m || (*m)[i]) s.t.push_back(t_s[i]), s.y.push_back(y[i]);
  return s;
}

// The figure's data: min and max of the plotted series; the peak as given.
FigureData data_of(const GoverningRun& run, const std::string& quantity, const std::string& location,
                   std::optional<double> stored, double peak, const Series& s) {
  FigureData d;
  d.quantity = quantity;
  d.location = location;
  d.job = run.job;
  d.stored_value = stored;
  d.plotted_peak = peak;
  if (!s.y.empty()) {
    const auto [lo, hi] = std::minmax_element(s.y.begin(), s.y.end());
    d.min = *lo;
    d.max = *hi;
    d.window_s = {s.t.front(), s.t.back()};
  }
  return d;
}

PlotSeries plot_series(const std::string& label, const Series& s, double scale) {
  PlotSeries p{label, {}};
  for (std::size_t i = 0; i < s.y.size(); ++i) p.points.emplace_back(s.t[i], s.y[i] * scale);
  return p;
}

std::string agreement(const FigureData& d, double scale, const char* unit) {
  if (!d.stored_value) return " The job stored no value of this quantity.";
  const double diff = d.plotted_peak - *d.stored_value;
  if (std::abs(diff) <= 1e-9 * std::max(1.0, std::abs(*d.stored_value)))
    return fmt::format(" Peak {:.6g} {}, the stored value.", d.plotted_peak * scale, unit);
  return fmt::format(" Peak {:.6g} {} against the stored {:.6g} {}: this run does not reproduce the job.",
                     d.plotted_peak * scale, unit, *d.stored_value * scale, unit);
}

// The output point with the largest stored value of `quantity` (the first
// point when none stored one).
std::size_t governing_point(const Histories& h, const std::string& quantity, const StoredEnvelope& stored) {
  std::size_t p = 0;
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < h.point_names.size(); ++k)
    if (const auto v = stored(quantity, h.point_names[k]); v && *v > best) best = *v, p = k;
  return p;
}

}  // namespace

std::vector<ReportFigure> governing_figures(const GoverningRun& run, const StoredEnvelope& stored) {
  std::vector<ReportFigure> figures;
  const Scene& scene = *run.scene;
  const Result& r = *run.result;
  const Histories& h = r.histories;
  if (h.t_s.empty()) return figures;
  // The train within the evaluation window: the first axle entering it to
  // the last one leaving it (deck envelopes count the whole run).
  const EvaluationWindow window = EvaluationWindow::of(scene);
  const double x0 = scene.start_x_m.value_or(default_start_x_m(scene));
  const std::pair<double, double> train_in{std::max(h.t_s.front(), (window.start_m - x0) / scene.speed_mps),
                                           std::min(h.t_s.back(), (window.end_m + scene.train.length_m() - x0) /
                                                                      scene.speed_mps)};
  const auto time_plot = [&](std::string title, std::string y_label) {
    LinePlot plot;
    plot.title = std::move(title);
    plot.x_label = "time [s]";
    plot.y_label = std::move(y_label);
    return plot;
  };
  // The run's own step (an escalation runs at a finer one), and its rule
  // for a deck peak: the modal rung refines each peak between its samples,
  // the FE rungs take the largest sample (RunState::record).
  const double dt = r.summary.dt_s > 0.0 ? r.summary.dt_s : scene.analysis.dt_s;
  const bool refined = r.summary.fidelity.solver_path == "modal-exact";
  const auto deck_peak = [&](const std::vector<double>& y) {
    if (refined) return refined_max_abs(y.data(), y.size());
    double m = 0.0;
    for (double v : y) m = std::max(m, std::abs(v));
    return m;
  };

  if (!h.point_names.empty()) {
    const std::string deck_quantity =
        run.check_quantity == "deck_displacement_m" ? "deck_displacement_m" : "deck_acceleration_mps2";
    const std::size_t p = governing_point(h, deck_quantity, stored);
    const std::string& point = h.point_names[p];
    const std::string shaded = "train in window";
    {
      const Series s = masked(h.t_s, h.deck_displacement_m[p], nullptr);
      LinePlot w = time_plot("Deck displacement at " + point, "displacement [mm]");
      w.series.push_back(plot_series(point, s, 1e3));
      w.shaded_x = train_in;
      w.shaded_label = shaded;
      FigureData d = data_of(run, "deck_displacement_m", point, stored("deck_displacement_m", point),
                             deck_peak(h.deck_displacement_m[p]), s);
      figures.push_back({w,
                         "Vertical deck displacement (positive up) at " + point +
                             "; the stored envelope is the largest |value| over the whole run (shaded: the train in "
                             "the evaluation window)." +
                             agreement(d, 1e3, "mm"),
                         d, ""});
    }
    const bool filter = run.cutoff_hz > 0.0 && run.cutoff_hz < 0.5 / dt;
    LinePlot a = time_plot("Deck acceleration at " + point, "acceleration [m/s2]");
    a.series.push_back(plot_series("raw", masked(h.t_s, h.deck_acceleration_mps2[p], nullptr), 1.0));
    a.shaded_x = train_in;
    a.shaded_label = shaded;
    if (filter) {
      const Series f = masked(h.t_s, code_low_pass(h.deck_acceleration_mps2[p], dt, run.cutoff_hz), nullptr);
      a.series.push_back(plot_series("filtered", f, 1.0));
      FigureData d = data_of(run, "deck_acceleration_mps2", point, stored("deck_acceleration_mps2", point),
                             refined_max_abs(f.y.data(), f.y.size()), f);
      figures.push_back({a,
                         "Deck acceleration at " + point + ", raw and after the code low-pass filter (" +
                             code_filter_description(dt, run.cutoff_hz) +
                             "); the stored envelope is the largest filtered |value| over the whole run." +
                             agreement(d, 1.0, "m/s2"),
                         d, ""});
    } else {
      figures.push_back({a, "Deck acceleration, raw: the code filter's cut-off is at or above the Nyquist frequency "
                            "of the run's step, so the job stored no filtered value.",
                         std::nullopt, ""});
    }
  }
  if (h.wheel_names.empty()) return figures;
  const TrainLayout layout(scene.train, scene.analysis.contact);
  if (layout.contacts.size() != h.wheel_names.size()) return figures;
  // The most unloaded wheel by its stored value; its force while it was
  // inside the evaluation window (outside it, near the ends of the modelled
  // rail, the force is the model's end, not the bridge's).
  std::size_t w = 0;
  double most = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < h.wheel_names.size(); ++k)
    if (const auto v = stored("unloading_ratio", h.wheel_names[k]); v && *v > most) most = *v, w = k;
  {
    const Mask m = wheel_mask(scene, h.t_s, layout.contacts[w]);
    const Series s = masked(h.t_s, h.contact_force_N[w], &m);
    if (!s.y.empty()) {
      LinePlot f = time_plot("Contact force of wheel " + h.wheel_names[w], "force [kN]");
      f.series.push_back(plot_series(h.wheel_names[w], s, 1e-3));
      f.shaded_x = mask_span(h.t_s, m);
      f.shaded_label = "wheel in window";
      FigureData d = data_of(run, "min_contact_force_N", h.wheel_names[w],
                             stored("min_contact_force_N", h.wheel_names[w]), *std::min_element(s.y.begin(), s.y.end()),
                             s);
      d.unilateral = r.summary.fidelity.unilateral;
      const std::string law = r.summary.fidelity.contact_law + (d.unilateral.value_or(false) ? ", unilateral" : "");
      figures.push_back({f,
                         "Contact force of wheel " + h.wheel_names[w] + " (the largest stored unloading), while it is "
                             "inside the evaluation window (" + law + "); the stored value is its smallest force there." +
                             agreement(d, 1e-3, "kN"),
                         d, ""});
    }
  }
  // The car body with the largest acceleration while one of its wheels is
  // in the window (the stored value is the largest over the bodies).
  const std::vector<BodyWheels> bodies = body_wheels(layout);
  if (bodies.size() != h.body_names.size()) return figures;
  std::vector<Mask> wheel_masks;
  for (const ContactSpec& c : layout.contacts) wheel_masks.push_back(wheel_mask(scene, h.t_s, c));
  std::optional<std::size_t> b;
  double largest = -1.0;
  Mask body_mask;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    Mask m(h.t_s.size(), false);
    for (Eigen::Index c : bodies[k].contacts)
      for (std::size_t i = 0; i < m.size(); ++i) m[i] = m[i] || wheel_masks[static_cast<std::size_t>(c)][i];
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m[i] && std::abs(h.carbody_acceleration_mps2[k][i]) > largest)
        largest = std::abs(h.carbody_acceleration_mps2[k][i]), b = k, body_mask = m;
  }
  if (!b) return figures;
  const Series s = masked(h.t_s, h.carbody_acceleration_mps2[*b], &body_mask);
  LinePlot c = time_plot("Car-body acceleration of " + h.body_names[*b], "acceleration [m/s2]");
  c.series.push_back(plot_series(h.body_names[*b], s, 1.0));
  c.shaded_x = mask_span(h.t_s, body_mask);
  c.shaded_label = "wheels in window";
  FigureData d = data_of(run, "carbody_acceleration_mps2", h.body_names[*b], stored("carbody_acceleration_mps2", ""),
                         largest, s);
  figures.push_back({c,
                     "Vertical car-body acceleration of " + h.body_names[*b] +
                         " (the largest), while one of its wheels is inside the evaluation window." +
                         agreement(d, 1.0, "m/s2"),
                     d, ""});
  return figures;
}

}  // namespace railvsi
