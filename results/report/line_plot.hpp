#pragma once
// A line plot drawn as inline SVG (no script, no font from the network), for
// the compliance report: series of points, an optional limit line, a marked
// point, vertical marks (e.g. resonance speeds) and a shaded x range (e.g.
// the evaluation window).
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace railvsi {

struct PlotSeries {
  std::string label;
  std::vector<std::pair<double, double>> points;  // (x, y), drawn in order; NaN y breaks the line
};

struct LinePlot {
  std::string title;
  std::string x_label, y_label;  // with units, e.g. "speed [km/h]"
  std::vector<PlotSeries> series;
  std::optional<double> limit;
  std::string limit_label;
  std::optional<std::pair<double, double>> marked;  // the governing point
  std::string marked_label;
  std::vector<double> x_marks;  // vertical thin lines
  std::vector<std::string> x_mark_labels;  // one per mark (drawn at its top), or none
  std::string x_marks_label;
  std::optional<std::pair<double, double>> shaded_x;
  std::string shaded_label;
};

// The plot as an <svg> element of the given size in CSS pixels.
std::string render_svg(const LinePlot& plot, int width_px = 680, int height_px = 300);

// Round tick values covering [lo, hi]: steps of 1, 2 or 5 times a power of ten.
std::vector<double> nice_ticks(double lo, double hi, int target_count = 6);

// The k-th series colour (colour-blind-safe palette, then greys; cycles).
const char* plot_colour(std::size_t k);

// Text safe inside HTML/SVG: & < > " ' escaped, control characters dropped.
std::string html_escape(const std::string& text);

}  // namespace railvsi
