#include "solver/modal_basis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/input_error.hpp"
#include "solver/cholmod_operator.hpp"
#include "solver/residual_flexibility.hpp"

namespace railvsi {
namespace {

// Every mode up to max_frequency_hz (a Sturm count certifies the count),
// at least min_modes.
ModalResult modes_up_to(const StructureModel& s, const ModalBasisOptions& o) {
  ModalOptions mo;
  mo.modes = o.min_modes;
  mo.max_frequency_hz = o.max_frequency_hz;
  ModalResult r = modal_analysis(s, mo);
  if (!r.status.ok()) throw InputError("/structure", "modal analysis: " + r.status.message());
  return r;
}

}  // namespace

ModalBasis::ModalBasis(std::shared_ptr<const StructureModel> structure, const ModalBasisOptions& options)
    : structure_(std::move(structure)), max_frequency_hz_(options.max_frequency_hz) {
  if (!(options.max_frequency_hz > 0.0)) throw InputError("", "modal cut-off frequency must be > 0");
  set_modes(modes_up_to(*structure_, options));
}

ModalBasis::ModalBasis(std::shared_ptr<const StructureModel> structure, const ModalResult& modes)
    : structure_(std::move(structure)),
      max_frequency_hz_(modes.frequencies_hz.empty() ? 0.0 : modes.frequencies_hz.back()) {
  set_modes(modes);
}

void ModalBasis::set_modes(const ModalResult& modes) {
  const StructureModel& s = *structure_;
  const auto n = static_cast<Eigen::Index>(modes.frequencies_hz.size());
  const DenseMatrix& Phi = modes.shapes;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double w = 2.0 * std::numbers::pi * modes.frequencies_hz[static_cast<std::size_t>(k)];
    const Vector phi = Phi.col(k);
    omega_.push_back(w);
    zeta_.push_back(phi.dot(s.C() * phi) / (2.0 * w));
  }
  rail_row_.assign(static_cast<std::size_t>(s.num_dofs()), -1);
  std::vector<int> kept = s.rail_dofs();
  for (const OutputPoint& o : s.outputs())
    if (o.dof >= 0 && std::find(kept.begin(), kept.end(), o.dof) == kept.end()) kept.push_back(o.dof);
  if (s.info().deck_beam) {
    // A beam deck's section forces read the end DOFs of its elements and
    // supports: keep every row (such a model has a few thousand DOFs).
    std::vector<char> is_kept(static_cast<std::size_t>(s.num_dofs()), 0);
    for (int d : kept) is_kept[static_cast<std::size_t>(d)] = 1;
    for (int d = 0; d < s.num_dofs(); ++d)
      if (!is_kept[static_cast<std::size_t>(d)]) kept.push_back(d);
  }
  rail_shapes_.resize(n, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t i = 0; i < kept.size(); ++i) {
    rail_row_[static_cast<std::size_t>(kept[i])] = static_cast<int>(i);
    rail_shapes_.col(static_cast<Eigen::Index>(i)) = Phi.row(kept[i]).transpose();
  }
  zero_row_.assign(static_cast<std::size_t>(n), 0.0);
  at_outputs_.resize(static_cast<Eigen::Index>(s.outputs().size()), n);
  for (std::size_t i = 0; i < s.outputs().size(); ++i)
    at_outputs_.row(static_cast<Eigen::Index>(i)) = Phi.row(s.outputs()[i].dof);
}

const double* ModalBasis::row(int dof) const {
  if (dof < 0) return zero_row_.data();
  const int r = rail_row_[static_cast<std::size_t>(dof)];
  return r < 0 ? zero_row_.data() : rail_shapes_.col(r).data();
}

const DenseMatrix& ModalBasis::rail_residual_flexibility() const {
  std::call_once(residual_once_, [this] {
    const auto nr = static_cast<Eigen::Index>(structure_->rail_dofs().size());
    // The rail DOFs are the first columns of the kept rows.
    residual_ = residual_flexibility(static_rail_flexibility(*structure_), rail_shapes_.leftCols(nr), omega_);
  });
  return residual_;
}

const DenseMatrix& ModalBasis::output_residual_flexibility() const {
  std::call_once(output_residual_once_, [this] {
    const StructureModel& s = *structure_;
    std::vector<int> outputs;
    for (const OutputPoint& o : s.outputs()) outputs.push_back(o.dof);
    output_residual_ = DenseMatrix::Zero(static_cast<Eigen::Index>(outputs.size()),
                                         static_cast<Eigen::Index>(s.rail_dofs().size()));
    if (outputs.empty() || s.rail_dofs().empty()) return;
    // K is symmetric: one solve per output point gives its row at every rail DOF.
    CholmodOperatorOptions no_rail_flexibility;
    no_rail_flexibility.rail_flexibility = false;
    const CholmodOperator K(s, EffectiveMatrixFactors{0.0, 0.0, 1.0}, no_rail_flexibility);
    const auto ws = K.make_workspace();
    const DenseMatrix F = K.inverse_block(s.rail_dofs(), outputs, *ws).transpose();
    // The rail DOFs are the first columns of the kept rows.
    const auto nr = static_cast<Eigen::Index>(s.rail_dofs().size());
    output_residual_ = residual_flexibility(F, at_outputs_.transpose(), rail_shapes_.leftCols(nr), omega_);
  });
  return output_residual_;
}

std::size_t ModalBasis::memory_bytes() const {
  const auto doubles = omega_.size() + zeta_.size() + zero_row_.size() +
                       static_cast<std::size_t>(rail_shapes_.size() + at_outputs_.size());
  return sizeof(*this) + doubles * sizeof(double) + rail_row_.size() * sizeof(int);
}

}  // namespace railvsi
