#pragma once
// The eigensolver of one spectrum slice (solver/lanczos_slices.hpp): the
// eigenpairs of K phi = lambda M phi nearest a factor's shift, by
// shift-invert Lanczos on (K - sigma M)^-1 M, M-orthogonal to pairs found
// before. Two backends, chosen by ModalOptions::lanczos_block:
// - single-vector implicitly restarted Lanczos (Spectra): one solve with
//   the factor per Lanczos vector;
// - block Lanczos (solver/block_lanczos.hpp): a block of vectors per solve,
//   so that the factor is read once for the block (BLAS-3 triangular
//   solves, as the constraint modes' solve of many columns).
#include <memory>
#include <vector>

#include "core/status.hpp"
#include "core/types.hpp"
#include "solver/modal_types.hpp"
#include "solver/shift_invert_factor.hpp"

namespace railvsi {

struct NearestPairs {
  Status status;
  std::vector<double> lambda;  // ascending
  DenseMatrix phi;             // M-normalised columns
  int iterations = 0;          // restarts (single vector) or block steps
};

class NearestEigenpairs {
 public:
  virtual ~NearestEigenpairs() = default;
  // The `count` eigenpairs nearest the factor's shift (the largest
  // |1 / (lambda - sigma)|), M-orthogonal to the M-orthonormal columns of
  // `found`, in at most max_restarts restarts.
  virtual NearestPairs nearest(const SparseMatrix& M, const ShiftInvertFactor& factor, Eigen::Index count,
                               const DenseMatrix& found, int max_restarts) const = 0;
};

// Block Lanczos when options.lanczos_block > 1, else Spectra's.
std::unique_ptr<NearestEigenpairs> make_nearest_eigenpairs(const ModalOptions& options);

}  // namespace railvsi
