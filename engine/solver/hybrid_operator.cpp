#include "solver/hybrid_operator.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {

HybridOperator::HybridOperator(std::shared_ptr<const HybridBasis> basis, const EffectiveMatrixFactors& factors,
                               const CholmodOperatorOptions& options)
    : basis_(std::move(basis)),
      reduced_(std::make_shared<const CholmodOperator>(basis_->reduced(), factors, options)),
      options_(options) {
  factors_ = factors;
  model_dofs_ = basis_->structure().num_dofs();
  factorization_s_ = reduced_->factorization_s();
  flexibility_s_ = reduced_->flexibility_s();
  flexibility_solves_ = reduced_->flexibility_solves();
  if (options.rail_flexibility) {
    // The rails are track DOFs, numbered in the same order in the reduced
    // model: its rail flexibility is the structure's.
    index_rail_dofs(basis_->structure());
    rail_flexibility_ = reduced_->rail_flexibility();
  }
}

DenseMatrix HybridOperator::inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                                          SolveWorkspace& ws) const {
  const HybridBasis& b = *basis_;
  const auto direct = [&](const std::vector<int>& dofs) {
    return std::all_of(dofs.begin(), dofs.end(), [&](int d) { return b.index(d) >= 0; });
  };
  const auto mapped = [&](const std::vector<int>& dofs) {
    std::vector<int> out;
    for (int d : dofs) out.push_back(b.index(d));
    return out;
  };
  if (direct(rows) && direct(cols)) return reduced_->inverse_block(mapped(rows), mapped(cols), ws);
  // A model DOF as a vector of the reduced coordinates: x(dof) = e' x.
  const int n = num_dofs(), g0 = b.track_dofs(), ng = b.interface_dofs() + b.num_modes();
  const auto selector = [&](int dof) {
    Vector e = Vector::Zero(n);
    if (const int i = b.index(dof); i >= 0) e[i] = 1.0;
    else if (const double* r = b.row(dof)) e.segment(g0, ng) = Eigen::Map<const Vector>(r, ng);
    else
      throw InputError("/structure",
                       fmt::format("DOF {} is inside the bridge and not kept by the hybrid structure", dof));
    return e;
  };
  DenseMatrix E(n, static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) E.col(static_cast<Eigen::Index>(i)) = selector(rows[i]);
  DenseMatrix F(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  Vector x;
  for (std::size_t j = 0; j < cols.size(); ++j) {
    const Status st = reduced_->solve(selector(cols[j]), x, ws);
    if (!st.ok()) throw InputError("/structure", st.message());
    F.col(static_cast<Eigen::Index>(j)) = E.transpose() * x;
  }
  return F;
}

std::string HybridOperator::backend_name() const {
  return fmt::format("hybrid (track in FE: {} DOFs; bridge: {} {}modes up to {:.4g} Hz and {} interface DOFs)",
                     basis_->track_dofs(), basis_->num_modes(), basis_->modes_label(), basis_->cutoff_hz(),
                     basis_->interface_dofs());
}

StructureCoordinates HybridOperator::coordinates(const StructureModel& model) const {
  if (model.num_dofs() != model_dofs_)
    throw InputError("/structure", fmt::format("the hybrid structure was built for {} DOFs, this one has {}",
                                               model_dofs_, model.num_dofs()));
  return StructureCoordinates(basis_);
}

std::shared_ptr<const StructureOperator> HybridOperator::static_operator(const StructureModel&) const {
  CholmodOperatorOptions statics = options_;
  statics.rail_flexibility = false;
  return std::make_shared<const HybridOperator>(basis_, EffectiveMatrixFactors{0.0, 0.0, 1.0}, statics);
}

}  // namespace railvsi
