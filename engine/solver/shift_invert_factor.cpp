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

const Status& ShiftInvertFactor::factorize(double sigma) {
  if (sigma_ == sigma) return status_;  // factorized (or failed) already
  sigma_ = sigma;
  const SparseMatrix A = K_ - sigma * M_;
  cholmod_sparse view = cholmod_view_symmetric(A);
  cholmod_common* c = common_->get();
  c->supernodal = CHOLMOD_AUTO;
  c->final_ll = 1;  // L L' also when simplicial (see the header)
  factor_ = Factor(cholmod_analyze(&view, c), CholmodFactorDeleter{c});
  const bool factorized = factor_ && cholmod_factorize(&view, factor_.get(), c);
  if (factorized && c->status != CHOLMOD_NOT_POSDEF && factor_->minor == factor_->n) {
    status_ = Status::Ok();
    return status_;
  }
  if (factorized)  // but not positive definite: CHOLMOD stopped at column `minor`
    status_ = {StatusCode::kDiverged,
               fmt::format("K - sigma M (sigma = {} rad^2/s^2) is not positive definite: a mechanism, or an "
                           "eigenvalue below the shift",
                           sigma)};
  else
    status_ = {StatusCode::kDiverged,
               fmt::format("CHOLMOD could not factorize K - sigma M of {} DOFs (status {}{})", K_.rows(), c->status,
                           c->status == CHOLMOD_OUT_OF_MEMORY ? ": out of memory" : "")};
  factor_.reset();
  return status_;
}

void ShiftInvertFactor::solve(const double* x, double* y) const {
  const Eigen::Index n = rows();
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
  if (!factor_) return false;
  DenseMatrix& b = const_cast<DenseMatrix&>(B);  // CHOLMOD reads B only
  cholmod_dense bview = cholmod_view(b);
  cholmod_common* c = common_->get();
  if (!cholmod_solve2(CHOLMOD_A, factor_.get(), &bview, nullptr, &X_, nullptr, &Y_, &E_, c)) return false;
  X.resize(B.rows(), B.cols());
  std::copy_n(static_cast<const double*>(X_->x), B.size(), X.data());
  return true;
}

}  // namespace railvsi
