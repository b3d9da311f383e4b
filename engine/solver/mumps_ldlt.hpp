#pragma once
// A symmetric indefinite factor A = L D L' by MUMPS (Amestoy, Duff,
// L'Excellent, Koster, "A fully asynchronous multifrontal solver using
// distributed dynamic scheduling", SIAM J. Matrix Anal. Appl. 23(1), 2001),
// its sequential library: multifrontal, BLAS-3 dense kernels, 1x1 and 2x2
// pivots. For spectrum slicing inside the spectrum, where CHOLMOD offers
// only its simplicial up-looking L D L' (one column at a time, no BLAS-3):
// on a 228,697-DOF bridge interior that factor took minutes per shift.
// Its count of negative pivots is the inertia (Sylvester), the Sturm count.
#include <memory>

#include "core/status.hpp"
#include "core/types.hpp"

namespace railvsi {

class MumpsLdlt {
 public:
  MumpsLdlt();
  ~MumpsLdlt();
  MumpsLdlt(const MumpsLdlt&) = delete;
  MumpsLdlt& operator=(const MumpsLdlt&) = delete;

  // Factorizes the symmetric A (its lower triangle is read). A singular A
  // (a zero pivot to MUMPS's threshold) or a failure is a Status, and no
  // factor is kept.
  Status factorize(const SparseMatrix& A);
  bool factorized() const;
  // The negative entries of D (2x2 pivots counted by their eigenvalues):
  // the number of negative eigenvalues of A.
  Eigen::Index negative_pivots() const;
  // y = A^-1 x for the factorized n; false if MUMPS fails. One caller at a
  // time (MUMPS solves in its own workspace).
  bool solve(const double* x, double* y) const;
  // X = A^-1 B, all columns in one solve.
  bool solve(const DenseMatrix& B, DenseMatrix& X) const;

 private:
  // Solves for the right-hand sides in the instance's workspace.
  bool solve_in_place(int columns) const;
  struct Instance;
  std::unique_ptr<Instance> instance_;
};

}  // namespace railvsi
