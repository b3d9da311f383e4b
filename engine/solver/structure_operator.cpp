#include "solver/structure_operator.hpp"

#include <chrono>

#include "core/input_error.hpp"
#include "solver/substructured_flexibility.hpp"

namespace railvsi {

SparseMatrix effective_matrix(const StructureModel& model, const EffectiveMatrixFactors& f) {
  SparseMatrix A = f.stiffness * model.K();
  if (f.mass != 0.0) A += f.mass * model.M();
  if (f.damping != 0.0) A += f.damping * model.C();
  A.makeCompressed();
  return A;
}

DenseMatrix StructureOperator::inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                                             SolveWorkspace& ws) const {
  const auto m = static_cast<Eigen::Index>(rows.size());
  DenseMatrix F(m, static_cast<Eigen::Index>(cols.size()));
  Vector e = Vector::Zero(num_dofs()), x(num_dofs());
  for (Eigen::Index j = 0; j < F.cols(); ++j) {
    e[cols[j]] = 1.0;
    const Status st = solve(e, x, ws);
    if (!st.ok()) throw InputError("/structure", "rail flexibility: " + st.message());
    e[cols[j]] = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) F(i, j) = x[rows[i]];
  }
  return F;
}

void StructureOperator::compute_rail_flexibility(const StructureModel& model, const SparseMatrix& Kbar) {
  const auto start = std::chrono::steady_clock::now();
  rail_index_.assign(static_cast<std::size_t>(model.num_dofs()), -1);
  const auto& dofs = model.rail_dofs();
  for (std::size_t i = 0; i < dofs.size(); ++i) rail_index_[dofs[i]] = static_cast<int>(i);
  auto ws = make_workspace();
  SubstructureSummary summary;
  rail_flexibility_ = substructured_flexibility(*this, Kbar, model, dofs, *ws, &summary);
  flexibility_solves_ = summary.direct_columns;
  flexibility_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace railvsi
