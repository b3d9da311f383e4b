// The fused history pass (integration/history_operator.hpp) against the
// three sparse products of hht_history_rhs and Eigen's own products K u,
// C v, M v, M a, on a model with track (consistent rail mass, pads with
// dashpots) and a random state.
#include <gtest/gtest.h>

#include "integration/history_operator.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

double relative(const Vector& x, const Vector& ref) { return (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff(); }

TEST(SparseHistoryOperator, EqualsTheThreeSparseProductsAndGivesTheEnergyProducts) {
  const auto s = testing::small_viaduct_with_dip(100.0, 0.01).structure;
  const HhtCoefficients h(HhtParameters::from_alpha(-0.1), 2.5e-4);
  KinematicState x;
  x.resize(s->num_dofs());
  std::srand(7);
  x.u = 1e-3 * Vector::Random(s->num_dofs());
  x.v = 1e-2 * Vector::Random(s->num_dofs());
  x.a = Vector::Random(s->num_dofs());

  Vector ref, work;
  hht_history_rhs(h, s->M(), s->C(), s->K(), x, ref, work);
  SparseHistoryOperator op(s->M(), s->C(), s->K());
  Vector rhs;
  StateProducts p;
  op.apply(h, x, rhs, &p);
  // Measured: 2.3e-16 for the history terms (another summation order), 0
  // for the products; tolerance 1e-14.
  EXPECT_LT(relative(rhs, ref), 1e-14);
  EXPECT_LT(relative(p.Ku, s->K() * x.u), 1e-14);
  EXPECT_LT(relative(p.Cv, s->C() * x.v), 1e-14);
  EXPECT_LT(relative(p.Mv, s->M() * x.v), 1e-14);
  EXPECT_LT(relative(p.Ma, s->M() * x.a), 1e-14);
  Vector rhs2;
  op.apply(h, x, rhs2);  // without the products: the same terms
  EXPECT_EQ(rhs2, rhs);
}

// y_i = sum_j A_ij x_j over row i of A alone, in column order: the sums of
// the one-row-at-a-time pass this operator replaced (before 2026-11-27).
Vector row_sums(const SparseMatrix& A, const Vector& x) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor, int> R = A;
  Vector y(A.rows());
  for (Eigen::Index i = 0; i < R.outerSize(); ++i) {
    double sum = 0.0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor, int>::InnerIterator it(R, i); it; ++it)
      sum += it.value() * x[it.col()];
    y[i] = sum;
  }
  return y;
}

// Two rows per SIMD pair, M's rows merged into the pattern of K and C, and
// zero padding must not move a bit: every term and product equals the
// scalar per-matrix row sums exactly (an odd DOF count exercises the
// padding row).
TEST(SparseHistoryOperator, EqualsTheScalarRowSumsBitForBit) {
  const auto s = testing::small_viaduct_with_dip(100.0, 0.01).structure;
  const HhtCoefficients h(HhtParameters::from_alpha(-0.05), 2.5e-4);
  for (const Eigen::Index n : {s->num_dofs(), s->num_dofs() - 1}) {
    const SparseMatrix M = s->M().topLeftCorner(n, n), C = s->C().topLeftCorner(n, n),
                       K = s->K().topLeftCorner(n, n);
    KinematicState x;
    x.resize(static_cast<int>(n));
    std::srand(11);
    x.u = 1e-3 * Vector::Random(n);
    x.v = 1e-2 * Vector::Random(n);
    x.a = Vector::Random(n);
    const double one_alpha = 1.0 + h.alpha;
    const Vector wc = one_alpha * (h.c3 * x.u - h.c4 * x.v - h.c5 * x.a) + h.alpha * x.v;
    const Vector ku = row_sums(K, x.u), cw = row_sums(C, wc), mu = row_sums(M, x.u), mv = row_sums(M, x.v),
                 ma = row_sums(M, x.a);
    Vector ref(n);
    for (Eigen::Index i = 0; i < n; ++i) ref[i] = h.c0 * mu[i] + h.c1 * mv[i] + h.c2 * ma[i] + cw[i] + h.alpha * ku[i];

    SparseHistoryOperator op(M, C, K);
    Vector rhs;
    StateProducts p;
    op.apply(h, x, rhs, &p);
    ASSERT_EQ(rhs.size(), n);
    ASSERT_TRUE(rhs.allFinite());
    // Exact equality (0 ulp): the fused pass does the same floating-point
    // operations in the same order for each row.
    EXPECT_EQ(rhs, ref) << "n = " << n;
    EXPECT_EQ(p.Ku, ku);
    EXPECT_EQ(p.Cv, row_sums(C, x.v));
    EXPECT_EQ(p.Mv, mv);
    EXPECT_EQ(p.Ma, ma);
  }
}

}  // namespace
}  // namespace railvsi
