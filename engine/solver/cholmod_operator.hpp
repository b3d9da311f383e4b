#pragma once
// Full finite-element backend: one supernodal CHOLMOD factor of K_bar,
// computed once and reused for every step of every run with the same
// (structure, dt, HHT parameters).
#include <memory>

#include "solver/cholmod_handles.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

struct CholmodOperatorOptions {
  bool rail_flexibility = true;
  int flexibility_block_columns = 64;  // right-hand sides per blocked solve
  // Order the rail DOFs last in the factor, so that a step costs one solve
  // (rail_suffix.hpp), when that adds at most this fraction of nonzeros to
  // CHOLMOD's own ordering; 0 keeps CHOLMOD's ordering. Only with
  // rail_flexibility (an operator for time steps).
  double rails_last_max_fill_growth = 0.10;
};

class CholmodOperator final : public StructureOperator {
 public:
  // Throws InputError naming the first DOF whose pivot is not positive
  // (a mechanism, or an indefinite matrix). With `analysis_of` (an operator
  // of the same model whose matrix pattern contains this one's, e.g. K_bar
  // for the static K), its ordering and symbolic analysis are reused.
  CholmodOperator(const StructureModel& model, const EffectiveMatrixFactors& factors,
                  const CholmodOperatorOptions& options = {}, const CholmodOperator* analysis_of = nullptr);

  int num_dofs() const override { return n_; }
  std::unique_ptr<SolveWorkspace> make_workspace() const override;
  Status solve(const Vector& b, Vector& x, SolveWorkspace& ws) const override;
  DenseMatrix inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                            SolveWorkspace& ws) const override;
  Status forward(const Vector& b, Vector& y, SolveWorkspace& ws) const override;
  Status rail_solution(const Vector& y, Vector& x, SolveWorkspace& ws) const override;
  void add_rail_forward(const Vector& load, Vector& y, SolveWorkspace& ws) const override;
  Status backward(const Vector& y, Vector& x, SolveWorkspace& ws) const override;
  bool splits_at_rails() const override { return suffix_start_ >= 0; }
  // First column of the factor's suffix that holds the rail DOFs, -1 when
  // they are not ordered last (rail_suffix.hpp).
  int suffix_start() const { return suffix_start_; }
  // Whether CHOLMOD chose a supernodal (LL') or a simplicial (LDL') factor.
  bool supernodal() const { return factor_->is_super != 0; }
  std::string backend_name() const override { return "cholmod"; }
  StructureCoordinates coordinates(const StructureModel& model) const override {
    return StructureCoordinates(model);
  }
  std::shared_ptr<const StructureOperator> static_operator(const StructureModel& model) const override;
  std::size_t memory_bytes() const override;
  // Nonzeros of the factor, for benchmarks.
  double factor_nonzeros() const override;
  // Part of factorization_s() spent in the ordering and symbolic analysis
  // (or in copying the lent analysis).
  double analysis_s() const { return analysis_s_; }

 private:
  void rail_flexibility_from_suffix(const StructureModel& model);
  int n_ = 0;
  int block_columns_ = 64;
  double analysis_s_ = 0.0;
  int suffix_start_ = -1;
  const StructureModel* model_ = nullptr;  // identity only (never dereferenced)
  // The factor's own common is used for factorization and freeing only.
  std::unique_ptr<CholmodCommon> common_;
  std::unique_ptr<cholmod_factor, CholmodFactorDeleter> factor_;
};

}  // namespace railvsi
