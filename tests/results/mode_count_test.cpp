// count_modes: the modes below the modal cut-off the planner weighs, read
// from a spectrum already computed when it reaches past the cut-off, else
// computed. Three equal simply supported spans have each bending frequency
// of one span three times: f_n = n^2 pi / (2 L^2) sqrt(EI / m).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "generators/bridge_2d.hpp"
#include "solver/modal_basis.hpp"
#include "planning/deck_frequencies.hpp"
#include "planning/scene_plan.hpp"

namespace railvsi {
namespace {

constexpr double kSpan_m = 25.0, kEI_Nm2 = 7.694e10, kMass_kg_per_m = 15000.0;

double span_hz(int n) {
  return n * n * std::numbers::pi / (2.0 * kSpan_m * kSpan_m) * std::sqrt(kEI_Nm2 / kMass_kg_per_m);
}

std::shared_ptr<const StructureModel> three_equal_spans() {
  Bridge2dOptions b;
  b.spans_m = {kSpan_m, kSpan_m, kSpan_m};
  b.deck_EI_Nm2 = kEI_Nm2;
  b.deck_mass_kg_per_m = kMass_kg_per_m;
  b.damping_ratio = 0.01;
  return make_bridge_2d(b);
}

TEST(ModeCount, ReadsTheSpectrumComputedBeforeWhenItReachesPastTheCutoff) {
  const auto structure = three_equal_spans();
  const DeckFrequencies f = deck_frequencies(*structure);
  ASSERT_GT(f.lowest_hz.size(), 9u);
  // Between the second and third bending frequencies: 2 x 3 spans. No DOF
  // may be solved for (max_dofs 0), so the count is the spectrum's.
  const double cutoff_hz = 0.5 * (span_hz(2) + span_hz(3));
  EXPECT_EQ(count_modes(structure, cutoff_hz, f.lowest_hz, 0), 6);
}

TEST(ModeCount, ComputesTheModesWhenTheSpectrumEndsBelowTheCutoff) {
  const auto structure = three_equal_spans();
  DeckFrequencies f = deck_frequencies(*structure);
  f.lowest_hz.resize(6);  // the first two frequencies of each span
  const double cutoff_hz = 0.5 * (span_hz(4) + span_hz(5));
  EXPECT_EQ(count_modes(structure, cutoff_hz, f.lowest_hz), 12);
  EXPECT_EQ(count_modes(structure, cutoff_hz), 12);  // nothing known
  // Nor computed above max_dofs: not counted.
  EXPECT_EQ(count_modes(structure, cutoff_hz, f.lowest_hz, structure->num_dofs() - 1), -1);
}

TEST(ModeCount, NoCutoffCountsNothing) {
  const auto structure = three_equal_spans();
  EXPECT_EQ(count_modes(structure, 0.0), -1);
  EXPECT_EQ(count_modes(structure, std::nan("")), -1);
}

TEST(ModeCount, ABasisHoldsExactlyTheModesCountedBelowItsCutoff) {
  // Twelve modes below the cut-off (four bending frequencies x three spans,
  // the closed form), in one solve.
  const auto structure = three_equal_spans();
  const double cutoff_hz = 0.5 * (span_hz(4) + span_hz(5));
  const int count = count_modes(structure, cutoff_hz);
  ASSERT_EQ(count, 12);
  ModalBasisOptions o;
  o.max_frequency_hz = cutoff_hz;
  const ModalBasis basis(structure, o);
  EXPECT_EQ(basis.num_modes(), 12);
}

}  // namespace
}  // namespace railvsi
