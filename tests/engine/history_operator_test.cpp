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

}  // namespace
}  // namespace railvsi
