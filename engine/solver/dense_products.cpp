#include "solver/dense_products.hpp"

#include <algorithm>

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
                       const double* beta, double* c, const int* ldc);

namespace railvsi {

void multiply_transposed(const DenseMatrix& A, const DenseMatrix& B, DenseMatrix& C, double alpha, double beta) {
  const int m = static_cast<int>(A.cols()), n = static_cast<int>(B.cols()), k = static_cast<int>(A.rows());
  if (beta == 0.0) C.resize(m, n);  // dgemm does not read C when beta is 0
  if (m == 0 || n == 0) return;
  if (k == 0) {  // an empty sum: C = beta C
    if (beta == 0.0) C.setZero();
    else C *= beta;
    return;
  }
  const int lda = static_cast<int>(A.rows()), ldb = static_cast<int>(B.rows()), ldc = static_cast<int>(C.rows());
  dgemm_("T", "N", &m, &n, &k, &alpha, A.data(), &lda, B.data(), &ldb, &beta, C.data(), &ldc);
}

void multiply_blocks(bool transpose_a, const Eigen::Ref<const DenseMatrix>& A, const Eigen::Ref<const DenseMatrix>& B,
                     Eigen::Ref<DenseMatrix> C, double alpha, double beta) {
  const int m = static_cast<int>(C.rows()), n = static_cast<int>(C.cols());
  const int k = static_cast<int>(transpose_a ? A.rows() : A.cols());
  if (m == 0 || n == 0) return;
  if (k == 0) {  // an empty sum: C = beta C
    if (beta == 0.0) C.setZero();
    else C *= beta;
    return;
  }
  const int lda = static_cast<int>(std::max<Eigen::Index>(1, A.outerStride()));
  const int ldb = static_cast<int>(std::max<Eigen::Index>(1, B.outerStride()));
  const int ldc = static_cast<int>(std::max<Eigen::Index>(1, C.outerStride()));
  dgemm_(transpose_a ? "T" : "N", "N", &m, &n, &k, &alpha, A.data(), &lda, B.data(), &ldb, &beta, C.data(), &ldc);
}

DenseMatrix sparse_times_dense(const SparseMatrix& A, const Eigen::Ref<const DenseMatrix>& X) {
  DenseMatrix Y;
  SparseProductWorkspace work;
  sparse_times_dense(A, X, Y, work);
  return Y;
}

void sparse_times_dense(const SparseMatrix& A, const Eigen::Ref<const DenseMatrix>& X, DenseMatrix& Y,
                        SparseProductWorkspace& work) {
  // 32 columns of X row by row (a 32-wide multiply-add per nonzero of A,
  // on memory next to the last one: FE orderings keep A's columns near
  // its rows).
  constexpr Eigen::Index kBlock = 32;
  Y.resize(A.rows(), X.cols());
  for (Eigen::Index c0 = 0; c0 < X.cols(); c0 += kBlock) {
    const Eigen::Index w = std::min(kBlock, X.cols() - c0);
    work.x.resize(X.rows(), w);
    work.y.resize(A.rows(), w);
    work.x = X.middleCols(c0, w);
    work.y.setZero();
    for (Eigen::Index j = 0; j < A.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) work.y.row(it.row()) += it.value() * work.x.row(j);
    Y.middleCols(c0, w) = work.y;
  }
}

}  // namespace railvsi
