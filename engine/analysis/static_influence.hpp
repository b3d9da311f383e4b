#pragma once
// Static response of a structure to vertical loads on its rail lines, by
// Maxwell's reciprocity: one solve K g = e_k per output point k gives the
// deflection of that point under a unit load anywhere on the rails (the
// influence line, interpolated on each rail element with the same Hermite
// rows a wheel uses). A train's quasi-static envelope and the deflection
// under Load Model 71 then cost no further solve.
//
// Sign convention: loads act downward, deflections are reported downward
// positive (the magnitude a designer compares with a limit).
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/structure_model.hpp"
#include "model/train.hpp"
#include "simulation/section_influence.hpp"

namespace railvsi {

struct StaticEnvelope {
  double max_deflection_m = 0.0;   // max over train positions, downward positive
  double first_axle_x_m = 0.0;     // position of the first axle where it occurs
};

// EN 1991-2 6.3.2(2), Figure 6.1: four point loads Q_vk = 250 kN at 1.6 m
// and a distributed q_vk = 80 kN/m on either side, starting 0.8 m beyond
// the outer point loads, applied where unfavourable (6.3.2(3) allows the
// distributed load to be interrupted). Characteristic values, to be
// multiplied by the classification factor alpha (6.3.2(3)) by the caller.
struct LoadModel71 {
  double point_load_N = 250.0e3;
  double point_spacing_m = 1.6;
  int point_loads = 4;
  double distributed_N_per_m = 80.0e3;
  double clear_distance_m = 0.8;  // between the outer point loads and q_vk
};

struct LoadModel71Result {
  double max_deflection_m = 0.0;   // characteristic LM71, alpha = 1
  double first_point_load_x_m = 0.0;
};

// The quasi-static envelope of a train for the section quantities of a beam
// deck (simulation/section_forms.hpp): per output point the largest
// |bending moment| and |shear| (both sides of the section), per support the
// largest reaction and |end rotation|. `unavailable` says why there is none.
struct StaticSectionEnvelope {
  std::string unavailable;
  std::vector<std::optional<double>> max_abs_bending_moment_Nm;  // per output point
  std::vector<std::optional<double>> max_abs_shear_force_N;
  std::vector<double> max_reaction_N;  // per support
  std::vector<double> max_abs_rotation_rad;
};

class StaticInfluence {
 public:
  // Factorizes K once. Throws InputError if K is singular (a mechanism).
  // Loads on several rail lines are shared equally between them, as a
  // plane train on a deck with two rails is (ContactOptions::rail_lines).
  StaticInfluence(const StructureModel& structure, std::vector<int> rail_lines = {0});

  const StructureModel& structure() const { return structure_; }
  int num_points() const { return static_cast<int>(influence_.size()); }

  // Downward deflection of output point k under a unit downward load at x
  // (shared between the rail lines); 0 where x is off the modelled track.
  double unit_deflection(int k, double x_m) const;

  // The quasi-static envelope of a train of axle loads crossing the whole
  // structure: every first-axle position from the first axle entering the
  // rails to the last axle leaving them, sampled at an eighth of the
  // shortest rail element and refined by golden-section search around the
  // best sample.
  StaticEnvelope train_envelope(int k, const std::vector<MovingForce>& axles) const;

  // Section forces (beam decks): the forms and their influence lines
  // (simulation/section_influence.hpp), with the same factor of K.
  const SectionInfluence& sections() const { return *sections_; }
  const SectionForms& section_forms() const { return sections_->forms(); }
  double unit_form_value(int form, double x_m) const { return sections_->unit_form_value(form, x_m); }
  // Every first-axle position as train_envelope, plus each axle standing
  // exactly on each section and support (where point-load maxima of moment,
  // shear and reaction occur).
  StaticSectionEnvelope section_envelope(const std::vector<MovingForce>& axles) const;

  // LM71 placed where it is most unfavourable for the deflection of point k:
  // the point-load group anywhere on the rails, q_vk wherever the influence
  // line is downward except within the clear distance of the group.
  LoadModel71Result lm71(int k, const LoadModel71& lm = {}) const;
  // The same for section form f (its largest positive value: sagging moment,
  // positive shear, upward reaction), the distributed load wherever f's
  // influence line is positive. `max_deflection_m` then holds f's value.
  LoadModel71Result lm71_form(int form, const LoadModel71& lm = {}) const;

 private:
  // Integral of max(unit_deflection, 0) from the start of the rails to x.
  double positive_area_to(int k, double x_m) const;
  // The same for any influence line h with its cumulative grid area.
  double positive_area_to(const std::function<double(double)>& h, const std::vector<double>& area, double x_m) const;
  LoadModel71Result lm71_of(const std::function<double(double)>& h, const std::vector<double>& area,
                            const LoadModel71& lm) const;
  double rails_start_m() const;
  double rails_end_m() const;
  // Where the first of the rail lines starts and where the last one ends.
  std::pair<double, double> tracks_extent_m() const;

  const StructureModel& structure_;
  std::vector<int> rail_lines_;
  std::vector<Vector> influence_;  // K^-1 e_k per output point
  std::optional<SectionInfluence> sections_;  // set by the constructor
  // Cumulative positive area at the grid x (per output point).
  std::vector<double> grid_x_m_;
  std::vector<std::vector<double>> grid_area_;
  std::vector<std::vector<double>> grid_form_area_;  // per section form
};

}  // namespace railvsi
