// MUMPS's L D L' factor (solver/mumps_ldlt.hpp) against Eigen's dense
// solvers: the inertia of shifted stiffness matrices, solves of one and of
// many right-hand sides, a singular matrix, a second shift on the kept
// analysis, and instances in two threads at once.
#include <algorithm>
#include <limits>
#include <thread>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "core/split_mix64.hpp"
#include "solver/mumps_ldlt.hpp"

namespace railvsi {
namespace {

// K - sigma M of a chain of n random masses on random springs (to the next
// and the one after; both ends held): symmetric, indefinite once sigma is
// above the lowest eigenvalue.
SparseMatrix shifted_chain(int n, double sigma, std::uint64_t seed = 7) {
  SplitMix64 random(seed);
  std::vector<Triplet> t;
  const auto spring = [&](int a, int b, double k) {
    t.emplace_back(a, a, k);
    if (b < 0) return;
    t.emplace_back(b, b, k);
    t.emplace_back(a, b, -k);
    t.emplace_back(b, a, -k);
  };
  spring(0, -1, 1e6);
  spring(n - 1, -1, 1e6);
  for (int i = 0; i < n; ++i) {
    if (i + 1 < n) spring(i, i + 1, 1e6 * (0.5 + random.next_unit()));
    if (i + 2 < n) spring(i, i + 2, 2e5 * random.next_unit());
    t.emplace_back(i, i, -sigma * 100.0 * (0.5 + random.next_unit()));
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

Eigen::Index dense_negative_eigenvalues(const SparseMatrix& A) {
  const Vector ev = Eigen::SelfAdjointEigenSolver<DenseMatrix>(DenseMatrix(A), Eigen::EigenvaluesOnly).eigenvalues();
  return std::count_if(ev.begin(), ev.end(), [](double x) { return x < 0.0; });
}

double relative_difference(const DenseMatrix& x, const DenseMatrix& ref) {
  return (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

TEST(MumpsLdlt, CountsTheNegativeEigenvaluesOfShiftedStiffnessAsTheDenseSolver) {
  MumpsLdlt f;
  for (const double sigma : {-1.0, 50.0, 2.0e3, 2.0e4, 1.0e5}) {
    const SparseMatrix A = shifted_chain(300, sigma);
    ASSERT_TRUE(f.factorize(A).ok()) << "sigma " << sigma;
    EXPECT_EQ(f.negative_pivots(), dense_negative_eigenvalues(A)) << "sigma " << sigma;
  }
  // The shifts reach deep into the spectrum: the last one has most of it below.
  EXPECT_GT(dense_negative_eigenvalues(shifted_chain(300, 1.0e5)), 100);
}

TEST(MumpsLdlt, SolvesOneAndManyRightHandSidesAsTheDenseLu) {
  const SparseMatrix A = shifted_chain(300, 2.0e4);  // indefinite
  ASSERT_GT(dense_negative_eigenvalues(A), 10);
  MumpsLdlt f;
  ASSERT_TRUE(f.factorize(A).ok());
  DenseMatrix B(300, 5);
  SplitMix64 random(3);
  for (Eigen::Index i = 0; i < B.size(); ++i) B.data()[i] = random.next_unit() - 0.5;
  const DenseMatrix ref = Eigen::PartialPivLU<DenseMatrix>(DenseMatrix(A)).solve(B);
  DenseMatrix X;
  ASSERT_TRUE(f.solve(B, X));
  // Measured 2.9e-15 against the dense LU (2026-11-27).
  EXPECT_LT(relative_difference(X, ref), 1e-14);
  Vector y(300);
  ASSERT_TRUE(f.solve(B.col(2).data(), y.data()));
  EXPECT_LT(relative_difference(y, ref.col(2)), 1e-14);
}

TEST(MumpsLdlt, ASecondShiftOnTheKeptAnalysisIsFactorizedAfresh) {
  MumpsLdlt f;
  ASSERT_TRUE(f.factorize(shifted_chain(200, 50.0)).ok());
  const SparseMatrix A = shifted_chain(200, 3.0e4);  // same pattern, other values
  ASSERT_TRUE(f.factorize(A).ok());
  EXPECT_EQ(f.negative_pivots(), dense_negative_eigenvalues(A));
  const Vector b = Vector::Ones(200);
  Vector x(200);
  ASSERT_TRUE(f.solve(b.data(), x.data()));
  EXPECT_LT(relative_difference(x, Eigen::PartialPivLU<DenseMatrix>(DenseMatrix(A)).solve(b)), 1e-14);
}

TEST(MumpsLdlt, ASingularMatrixIsAStatusAndNoFactor) {
  // A free chain (no spring to the ground, no shift): the rigid motion is a
  // null vector.
  std::vector<Triplet> t;
  for (int i = 0; i + 1 < 20; ++i) {
    t.emplace_back(i, i, 1.0);
    t.emplace_back(i + 1, i + 1, 1.0);
    t.emplace_back(i, i + 1, -1.0);
    t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix A(20, 20);
  A.setFromTriplets(t.begin(), t.end());
  MumpsLdlt f;
  const Status s = f.factorize(A);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("singular"), std::string::npos) << s.message();
  EXPECT_FALSE(f.factorized());
  const Vector b = Vector::Ones(20);
  Vector x(20);
  EXPECT_FALSE(f.solve(b.data(), x.data()));
}

TEST(MumpsLdlt, InstancesInTwoThreadsGiveWhatEachGivesAlone) {
  const SparseMatrix A1 = shifted_chain(400, 2.0e4, 11), A2 = shifted_chain(400, 6.0e4, 12);
  const Vector b = Vector::LinSpaced(400, -1.0, 1.0);
  const auto run = [&b](const SparseMatrix& A, Eigen::Index& negative, Vector& x) {
    for (int repeat = 0; repeat < 20; ++repeat) {
      MumpsLdlt f;
      if (!f.factorize(A).ok()) return;
      negative = f.negative_pivots();
      x.resize(b.size());
      if (!f.solve(b.data(), x.data())) x.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  };
  Eigen::Index n1 = -1, n2 = -1, s1 = -1, s2 = -1;
  Vector x1, x2, y1, y2;
  run(A1, s1, y1);
  run(A2, s2, y2);
  std::thread a([&] { run(A1, n1, x1); });
  std::thread c([&] { run(A2, n2, x2); });
  a.join();
  c.join();
  EXPECT_EQ(n1, dense_negative_eigenvalues(A1));
  EXPECT_EQ(n2, dense_negative_eigenvalues(A2));
  EXPECT_EQ(n1, s1);
  EXPECT_EQ(n2, s2);
  ASSERT_EQ(x1.size(), 400);
  ASSERT_EQ(x2.size(), 400);
  EXPECT_EQ(x1, y1);  // the same arithmetic, bit for bit
  EXPECT_EQ(x2, y2);
}

}  // namespace
}  // namespace railvsi
