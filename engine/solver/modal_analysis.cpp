#include "solver/modal_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>

#include "solver/cholmod_handles.hpp"

namespace railvsi {
namespace {

// y = (K - sigma M)^-1 x for Spectra's shift-invert mode. Spectra sets the
// shift once, in the solver's constructor; a failed factorization is kept
// as a Status and checked before the iteration starts.
class ShiftInvertOp {
 public:
  using Scalar = double;

  ShiftInvertOp(const SparseMatrix& K, const SparseMatrix& M) : K_(K), M_(M) {}

  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  const Status& status() const { return status_; }

  void set_shift(double sigma) {
    if (sigma == sigma_ && (factor_ || !status_.ok())) return;  // a retry with the same shift
    sigma_ = sigma;
    const SparseMatrix A = K_ - sigma * M_;
    cholmod_sparse view = cholmod_view_symmetric(A);
    cholmod_common* c = common_->get();
    c->supernodal = CHOLMOD_AUTO;
    // LL' also when simplicial: an LDL' factor would accept an indefinite
    // matrix, i.e. a shift above some eigenvalue, and the "lowest" modes
    // found would silently skip those below it.
    c->final_ll = 1;
    factor_ = Factor(cholmod_analyze(&view, c), CholmodFactorDeleter{c});
    if (!factor_ || !cholmod_factorize(&view, factor_.get(), c) || c->status == CHOLMOD_NOT_POSDEF ||
        factor_->minor < factor_->n) {
      status_ = {StatusCode::kDiverged,
                 fmt::format("K - sigma M (sigma = {} rad^2/s^2) is not positive definite: a mechanism, or an "
                             "eigenvalue below the shift",
                             sigma)};
      factor_.reset();
    }
  }

  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Index n = rows();
    if (!factor_) {  // not reached: the caller checks status() first
      std::fill(y_out, y_out + n, 0.0);
      return;
    }
    Eigen::Map<DenseMatrix> b(const_cast<double*>(x_in), n, 1);
    cholmod_dense bview = cholmod_view(b);
    cholmod_common* c = common_->get();
    if (!cholmod_solve2(CHOLMOD_A, factor_.get(), &bview, nullptr, &X_, nullptr, &Y_, &E_, c)) {
      std::fill(y_out, y_out + n, std::numeric_limits<double>::quiet_NaN());  // Spectra then fails to converge
      return;
    }
    std::copy_n(static_cast<const double*>(X_->x), n, y_out);
  }

  ~ShiftInvertOp() {
    cholmod_common* c = common_->get();
    cholmod_free_dense(&X_, c);
    cholmod_free_dense(&Y_, c);
    cholmod_free_dense(&E_, c);
    factor_.reset();
  }
  ShiftInvertOp(const ShiftInvertOp&) = delete;
  ShiftInvertOp& operator=(const ShiftInvertOp&) = delete;

 private:
  using Factor = std::unique_ptr<cholmod_factor, CholmodFactorDeleter>;
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  std::unique_ptr<CholmodCommon> common_ = std::make_unique<CholmodCommon>();
  Factor factor_{nullptr, CholmodFactorDeleter{nullptr}};
  // Solve workspaces, reused between the iterations of one analysis.
  mutable cholmod_dense* X_ = nullptr;
  mutable cholmod_dense* Y_ = nullptr;
  mutable cholmod_dense* E_ = nullptr;
  Status status_;
  double sigma_ = 0.0;
};

}  // namespace

ModalResult modal_analysis(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& options) {
  ModalResult result;
  const Eigen::Index n = K.rows();
  const Eigen::Index nev = std::min<Eigen::Index>(options.modes, n - 1);
  if (nev < 1) {
    result.status = {StatusCode::kInvalidInput,
                     fmt::format("cannot compute {} modes of a model with {} DOFs", options.modes, n)};
    return result;
  }
  ShiftInvertOp op(K, M);  // factorized once, at the first solver's set_shift
  Spectra::SparseSymMatProd<double> mass(M);
  // A track on embankments has hundreds of nearly equal sleeper-on-ballast
  // modes. Lanczos converges slowly when the edge of the wanted set falls
  // into such a cluster: more eigenpairs than asked (and a basis twice as
  // large) converge much faster, and a miss is retried with twice as many.
  Eigen::Index wanted = std::min<Eigen::Index>(n - 1, std::max<Eigen::Index>(2 * nev, options.min_lanczos_pairs));
  for (;;) {
    const Eigen::Index ncv = std::min<Eigen::Index>(n, 2 * wanted + 1);
    Spectra::SymGEigsShiftSolver<ShiftInvertOp, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
        solver(op, mass, wanted, ncv, options.shift_rad2_per_s2);
    if (!op.status().ok()) {
      result.status = op.status();
      return result;
    }
    solver.init();
    // Largest |1/(lambda - sigma)| are the eigenvalues nearest the shift;
    // reported in ascending lambda.
    solver.compute(Spectra::SortRule::LargestMagn, options.max_iterations, options.tolerance,
                   Spectra::SortRule::SmallestAlge);
    if (solver.info() == Spectra::CompInfo::Successful) {
      const Vector lambda = solver.eigenvalues().head(nev);
      result.shapes = solver.eigenvectors().leftCols(nev);
      for (Eigen::Index k = 0; k < nev; ++k) {
        // A rigid-body mode comes out as a tiny negative lambda: frequency 0.
        result.frequencies_hz.push_back(std::sqrt(std::max(lambda[k], 0.0)) / (2.0 * std::numbers::pi));
        auto phi = result.shapes.col(k);
        phi /= std::sqrt(phi.dot(M * phi));
      }
      return result;
    }
    if (wanted >= std::min<Eigen::Index>(n - 1, options.max_lanczos_pairs)) break;
    wanted = std::min<Eigen::Index>({n - 1, 2 * wanted, options.max_lanczos_pairs});
  }
  result.status = {StatusCode::kNoConvergence,
                   fmt::format("the eigenvalue iteration did not converge ({} iterations with up to {} eigenpairs)",
                               options.max_iterations, wanted)};
  return result;
}

ModalResult modal_analysis(const StructureModel& structure, const ModalOptions& options) {
  return modal_analysis(structure.K(), structure.M(), options);
}

}  // namespace railvsi
