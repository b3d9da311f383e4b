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
#include "solver/structure_coordinates.hpp"

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
  // Length of the vectors solve() takes: the structure's state in the
  // backend's coordinates (DOFs, or modes).
  virtual int num_dofs() const = 0;
  // DOFs of the structure model the operator was built for.
  int model_dofs() const { return model_dofs_; }
  // The coordinates of solve()'s vectors for `model` (the model this
  // operator was built for, or one with the same matrices: cached operators
  // outlive the model instance they were built from, so nothing of it is
  // kept).
  virtual StructureCoordinates coordinates(const StructureModel& model) const = 0;
  // The static stiffness operator (factors 0, 0, 1, no rail flexibility) of
  // the same backend and structure: a new factorization of K (FE), the same
  // modes (modal). Throws InputError as the constructors do.
  virtual std::shared_ptr<const StructureOperator> static_operator(const StructureModel& model) const = 0;
  // Memory held (factor or modes, and the rail flexibility), for caches.
  virtual std::size_t memory_bytes() const = 0;
  virtual std::unique_ptr<SolveWorkspace> make_workspace() const = 0;
  // x = K_bar^-1 b. x may not alias b.
  virtual Status solve(const Vector& b, Vector& x, SolveWorkspace& ws) const = 0;
  // K_bar^-1(rows, cols) at model DOFs (physical, whatever the coordinates):
  // the columns of K_bar^-1 for the DOFs `cols`, restricted to the DOFs
  // `rows` (blocked solves on the FE backend, Phi D Phi^T on the modal one).
  virtual DenseMatrix inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                                    SolveWorkspace& ws) const = 0;
  // The solve in two halves around the contact problem: y = forward(b),
  // then backward(y) = K_bar^-1 b. In between, rail_solution(y) writes the
  // rows of K_bar^-1 b at the rail DOFs into x (other rows are left
  // undefined), and add_rail_forward(load, y) makes y the forward image of
  // b + load for a load on the rail DOFs only. These defaults cost two
  // solves; the FE backend with the rail DOFs last in its factor does it
  // in one (rail_suffix.hpp, splits_at_rails()).
  virtual Status forward(const Vector& b, Vector& y, SolveWorkspace& ws) const;
  virtual Status rail_solution(const Vector& y, Vector& x, SolveWorkspace& ws) const;
  virtual void add_rail_forward(const Vector& load, Vector& y, SolveWorkspace& ws) const;
  virtual Status backward(const Vector& y, Vector& x, SolveWorkspace& ws) const;
  // Whether forward + backward is one solve, and rail_solution and
  // add_rail_forward work on the rail DOFs alone.
  virtual bool splits_at_rails() const { return false; }

  // Columns of K_bar^-1 for the given model DOFs, restricted to the same DOFs.
  DenseMatrix flexibility_block(const std::vector<int>& dofs, SolveWorkspace& ws) const {
    return inverse_block(dofs, dofs, ws);
  }

  // Rail flexibility (K_bar^-1 at the rail DOFs of the model), computed once
  // when the operator is built with rail flexibility requested.
  const DenseMatrix& rail_flexibility() const { return rail_flexibility_; }
  // The static flexibility at the rail DOFs (rail_flexibility()'s order)
  // that the operator's coordinates leave out, or null when they leave
  // none out (FE) or it is not wanted: the modal backend's dropped modes
  // (residual_flexibility.hpp). The rail displacement is the coordinates'
  // part plus this times the load on the rail DOFs at the same instant: a
  // quasi-static part, without velocity or acceleration of its own and
  // independent of dt (no 1 + alpha: K_bar's HHT shift is the kept modes').
  virtual const DenseMatrix* rail_residual_flexibility() const { return nullptr; }
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
  // Kbar: the matrix the operator inverts, for the track substructure
  // (substructured_flexibility.hpp); null: flexibility_block of all rail DOFs.
  void compute_rail_flexibility(const StructureModel& model, const SparseMatrix* Kbar = nullptr);
  // Sets rail_index() for the model's rail DOFs (rail_flexibility()'s order).
  void index_rail_dofs(const StructureModel& model);
  EffectiveMatrixFactors factors_;
  DenseMatrix rail_flexibility_;
  std::vector<int> rail_index_;
  int model_dofs_ = 0;
  double factorization_s_ = 0.0;
  double flexibility_s_ = 0.0;
  int flexibility_solves_ = 0;
};

// K_bar = f.mass*M + f.damping*C + f.stiffness*K of the model.
SparseMatrix effective_matrix(const StructureModel& model, const EffectiveMatrixFactors& f);

}  // namespace railvsi
