#include "study/deck_frequencies.hpp"

#include <algorithm>

#include "solver/modal_analysis.hpp"
#include "analysis/mode_classification.hpp"

namespace railvsi::scheduler {

DeckFrequencies deck_frequencies(const StructureModel& structure) {
  // A few spans' first, second and third bending modes, with track modes
  // in between.
  ModalOptions options;
  options.modes = 24;
  const ModalResult modes = modal_analysis(structure, options);
  DeckFrequencies f;
  if (!modes.status.ok()) return f;
  f.supports = span_supports(structure, modes);
  for (std::size_t k = 0; k < modes.frequencies_hz.size(); ++k) {
    const ModeType type = classify_mode(structure, modes.shapes.col(static_cast<Eigen::Index>(k)), f.supports.x_m);
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
  // Not found among the modes computed: unknown (0), the code frequency is
  // then max(30 Hz, 1.5 f0).
  return f;
}

}  // namespace railvsi::scheduler
