#include "solver/spectra_lanczos.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>

#include "core/split_mix64.hpp"

namespace railvsi {
namespace {

// Spectra's shift-invert operator on a factor at its shift, its range kept
// M-orthogonal to pairs found already (a slice searched again for the
// eigenvalues it missed). Spectra passes x = M v.
class SliceOperator {
 public:
  using Scalar = double;
  SliceOperator(const ShiftInvertFactor& factor, const DenseMatrix& found, const DenseMatrix& M_found)
      : factor_(factor), found_(found), M_found_(M_found) {}
  Eigen::Index rows() const { return factor_.rows(); }
  Eigen::Index cols() const { return factor_.rows(); }
  void set_shift(double) {}  // the factor is at its shift already
  void perform_op(const double* x, double* y) const {
    factor_.solve(x, y);  // NaN on failure: Spectra then does not converge
    if (found_.cols() == 0) return;
    Eigen::Map<Vector> v(y, rows());
    v -= found_ * (M_found_.transpose() * v);
  }

 private:
  const ShiftInvertFactor& factor_;
  const DenseMatrix& found_;
  const DenseMatrix& M_found_;
};

}  // namespace

// Lanczos converges the extremes of the spectrum of (K - sigma M)^-1 M:
// asking for the largest 1 / (lambda - sigma) alone would leave the huge
// negative ones (the eigenvalues just below an interior shift) to dominate
// every restart; a dense band then did not converge in 1,000 restarts.
NearestPairs SpectraLanczos::nearest(const SparseMatrix& M, const ShiftInvertFactor& factor, Eigen::Index count,
                                     const DenseMatrix& found, int max_restarts) const {
  NearestPairs out;
  const Eigen::Index n = M.rows();
  const Eigen::Index dims = n - found.cols();  // the operator's range
  // Twice the pairs wanted: Lanczos then converges in a few restarts, and
  // its dense work (n x ncv) stays small.
  const Eigen::Index ncv = std::min(dims, std::max(2 * count + 1, count + 20));
  count = std::min(count, ncv - 1);
  if (count < 1) return out;
  const DenseMatrix M_found = M * found;
  SliceOperator op(factor, found, M_found);
  Spectra::SparseSymMatProd<double> mass(M);
  Spectra::SymGEigsShiftSolver<SliceOperator, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
      solver(op, mass, count, ncv, factor.sigma());
  // A fixed pseudo-random start (the same modes to the last bit on every
  // run), deflated like the operator.
  SplitMix64 random(0x5eed + static_cast<std::uint64_t>(found.cols()));
  Vector start(n);
  for (Eigen::Index i = 0; i < n; ++i) start[i] = random.next_unit() - 0.5;
  if (found.cols() > 0) start -= found * (M_found.transpose() * start);
  solver.init(start.data());
  solver.compute(Spectra::SortRule::LargestMagn, max_restarts, tolerance_, Spectra::SortRule::SmallestAlge);
  out.iterations = static_cast<int>(solver.num_iterations());
  if (solver.info() != Spectra::CompInfo::Successful) {
    out.status = {StatusCode::kNoConvergence,
                  fmt::format("Lanczos did not converge the {} eigenpairs nearest {:.6g} rad^2/s^2 in {} restarts",
                              count, factor.sigma(), max_restarts)};
    return out;
  }
  const Vector lambda = solver.eigenvalues();
  const DenseMatrix phi = solver.eigenvectors();
  std::vector<Eigen::Index> keep;
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
    if (std::isfinite(lambda[k])) keep.push_back(k);
  out.phi.resize(n, static_cast<Eigen::Index>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j) {
    out.lambda.push_back(lambda[keep[j]]);
    auto col = out.phi.col(static_cast<Eigen::Index>(j));
    col = phi.col(keep[j]);
    col /= std::sqrt(col.dot(M * col));
  }
  return out;
}

}  // namespace railvsi
