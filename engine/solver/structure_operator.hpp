#pragma once
// What a time step needs from the structure for one time step size: apply
// K_bar^-1, and the rail flexibility block. Immutable once built and shared
// between threads; each thread brings its own SolveWorkspace.
#include <memory>
#include <string>
#include <vector>

#include "core/status.hpp"
#include "core/types.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

// Coefficients of the effective matrix mass*M + damping*C + stiffness*K.
struct EffectiveMatrixFactors {
  double mass = 0.0;
  double damping = 0.0;
  double stiffness = 1.0;  // (0, 0, 1) is the static stiffness
};

class SolveWorkspace {
 public:
  virtual ~SolveWorkspace() = default;
};

class StructureOperator {
 public:
  virtual ~StructureOperator() = default;
  virtual int num_dofs() const = 0;
  virtual std::unique_ptr<SolveWorkspace> make_workspace() const = 0;
  // x = K_bar^-1 b. x may not alias b.
  virtual Status solve(const Vector& b, Vector& x, SolveWorkspace& ws) const = 0;
  // K_bar^-1(rows, cols): the columns of K_bar^-1 for the DOFs `cols`,
  // restricted to the DOFs `rows` (one solve per column, blocked where the
  // backend can).
  virtual DenseMatrix inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                                    SolveWorkspace& ws) const;
  // Columns of K_bar^-1 for the given DOFs, restricted to the same DOFs.
  DenseMatrix flexibility_block(const std::vector<int>& dofs, SolveWorkspace& ws) const {
    return inverse_block(dofs, dofs, ws);
  }

  // Rail flexibility (K_bar^-1 at the rail DOFs of the model), computed once
  // when the operator is built with rail flexibility requested.
  const DenseMatrix& rail_flexibility() const { return rail_flexibility_; }
  // Index of a structure DOF in rail_flexibility(), -1 if not a rail DOF.
  int rail_index(int dof) const { return rail_index_[static_cast<std::size_t>(dof)]; }
  const EffectiveMatrixFactors& factors() const { return factors_; }
  // Statistics of the build, for benchmarks and the run summary.
  double factorization_s() const { return factorization_s_; }
  double flexibility_s() const { return flexibility_s_; }
  // Columns of the rail flexibility solved with the whole structure (the
  // rest come from the track substructure, substructured_flexibility.hpp).
  int flexibility_solves() const { return flexibility_solves_; }
  virtual std::string backend_name() const = 0;
  // Nonzeros read by one solve pass (the factor's), a cost measure.
  virtual double factor_nonzeros() const { return static_cast<double>(num_dofs()); }

 protected:
  // Kbar: the matrix the operator inverts (for the track substructure).
  void compute_rail_flexibility(const StructureModel& model, const SparseMatrix& Kbar);
  EffectiveMatrixFactors factors_;
  DenseMatrix rail_flexibility_;
  std::vector<int> rail_index_;
  double factorization_s_ = 0.0;
  double flexibility_s_ = 0.0;
  int flexibility_solves_ = 0;
};

// K_bar = f.mass*M + f.damping*C + f.stiffness*K of the model.
SparseMatrix effective_matrix(const StructureModel& model, const EffectiveMatrixFactors& f);

}  // namespace railvsi
