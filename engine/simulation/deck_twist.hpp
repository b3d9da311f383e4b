#pragma once
// Deck twist (EN 1990 A2.4.4.2.2): the cross level of a track is the
// difference of the vertical displacements of its two rails,
// c(x) = w_a(x) - w_b(x), and the twist over a base of 3 m is
// t(x) = c(x + 3 m) - c(x). The gauge samples t at start points x spread
// evenly over the deck [bridge start, bridge end - 3 m], at most
// `spacing_m` apart, each value a linear form of the structure's rail DOFs
// (the rails' cubic Hermite interpolation, RailLine::locate), so both the
// finite-element and the modal coordinates evaluate the same thing.
//
// The cross level is taken between the two modelled rail lines, i.e. over
// their lateral distance (rail centres, 1.5 m in deck-3d), not scaled to
// the 1.435 m gauge: the value is the larger of the two (by 1.5/1.435 for
// deck-3d), so the check errs on the safe side.
//
// Which two rails: the two of analysis.contact.rail_lines when it names
// two, else rail lines 0 and 1 of a structure that has exactly two. A
// plane model (one rail line) has no cross level: no gauge, with the
// reason, never a twist of 0.
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "model/structure_model.hpp"
#include "solver/structure_coordinates.hpp"

namespace railvsi {

inline constexpr double kTwistBase_m = 3.0;  // EN 1990 A2.4.4.2.2: twist over 3 m

struct DeckTwistGauge {
  std::string unavailable;  // why there is no twist ("" when there is)
  int rail_a = -1, rail_b = -1;
  double base_m = kTwistBase_m;
  std::vector<double> x_m;  // start of each sampled base
  std::vector<int> dofs;    // the distinct model DOFs the forms read
  // Per sample: t = sum of coefficient x u[dofs[index]].
  std::vector<std::vector<std::pair<int, double>>> forms;
  bool available() const { return unavailable.empty(); }
};

DeckTwistGauge make_deck_twist_gauge(const StructureModel& structure, const std::vector<int>& contact_rail_lines,
                                     double base_m = kTwistBase_m, double spacing_m = 0.25);

// The values of the gauge's DOFs in the state u (coordinates `coords`),
// into dof_values, and the twist t of sample k from them (m over the base).
void read_twist_dofs(const DeckTwistGauge& gauge, const Vector& u, const StructureCoordinates& coords,
                     std::vector<double>& dof_values);
double twist_m(const DeckTwistGauge& gauge, std::size_t sample, const std::vector<double>& dof_values);

// Largest |t| over the samples of the displacement state u (coordinates
// `coords`), in m over the base; `at` gets the sample's start x.
// `scratch` holds the DOF values between calls (no allocation per step).
double max_abs_twist_m(const DeckTwistGauge& gauge, const Vector& u, const StructureCoordinates& coords,
                       std::vector<double>& scratch, double* at_x_m = nullptr);

}  // namespace railvsi
