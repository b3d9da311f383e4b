#pragma once
// The single-vector backend of a spectrum slice (solver/nearest_eigenpairs.hpp):
// Spectra's implicitly restarted shift-invert Lanczos, one solve with the
// factor per Lanczos vector.
#include "solver/nearest_eigenpairs.hpp"

namespace railvsi {

class SpectraLanczos final : public NearestEigenpairs {
 public:
  explicit SpectraLanczos(const ModalOptions& options) : tolerance_(options.lanczos_tolerance) {}
  NearestPairs nearest(const SparseMatrix& M, const ShiftInvertFactor& factor, Eigen::Index count,
                       const DenseMatrix& found, int max_restarts) const override;

 private:
  double tolerance_;
};

}  // namespace railvsi
