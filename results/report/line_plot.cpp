#include "report/line_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace railvsi {
namespace {

// Colour-blind-safe palette (Okabe & Ito, 2008), then greys.
constexpr const char* kPalette[] = {"#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9",
                                    "#D55E00", "#F0E442", "#000000", "#777777", "#AAAAAA"};

std::string num(double v) { return fmt::format("{:.2f}", v); }

// A long history drawn at this size keeps, per pixel column, its first,
// lowest, highest and last point: every peak survives, the file stays small.
std::vector<std::pair<double, double>> decimated(const std::vector<std::pair<double, double>>& points, double x0,
                                                 double x1, double columns) {
  if (points.size() <= static_cast<std::size_t>(4 * columns)) return points;
  std::vector<std::pair<double, double>> out;
  long column = -1;
  std::size_t first = 0, lo = 0, hi = 0, last = 0;
  const auto flush = [&] {
    std::size_t idx[4] = {first, lo, hi, last};
    std::sort(idx, idx + 4);
    for (int k = 0; k < 4; ++k)
      if (k == 0 || idx[k] != idx[k - 1]) out.push_back(points[idx[k]]);
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& [x, y] = points[i];
    const long c = std::isfinite(x) ? static_cast<long>((x - x0) / (x1 - x0) * columns) : -2;
    if (c != column || !std::isfinite(y)) {
      if (column != -1) flush();
      column = c;
      first = lo = hi = last = i;
      if (!std::isfinite(y)) {
        out.push_back(points[i]);
        column = -1;
      }
      continue;
    }
    if (y < points[lo].second) lo = i;
    if (y > points[hi].second) hi = i;
    last = i;
  }
  if (column != -1) flush();
  return out;
}

std::string tick_text(double v) {
  if (v == 0.0) return "0";
  const double a = std::abs(v);
  if (a >= 1e4 || a < 1e-3) return fmt::format("{:.2g}", v);
  return fmt::format("{:g}", v);
}

}  // namespace

const char* plot_colour(std::size_t k) { return kPalette[k % std::size(kPalette)]; }

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default:
        if (c >= 0x20 && c != 0x7f)
          out += ch;
        else if (ch == '\n' || ch == '\t')
          out += ch;
    }
  }
  return out;
}

std::vector<double> nice_ticks(double lo, double hi, int target_count) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(1, target_count);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step)
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  return ticks;
}

