#pragma once
// The block backend of a spectrum slice (solver/nearest_eigenpairs.hpp):
// block shift-invert Lanczos on (K - sigma M)^-1 M in the M inner product,
// with full reorthogonalization and thick restarts (the block form of
// Krylov-Schur; Grimes, Lewis and Simon, SIAM J. Matrix Anal. Appl. 15(1),
// 1994, use blocks for the same reason). Each step solves the factor for a
// block of b vectors at once: the factor, of 10^8 nonzeros at seed scale, is
// read once per block instead of once per vector, and its triangular solves
// run on BLAS-3 kernels. The Lanczos vectors and M times them are kept
// (one sparse product with M per block); the Gram-Schmidt passes and the
// Ritz vectors are dense products (the BLAS).
#include "solver/nearest_eigenpairs.hpp"

namespace railvsi {

class BlockLanczos final : public NearestEigenpairs {
 public:
  explicit BlockLanczos(const ModalOptions& options)
      : block_(options.lanczos_block), tolerance_(options.lanczos_tolerance) {}
  // Converged when every wanted Ritz pair (theta, x) of the operator has
  // |OP x - theta x|_M <= tolerance * max(eps^(2/3), |theta|), Spectra's
  // test; max_restarts thick restarts at most.
  NearestPairs nearest(const SparseMatrix& M, const ShiftInvertFactor& factor, Eigen::Index count,
                       const DenseMatrix& found, int max_restarts) const override;

 private:
  int block_;
  double tolerance_;
};

}  // namespace railvsi
