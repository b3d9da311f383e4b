#include "solver/structure_operator.hpp"

#include <chrono>

#include "solver/substructured_flexibility.hpp"

namespace railvsi {

SparseMatrix effective_matrix(const StructureModel& model, const EffectiveMatrixFactors& f) {
  SparseMatrix A = f.stiffness * model.K();
  if (f.mass != 0.0) A += f.mass * model.M();
  if (f.damping != 0.0) A += f.damping * model.C();
  A.makeCompressed();
  return A;
}

Status StructureOperator::forward(const Vector& b, Vector& y, SolveWorkspace&) const {
  y = b;
  return Status::Ok();
}

Status StructureOperator::rail_solution(const Vector& y, Vector& x, SolveWorkspace& ws) const {
  return solve(y, x, ws);
}

void StructureOperator::add_rail_forward(const Vector& load, Vector& y, SolveWorkspace&) const { y += load; }

Status StructureOperator::backward(const Vector& y, Vector& x, SolveWorkspace& ws) const { return solve(y, x, ws); }

void StructureOperator::index_rail_dofs(const StructureModel& model) {
  rail_index_.assign(static_cast<std::size_t>(model.num_dofs()), -1);
  const auto& dofs = model.rail_dofs();
  for (std::size_t i = 0; i < dofs.size(); ++i) rail_index_[dofs[i]] = static_cast<int>(i);
}

void StructureOperator::compute_rail_flexibility(const StructureModel& model, const SparseMatrix* Kbar) {
  const auto start = std::chrono::steady_clock::now();
  index_rail_dofs(model);
  const auto& dofs = model.rail_dofs();
  auto ws = make_workspace();
  if (Kbar) {
    SubstructureSummary summary;
    rail_flexibility_ = substructured_flexibility(*this, *Kbar, model, dofs, *ws, &summary);
    flexibility_solves_ = summary.direct_columns;
  } else {
    rail_flexibility_ = flexibility_block(dofs, *ws);
    flexibility_solves_ = 0;
  }
  flexibility_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace railvsi
