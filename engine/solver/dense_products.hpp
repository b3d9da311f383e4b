#pragma once
// The dense products of a model reduction at scale (hundreds of thousands
// of rows times a thousand columns), where Eigen's own kernels, compiled
// for the baseline x86-64, run at a fraction of the machine: the BLAS's
// (OpenBLAS picks its kernel for the CPU at run time), and a sparse times
// dense product that reads the sparse matrix once per block of columns
// instead of once per column.
#include "core/types.hpp"

namespace railvsi {

// C = alpha A' B + beta C (BLAS dgemm); C is resized when beta is 0.
void multiply_transposed(const DenseMatrix& A, const DenseMatrix& B, DenseMatrix& C, double alpha = 1.0,
                         double beta = 0.0);

// C = alpha op(A) B + beta C (BLAS dgemm) on blocks of matrices (column
// ranges of a basis), op(A) = A' when transpose_a; C keeps its size.
void multiply_blocks(bool transpose_a, const Eigen::Ref<const DenseMatrix>& A, const Eigen::Ref<const DenseMatrix>& B,
                     Eigen::Ref<DenseMatrix> C, double alpha = 1.0, double beta = 0.0);

// Y = A X for a sparse A and a tall dense X, column block by column block.
DenseMatrix sparse_times_dense(const SparseMatrix& A, const Eigen::Ref<const DenseMatrix>& X);

// The same into Y, with the row-major blocks in `work`: a loop over column
// blocks of a tall X keeps one allocation of each (a fresh allocation of
// hundreds of MB is a page fault and a cleared page per 4 kB: 19.6 % of
// the seed-scale hybrid run's samples, perf 2026-11-28). Y and work are
// resized only when their sizes change.
struct SparseProductWorkspace {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x, y;
};
void sparse_times_dense(const SparseMatrix& A, const Eigen::Ref<const DenseMatrix>& X, DenseMatrix& Y,
                        SparseProductWorkspace& work);

}  // namespace railvsi
