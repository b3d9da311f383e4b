#pragma once
// Static influence lines of the section forms of a beam deck
// (section_forms.hpp), by Maxwell's reciprocity: one solve K g_f = c_f per
// form f gives its value under a downward unit load anywhere on the rails,
// -N g_f (N: the load's Hermite row on its rail line), plus the load's own
// term when it stands on the deck line itself. The quasi-static section
// forces of any set of rail loads then cost no further solve: the static
// part of the mode-acceleration method on both modal rungs, and the static
// envelopes of analysis/static_influence.
// Immutable once built; the model is referenced and must outlive it.
#include <vector>

#include "model/structure_model.hpp"
#include "simulation/section_forms.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

class SectionInfluence {
 public:
  // Solves with `static_K`, an FE operator of K (factors 0, 0, 1) of the
  // same model. Loads given on several rail lines are shared equally
  // between them (unit_form_value(form, x)). No forms when the deck is not
  // a beam (forms().unavailable says why). Throws InputError when a rail
  // line does not exist or a solve fails.
  SectionInfluence(const StructureModel& structure, std::vector<int> rail_lines, const StructureOperator& static_K);
  // The same with its own factorization of K.
  SectionInfluence(const StructureModel& structure, std::vector<int> rail_lines);

  const SectionForms& forms() const { return forms_; }
  const StructureModel& structure() const { return structure_; }
  // Value of form f under a downward unit load at x standing on rail line
  // r alone; 0 where x is off that rail line.
  double unit_form_value(int form, int rail, double x_m) const;
  // The same for a unit load shared between the rail lines.
  double unit_form_value(int form, double x_m) const;
  // Adds scale x unit_form_value(f, rail, x) to values[f] for every form.
  void add_form_values(int rail, double x_m, double scale, std::vector<double>& values) const;
  // The influence vectors K^-1 c_f, one per form, of the model's size.
  std::size_t memory_bytes() const;

 private:
  double form_value_at(std::size_t form, const RailContactRow& row, const DeckPoint& on_deck) const;
  DeckPoint on_deck(int rail, double x_m) const;

  const StructureModel& structure_;
  std::vector<int> rail_lines_;
  SectionForms forms_;
  std::vector<Vector> form_influence_;  // K^-1 c_f per form
};

}  // namespace railvsi
