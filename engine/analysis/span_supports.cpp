#include "analysis/span_supports.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/mode_classification.hpp"
#include "solver/structure_coordinates.hpp"

namespace railvsi {
namespace {

constexpr int kSamples = 4000;  // along the bridge

}  // namespace

SpanSupports span_supports(const StructureModel& s, const ModalResult& modes) {
  const StructureInfo& info = s.info();
  SpanSupports out;
  if (info.support_x_m.size() >= 2) {
    out.x_m = info.support_x_m;
    return out;
  }
  if (!modes.status.ok()) return out;
  const RailLine& line = !info.deck_line.x_m.empty() ? info.deck_line : s.rails().front();
  const bool extent = info.bridge_end_m > info.bridge_start_m;
  const double b0 = extent ? info.bridge_start_m : line.start_m();
  const double b1 = extent ? info.bridge_end_m : line.end_m();
  const StructureCoordinates dofs(s);

  std::vector<double> x(kSamples);
  for (int j = 0; j < kSamples; ++j) x[static_cast<std::size_t>(j)] = b0 + (j + 0.5) / kSamples * (b1 - b0);
  // Each deck mode's displacement along the bridge, scaled to its largest.
  std::vector<std::vector<double>> w;
  double f0 = 0.0;
  for (std::size_t k = 0; k < modes.frequencies_hz.size(); ++k) {
    const Vector shape = modes.shapes.col(static_cast<Eigen::Index>(k));
    if (!is_deck_mode(deck_energy_fraction(s, shape))) continue;
    if (f0 == 0.0) f0 = modes.frequencies_hz[k];
    if (modes.frequencies_hz[k] > kSupportModesBelowF0 * f0) break;
    std::vector<double> wk(x.size());
    double largest = 0.0;
    for (std::size_t j = 0; j < x.size(); ++j) {
      wk[j] = rail_top(line.locate(x[j]), shape, dofs);
      largest = std::max(largest, std::abs(wk[j]));
    }
    if (!(largest > 0.0)) continue;
    for (double& v : wk) v /= largest;
    w.push_back(std::move(wk));
  }
  if (w.empty()) return out;
  std::vector<double> envelope(x.size(), 0.0);
  for (const auto& wk : w)
    for (std::size_t j = 0; j < x.size(); ++j) envelope[j] = std::max(envelope[j], std::abs(wk[j]));

  // Between two stretches where a mode moves, the point where all are most
  // at rest: a support when they are at rest there. Embankments beyond the
  // last moving stretch are not between two. A gap wider than half of a
  // stretch beside it is a span that no mode used bends (a short span
  // beside long ones): then the supports are not read at all, rather than
  // one where there are two.
  std::vector<double> interior;
  double largest_rest = 0.0;
  std::size_t j = 0;
  while (j < x.size() && envelope[j] < kSpanMoving) ++j;  // the first moving stretch
  std::size_t stretch_start = j;
  while (j < x.size()) {
    while (j < x.size() && envelope[j] >= kSpanMoving) ++j;
    const std::size_t gap = j, stretch_before = gap - stretch_start;
    while (j < x.size() && envelope[j] < kSpanMoving) ++j;
    if (j == x.size()) break;  // no moving stretch after this gap
    std::size_t next_end = j;
    while (next_end < x.size() && envelope[next_end] >= kSpanMoving) ++next_end;
    const std::size_t gap_width = j - gap, stretch_after = next_end - j;
    stretch_start = j;
    const auto rest = std::min_element(envelope.begin() + static_cast<std::ptrdiff_t>(gap),
                                       envelope.begin() + static_cast<std::ptrdiff_t>(j));
    if (*rest > kSupportAtRest) continue;  // the deck bends through here: no support
    if (2 * gap_width > std::min(stretch_before, stretch_after)) return out;
    const auto m = static_cast<std::size_t>(rest - envelope.begin());
    // The support itself: where the mode that moves most around it changes
    // sign, between samples (the envelope is |w|, a V at a support).
    double at = x[m];
    const std::size_t lo = m > 0 ? m - 1 : m, hi = std::min(m + 1, x.size() - 1);
    const std::vector<double>* steepest = &w.front();
    for (const auto& wk : w)
      if (std::abs(wk[hi] - wk[lo]) > std::abs((*steepest)[hi] - (*steepest)[lo])) steepest = &wk;
    for (std::size_t i = lo; i < hi; ++i) {
      const double a = (*steepest)[i], b = (*steepest)[i + 1];
      if ((a <= 0.0 && b > 0.0) || (a >= 0.0 && b < 0.0)) at = x[i] + a / (a - b) * (x[i + 1] - x[i]);
    }
    interior.push_back(at);
    largest_rest = std::max(largest_rest, *rest);
  }
  if (interior.empty()) return out;
  out.x_m.push_back(b0);
  out.x_m.insert(out.x_m.end(), interior.begin(), interior.end());
  out.x_m.push_back(b1);
  out.from_modes = true;
  out.largest_rest = largest_rest;
  out.modes_used = static_cast<int>(w.size());
  return out;
}

}  // namespace railvsi
