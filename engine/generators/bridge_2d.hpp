#pragma once
// Generator of plane bridge models: a deck of Euler-Bernoulli beams over one
// or more spans, optionally carrying a ballasted track (rail beam, pads,
// sleepers, ballast) that continues over approach embankments.
#include <memory>
#include <optional>
#include <vector>

#include "model/structure_model.hpp"

namespace railvsi {

// Defaults: Zhai et al. (2004), both rails lumped (reference/DATA.md).
struct TrackOptions {
  double rail_EI_Nm2 = 2.059e11 * 2.0 * 3.217e-5;
  double rail_mass_kg_per_m = 2.0 * 60.64;
  double pad_k_N_per_m = 6.5e7;       // per sleeper, both rails
  double pad_c_Ns_per_m = 7.5e4;
  double sleeper_spacing_m = 0.6;
  double sleeper_mass_kg = 2.0 * 125.5;
  double ballast_k_N_per_m = 137.75e6;  // per sleeper
  double ballast_c_Ns_per_m = 5.88e4;
  double ballast_mass_kg = 531.4;       // per sleeper, on the embankments only
  double subballast_k_N_per_m = 77.5e6;
  double subballast_c_Ns_per_m = 3.115e4;
  // Embankment track before and after the bridge. A train that starts with
  // all its wheels on the track starts from a true static equilibrium; a
  // wheel that rolls from the rigid path onto the anchored rail end gets a
  // transient instead (see default_start_x_m in simulation.hpp).
  double approach_m = 40.0;
  double exit_m = 40.0;
};

struct Bridge2dOptions {
  std::vector<double> spans_m;
  bool continuous = false;
  double deck_EI_Nm2 = 0.0;
  double deck_mass_kg_per_m = 0.0;
  double damping_ratio = 0.0;
  // Rayleigh damping matched at these two frequencies; 0 means default
  // (first bending frequency of the longest span, and max(30 Hz, f3)).
  double damping_f1_hz = 0.0;
  double damping_f2_hz = 0.0;
  double element_length_m = 0.5;  // target deck element length
  std::optional<double> bearing_k_N_per_m;  // vertical bearing spring; rigid if absent
  std::optional<TrackOptions> track;
  // Deck output points (name, x); the mesh gets a node at each. Midspans
  // are added as "span<i>_mid" when the list is empty.
  std::vector<std::pair<std::string, double>> output_points;
};

// Throws InputError (paths relative to /structure) on bad options.
std::shared_ptr<const StructureModel> make_bridge_2d(const Bridge2dOptions& options);

// First bending frequency of a simply supported Euler-Bernoulli span.
double simply_supported_frequency_hz(double span_m, double EI_Nm2, double mass_kg_per_m);

}  // namespace railvsi
