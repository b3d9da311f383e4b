#pragma once
// The supports a bridge is read span by span with. A generated structure
// knows them; an imported one knows them when its map gives supports_x_m.
// Otherwise they are read from its deck modes: at an interior support
// every low deck mode is at rest, inside a span at least one moves.
// Without them a bridge of several spans is read as one, and the spans'
// first modes (in phase and out of phase) look like a third bending mode:
// f3 came out as f0 and the code cut-off fell below a span's third mode.
#include <vector>

#include "model/structure_model.hpp"
#include "solver/modal_analysis.hpp"

namespace railvsi {

struct SpanSupports {
  // Bridge start, interior supports, bridge end; empty when the bridge is
  // read as one span (none known, none found).
  std::vector<double> x_m;
  bool from_modes = false;  // read from the modes, not given by the model
  // From the modes: the largest normalised deck displacement of any mode
  // used at a support found (0 at a perfect support), and how many modes.
  double largest_rest = 0.0;
  int modes_used = 0;
};

// The model's supports when it has them, else those read from `modes`
// (deck modes below kSupportModesBelowF0 times the lowest deck mode).
SpanSupports span_supports(const StructureModel& structure, const ModalResult& modes);

// The lowest deck modes, up to this multiple of f0, bend every span of a
// bridge whose spans differ by up to a factor of 1.58 in length (a span's
// first mode scales as 1/L^2). Higher ones are left out: on a 3D deck its
// torsion and plate modes move the rail above the bearings (measured on the
// 3 x 25 m deck-3d: by 30 % of their largest displacement with the modes up
// to 4.5 f0, by 4.8 % with those up to 2.5 f0, its first three).
constexpr double kSupportModesBelowF0 = 2.5;
// A point is a support when no mode used moves there by more than this
// fraction of its largest deck displacement; a span moves where one moves
// by more than kSpanMoving.
constexpr double kSupportAtRest = 0.1;
constexpr double kSpanMoving = 0.25;
// Supports read from the modes are placed to about 0.5 % of a span, and the
// rail over them moves with the longer span beside: the modes are read
// span by span without this fraction of each span at either end.
constexpr double kReadSupportBand = 0.05;

}  // namespace railvsi
