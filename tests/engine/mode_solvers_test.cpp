// The two mode solvers (Lanczos on spectrum slices, subspace iteration):
// each against closed forms, against each other, and on the structures
// one-shift methods are slow on. Against a dense solver and with a cut-off:
// lanczos_slices_test.cpp.
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "generators/bridge_2d.hpp"
#include "generators/deck_3d.hpp"
#include "solver/modal_analysis.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;

std::string solver_name(ModeSolver s) {
  switch (s) {
    case ModeSolver::kAuto:
      return "Auto";
    case ModeSolver::kLanczos:
      return "Lanczos";
    case ModeSolver::kSubspace:
      return "Subspace";
  }
  return "?";
}

// The largest |K phi - lambda M phi| / |K phi| over the pairs (subspace
// iteration stops below 1e-8, measured 3.8e-9 to 9.4e-9 here; Lanczos
// 1e-13 to 8e-10), and the largest deviation of Phi' M Phi from the
// identity (measured <= 1.5e-14).
struct PairErrors {
  double residual = 0.0;
  double orthonormality = 0.0;
};
PairErrors pair_errors(const SparseMatrix& K, const SparseMatrix& M, const ModalResult& r) {
  PairErrors e;
  for (std::size_t k = 0; k < r.frequencies_hz.size(); ++k) {
    const Vector phi = r.shapes.col(static_cast<Eigen::Index>(k));
    const double lambda = std::pow(2.0 * kPi * r.frequencies_hz[k], 2);
    const Vector Kphi = K * phi;
    e.residual = railvsi::testing::worst_of(e.residual, (Kphi - lambda * (M * phi)).norm() / Kphi.norm());
  }
  const DenseMatrix gram = r.shapes.transpose() * (M * r.shapes);
  e.orthonormality = (gram - DenseMatrix::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff();
  return e;
}

// n masses m in a line joined by springs k; with fixed ends, one more
// spring k from each end mass to the ground.
std::pair<SparseMatrix, SparseMatrix> spring_chain(int n, double k, double m, bool fixed_ends) {
  std::vector<Triplet> kt, mt;
  for (int i = 0; i + 1 < n; ++i)
    for (const auto& [a, b, v] : {std::tuple{i, i, k}, {i + 1, i + 1, k}, {i, i + 1, -k}, {i + 1, i, -k}})
      kt.emplace_back(a, b, v);
  if (fixed_ends) {
    kt.emplace_back(0, 0, k);
    kt.emplace_back(n - 1, n - 1, k);
  }
  for (int i = 0; i < n; ++i) mt.emplace_back(i, i, m);
  SparseMatrix K(n, n), M(n, n);
  K.setFromTriplets(kt.begin(), kt.end());
  M.setFromTriplets(mt.begin(), mt.end());
  return {std::move(K), std::move(M)};
}

// The smallest generated 3D deck (three 25 m spans, rails on pads): its
// modes come in groups of three nearly equal ones, one per span.
const StructureModel& small_deck_3d() {
  static const auto deck = [] {
    Deck3dOptions o;
    o.target_dofs = 3500;
    return make_deck_3d(o).model;
  }();
  return *deck;
}

class ModeSolvers : public ::testing::TestWithParam<ModeSolver> {
 protected:
  ModalOptions options(int modes) const {
    ModalOptions o;
    o.modes = modes;
    o.solver = GetParam();
    return o;
  }
};

TEST_P(ModeSolvers, SpringMassChainMatchesItsClosedForm) {
  // n masses m between n + 1 springs k, both ends fixed:
  // omega_j = 2 sqrt(k/m) sin(j pi / (2 (n + 1))).
  const int n = 60;
  const double k = 4.0e6, m = 250.0;
  const auto [K, M] = spring_chain(n, k, m, true);
  const ModalResult r = modal_analysis(K, M, options(8));
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  ASSERT_EQ(r.frequencies_hz.size(), 8u);
  for (int j = 1; j <= 8; ++j) {
    const double expected = 2.0 * std::sqrt(k / m) * std::sin(j * kPi / (2.0 * (n + 1))) / (2.0 * kPi);
    EXPECT_NEAR(r.frequencies_hz[j - 1] / expected, 1.0, 1e-12) << "mode " << j;  // measured: 9.2e-15
  }
  EXPECT_LT(pair_errors(K, M, r).orthonormality, 1e-12);
}

TEST_P(ModeSolvers, FreeChainHasARigidBodyModeAndItsClosedForm) {
  // n masses m joined by n - 1 springs k, both ends free: K is singular,
  // omega_j = 2 sqrt(k/m) sin(j pi / (2 n)), j = 0 (the rigid translation),
  // 1, ..., n - 1.
  const int n = 40;
  const double k = 4.0e6, m = 250.0;
  const auto [K, M] = spring_chain(n, k, m, false);
  const ModalResult r = modal_analysis(K, M, options(6));
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  ASSERT_EQ(r.frequencies_hz.size(), 6u);
  EXPECT_LT(r.frequencies_hz[0], 1e-6) << "the rigid translation";  // lambda rounds to 0 or a tiny value
  for (int j = 1; j < 6; ++j) {
    const double expected = 2.0 * std::sqrt(k / m) * std::sin(j * kPi / (2.0 * n)) / (2.0 * kPi);
    EXPECT_NEAR(r.frequencies_hz[static_cast<std::size_t>(j)] / expected, 1.0, 1e-12) << "mode " << j + 1;
  }
  EXPECT_LT(pair_errors(K, M, r).orthonormality, 1e-12);
}

TEST_P(ModeSolvers, ThreeSeparateEqualSpansGiveEachFrequencyThreeTimes) {
  // Three simply supported spans with no track: three identical beams, so
  // every eigenvalue is exactly threefold. f_n = n^2 pi / (2 L^2) sqrt(EI/m).
  const double L = 20.0, EI = 4.0e10, m = 14000.0;
  Bridge2dOptions o;
  o.spans_m = {L, L, L};
  o.deck_EI_Nm2 = EI;
  o.deck_mass_kg_per_m = m;
  const auto s = make_bridge_2d(o);
  const ModalResult r = modal_analysis(*s, options(9));
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  ASSERT_EQ(r.frequencies_hz.size(), 9u);
  for (int k = 0; k < 9; ++k) {
    const int n = k / 3 + 1;
    const double expected = n * n * kPi / (2.0 * L * L) * std::sqrt(EI / m);
    EXPECT_NEAR(r.frequencies_hz[k] / expected, 1.0, 1e-5) << "mode " << k + 1;  // the mesh's: 2.1e-6
  }
  const PairErrors e = pair_errors(s->K(), s->M(), r);
  EXPECT_LT(e.residual, 1e-8);
  EXPECT_LT(e.orthonormality, 1e-12) << "the three shapes of a frequency are M-orthogonal";
}

TEST_P(ModeSolvers, EachAgreesWithTheOtherMethodOnTheLowestModesOfA3dDeck) {
  // The reference is the other method than the one that ran (kAuto runs
  // Lanczos). Measured: they agree to 8e-14.
  const StructureModel& deck = small_deck_3d();
  const ModalResult r = modal_analysis(deck, options(24));
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  if (GetParam() != ModeSolver::kAuto) {
    EXPECT_EQ(r.solver, GetParam());
  }
  ModalOptions other;
  other.modes = 24;
  other.solver = r.solver == ModeSolver::kSubspace ? ModeSolver::kLanczos : ModeSolver::kSubspace;
  const ModalResult reference = modal_analysis(deck, other);
  ASSERT_TRUE(reference.status.ok()) << reference.status.message();
  ASSERT_EQ(reference.solver, other.solver);
  ASSERT_EQ(r.frequencies_hz.size(), 24u);
  for (int k = 0; k < 24; ++k)
    EXPECT_NEAR(r.frequencies_hz[k] / reference.frequencies_hz[k], 1.0, 1e-12) << "mode " << k + 1;
  const PairErrors e = pair_errors(deck.K(), deck.M(), r);
  EXPECT_LT(e.residual, 1e-8);
  EXPECT_LT(e.orthonormality, 1e-12);
}

TEST_P(ModeSolvers, ShiftAboveTheLowestEigenvalueIsAStatusNotAnException) {
  Bridge2dOptions o;
  o.spans_m = {25.0};
  o.deck_EI_Nm2 = 7.694e10;
  o.deck_mass_kg_per_m = 15000.0;
  const auto s = make_bridge_2d(o);
  ModalOptions opts = options(6);
  opts.shift_rad2_per_s2 = std::pow(2.0 * kPi * 10.0, 2);  // 10 Hz > f1 = 5.7 Hz
  const ModalResult r = modal_analysis(*s, opts);
  EXPECT_EQ(r.status.code(), StatusCode::kDiverged);
  EXPECT_NE(r.status.message().find("not positive definite"), std::string::npos) << r.status.message();
  EXPECT_TRUE(r.frequencies_hz.empty());
}

INSTANTIATE_TEST_SUITE_P(Solvers, ModeSolvers,
                         ::testing::Values(ModeSolver::kLanczos, ModeSolver::kSubspace, ModeSolver::kAuto),
                         [](const ::testing::TestParamInfo<ModeSolver>& info) { return solver_name(info.param); });

TEST(ModeSolverChoice, AutoConvergesTwelveGroupsOfThreeEqualModesExactlyAsAsked) {
  // 36 modes of the small deck: twelve groups of three (Lanczos on one shift
  // needed 418 restarts here; the slices with their Sturm counts converge
  // them as asked, no more).
  const StructureModel& deck = small_deck_3d();
  ModalOptions o;
  o.modes = 36;
  const ModalResult r = modal_analysis(deck, o);
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_EQ(r.solver, ModeSolver::kLanczos);
  ASSERT_EQ(r.frequencies_hz.size(), 36u);
  const PairErrors e = pair_errors(deck.K(), deck.M(), r);
  EXPECT_LT(e.residual, 1e-8);
  EXPECT_LT(e.orthonormality, 1e-12);
  // The lowest 24 against subspace iteration (the other method).
  ModalOptions block;
  block.modes = 24;
  block.solver = ModeSolver::kSubspace;
  const ModalResult reference = modal_analysis(deck, block);
  ASSERT_TRUE(reference.status.ok());
  for (int k = 0; k < 24; ++k)  // measured: 8.2e-14
    EXPECT_NEAR(r.frequencies_hz[k] / reference.frequencies_hz[k], 1.0, 1e-12) << "mode " << k + 1;
  for (int k = 1; k < 36; ++k) EXPECT_GE(r.frequencies_hz[k], r.frequencies_hz[k - 1]);
}

TEST(ModeSolverChoice, SubspaceIterationGivesUpEarlyBeforeADenseClusterAndAutoKeepsLanczos) {
  // A viaduct with a ballasted track: nine deck modes below ~45 Hz, then
  // hundreds of nearly equal sleeper-on-ballast modes right after the wanted
  // ones. The block converges by lambda_24 / lambda_49 ~ 1 an iteration: it
  // says so after its first rate window instead of running its budget out.
  Bridge2dOptions o;
  o.spans_m = {25.0, 25.0, 25.0};
  o.deck_EI_Nm2 = 7.124e10;
  o.deck_mass_kg_per_m = 18000.0;
  o.track = TrackOptions{};
  o.track->approach_m = 203.3;
  const auto s = make_bridge_2d(o);
  ModalOptions block;
  block.modes = 24;
  block.solver = ModeSolver::kSubspace;
  const ModalResult stalled = modal_analysis(*s, block);
  EXPECT_EQ(stalled.status.code(), StatusCode::kNoConvergence);
  EXPECT_NE(stalled.status.message().find("would not converge in 200 iterations"), std::string::npos)
      << stalled.status.message();
  EXPECT_EQ(stalled.solver, ModeSolver::kSubspace);
  EXPECT_GE(stalled.iterations, 20) << "two rate windows";
  EXPECT_LE(stalled.iterations, 30) << "far from the budget of 200";

  ModalOptions automatic;
  automatic.modes = 24;
  const ModalResult r = modal_analysis(*s, automatic);
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_EQ(r.solver, ModeSolver::kLanczos);
  EXPECT_LT(pair_errors(s->K(), s->M(), r).residual, 1e-8);
}

}  // namespace
}  // namespace railvsi
