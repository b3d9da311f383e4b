#include "planning/deck_frequencies.hpp"

#include <algorithm>

#include "solver/modal_analysis.hpp"
#include "analysis/mode_classification.hpp"

namespace railvsi {
namespace {

// A few spans' first, second and third bending modes, with track modes in
// between, are among the 24 lowest modes of a short bridge. A long viaduct
// has one mode per span in each family, and its track's rail-on-pad modes
// before its spans' third modes: measured, a viaduct of ten 25 m spans with
// ballasted track has no third mode among its lowest 24 (nor has a deck of
// twelve without track), and f3 went unfound, the code frequency falling
// to its floor (30 Hz against 50 Hz). So the count is doubled until one is
// found, within a budget of DOFs times modes (96 modes up to 20,000 DOFs).
constexpr int kFirstModes = 24;
constexpr int kMaxModes = 192;
constexpr double kModeBudget = 2.0e6;

DeckFrequencies read_frequencies(const StructureModel& structure, const ModalResult& modes) {
  DeckFrequencies f;
  f.supports = span_supports(structure, modes);
  for (std::size_t k = 0; k < modes.frequencies_hz.size(); ++k) {
    const ModeType type = classify_mode(structure, modes.shapes.col(static_cast<Eigen::Index>(k)), f.supports.x_m,
                                        f.supports.from_modes ? kReadSupportBand : 0.0);
    if (!type.deck) continue;
    if (f.f0_hz == 0.0) f.f0_hz = modes.frequencies_hz[k];
    // A span's third bending mode: at least 3 half-waves in every span
    // that moves (a span at rest counts 0 and is left out). The fewest, not
    // the most: on a 3D deck a torsion or plate mode can show a few
    // half-waves in a span that hardly moves vertically, and taking it for
    // f3 would lower the code frequency (the unsafe side).
    int half_waves = 0;
    for (const int h : type.half_waves)
      if (h > 0) half_waves = half_waves == 0 ? h : std::min(half_waves, h);
    if (half_waves >= 3) {
      f.f3_hz = modes.frequencies_hz[k];
      break;
    }
  }
  return f;
}

}  // namespace

DeckFrequencies deck_frequencies(const StructureModel& structure) {
  for (int n = kFirstModes;; n *= 2) {
    ModalOptions options;
    options.modes = n;
    const ModalResult modes = modal_analysis(structure, options);
    if (!modes.status.ok()) {
      DeckFrequencies none;
      none.status = modes.status;
      return none;
    }
    DeckFrequencies f = read_frequencies(structure, modes);
    f.modes_searched = static_cast<int>(modes.frequencies_hz.size());
    f.lowest_hz = modes.frequencies_hz;
    const bool more = f.f3_hz == 0.0 && f.f0_hz > 0.0 && f.modes_searched == n && 2 * n <= kMaxModes &&
                      2.0 * n * structure.num_dofs() <= kModeBudget;
    // Not found among the modes computed: unknown (0), the code frequency
    // is then max(30 Hz, 1.5 f0).
    if (!more) return f;
  }
}

}  // namespace railvsi
