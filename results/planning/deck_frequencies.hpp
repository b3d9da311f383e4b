#pragma once
// f0 and f3 of a structure for the code filter: EN 1990 A2.4.4.2.1 keeps
// frequencies up to the greater of 30 Hz, 1.5 times the fundamental
// frequency of the member and the frequency of its third mode. For a span
// (the member of a bridge of simply supported spans) the third mode is its
// third bending mode, three half-waves: f3 is the lowest deck mode with
// three or more half-waves in a span, found among the modes of the whole
// structure with the track modes skipped (24 of them, doubled while f3 is
// not among them, up to 96 for 20,000 DOFs).
#include <vector>

#include "analysis/span_supports.hpp"
#include "core/status.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

struct DeckFrequencies {
  double f0_hz = 0.0;  // 0 when not found (the code frequency is then at least 30 Hz)
  double f3_hz = 0.0;
  // The supports the modes were read span by span with: the structure's,
  // or read from its modes (analysis/span_supports.hpp); empty: one span.
  SpanSupports supports;
  int modes_searched = 0;  // the lowest modes f3 was looked for in
  // Their frequencies, ascending: count_modes reads the modes below a
  // cut-off from them when they reach past it.
  std::vector<double> lowest_hz;
  Status status;           // of the modal analysis: not ok, nothing was found
};

DeckFrequencies deck_frequencies(const StructureModel& structure);

// The largest structure vsi simulate and vsi price compute f0 and f3 for
// (larger ones take the code frequency's floor of 30 Hz, with a warning):
// the 233,000-DOF seed-scale deck took 28 s and 2.1 GB for its 24 modes by
// subspace iteration, 5 % of its FE run; a miss leaves the floor, with the
// reason.
inline constexpr int kMaxDofsForDeckFrequencies = 300000;

}  // namespace railvsi
