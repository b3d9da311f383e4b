#include "solver/structure_operator.hpp"

#include <chrono>

#include "core/input_error.hpp"

namespace railvsi {

SparseMatrix effective_matrix(const StructureModel& model, const EffectiveMatrixFactors& f) {
  SparseMatrix A = f.stiffness * model.K();
  if (f.mass != 0.0) A += f.mass * model.M();
  if (f.damping != 0.0) A += f.damping * model.C();
  A.makeCompressed();
  return A;
}

DenseMatrix StructureOperator::flexibility_block(const std::vector<int>& dofs, SolveWorkspace& ws) const {
  const auto m = static_cast<Eigen::Index>(dofs.size());
  DenseMatrix F(m, m);
  Vector e = Vector::Zero(num_dofs()), x(num_dofs());
  for (Eigen::Index j = 0; j < m; ++j) {
    e[dofs[j]] = 1.0;
    const Status st = solve(e, x, ws);
    if (!st.ok()) throw InputError("/structure", "rail flexibility: " + st.message());
    e[dofs[j]] = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) F(i, j) = x[dofs[i]];
  }
  return F;
}

void StructureOperator::compute_rail_flexibility(const StructureModel& model) {
  const auto start = std::chrono::steady_clock::now();
  rail_index_.assign(static_cast<std::size_t>(model.num_dofs()), -1);
  const auto& dofs = model.rail_dofs();
  for (std::size_t i = 0; i < dofs.size(); ++i) rail_index_[dofs[i]] = static_cast<int>(i);
  auto ws = make_workspace();
  rail_flexibility_ = flexibility_block(dofs, *ws);
  flexibility_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace railvsi
