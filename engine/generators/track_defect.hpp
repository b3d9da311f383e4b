#pragma once
// Isolated track defects (a rail joint, a local settlement): a cosine dip or
// bump of depth d over a length L starting at x0,
//   r(x) = -+ d/2 * (1 - cos(2*pi*(x - x0)/L))  on [x0, x0 + L], 0 elsewhere,
// so r = -d (dip) or +d (bump) at the centre and r and dr/dx are continuous.
#include <string>
#include <vector>

#include "model/irregularity.hpp"

namespace railvsi {

enum class DefectShape { kDip, kBump };

struct TrackDefect {
  DefectShape shape = DefectShape::kDip;
  double x_m = 0.0;       // start
  double length_m = 0.0;  // > 0
  double depth_m = 0.0;   // > 0, whatever the shape

  double at(double x_m) const;
  std::string describe() const;  // "dip 0.005 m deep, 1 m long at x = 30 m"
};

// Samples per defect: the cosine between them is linear to 0.13 % of d.
inline constexpr int kDefectIntervals = 64;

// The base profile (null: a perfect track) plus the defects: sampled at the
// base's samples and kDefectIntervals + 1 points over each defect. Defects
// may overlap (they add). Throws InputError at "/defects/k/..." for a
// non-positive length or depth, or a defect reaching outside the base's
// samples (the base is zero there, and interpolating to it would invent a
// ramp).
Irregularity with_defects(const Irregularity* base, const std::vector<TrackDefect>& defects);

}  // namespace railvsi
