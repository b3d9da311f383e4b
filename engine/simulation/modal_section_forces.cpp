#include "simulation/modal_section_forces.hpp"

#include "core/input_error.hpp"

namespace railvsi {

ModalSectionForces::ModalSectionForces(const ModalBasis& basis, const std::vector<int>& rail_lines)
    : statics_(basis.structure(), rail_lines) {
  const SectionForms& f = statics_.forms();
  if (!f.available()) throw InputError("/structure", "no section forces: " + f.unavailable);
  for (double w : basis.omega_rad_s()) inverse_omega2_.push_back(1.0 / (w * w));
  const auto nf = static_cast<Eigen::Index>(f.forms.size());
  const auto n = static_cast<Eigen::Index>(basis.num_modes());
  on_u_ = on_v_ = on_a_ = DenseMatrix::Zero(nf, n);
  const auto add = [&](DenseMatrix& to, Eigen::Index row, const std::vector<std::pair<int, double>>& terms) {
    for (const auto& [dof, c] : terms) {
      const double* phi = basis.row(dof);
      for (Eigen::Index k = 0; k < n; ++k) to(row, k) += c * phi[k];
    }
  };
  for (Eigen::Index i = 0; i < nf; ++i) {
    const LinearForm& form = f.forms[static_cast<std::size_t>(i)];
    add(on_u_, i, form.u);
    add(on_v_, i, form.v);
    add(on_a_, i, form.a);
  }
}

std::size_t ModalSectionForces::memory_bytes() const {
  return sizeof(*this) + statics_.memory_bytes() +
         (inverse_omega2_.size() + 3 * static_cast<std::size_t>(on_u_.size())) * sizeof(double);
}

std::shared_ptr<const ModalSectionForces> modal_section_forces(const ModalBasis& basis,
                                                               const std::vector<int>& rail_lines) {
  if (!make_section_forms(basis.structure()).available()) return nullptr;
  return std::make_shared<const ModalSectionForces>(basis, rail_lines);
}

}  // namespace railvsi
