#include "analysis/modal_basis.hpp"

#include <cmath>
#include <numbers>

#include "analysis/modal_analysis.hpp"
#include "core/input_error.hpp"

namespace railvsi {
namespace {

// The lowest modes, enough of them to pass max_frequency_hz: asked in
// growing batches until the highest one computed lies above it (or the
// model has no more).
ModalResult modes_up_to(const StructureModel& s, const ModalBasisOptions& o) {
  int asked = std::max(8, o.min_modes);
  for (;;) {
    ModalOptions mo;
    mo.modes = std::min(asked, s.num_dofs() - 1);
    ModalResult r = modal_analysis(s, mo);
    if (!r.status.ok()) throw InputError("/structure", "modal analysis: " + r.status.message());
    const bool enough = r.frequencies_hz.empty() || r.frequencies_hz.back() > o.max_frequency_hz;
    if (enough || mo.modes >= s.num_dofs() - 1) {
      int keep = 0;
      while (keep < static_cast<int>(r.frequencies_hz.size()) &&
             (r.frequencies_hz[static_cast<std::size_t>(keep)] <= o.max_frequency_hz || keep < o.min_modes))
        ++keep;
      r.frequencies_hz.resize(static_cast<std::size_t>(keep));
      r.shapes = r.shapes.leftCols(keep).eval();
      return r;
    }
    asked *= 2;
  }
}

}  // namespace

ModalBasis::ModalBasis(std::shared_ptr<const StructureModel> structure, const ModalBasisOptions& options)
    : structure_(std::move(structure)), max_frequency_hz_(options.max_frequency_hz) {
  if (!(options.max_frequency_hz > 0.0)) throw InputError("", "modal cut-off frequency must be > 0");
  const StructureModel& s = *structure_;
  const ModalResult modes = modes_up_to(s, options);
  const auto n = static_cast<Eigen::Index>(modes.frequencies_hz.size());
  const DenseMatrix& Phi = modes.shapes;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double w = 2.0 * std::numbers::pi * modes.frequencies_hz[static_cast<std::size_t>(k)];
    const Vector phi = Phi.col(k);
    omega_.push_back(w);
    zeta_.push_back(phi.dot(s.C() * phi) / (2.0 * w));
  }
  rail_row_.assign(static_cast<std::size_t>(s.num_dofs()), -1);
  const auto& rail = s.rail_dofs();
  rail_shapes_.resize(n, static_cast<Eigen::Index>(rail.size()));
  for (std::size_t i = 0; i < rail.size(); ++i) {
    rail_row_[static_cast<std::size_t>(rail[i])] = static_cast<int>(i);
    rail_shapes_.col(static_cast<Eigen::Index>(i)) = Phi.row(rail[i]).transpose();
  }
  zero_row_.assign(static_cast<std::size_t>(n), 0.0);
  at_outputs_.resize(static_cast<Eigen::Index>(s.outputs().size()), n);
  for (std::size_t i = 0; i < s.outputs().size(); ++i)
    at_outputs_.row(static_cast<Eigen::Index>(i)) = Phi.row(s.outputs()[i].dof);
  if (!s.info().deck_beam) return;  // no section forces
  statics_ = std::make_shared<const StaticInfluence>(s);
  const auto& forms = statics_->section_forms().forms;
  const auto nf = static_cast<Eigen::Index>(forms.size());
  forms_u_ = forms_v_ = forms_a_ = DenseMatrix::Zero(nf, n);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const LinearForm& form = forms[static_cast<std::size_t>(f)];
    for (const auto& [d, c] : form.u) forms_u_.row(f) += c * Phi.row(d);
    for (const auto& [d, c] : form.v) forms_v_.row(f) += c * Phi.row(d);
    for (const auto& [d, c] : form.a) forms_a_.row(f) += c * Phi.row(d);
  }
}

const double* ModalBasis::row(int dof) const {
  if (dof < 0) return zero_row_.data();
  const int r = rail_row_[static_cast<std::size_t>(dof)];
  return r < 0 ? zero_row_.data() : rail_shapes_.col(r).data();
}

}  // namespace railvsi
