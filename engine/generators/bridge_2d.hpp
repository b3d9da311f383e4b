#pragma once
// Generator of plane bridge models: a deck of Euler-Bernoulli beams over one
// or more spans, optionally carrying a ballasted track (rail beam, pads,
// sleepers, ballast) that continues over approach embankments.
#include <memory>
#include <optional>
#include <vector>

#include "model/en1991_damping.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

// Defaults: Zhai, Wang & Lin (2004), J. Sound Vib. 270, 673-683,
// both rails lumped.
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
  // Bending stiffness: deck_EI_Nm2, or derived from the designer's first
  // frequency as EI = m (2 L^2 f1 / pi)^2 with L the longest span, i.e. f1
  // is the first bending frequency of the deck alone on rigid supports
  // (exact for simply supported spans and for a continuous girder of equal
  // spans). Give exactly one of the two (> 0). A continuous girder of
  // unequal spans needs EI: its first frequency is not its longest span's.
  double deck_EI_Nm2 = 0.0;
  double deck_first_frequency_hz = 0.0;
  double deck_mass_kg_per_m = 0.0;
  // Damping ratio of the deck; when damping_en1991 is set, the lower bound of
  // EN 1991-2 Table 6.6 for that bridge type instead, taken at the longest
  // span (the smallest ratio of all spans: the table decreases with L).
  double damping_ratio = 0.0;
  std::optional<En1991BridgeType> damping_en1991;
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
// Its inverse: the EI that gives a simply supported span this first frequency.
double simply_supported_EI_Nm2(double span_m, double frequency_hz, double mass_kg_per_m);

}  // namespace railvsi
