#include "solver/shift_invert_factor.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

namespace railvsi {

ShiftInvertFactor::~ShiftInvertFactor() {
  cholmod_common* c = common_->get();
  cholmod_free_dense(&X_, c);
  cholmod_free_dense(&Y_, c);
  cholmod_free_dense(&E_, c);
  factor_.reset();
}

ShiftInvertFactor::Outcome ShiftInvertFactor::factor_at(double sigma, bool indefinite) {
  sigma_ = sigma;
  indefinite_ = indefinite;
  eigenvalues_below_ = 0;
  const SparseMatrix A = K_ - sigma * M_;
  cholmod_sparse view = cholmod_view_symmetric(A);
  cholmod_common* c = common_->get();
  c->supernodal = indefinite ? CHOLMOD_SIMPLICIAL : CHOLMOD_AUTO;
  c->final_ll = indefinite ? 0 : 1;  // L L' also when simplicial (see the header)
  // The pattern of K - sigma M is the same for every shift: a simplicial
  // L D L' factor of an earlier shift keeps its ordering and is refactorized.
  if (!indefinite && !given_ordering_.empty()) {
    // The given ordering as it is: one method, no postorder.
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_GIVEN;
    c->postorder = 0;
    factor_ = Factor(cholmod_analyze_p(&view, given_ordering_.data(), nullptr, 0, c), CholmodFactorDeleter{c});
  } else if (!indefinite || !factor_ || factor_->is_super || factor_->is_ll) {
    c->nmethods = 0;  // CHOLMOD's default suite
    c->postorder = 1;
    factor_ = Factor(cholmod_analyze(&view, c), CholmodFactorDeleter{c});
  }
  if (!factor_ || !cholmod_factorize(&view, factor_.get(), c)) return Outcome::kFailed;
  return c->status != CHOLMOD_NOT_POSDEF && factor_->minor == factor_->n ? Outcome::kComplete : Outcome::kStopped;
}

const Status& ShiftInvertFactor::factorize(double sigma) {
  if (sigma_ == sigma && !indefinite_) return status_;  // factorized (or failed) already
  const Outcome o = factor_at(sigma, false);
  if (o == Outcome::kComplete) {
    status_ = Status::Ok();
    return status_;
  }
  if (o == Outcome::kStopped)  // not positive definite: CHOLMOD stopped at column `minor`
    status_ = {StatusCode::kDiverged,
               fmt::format("K - sigma M (sigma = {} rad^2/s^2) is not positive definite: a mechanism, or an "
                           "eigenvalue below the shift",
                           sigma)};
  else
    status_ = failed(common_->get()->status);
  factor_.reset();
  return status_;
}

const Status& ShiftInvertFactor::factorize_indefinite(double sigma) {
  if (sigma_ == sigma && indefinite_) return status_;
  if (indefinite_factorizer_ == IndefiniteFactorizer::kMumps) {
    sigma_ = sigma;
    indefinite_ = true;
    factor_.reset();
    if (!mumps_) mumps_ = std::make_unique<MumpsLdlt>();
    status_ = mumps_->factorize(K_ - sigma * M_);
    eigenvalues_below_ = status_.ok() ? mumps_->negative_pivots() : 0;
    return status_;
  }
  const Outcome o = factor_at(sigma, true);
  if (o == Outcome::kComplete) {
    // Simplicial L D L': D(j, j) is the first entry of column j.
    // (The int interface: cholmod_start, CHOLMOD_INT indices.)
    const auto* Lp = static_cast<const int*>(factor_->p);
    const auto* Lx = static_cast<const double*>(factor_->x);
    for (std::size_t j = 0; j < factor_->n; ++j)
      if (Lx[Lp[j]] < 0.0) ++eigenvalues_below_;
    status_ = Status::Ok();
    return status_;
  }
  status_ = o == Outcome::kStopped
                ? Status{StatusCode::kDiverged,
                         fmt::format("K - sigma M (sigma = {} rad^2/s^2) is singular: sigma is an eigenvalue "
                                     "to rounding, or the model has a mechanism",
                                     sigma)}
                : failed(common_->get()->status);
  factor_.reset();
  return status_;
}

Status ShiftInvertFactor::failed(int cholmod_status) const {
  return {StatusCode::kDiverged,
          fmt::format("CHOLMOD could not factorize K - sigma M of {} DOFs (status {}{})", K_.rows(), cholmod_status,
                      cholmod_status == CHOLMOD_OUT_OF_MEMORY ? ": out of memory" : "")};
}

void ShiftInvertFactor::solve(const double* x, double* y) const {
  const Eigen::Index n = rows();
  if (uses_mumps()) {
    if (!mumps_->solve(x, y)) std::fill(y, y + n, std::numeric_limits<double>::quiet_NaN());
    return;
  }
  if (!factor_) {  // not reached: callers check the status first
    std::fill(y, y + n, std::numeric_limits<double>::quiet_NaN());
    return;
  }
  Eigen::Map<DenseMatrix> b(const_cast<double*>(x), n, 1);
  cholmod_dense bview = cholmod_view(b);
  cholmod_common* c = common_->get();
  if (!cholmod_solve2(CHOLMOD_A, factor_.get(), &bview, nullptr, &X_, nullptr, &Y_, &E_, c)) {
    std::fill(y, y + n, std::numeric_limits<double>::quiet_NaN());
    return;
  }
  std::copy_n(static_cast<const double*>(X_->x), n, y);
}

bool ShiftInvertFactor::solve(const DenseMatrix& B, DenseMatrix& X) const {
  if (uses_mumps()) return mumps_->solve(B, X);
  return solve(CHOLMOD_A, B, X);
}

bool ShiftInvertFactor::solve(int cholmod_system, const DenseMatrix& B, DenseMatrix& X) const {
  if (uses_mumps() || !factor_) return false;
  DenseMatrix& b = const_cast<DenseMatrix&>(B);  // CHOLMOD reads B only
  cholmod_dense bview = cholmod_view(b);
  cholmod_common* c = common_->get();
  if (!cholmod_solve2(cholmod_system, factor_.get(), &bview, nullptr, &X_, nullptr, &Y_, &E_, c)) return false;
  X.resize(B.rows(), B.cols());
  std::copy_n(static_cast<const double*>(X_->x), B.size(), X.data());
  return true;
}

}  // namespace railvsi
