// The reduction's dense products (solver/dense_products.hpp) against
// Eigen's own: the BLAS's A' B and the column-blocked sparse times dense.
#include <gtest/gtest.h>

#include "core/split_mix64.hpp"
#include "solver/dense_products.hpp"

namespace railvsi {
namespace {

DenseMatrix random_dense(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  SplitMix64 random(seed);
  DenseMatrix X(rows, cols);
  for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] = random.next_unit() - 0.5;
  return X;
}

double relative_difference(const DenseMatrix& x, const DenseMatrix& ref) {
  if (x.rows() != ref.rows() || x.cols() != ref.cols() || !x.allFinite()) return 1.0;
  return (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

TEST(DenseProducts, TransposedProductEqualsEigensWithAndWithoutAccumulation) {
  const DenseMatrix A = random_dense(500, 37, 1), B = random_dense(500, 53, 2), C0 = random_dense(37, 53, 3);
  DenseMatrix C;
  multiply_transposed(A, B, C);
  const DenseMatrix ref = A.transpose() * B;
  // The BLAS blocks the sums otherwise: measured 1.9e-15 of the largest entry.
  EXPECT_LT(relative_difference(C, ref), 5.5e-15);
  DenseMatrix D = C0;
  multiply_transposed(A, B, D, 2.0, 1.0);
  EXPECT_LT(relative_difference(D, C0 + 2.0 * ref), 5.5e-15);  // measured 1.9e-15
  // An empty sum (A and B without rows) is zero, and beta C when accumulated.
  DenseMatrix E;
  multiply_transposed(DenseMatrix(0, 37), DenseMatrix(0, 53), E);
  ASSERT_EQ(E.rows(), 37);
  ASSERT_EQ(E.cols(), 53);
  EXPECT_TRUE((E.array() == 0.0).all());
  DenseMatrix F = C0;
  multiply_transposed(DenseMatrix(0, 37), DenseMatrix(0, 53), F, 1.0, 0.5);
  EXPECT_TRUE(F == 0.5 * C0);
}

TEST(DenseProducts, SparseTimesDenseEqualsEigensOverSeveralColumnBlocks) {
  // 70 columns: two whole blocks of 32 and a part.
  SplitMix64 random(9);
  std::vector<Triplet> t;
  for (int j = 0; j < 400; ++j)
    for (int k = 0; k < 6; ++k) t.emplace_back(static_cast<int>(random.next() % 300), j, random.next_unit() - 0.5);
  SparseMatrix A(300, 400);
  A.setFromTriplets(t.begin(), t.end());
  const DenseMatrix X = random_dense(400, 70, 4);
  const DenseMatrix ref = A * X;
  // The same sums in the same order (A's columns in turn): equal to the bit.
  EXPECT_EQ(relative_difference(sparse_times_dense(A, X), ref), 0.0);
  // A block of a larger matrix, as the reduction passes it.
  EXPECT_EQ(relative_difference(sparse_times_dense(A, X.middleCols(5, 40)), ref.middleCols(5, 40)), 0.0);
}

}  // namespace
}  // namespace railvsi
