// Envelope over speeds per train (results/envelopes/speed_envelope.hpp) and
// the store rows of one job's envelopes (envelope_rows.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "envelopes/envelope_rows.hpp"
#include "envelopes/speed_envelope.hpp"

namespace railvsi {
namespace {

std::vector<CaseValue> two_trains() {
  return {
      {"ICE3", 250.0, "none", 2.1},     {"ICE3", 300.0, "none", 3.4},      {"ICE3", 350.0, "none", 2.9},
      {"HSLM-A1", 200.0, "none", 1.2},  {"HSLM-A1", 220.0, "none", 4.0},   {"HSLM-A1", 240.0, "none", 4.0},
      {"HSLM-A1", 180.0, "none", 4.0},  {"HSLM-A1", 260.0, "none", std::nullopt},
  };
}

TEST(EnvelopeOverSpeeds, GivesTheMaximumAndItsSpeedPerTrainOrderedByName) {
  const auto env = envelope_over_speeds(two_trains());
  ASSERT_EQ(env.size(), 2u);
  EXPECT_EQ(env[0].train, "HSLM-A1");
  EXPECT_EQ(env[1].train, "ICE3");
  EXPECT_DOUBLE_EQ(*env[1].value, 3.4);
  EXPECT_DOUBLE_EQ(env[1].governing_speed_kmh, 300.0);
  EXPECT_EQ(env[1].cases, 3);
  EXPECT_EQ(env[1].cases_without_value, 0);
}

TEST(EnvelopeOverSpeeds, TieGoesToTheLowestSpeedWhateverTheRowOrder) {
  auto rows = two_trains();
  std::mt19937 shuffle(7);
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(rows.begin(), rows.end(), shuffle);
    const auto env = envelope_over_speeds(rows);
    ASSERT_EQ(env[0].train, "HSLM-A1");
    EXPECT_DOUBLE_EQ(*env[0].value, 4.0);
    EXPECT_DOUBLE_EQ(env[0].governing_speed_kmh, 180.0);  // 4.0 at 180, 220 and 240 km/h
  }
}

TEST(EnvelopeOverSpeeds, CountsCasesWithoutAValue) {
  const auto env = envelope_over_speeds(two_trains());
  EXPECT_EQ(env[0].cases, 5);
  EXPECT_EQ(env[0].cases_without_value, 1);
  const auto none = envelope_over_speeds({{"X", 100.0, "none", std::nullopt}});
  ASSERT_EQ(none.size(), 1u);
  EXPECT_FALSE(none[0].value.has_value());
  EXPECT_EQ(none[0].cases_without_value, 1);
}

TEST(EnvelopeOverSpeeds, MinimumGovernsForContactForceTiesByIrregularityAtEqualSpeed) {
  const std::vector<CaseValue> rows = {
      {"ICE3", 300.0, "profile-b", 20e3}, {"ICE3", 300.0, "profile-a", 20e3}, {"ICE3", 250.0, "profile-a", 35e3}};
  ASSERT_EQ(extreme_of("min_contact_force_N"), Extreme::kMin);
  const auto env = envelope_over_speeds(rows, Extreme::kMin);
  EXPECT_DOUBLE_EQ(*env[0].value, 20e3);
  EXPECT_DOUBLE_EQ(env[0].governing_speed_kmh, 300.0);
  EXPECT_EQ(env[0].governing_irregularity, "profile-a");
}

TEST(EnvelopeRows, DeckRowsPerPointAndOverallWheelRowsOnlyForWheels) {
  JobEnvelopes e;
  e.points = {{"mid", 12.5, 0.004, 2.5, 3.0, std::nullopt, std::nullopt}};
  e.max_abs_displacement_m = 0.004;
  e.max_abs_acceleration_mps2 = 2.5;
  e.max_abs_acceleration_unfiltered_mps2 = 3.0;
  e.newton_iterations = 1234;
  auto rows = envelope_rows(e);
  const auto find = [&](const std::string& q, const std::string& loc) {
    return std::find_if(rows.begin(), rows.end(),
                        [&](const EnvelopeRow& r) { return r.quantity == q && r.location == loc; });
  };
  ASSERT_NE(find("deck_acceleration_mps2", "mid"), rows.end());
  EXPECT_DOUBLE_EQ(*find("deck_acceleration_mps2", "mid")->value, 2.5);
  EXPECT_DOUBLE_EQ(*find("deck_displacement_m", "")->value, 0.004);
  EXPECT_DOUBLE_EQ(*find("newton_iterations", "")->value, 1234.0);
  EXPECT_EQ(find("unloading_ratio", ""), rows.end());  // moving forces: no wheel rows
  for (const EnvelopeRow& r : rows) EXPECT_TRUE(extreme_of(r.quantity).has_value()) << r.quantity;

  e.wheels = {{"v1_w1", true, 80e3, 30e3, 0.625, 0.0}, {"v1_w2", false, 80e3, {}, {}, {}}};
  e.max_unloading_ratio = 0.625;
  rows = envelope_rows(e);
  EXPECT_DOUBLE_EQ(*find("unloading_ratio", "v1_w1")->value, 0.625);
  EXPECT_EQ(find("unloading_ratio", "v1_w2"), rows.end());  // never in the evaluation window
  EXPECT_DOUBLE_EQ(*find("unloading_ratio", "")->value, 0.625);
}

}  // namespace
}  // namespace railvsi
