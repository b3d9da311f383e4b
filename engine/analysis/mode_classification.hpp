#pragma once
// What a mode shape is, in words an engineer checks a model with: deck or
// track, and for a deck mode how many half-waves each span bends in.
#include <string>
#include <vector>

#include "core/types.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

struct ModeType {
  // Share of the mode's kinetic energy (phi_i (M phi)_i summed) in the deck
  // DOFs of StructureInfo; 1 for a model without a track.
  double deck_energy_fraction = 0.0;
  bool deck = false;  // at least half of the energy in the deck
  // Half-waves of the deck's vertical displacement per span (sign changes
  // + 1), 0 for a span that hardly moves (< 10 % of the largest amplitude).
  // One entry for the whole bridge when the supports are unknown (rail
  // line 0 between bridge_start_m and bridge_end_m; see span_supports.hpp).
  std::vector<int> half_waves;
  // "deck bending, 1 half-wave in span 2", "deck bending, 1 half-wave in
  // each of spans 1-3", "deck bending, half-waves per span 1/2/0", "track".
  std::string description;
};

// Share of the mode's kinetic energy in the deck DOFs, and whether that
// makes it a deck mode (ModeType::deck), without reading its half-waves.
double deck_energy_fraction(const StructureModel& structure, const Vector& shape);
inline bool is_deck_mode(double deck_energy_fraction) { return deck_energy_fraction >= 0.5; }

// Span by span between the structure's supports (StructureInfo::support_x_m)...
ModeType classify_mode(const StructureModel& structure, const Vector& shape);
// ...or between `supports_x_m` (bridge start, interior supports, bridge
// end; fewer than 2: the bridge as one span), leaving out `support_band`
// of each span at either end (supports whose place is known only roughly).
ModeType classify_mode(const StructureModel& structure, const Vector& shape, const std::vector<double>& supports_x_m,
                       double support_band = 0.0);

}  // namespace railvsi
