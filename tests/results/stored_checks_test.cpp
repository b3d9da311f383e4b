// The EN checks on stored quantities, as a table of rules over plain cases
// (no store): which checks a study gets, their limits from EN 1990 A2 or
// from the study, the verdict rules, and trains of axle forces left out of
// the wheel and car-body checks.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "compliance/stored_checks.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

StoredCase a_case(const std::string& train, double speed_kmh, std::optional<double> deck_mps2,
                  bool axle_forces = false, std::optional<double> carbody_mps2 = std::nullopt,
                  std::optional<double> unloading = std::nullopt) {
  StoredCase c;
  c.at.train = train;
  c.at.speed_kmh = speed_kmh;
  c.at.job_id = train + "@" + std::to_string(speed_kmh);
  c.axle_forces = axle_forces;
  c.values["deck_acceleration_mps2"] = deck_mps2;
  c.values["carbody_acceleration_mps2"] = carbody_mps2;
  c.values["unloading_ratio"] = unloading;
  return c;
}

std::vector<std::string> ids(const std::vector<CheckResult>& checks) {
  std::vector<std::string> out;
  for (const CheckResult& c : checks) out.push_back(c.id);
  return out;
}

TEST(StoredChecks, AnHslmStudyGetsTheDeckAccelerationCheckAloneAtTheBallastedLimit) {
  const std::vector<CheckResult> checks =
      evaluate_stored_checks(json::object(), {a_case("A1", 200, 3.1, true), a_case("A1", 300, 3.6, true)});
  ASSERT_EQ(ids(checks), std::vector<std::string>{"deck_acceleration"});
  EXPECT_EQ(checks[0].limit, 3.5);  // EN 1990 A2.4.4.2.1(4)P, ballasted track
  EXPECT_EQ(checks[0].verdict, Verdict::kFail);
  ASSERT_TRUE(checks[0].governing && checks[0].governing->value);
  EXPECT_EQ(*checks[0].governing->value, 3.6);
  EXPECT_EQ(checks[0].governing->speed_kmh, 300);
}

TEST(StoredChecks, DirectFasteningTakesFiveMetresPerSecondSquared) {
  const std::vector<CheckResult> checks =
      evaluate_stored_checks({{"track_type", "direct_fastening"}}, {a_case("A1", 300, 4.9, true)});
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].limit, 5.0);  // EN 1990 A2.4.4.2.1(4)P, direct fastening
  EXPECT_EQ(checks[0].verdict, Verdict::kPass);
}

TEST(StoredChecks, AMissingValueMakesACheckIncompleteNeverAPass) {
  const std::vector<CheckResult> checks =
      evaluate_stored_checks(json::object(), {a_case("A1", 200, 1.0, true), a_case("A1", 210, std::nullopt, true)});
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].verdict, Verdict::kIncomplete);
  EXPECT_EQ(checks[0].missing, 1);
}

TEST(StoredChecks, ADisplacementCheckOnlyWhenTheStudyGivesItsLimit) {
  StoredCase c = a_case("A1", 200, 1.0, true);
  c.values["deck_displacement_m"] = 0.012;
  EXPECT_EQ(ids(evaluate_stored_checks(json::object(), {c})), std::vector<std::string>{"deck_acceleration"});
  const std::vector<CheckResult> checks = evaluate_stored_checks({{"deck_displacement_limit_m", 0.01}}, {c});
  ASSERT_EQ(ids(checks), (std::vector<std::string>{"deck_acceleration", "deck_displacement"}));
  EXPECT_EQ(checks[1].limit, 0.01);
  EXPECT_EQ(checks[1].verdict, Verdict::kFail);
}

TEST(StoredChecks, TrainsOfAxleForcesAreLeftOutOfTheWheelAndCarBodyChecks) {
  const std::vector<CheckResult> checks = evaluate_stored_checks(
      json::object(), {a_case("ICE3", 300, 2.0, false, 0.8, 0.3), a_case("A1", 300, 2.5, true)});
  ASSERT_EQ(ids(checks), (std::vector<std::string>{"deck_acceleration", "wheel_unloading", "passenger_comfort"}));
  EXPECT_EQ(checks[0].cases, 2);  // the deck check has both trains
  for (const CheckResult* c : {&checks[1], &checks[2]}) {
    EXPECT_EQ(c->cases, 1) << c->id;
    EXPECT_EQ(c->verdict, Verdict::kPass) << c->id;
    EXPECT_NE(c->note.find("The 1 cases of trains given as axle forces"), std::string::npos) << c->note;
  }
  EXPECT_EQ(checks[1].limit, 0.6);  // the common wheel-unloading limit
  // EN 1990 Table A2.9: "very good" comfort is b_v <= 1.0 m/s2.
  EXPECT_EQ(checks[2].limit, 1.0);
  EXPECT_NE(checks[2].note.find("Level reached by the governing case: very good."), std::string::npos)
      << checks[2].note;
}

TEST(StoredChecks, ACarBodyCheckOfAxleForcesAloneIsNotEvaluated) {
  const std::vector<CheckResult> checks =
      evaluate_stored_checks({{"carbody_acceleration_limit_mps2", 1.3}}, {a_case("A1", 300, 2.5, true)});
  ASSERT_EQ(ids(checks), (std::vector<std::string>{"deck_acceleration", "passenger_comfort"}));
  EXPECT_EQ(checks[1].verdict, Verdict::kNotEvaluated);
  EXPECT_EQ(checks[1].cases, 0);
  EXPECT_NE(checks[1].note.find("Not evaluated: every train of the study is given as axle forces"), std::string::npos);
}

TEST(StoredChecks, TheComfortLevelReachedFollowsTableA29) {
  // EN 1990 Table A2.9: very good 1.0, good 1.3, acceptable 2.0 m/s2.
  for (const auto& [b_v, level] : std::vector<std::pair<double, std::string>>{
           {1.2, "good"}, {1.9, "acceptable"}, {2.1, "below acceptable"}}) {
    const std::vector<CheckResult> checks =
        evaluate_stored_checks({{"comfort_level", "acceptable"}}, {a_case("ICE3", 300, 2.0, false, b_v, 0.2)});
    ASSERT_EQ(checks.size(), 3u);
    EXPECT_EQ(checks[2].limit, 2.0);
    EXPECT_NE(checks[2].note.find("Level reached by the governing case: " + level + "."), std::string::npos)
        << b_v << ": " << checks[2].note;
  }
}

}  // namespace
}  // namespace railvsi
