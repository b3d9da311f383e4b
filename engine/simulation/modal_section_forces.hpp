#pragma once
// Section forces of a beam deck on the modal rungs (the exact moving-force
// sweep and the modal interaction rung), by the mode-acceleration method:
// the exact static value of each section form under the loads at t (its
// influence line, SectionInfluence), plus the modes' dynamic part, the form
// applied to Phi (q - p/omega^2) on u, to Phi q' on v and Phi q'' on a
// (p = Phi^T f: the modal loads of the same loads). Superposing the modes
// on u alone would miss the static share of the modes above the cut-off:
// about 10 % of the midspan moment of a point load with three modes kept
// (Cornwell, Craig & Johnson, Earthquake Eng. Struct. Dyn. 11, 1983, on
// the method).
// Built once per structure and rail lines, immutable.
#include <memory>
#include <vector>

#include "core/types.hpp"
#include "simulation/section_influence.hpp"
#include "solver/modal_basis.hpp"

namespace railvsi {

class ModalSectionForces {
 public:
  // The basis must be of a beam deck (StructureInfo::deck_beam) whose rows
  // it keeps for every DOF. Throws InputError when the forms are unavailable
  // or K is singular.
  ModalSectionForces(const ModalBasis& basis, const std::vector<int>& rail_lines);

  const SectionForms& forms() const { return statics_.forms(); }
  const SectionInfluence& statics() const { return statics_; }
  int num_forms() const { return static_cast<int>(forms().forms.size()); }
  int num_modes() const { return static_cast<int>(inverse_omega2_.size()); }
  // Each form applied to the modes: rows = forms, columns = modes.
  const DenseMatrix& on_u() const { return on_u_; }
  const DenseMatrix& on_v() const { return on_v_; }
  const DenseMatrix& on_a() const { return on_a_; }
  // values[f] (num_forms, in: the static value of form f under the loads,
  // from statics()) += the modes' dynamic part of the state q, qd, qdd
  // under the modal loads p of the same loads (num_modes each).
  void add_dynamic_part(const double* q, const double* qd, const double* qdd, const double* p,
                        double* values) const {
    add_dynamic_part_of<double>(q, qd, qdd, p, values);
  }
  // The same for T a double or a vector of doubles (GCC's vector
  // extension: several runs side by side, each with the arithmetic of one).
  template <class T>
  [[gnu::always_inline]] void add_dynamic_part_of(const T* q, const T* qd, const T* qdd, const T* p, T* values) const {
    const auto n = inverse_omega2_.size();
    const auto nf = static_cast<std::size_t>(num_forms());
    const double* on_u = on_u_.data();  // column-major: nf x n
    const double* on_v = on_v_.data();
    const double* on_a = on_a_.data();
    for (std::size_t k = 0; k < n; ++k) {
      // The mode's dynamic part on u: q - p / omega^2.
      const T du = q[k] - p[k] * inverse_omega2_[k], v = qd[k], a = qdd[k];
      const std::size_t col = k * nf;
      for (std::size_t f = 0; f < nf; ++f) values[f] += on_u[col + f] * du + on_v[col + f] * v + on_a[col + f] * a;
    }
  }
  // The influence vectors (one per form, the size of the model) and the
  // matrices; the factor of K is not kept.
  std::size_t memory_bytes() const;

 private:
  SectionInfluence statics_;
  std::vector<double> inverse_omega2_;
  DenseMatrix on_u_, on_v_, on_a_;
};

// The section forces of the basis's structure on these rail lines, null
// when it has none (not a beam deck): why is then in the run's
// section_forces_note.
std::shared_ptr<const ModalSectionForces> modal_section_forces(const ModalBasis& basis,
                                                               const std::vector<int>& rail_lines);

}  // namespace railvsi