std::string render_svg(const LinePlot& plot, int width_px, int height_px) {
  const double left = 70, right = 150, top = 30, bottom = 45;
  const double w = width_px - left - right, h = height_px - top - bottom;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = 0.0, y1 = -x0;
  for (const PlotSeries& s : plot.series)
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x)) continue;
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      if (!std::isfinite(y)) continue;
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  if (plot.limit) y1 = std::max(y1, *plot.limit), y0 = std::min(y0, *plot.limit);
  if (!std::isfinite(x0)) x0 = 0.0, x1 = 1.0;
  if (!(x1 > x0)) {  // one abscissa (a study at one speed): centred
    const double pad = std::max(1.0, 0.05 * std::abs(x0));
    x0 -= pad;
    x1 += pad;
  }
  if (!std::isfinite(y1) || !(y1 > y0)) y1 = y0 + 1.0;
  // Room above the data for the marks' labels: a governing peak drawn under
  // a label hid it (the HSLM example's i=1 at 410 km/h).
  y1 += (plot.x_mark_labels.empty() ? 0.05 : 0.12) * (y1 - y0);
  const auto X = [&](double x) { return left + (x - x0) / (x1 - x0) * w; };
  const auto Y = [&](double y) { return top + h - (y - y0) / (y1 - y0) * h; };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" role=\"img\" aria-label=\"{2}\">\n",
      width_px, height_px, html_escape(plot.title));
  svg += fmt::format("<text x=\"{}\" y=\"18\" class=\"plot-title\">{}</text>\n", num(left), html_escape(plot.title));
  if (plot.shaded_x) {
    const double a = std::clamp(plot.shaded_x->first, x0, x1), b = std::clamp(plot.shaded_x->second, x0, x1);
    svg += fmt::format("<rect class=\"window\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#eeeeee\"/>\n",
                       num(X(a)), num(top), num(X(b) - X(a)), num(h));
  }
  // Grid and ticks.
  for (double t : nice_ticks(x0, x1)) {
    svg += fmt::format("<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#dddddd\"/>\n", num(X(t)), num(top),
                       num(top + h));
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" class=\"tick\">{}</text>\n", num(X(t)),
                       num(top + h + 15), tick_text(t));
  }
  for (double t : nice_ticks(y0, y1)) {
    svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#dddddd\"/>\n", num(left),
                       num(left + w), num(Y(t)));
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\" class=\"tick\">{}</text>\n", num(left - 5),
                       num(Y(t) + 4), tick_text(t));
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333333\"/>\n",
                     num(left), num(top), num(w), num(h));
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" class=\"axis\">{}</text>\n", num(left + w / 2),
                     num(height_px - 8), html_escape(plot.x_label));
  svg += fmt::format("<text transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\" class=\"axis\">{}</text>\n",
                     num(top + h / 2), html_escape(plot.y_label));
  for (std::size_t i = 0; i < plot.x_marks.size(); ++i) {
    const double m = plot.x_marks[i];
    if (m < x0 || m > x1) continue;
    svg += fmt::format(
        "<line class=\"mark\" x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#999999\" "
        "stroke-dasharray=\"2 3\"/>\n",
        num(X(m)), num(top), num(top + h));
    if (i < plot.x_mark_labels.size())
      // Kept inside the frame: a label centred on a mark at its edge crossed it.
      svg += fmt::format("<text class=\"tick mark-label\" x=\"{}\" y=\"{}\" text-anchor=\"{}\">{}</text>\n",
                         num(X(m) - left < 15 ? X(m) + 2 : left + w - X(m) < 15 ? X(m) - 2 : X(m)), num(top + 10),
                         X(m) - left < 15 ? "start" : left + w - X(m) < 15 ? "end" : "middle",
                         html_escape(plot.x_mark_labels[i]));
  }
  if (plot.limit)
    svg += fmt::format(
        "<line class=\"limit\" x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#CC0000\" stroke-width=\"1.5\" "
        "stroke-dasharray=\"8 4\"/>\n",
        num(left), num(left + w), num(Y(*plot.limit)));
  // Series.
  std::size_t k = 0;
  for (const PlotSeries& s : plot.series) {
    const char* colour = plot_colour(k++);
    std::string path;
    // A point with no drawn neighbour (one speed, or between gaps) is a dot:
    // a path of one point draws nothing.
    std::vector<std::pair<double, double>> run;
    const auto end_run = [&] {
      if (run.size() == 1)
        svg += fmt::format("<circle class=\"point\" cx=\"{}\" cy=\"{}\" r=\"3\" fill=\"{}\"/>\n",
                           num(X(run[0].first)), num(Y(run[0].second)), colour);
      run.clear();
    };
    for (const auto& [x, y] : decimated(s.points, x0, x1, w)) {
      if (!std::isfinite(x) || !std::isfinite(y)) {
        end_run();
        continue;
      }
      path += fmt::format("{}{} {} ", run.empty() ? "M" : "L", num(X(x)), num(Y(y)));
      run.emplace_back(x, y);
    }
    end_run();
    if (!path.empty())
      svg += fmt::format("<path class=\"series\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n",
                         path, colour);
  }
  if (plot.marked)
    svg += fmt::format(
        "<circle class=\"governing\" cx=\"{}\" cy=\"{}\" r=\"5\" fill=\"none\" stroke=\"#CC0000\" "
        "stroke-width=\"2\"/>\n",
        num(X(plot.marked->first)), num(Y(plot.marked->second)));
  // Legend.
  double ly = top + 10;
  k = 0;
  for (const PlotSeries& s : plot.series) {
    const char* colour = plot_colour(k++);
    svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"{3}\" stroke-width=\"2\"/>"
                       "<text x=\"{4}\" y=\"{5}\" class=\"legend\">{6}</text>\n",
                       num(left + w + 10), num(left + w + 30), num(ly), colour, num(left + w + 35), num(ly + 4),
                       html_escape(s.label));
    ly += 15;
  }
  if (plot.limit) {
    svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#CC0000\" stroke-dasharray=\"8 4\"/>"
                       "<text x=\"{3}\" y=\"{4}\" class=\"legend\">{5}</text>\n",
                       num(left + w + 10), num(left + w + 30), num(ly), num(left + w + 35), num(ly + 4),
                       html_escape(plot.limit_label));
    ly += 15;
  }
  if (plot.marked) {
    svg += fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"4\" fill=\"none\" stroke=\"#CC0000\" stroke-width=\"2\"/>"
                       "<text x=\"{}\" y=\"{}\" class=\"legend\">{}</text>\n",
                       num(left + w + 20), num(ly), num(left + w + 35), num(ly + 4), html_escape(plot.marked_label));
    ly += 15;
  }
  if (!plot.x_marks.empty()) {
    svg += fmt::format("<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#999999\" stroke-dasharray=\"2 3\"/>"
                       "<text x=\"{3}\" y=\"{4}\" class=\"legend\">{5}</text>\n",
                       num(left + w + 20), num(ly - 6), num(ly + 6), num(left + w + 35), num(ly + 4),
                       html_escape(plot.x_marks_label));
    ly += 15;
  }
  if (plot.shaded_x)
    svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"20\" height=\"10\" fill=\"#eeeeee\" stroke=\"#cccccc\"/>"
                       "<text x=\"{}\" y=\"{}\" class=\"legend\">{}</text>\n",
                       num(left + w + 10), num(ly - 5), num(left + w + 35), num(ly + 4),
                       html_escape(plot.shaded_label));
  svg += "</svg>\n";
  return svg;
}

}  // namespace railvsi
