// EN 1991-2 Table 6.6 damping, against values worked out by hand from the
// table (EN 1991-2:2003 Table 6.6), and its use by the bridge generator.
#include <gtest/gtest.h>

#include "generators/bridge_2d.hpp"
#include "model/en1991_damping.hpp"

namespace railvsi {
namespace {

TEST(En1991Damping, SteelCompositeRisesBelowTwentyMetres) {
  // 0.5 + 0.125 (20 - 10) = 1.75 %; 0.5 % at and above 20 m.
  EXPECT_NEAR(en1991_damping_ratio(En1991BridgeType::kSteelComposite, 10.0), 0.0175, 1e-12);
  EXPECT_NEAR(en1991_damping_ratio(En1991BridgeType::kSteelComposite, 20.0), 0.005, 1e-12);
  EXPECT_NEAR(en1991_damping_ratio(En1991BridgeType::kSteelComposite, 40.0), 0.005, 1e-12);
}

TEST(En1991Damping, PrestressedConcreteIsOnePercentFromTwentyMetres) {
  // 1.0 + 0.07 (20 - 15) = 1.35 %.
  EXPECT_NEAR(en1991_damping_ratio(En1991BridgeType::kPrestressedConcrete, 15.0), 0.0135, 1e-12);
  EXPECT_NEAR(en1991_damping_ratio(En1991BridgeType::kPrestressedConcrete, 25.0), 0.010, 1e-12);
}

TEST(En1991Damping, ReinforcedConcreteAndFillerBeamShareTheirRow) {
  // 1.5 + 0.07 (20 - 5) = 2.55 %; 1.5 + 0.07 (20 - 12) = 2.06 %.
  EXPECT_NEAR(en1991_damping_ratio(En1991BridgeType::kReinforcedConcrete, 5.0), 0.0255, 1e-12);
  EXPECT_NEAR(en1991_damping_ratio(En1991BridgeType::kFillerBeam, 12.0), 0.0206, 1e-12);
  EXPECT_NEAR(en1991_damping_ratio(En1991BridgeType::kReinforcedConcrete, 30.0), 0.015, 1e-12);
}

TEST(En1991Damping, NamesRoundTripAndUnknownNamesAreRefused) {
  for (const auto type : {En1991BridgeType::kSteelComposite, En1991BridgeType::kPrestressedConcrete,
                          En1991BridgeType::kReinforcedConcrete, En1991BridgeType::kFillerBeam})
    EXPECT_EQ(en1991_bridge_type_from_name(en1991_bridge_type_name(type)), type);
  EXPECT_EQ(en1991_bridge_type_name(En1991BridgeType::kSteelComposite), "steel-composite");
  EXPECT_FALSE(en1991_bridge_type_from_name("timber").has_value());
}

TEST(En1991Damping, GeneratedViaductTakesTheLongestSpansValueAndRecordsIt) {
  Bridge2dOptions o;
  o.spans_m = {15.0, 25.0};  // 1.35 % and 1.0 %: the smaller applies
  o.deck_EI_Nm2 = 5.0e10;
  o.deck_mass_kg_per_m = 15000.0;
  o.damping_en1991 = En1991BridgeType::kPrestressedConcrete;
  const auto s = make_bridge_2d(o);
  ASSERT_TRUE(s->info().damping_ratio.has_value());
  EXPECT_NEAR(*s->info().damping_ratio, 0.010, 1e-12);
  EXPECT_NE(s->info().damping_source.find("Table 6.6"), std::string::npos) << s->info().damping_source;
  EXPECT_NE(s->info().damping_source.find("prestressed-concrete"), std::string::npos);
}

TEST(En1991Damping, GivenRatioIsRecordedAsGiven) {
  Bridge2dOptions o;
  o.spans_m = {20.0};
  o.deck_EI_Nm2 = 5.0e10;
  o.deck_mass_kg_per_m = 15000.0;
  o.damping_ratio = 0.02;
  const auto s = make_bridge_2d(o);
  EXPECT_EQ(s->info().damping_ratio, 0.02);
  EXPECT_EQ(s->info().damping_source, "given");
}

}  // namespace
}  // namespace railvsi
