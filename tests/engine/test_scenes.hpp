#pragma once
// Small scenes shared by the tests and benchmarks.
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "generators/bridge_2d.hpp"
#include "generators/deck_3d.hpp"
#include "generators/vehicle_2d.hpp"
#include "simulation/scene.hpp"
#include "../support/worst_of.hpp"

namespace railvsi::testing {

// Three 25 m spans of the 3D deck, coarse (25 elements a span, 4 across, 2
// deep), with 20 m of track either side: a few thousand DOFs.
inline Deck3dOptions coarse_three_span_deck_3d() {
  Deck3dOptions o;
  o.spans_m = {25.0, 25.0, 25.0};
  o.approach_m = 20.0;
  o.exit_m = 20.0;
  o.mesh = Deck3dMesh{{25, 25, 25}, 4, 2};
  return o;
}

// ICE3 coach (Goicolea 2014, AVE S-103 simplified description; see
// jobs/trains/ICE3.json).
inline Car2dOptions ice3_coach() {
  Car2dOptions c;
  c.name = "ICE3 coach";
  c.body_mass_kg = 47800;
  c.body_pitch_inertia_kgm2 = 1957888;
  c.bogie_mass_kg = 3500;
  c.bogie_pitch_inertia_kgm2 = 1715;
  c.wheelset_mass_kg = 1800;
  c.bogie_spacing_m = 17.375;
  c.axle_spacing_m = 2.5;
  c.primary = {2.4e6, 2e4};
  c.secondary = {7e5, 4e4};
  return c;
}

// A cosine dip of the rail top: r = -depth/2 (1 - cos(2 pi (x - x0)/length)).
inline std::shared_ptr<const Irregularity> cosine_dip(double x0_m, double length_m, double depth_m) {
  std::vector<double> x, r;
  for (double xi = x0_m - 1.0; xi <= x0_m + length_m + 1.0 + 1e-9; xi += 0.01) {
    x.push_back(xi);
    const double s = (xi - x0_m) / length_m;
    r.push_back(s > 0.0 && s < 1.0 ? -0.5 * depth_m * (1.0 - std::cos(2.0 * std::numbers::pi * s)) : 0.0);
  }
  return std::make_shared<const Irregularity>(x, r, "cosine dip");
}

// The span of the standard EN 1991-2 HSLM check: 15 m simply supported,
// f0 = 5 Hz, 15 t/m, 1 % damping, output at midspan.
inline Bridge2dOptions hslm_check_span_options() {
  Bridge2dOptions b;
  b.spans_m = {15.0};
  b.deck_first_frequency_hz = 5.0;
  b.deck_mass_kg_per_m = 15000.0;
  b.damping_ratio = 0.01;
  b.output_points = {{"midspan", 7.5}};
  return b;
}

// The hard cases' two spans: 2 x 15 m, EI 1.2e10 N m^2, 15 t/m, 2 %, 0.6 m
// elements (f0 about 6.2 Hz); no track unless given.
inline Bridge2dOptions two_fifteen_metre_spans(std::optional<TrackOptions> track = std::nullopt) {
  Bridge2dOptions b;
  b.spans_m = {15.0, 15.0};
  b.deck_EI_Nm2 = 1.2e10;
  b.deck_mass_kg_per_m = 15000.0;
  b.damping_ratio = 0.02;
  b.element_length_m = 0.6;
  b.track = track;
  return b;
}

// One ICE3 coach as a train.
inline Train one_ice3_coach() {
  Train t;
  t.name = "one coach";
  t.vehicles.push_back({make_car_2d(ice3_coach()), 0.0});
  return t;
}

// Two 10 m spans with ballasted track (24 m approach, 6 m exit).
inline Bridge2dOptions small_viaduct_options() {
  Bridge2dOptions b;
  b.spans_m = {10.0, 10.0};
  b.deck_EI_Nm2 = 1.0e10;
  b.deck_mass_kg_per_m = 10000.0;
  b.damping_ratio = 0.02;
  b.element_length_m = 1.0;
  TrackOptions t;
  t.approach_m = 24.0;
  t.exit_m = 6.0;
  b.track = t;
  return b;
}

// The small viaduct, one ICE3 coach fully on the approach at t = 0, a dip
// on the first span deep enough to lift the wheels at speed.
inline Scene small_viaduct_with_dip(double speed_kmh, double dip_depth_m) {
  Scene s;
  s.structure = make_bridge_2d(small_viaduct_options());
  s.train.name = "one coach";
  s.train.vehicles.push_back({make_car_2d(ice3_coach()), 0.0});
  s.speed_mps = speed_kmh / 3.6;
  s.irregularity = cosine_dip(4.0, 1.0, dip_depth_m);
  s.analysis.dt_s = 2.0e-4;
  s.analysis.contact.law = "hertz";
  return s;
}

// max |a - b| / max |b| over a set of histories.
inline double relative_history_difference(const std::vector<std::vector<double>>& a,
                                          const std::vector<std::vector<double>>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t k = 0; k < b[i].size(); ++k) {
      diff = railvsi::testing::worst_of(diff, std::abs(a[i][k] - b[i][k]));
      scale = railvsi::testing::worst_of(scale, std::abs(b[i][k]));
    }
  return scale > 0.0 ? diff / scale : diff;
}

}  // namespace railvsi::testing
