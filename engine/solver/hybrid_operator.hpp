#pragma once
// Hybrid backend of the structure: the track in finite elements, the bridge
// in its modes (HybridBasis: constraint modes and bridge modes). The reduced model
// is sparse where the track is and dense only in the interface and modal
// blocks, and it is factorized like any finite-element model (one CHOLMOD
// factor of its K_bar, rail DOFs last where that pays): the condensed direct
// method, every contact law and the run monitor see an FE structure whose
// coordinates are [u_track; u_interface; q].
#include <memory>

#include "solver/cholmod_operator.hpp"
#include "solver/hybrid_basis.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

class HybridOperator final : public StructureOperator {
 public:
  // Throws InputError when the reduced K_bar is not positive definite.
  HybridOperator(std::shared_ptr<const HybridBasis> basis, const EffectiveMatrixFactors& factors,
                 const CholmodOperatorOptions& options = {});

  int num_dofs() const override { return reduced_->num_dofs(); }
  std::unique_ptr<SolveWorkspace> make_workspace() const override { return reduced_->make_workspace(); }
  Status solve(const Vector& b, Vector& x, SolveWorkspace& ws) const override { return reduced_->solve(b, x, ws); }
  // At model DOFs: a track or interface DOF is a coordinate, an interior
  // one the combination HybridBasis::row() gives.
  DenseMatrix inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                            SolveWorkspace& ws) const override;
  Status forward(const Vector& b, Vector& y, SolveWorkspace& ws) const override {
    return reduced_->forward(b, y, ws);
  }
  Status rail_solution(const Vector& y, Vector& x, SolveWorkspace& ws) const override {
    return reduced_->rail_solution(y, x, ws);
  }
  void add_rail_forward(const Vector& load, Vector& y, SolveWorkspace& ws) const override {
    reduced_->add_rail_forward(load, y, ws);
  }
  Status backward(const Vector& y, Vector& x, SolveWorkspace& ws) const override {
    return reduced_->backward(y, x, ws);
  }
  bool splits_at_rails() const override { return reduced_->splits_at_rails(); }
  std::string backend_name() const override;
  StructureCoordinates coordinates(const StructureModel& model) const override;
  std::shared_ptr<const StructureOperator> static_operator(const StructureModel& model) const override;
  std::size_t memory_bytes() const override { return reduced_->memory_bytes() + basis_->memory_bytes(); }
  double factor_nonzeros() const override { return reduced_->factor_nonzeros(); }
  const HybridBasis& basis() const { return *basis_; }
  std::shared_ptr<const HybridBasis> shared_basis() const { return basis_; }

 private:
  std::shared_ptr<const HybridBasis> basis_;
  std::shared_ptr<const CholmodOperator> reduced_;
  CholmodOperatorOptions options_;
};

}  // namespace railvsi
