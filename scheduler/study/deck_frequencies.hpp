#pragma once
// f0 and f3 of a structure for the code: the first and third deck bending
// frequencies (EN 1990 A2.4.4.2.1 keeps frequencies up to max(30 Hz, 1.5 f0,
// f3)), from the modal analysis, skipping track modes.
#include "model/structure_model.hpp"

namespace railvsi::scheduler {

struct DeckFrequencies {
  double f0_hz = 0.0;  // 0 when not found (the code frequency is then at least 30 Hz)
  double f3_hz = 0.0;
};

DeckFrequencies deck_frequencies(const StructureModel& structure);

}  // namespace railvsi::scheduler
