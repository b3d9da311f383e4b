// The rail flexibility from the track substructure (solver/
// substructured_flexibility.hpp) against the old path, one blocked solve of
// the whole structure per rail DOF: the same matrix to round-off, with
// fewer solves, for the dynamic K_bar and for the static K.
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdio>

#include "generators/deck_3d.hpp"
#include "integration/hht.hpp"
#include "solver/cholmod_operator.hpp"
#include "solver/substructured_flexibility.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

EffectiveMatrixFactors dynamic_factors() {
  const HhtCoefficients h(HhtParameters::from_alpha(-0.05), 2.5e-4);
  return {h.mass_factor(), h.damping_factor(), h.stiffness_factor()};
}

// A small direct-fastened 3D deck with rails on rigid ground before and after.
std::shared_ptr<const StructureModel> small_deck_3d() {
  Deck3dOptions o;
  o.spans_m = {10.0, 10.0};
  o.mesh = Deck3dMesh{{10, 10}, 4, 2};
  o.approach_m = 12.0;
  o.exit_m = 6.0;
  return make_deck_3d(o).model;
}

// A 2D viaduct with ballasted track (sleepers, embankment ballast).
std::shared_ptr<const StructureModel> viaduct_2d() { return testing::small_viaduct_with_dip(100.0, 0.01).structure; }

double max_abs(const DenseMatrix& A) { return A.cwiseAbs().maxCoeff(); }

struct Comparison {
  double relative_difference;  // max |F_new - F_old| / max |F_old|
  int direct_columns, dofs;
};

Comparison compare(const StructureModel& s, const EffectiveMatrixFactors& f, const std::vector<int>& W) {
  CholmodOperatorOptions o;
  o.rail_flexibility = false;
  const CholmodOperator op(s, f, o);
  auto ws = op.make_workspace();
  const DenseMatrix old_path = op.flexibility_block(W, *ws);
  SubstructureSummary summary;
  // Whatever the cost rule would choose on these small models: the path itself.
  const DenseMatrix F = substructured_flexibility(op, effective_matrix(s, f), s, W, *ws, &summary, /*by_cost=*/false);
  std::printf("[substructured flexibility] max diff / max F %.2e, %d of %zu columns solved directly\n", max_abs(F - old_path) / max_abs(old_path), summary.direct_columns, W.size());
  return {max_abs(F - old_path) / max_abs(old_path), summary.direct_columns, static_cast<int>(W.size())};
}

// Measured max |difference| / max |F| (2026-11-22, printed by the test):
// 3D deck 3.0e-16 with K_bar, 8.3e-16 with K; a few DOFs on the approach
// 4.2e-16; the 2D viaduct with ballasted track 3.0e-16 and 1.2e-15 (33 of
// 168 columns solved directly). Tolerance 1e-14.
constexpr double kTolerance = 1e-14;

TEST(SubstructuredFlexibility, DeckRailFlexibilityEqualsTheSolvesOfTheWholeStructure) {
  const auto s = small_deck_3d();
  for (const auto& f : {dynamic_factors(), EffectiveMatrixFactors{0.0, 0.0, 1.0}}) {
    const Comparison c = compare(*s, f, s->rail_dofs());
    EXPECT_LT(c.relative_difference, kTolerance) << "mass factor " << f.mass;
    // Only the rail DOFs on the deck (the pads' vertical DOFs) are solved.
    EXPECT_LT(c.direct_columns, c.dofs / 2) << c.direct_columns << " of " << c.dofs;
  }
}

TEST(SubstructuredFlexibility, ViaductRailFlexibilityEqualsTheSolvesOfTheWholeStructure) {
  const auto s = viaduct_2d();
  for (const auto& f : {dynamic_factors(), EffectiveMatrixFactors{0.0, 0.0, 1.0}}) {
    const Comparison c = compare(*s, f, s->rail_dofs());
    EXPECT_LT(c.relative_difference, kTolerance) << "mass factor " << f.mass;
    EXPECT_LT(c.direct_columns, c.dofs) << c.direct_columns << " of " << c.dofs;
  }
}

TEST(SubstructuredFlexibility, FewDofsOnTheApproachNeedOnlyTheCouplingColumns) {
  // The static flexibility under a train standing on the approach: a few
  // DOFs far from the deck, and one on the deck, in no particular order.
  const auto s = small_deck_3d();
  const std::vector<int>& r = s->rail_dofs();
  std::vector<int> W(r.begin(), r.begin() + 36);  // the first 9 m of rail 1
  std::reverse(W.begin(), W.end());
  W.push_back(r[r.size() / 4]);  // on the deck
  const Comparison c = compare(*s, {0.0, 0.0, 1.0}, W);
  EXPECT_LT(c.relative_difference, kTolerance);
  EXPECT_LT(c.direct_columns, c.dofs / 2) << c.direct_columns << " of " << c.dofs;
}

}  // namespace
}  // namespace railvsi
