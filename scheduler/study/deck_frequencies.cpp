#include "study/deck_frequencies.hpp"

#include <vector>

#include "analysis/modal_analysis.hpp"
#include "analysis/mode_classification.hpp"

namespace railvsi::scheduler {

DeckFrequencies deck_frequencies(const StructureModel& structure) {
  // Enough modes to find three of the deck among those of the track.
  ModalOptions options;
  options.modes = 12;
  const ModalResult modes = modal_analysis(structure, options);
  std::vector<double> deck_hz;
  if (modes.status.ok())
    for (std::size_t k = 0; k < modes.frequencies_hz.size() && deck_hz.size() < 3; ++k)
      if (classify_mode(structure, modes.shapes.col(static_cast<Eigen::Index>(k))).deck)
        deck_hz.push_back(modes.frequencies_hz[k]);
  DeckFrequencies f;
  if (!deck_hz.empty()) f.f0_hz = deck_hz[0];
  if (deck_hz.size() >= 3) f.f3_hz = deck_hz[2];
  return f;
}

}  // namespace railvsi::scheduler
