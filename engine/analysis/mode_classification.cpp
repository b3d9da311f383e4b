#include "analysis/mode_classification.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "solver/structure_coordinates.hpp"

namespace railvsi {
namespace {

constexpr int kSamplesPerSpan = 200;
constexpr double kSpanAtRest = 0.1;  // of the largest amplitude on the deck
constexpr double kNearZero = 0.05;   // of the span's amplitude: ignored when counting sign changes

struct Segment {
  double start_m, end_m;
};

// Vertical displacement of the deck at interior points of each span: on
// the deck's own line when the model has one (a beam deck), else on the
// first rail (a 3D deck or an imported model, where the rail follows the deck).
std::vector<std::vector<double>> deck_samples(const StructureModel& s, const Vector& shape,
                                              const std::vector<double>& supports_x_m, double band) {
  const StructureInfo& info = s.info();
  const RailLine& line = !info.deck_line.x_m.empty() ? info.deck_line : s.rails().front();
  std::vector<Segment> segments;
  if (supports_x_m.size() >= 2) {
    for (std::size_t i = 0; i + 1 < supports_x_m.size(); ++i) segments.push_back({supports_x_m[i], supports_x_m[i + 1]});
  } else {
    const double start = info.bridge_end_m > info.bridge_start_m ? info.bridge_start_m : line.start_m();
    const double end = info.bridge_end_m > info.bridge_start_m ? info.bridge_end_m : line.end_m();
    segments.push_back({start, end});
  }
  std::vector<std::vector<double>> w(segments.size());
  const StructureCoordinates dofs(s);
  for (std::size_t k = 0; k < segments.size(); ++k)
    for (int j = 0; j < kSamplesPerSpan; ++j) {
      const double x = segments[k].start_m + (band + (1.0 - 2.0 * band) * (j + 0.5) / kSamplesPerSpan) *
                                                 (segments[k].end_m - segments[k].start_m);
      w[k].push_back(rail_top(line.locate(x), shape, dofs));
    }
  return w;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

int count_half_waves(const std::vector<double>& w, double amplitude) {
  int changes = 0, last_sign = 0;
  for (const double x : w) {
    if (std::abs(x) < kNearZero * amplitude) continue;
    const int sign = x > 0.0 ? 1 : -1;
    if (last_sign != 0 && sign != last_sign) ++changes;
    last_sign = sign;
  }
  return changes + 1;
}

// "1-3" for consecutive spans, "1, 3" otherwise (1-based).
std::string span_list(const std::vector<int>& spans) {
  bool consecutive = true;
  for (std::size_t i = 1; i < spans.size(); ++i) consecutive = consecutive && spans[i] == spans[i - 1] + 1;
  if (consecutive && spans.size() > 2) return fmt::format("{}-{}", spans.front(), spans.back());
  return fmt::format("{}", fmt::join(spans, ", "));
}

std::string deck_description(const std::vector<int>& half_waves, bool per_span) {
  const auto waves = [](int h) { return fmt::format("{} half-wave{}", h, h == 1 ? "" : "s"); };
  if (!per_span) return fmt::format("deck bending, {} along the bridge", waves(half_waves.front()));
  std::vector<int> moving;
  for (std::size_t i = 0; i < half_waves.size(); ++i)
    if (half_waves[i] > 0) moving.push_back(static_cast<int>(i) + 1);
  if (moving.empty()) return "deck";
  const int first = half_waves[moving.front() - 1];
  const bool same = std::all_of(moving.begin(), moving.end(), [&](int s) { return half_waves[s - 1] == first; });
  if (moving.size() == 1) return fmt::format("deck bending, {} in span {}", waves(first), moving.front());
  if (same) return fmt::format("deck bending, {} in each of spans {}", waves(first), span_list(moving));
  return fmt::format("deck bending, half-waves per span {}", fmt::join(half_waves, "/"));
}

}  // namespace

double deck_energy_fraction(const StructureModel& s, const Vector& shape) {
  const Vector energy = shape.cwiseProduct(s.M() * shape);
  const double total = energy.sum();
  double deck = 0.0;
  for (Eigen::Index i = 0; i < energy.size(); ++i)
    if (!s.info().is_track_dof(static_cast<int>(i))) deck += energy[i];
  return total > 0.0 ? deck / total : 0.0;
}

ModeType classify_mode(const StructureModel& s, const Vector& shape) {
  return classify_mode(s, shape, s.info().support_x_m);
}

ModeType classify_mode(const StructureModel& s, const Vector& shape, const std::vector<double>& supports_x_m,
                       double support_band) {
  ModeType t;
  t.deck_energy_fraction = deck_energy_fraction(s, shape);
  t.deck = is_deck_mode(t.deck_energy_fraction);
  if (!t.deck) {
    t.description = "track";
    return t;
  }
  const auto w = deck_samples(s, shape, supports_x_m, support_band);
  double largest = 0.0;
  for (const auto& span : w) largest = std::max(largest, max_abs(span));
  for (const auto& span : w) {
    const double amplitude = max_abs(span);
    t.half_waves.push_back(amplitude > kSpanAtRest * largest ? count_half_waves(span, amplitude) : 0);
  }
  t.description = deck_description(t.half_waves, supports_x_m.size() >= 2);
  return t;
}

}  // namespace railvsi
