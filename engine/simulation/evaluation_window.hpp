#pragma once
// The stretch of track whose wheels give results: the bridge and
// AnalysisOptions::evaluation_margin_m on either side. Wheel and car-body
// envelopes, and the contact-health warnings about them, count only there:
// where wheels enter or leave the modelled track the transients are the
// model's ends, not the bridge's.
#include "simulation/scene.hpp"

namespace railvsi {

struct EvaluationWindow {
  double start_m = 0.0, end_m = 0.0;

  static EvaluationWindow of(const Scene& scene) {
    const auto [b0, b1] = bridge_extent_m(*scene.structure);
    return {b0 - scene.analysis.evaluation_margin_m, b1 + scene.analysis.evaluation_margin_m};
  }
  bool contains(double x_m) const { return x_m >= start_m && x_m <= end_m; }
};

}  // namespace railvsi
