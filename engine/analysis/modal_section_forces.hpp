#pragma once
// Section forces of a beam deck on the exact modal rung, by the
// mode-acceleration method: the exact static value of each section form
// under the loads at t (its influence line, StaticInfluence), plus the
// modes' dynamic part, the form applied to Phi (q - p/omega^2) on u, to
// Phi q' on v and Phi q'' on a. Superposing the modes on u alone would miss
// the static share of the modes above the cut-off: about 10 % of the
// midspan moment of a point load with three modes kept (Cornwell, Craig &
// Johnson, Earthquake Eng. Struct. Dyn. 11, 1983, on the method).
// Built once per structure and rail lines, immutable.
#include <memory>
#include <vector>

#include "analysis/static_influence.hpp"
#include "core/types.hpp"
#include "solver/modal_basis.hpp"

namespace railvsi {

class ModalSectionForces {
 public:
  // The basis must be of a beam deck (StructureInfo::deck_beam) whose rows
  // it keeps for every DOF. Throws InputError when the forms are unavailable
  // or K is singular.
  ModalSectionForces(const ModalBasis& basis, const std::vector<int>& rail_lines);

  const SectionForms& forms() const { return statics_.section_forms(); }
  const StaticInfluence& statics() const { return statics_; }
  int num_forms() const { return static_cast<int>(forms().forms.size()); }
  // Each form applied to the modes: rows = forms, columns = modes.
  const DenseMatrix& on_u() const { return on_u_; }
  const DenseMatrix& on_v() const { return on_v_; }
  const DenseMatrix& on_a() const { return on_a_; }
  // The influence vectors (one per output point and per form, the size of
  // the model) and the matrices; the factor of K is not kept.
  std::size_t memory_bytes() const;

 private:
  StaticInfluence statics_;
  DenseMatrix on_u_, on_v_, on_a_;
};

}  // namespace railvsi
