#include "report/price_chart.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <fmt/format.h>

#include "report/line_plot.hpp"

namespace railvsi {
namespace {

std::string num(double v) { return fmt::format("{:.2f}", v); }

std::string decade_text(int k) { return fmt::format("{:g}", std::pow(10.0, k)); }

}  // namespace

std::string render_price_chart(const PriceChart& chart, int width_px, int height_px) {
  const double left = 70, right = 215, top = 30, bottom = 45;
  const double w = width_px - left - right, h = height_px - top - bottom;
  double cpu_lo = std::numeric_limits<double>::infinity(), cpu_hi = 0.0;
  double err_lo = std::numeric_limits<double>::infinity(), err_hi = 0.05;  // the 5 % band is always shown
  for (const PricePoint& p : chart.points) {
    cpu_lo = std::min(cpu_lo, p.cpu_s);
    cpu_hi = std::max(cpu_hi, p.cpu_s);
    const double e = std::abs(p.error);
    if (e > 0.0) err_lo = std::min(err_lo, e);
    err_hi = std::max(err_hi, e);
  }
  if (!std::isfinite(cpu_lo) || !(cpu_lo > 0.0)) cpu_lo = cpu_hi = 1.0;
  if (!std::isfinite(err_lo)) err_lo = kPriceChartMinError;
  // Whole decades.
  const int x_lo = static_cast<int>(std::floor(std::log10(cpu_lo)));
  int x_hi = static_cast<int>(std::ceil(std::log10(cpu_hi)));
  if (x_hi <= x_lo) x_hi = x_lo + 1;
  const int y_lo = std::max(static_cast<int>(std::floor(std::log10(kPriceChartMinError))),
                            static_cast<int>(std::floor(std::log10(err_lo))));
  int y_hi = static_cast<int>(std::ceil(std::log10(err_hi)));
  if (y_hi <= y_lo) y_hi = y_lo + 1;
  const auto X = [&](double cpu_s) { return left + (std::log10(cpu_s) - x_lo) / (x_hi - x_lo) * w; };
  const auto Y = [&](double error) {
    const double e = std::max(std::abs(error), std::pow(10.0, y_lo));
    return top + h - (std::log10(e) - y_lo) / (y_hi - y_lo) * h;
  };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot price-chart\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" role=\"img\" aria-label=\"{2}\" data-x-decades=\"{3} {4}\" "
      "data-y-decades=\"{5} {6}\">\n",
      width_px, height_px, html_escape(chart.title), x_lo, x_hi, y_lo, y_hi);
  svg += fmt::format("<text x=\"{}\" y=\"18\" class=\"plot-title\">{}</text>\n", num(left), html_escape(chart.title));
  for (int k = x_lo; k <= x_hi; ++k) {
    svg += fmt::format("<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#dddddd\"/>\n", num(X(std::pow(10.0, k))),
                       num(top), num(top + h));
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" class=\"tick\">{}</text>\n",
                       num(X(std::pow(10.0, k))), num(top + h + 15), decade_text(k));
  }
  for (int k = y_lo; k <= y_hi; ++k) {
    svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#dddddd\"/>\n", num(left),
                       num(left + w), num(Y(std::pow(10.0, k))));
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\" class=\"tick\">{}</text>\n", num(left - 5),
                       num(Y(std::pow(10.0, k)) + 4), decade_text(k));
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333333\"/>\n",
                     num(left), num(top), num(w), num(h));
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" class=\"axis\">CPU time of the run [s], log "
                     "scale</text>\n",
                     num(left + w / 2), num(height_px - 8));
  svg += fmt::format("<text transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\" class=\"axis\">"
                     "|error| against the reference, log scale</text>\n",
                     num(top + h / 2));
  // The 1 % and 5 % bands.
  for (const auto& [band, dash, label] :
       {std::tuple{0.01, "6 3", "1 %"}, std::tuple{0.05, "2 3", "5 %"}}) {
    svg += fmt::format("<line class=\"band\" data-band=\"{3}\" x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" "
                       "stroke=\"#CC0000\" stroke-dasharray=\"{4}\"/>\n",
                       num(left), num(left + w), num(Y(band)), label, dash);
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\" class=\"tick\" fill=\"#CC0000\">{}</text>\n",
                       num(left + w - 3), num(Y(band) - 3), label);
  }
  // Rungs, in the order they first appear.
  std::vector<std::string> rungs;
  for (const PricePoint& p : chart.points)
    if (std::find(rungs.begin(), rungs.end(), p.rung) == rungs.end()) rungs.push_back(p.rung);
  const auto colour = [&](const std::string& rung) {
    return plot_colour(static_cast<std::size_t>(std::find(rungs.begin(), rungs.end(), rung) - rungs.begin()));
  };
  for (const std::string& rung : rungs) {
    std::string path;
    for (const PricePoint& p : chart.points)
      if (p.rung == rung) path += fmt::format("{}{} {} ", path.empty() ? "M" : "L", num(X(p.cpu_s)), num(Y(p.error)));
    svg += fmt::format("<path class=\"rung-line\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-opacity=\"0.5\"/>\n",
                       path, colour(rung));
  }
  // The Pareto front, cheapest first.
  std::vector<const PricePoint*> front;
  for (const PricePoint& p : chart.points)
    if (p.pareto) front.push_back(&p);
  std::stable_sort(front.begin(), front.end(), [](const PricePoint* a, const PricePoint* b) { return a->cpu_s < b->cpu_s; });
  if (!front.empty()) {
    std::string path;
    for (const PricePoint* p : front)
      path += fmt::format("{}{} {} ", path.empty() ? "M" : "L", num(X(p->cpu_s)), num(Y(p->error)));
    svg += fmt::format("<path class=\"pareto-front\" d=\"{}\" fill=\"none\" stroke=\"#000000\" stroke-width=\"1.5\"/>\n",
                       path);
  }
  for (const PricePoint& p : chart.points) {
    const double cx = X(p.cpu_s), cy = Y(p.error);
    svg += fmt::format(
        "<circle class=\"price-point{}\" data-rung=\"{}\" data-dt-s=\"{:.17g}\" cx=\"{}\" cy=\"{}\" r=\"{}\" "
        "fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\"><title>{}, dt {:g} ms: {:.3g} s, error {:+.3g} %</title>"
        "</circle>\n",
        p.pareto ? " pareto" : "", html_escape(p.rung), p.dt_s, num(cx), num(cy), p.pareto ? 5 : 3.5, colour(p.rung),
        p.pareto ? "#000000" : colour(p.rung), p.pareto ? 1.5 : 0.5, html_escape(p.rung), 1e3 * p.dt_s, p.cpu_s,
        100.0 * p.error);
    if (p.reference)
      svg += fmt::format("<path class=\"reference\" d=\"M{0} {1} l8 8 l-8 8 l-8 -8 z\" fill=\"none\" stroke=\"#000000\" "
                         "stroke-width=\"1.5\" transform=\"translate(0 -8)\"/>\n",
                         num(cx), num(cy));
  }
  // Legend.
  double ly = top + 10;
  const double lx = left + w + 8;
  for (const std::string& rung : rungs) {
    svg += fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"3.5\" fill=\"{}\"/><text x=\"{}\" y=\"{}\" class=\"legend\">{}"
                       "</text>\n",
                       num(lx + 8), num(ly), colour(rung), num(lx + 16), num(ly + 4), html_escape(rung));
    ly += 15;
  }
  svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#000000\" stroke-width=\"1.5\"/>"
                     "<text x=\"{3}\" y=\"{4}\" class=\"legend\">Pareto front</text>\n",
                     num(lx), num(lx + 14), num(ly), num(lx + 16), num(ly + 4));
  ly += 15;
  svg += fmt::format("<path d=\"M{0} {1} l6 6 l-6 6 l-6 -6 z\" fill=\"none\" stroke=\"#000000\"/>"
                     "<text x=\"{2}\" y=\"{3}\" class=\"legend\">reference (error 0)</text>\n",
                     num(lx + 8), num(ly - 6), num(lx + 16), num(ly + 4));
  ly += 15;
  svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#CC0000\" stroke-dasharray=\"6 3\"/>"
                     "<text x=\"{3}\" y=\"{4}\" class=\"legend\">1 % and 5 %</text>\n",
                     num(lx), num(lx + 14), num(ly), num(lx + 16), num(ly + 4));
  svg += "</svg>\n";
  return svg;
}

}  // namespace railvsi
