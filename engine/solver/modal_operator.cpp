#include "solver/modal_operator.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "core/input_error.hpp"

namespace railvsi {

ModalOperator::ModalOperator(std::shared_ptr<const ModalBasis> basis, const EffectiveMatrixFactors& factors,
                             const ModalOperatorOptions& options)
    : basis_(std::move(basis)) {
  factors_ = factors;
  const StructureModel& model = basis_->structure();
  model_dofs_ = model.num_dofs();
  const auto start = std::chrono::steady_clock::now();
  const int n = basis_->num_modes();
  d_.resize(n);
  for (int k = 0; k < n; ++k) {
    const double w = basis_->omega_rad_s()[static_cast<std::size_t>(k)];
    const double kbar = factors.mass + factors.damping * 2.0 * basis_->zeta()[static_cast<std::size_t>(k)] * w +
                        factors.stiffness * w * w;
    if (!(kbar > 0.0) || !std::isfinite(kbar))
      throw InputError("/structure", fmt::format("mode {} ({:.4g} Hz) has no positive effective stiffness: the "
                                                 "structure is a mechanism",
                                                 k + 1, w / (2.0 * std::numbers::pi)));
    d_[k] = 1.0 / kbar;
  }
  factorization_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.rail_flexibility) compute_rail_flexibility(model);
  if (options.static_correction) {
    const auto t0 = std::chrono::steady_clock::now();
    index_rail_dofs(model);
    residual_ = &basis_->rail_residual_flexibility();
    flexibility_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
}

Status ModalOperator::solve(const Vector& b, Vector& x, SolveWorkspace&) const {
  x = d_.cwiseProduct(b);
  return Status::Ok();
}

DenseMatrix ModalOperator::inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                                         SolveWorkspace&) const {
  // Phi_rows D Phi_cols^T, Phi_d the rows of the modes at the DOFs d.
  const auto modes_at = [&](const std::vector<int>& dofs) {
    DenseMatrix R(basis_->num_modes(), static_cast<Eigen::Index>(dofs.size()));
    for (std::size_t j = 0; j < dofs.size(); ++j)
      R.col(static_cast<Eigen::Index>(j)) = Eigen::Map<const Vector>(basis_->row(dofs[j]), basis_->num_modes());
    return R;
  };
  const DenseMatrix R = modes_at(rows);
  if (rows == cols) return R.transpose() * d_.asDiagonal() * R;
  return R.transpose() * d_.asDiagonal() * modes_at(cols);
}

std::string ModalOperator::backend_name() const {
  const auto& w = basis_->omega_rad_s();
  return fmt::format("modal ({} modes up to {:.4g} Hz, HHT{})", basis_->num_modes(),
                     w.empty() ? 0.0 : w.back() / (2.0 * std::numbers::pi),
                     residual_ ? ", static correction" : "");
}

StructureCoordinates ModalOperator::coordinates(const StructureModel& model) const {
  if (model.num_dofs() != model_dofs_)
    throw InputError("/structure", fmt::format("the modes are of a structure with {} DOFs, this one has {}",
                                               model_dofs_, model.num_dofs()));
  return StructureCoordinates(basis_);
}

std::shared_ptr<const StructureOperator> ModalOperator::static_operator(const StructureModel&) const {
  return std::make_shared<const ModalOperator>(basis_, EffectiveMatrixFactors{0.0, 0.0, 1.0},
                                               ModalOperatorOptions{false, residual_ != nullptr});
}

std::size_t ModalOperator::memory_bytes() const {
  const Eigen::Index residual = residual_ ? residual_->size() : 0;
  return static_cast<std::size_t>(basis_->kept_rows().size() + rail_flexibility_.size() + d_.size() + residual) *
         sizeof(double);
}

}  // namespace railvsi
