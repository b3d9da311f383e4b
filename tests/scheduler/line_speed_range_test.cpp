// The speeds of EN 1991-2 6.4.6.2 built from the line speed: from a start
// speed up to the maximum design speed 1.2 x the line speed, in steps, plus
// 9 speeds around each resonance speed v = f0 D / i of a train with a
// regular spacing D. Expected speeds computed by hand.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "core/input_error.hpp"
#include "scheduler_test_support.hpp"
#include "study/speed_list.hpp"
#include "study/study_plan.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

std::vector<double> job_speeds(const scheduler::StudyPlan& plan) {
  std::set<double> speeds;
  for (const auto& j : plan.jobs) speeds.insert(j.speed_kmh);
  return {speeds.begin(), speeds.end()};
}

scheduler::StudyPlan expand(const json& doc) {
  return scheduler::expand_study(doc, std::filesystem::temp_directory_path(), "study.json");
}

// tiny_study's 10 m span: EI 5e9 N m^2, 8000 kg/m, 1 % damping. First
// bending frequency pi / (2 L^2) sqrt(EI / m) = 12.4182 Hz.
const double kF0Hz = std::numbers::pi / (2.0 * 100.0) * std::sqrt(5.0e9 / 8000.0);

TEST(LineSpeedRange, StepsFromTheStartToOnePointTwoTimesTheLineSpeed) {
  json doc = tiny_study();
  doc.erase("speeds_kmh");
  doc["trains"] = json::array({doc["trains"][0]});  // moving forces: no regular spacing, no resonance speeds
  doc["line_speed_kmh"] = 100;
  doc["speed_min_kmh"] = 60;
  doc["speed_step_kmh"] = 20;
  // 60, 80, 100, 120 = 1.2 x 100.
  EXPECT_EQ(job_speeds(expand(doc)), (std::vector<double>{60, 80, 100, 120}));
  // A step that does not reach the end exactly still ends at 1.2 x line speed: 60, 85, 110, 120.
  doc["speed_step_kmh"] = 25;
  EXPECT_EQ(job_speeds(expand(doc)), (std::vector<double>{60, 85, 110, 120}));
  // Given speeds are kept beside the range.
  doc["speeds_kmh"] = json::array({30, 85});
  EXPECT_EQ(job_speeds(expand(doc)), (std::vector<double>{30, 60, 85, 110, 120}));
  // Default start 144 km/h (40 m/s), default step 10: 144, 154, ..., 354 and 360 for a line speed of 300.
  doc.erase("speeds_kmh");
  doc.erase("speed_min_kmh");
  doc.erase("speed_step_kmh");
  doc["line_speed_kmh"] = 300;
  std::vector<double> expected;
  for (int k = 0; k <= 21; ++k) expected.push_back(144.0 + 10.0 * k);
  expected.push_back(360.0);
  EXPECT_EQ(job_speeds(expand(doc)), expected);
}

TEST(LineSpeedRange, ResonanceSpeedsOfTheRegularSpacingAreAddedWithNineSpeedsAroundEach) {
  json doc = tiny_study();
  doc.erase("speeds_kmh");
  // HSLM-B, d = 3 m: v_i = f0 d / i = 12.4182 x 3 x 3.6 / i = 134.12, 67.06, 44.71, 33.53 km/h.
  doc["trains"] = json::array({{{"name", "B"}, {"hslm_b", {{"point_forces", 10}, {"spacing_m", 3.0}}}}});
  doc["line_speed_kmh"] = 150;  // up to 180 km/h
  doc["speed_min_kmh"] = 40;
  doc["speed_step_kmh"] = 20;
  const std::vector<double> speeds = job_speeds(expand(doc));
  EXPECT_EQ(speeds.front(), 40.0);
  EXPECT_EQ(speeds.back(), 180.0);  // 1.2 x 150
  // The grid 40, 60, ..., 180 (8 speeds), and for i = 1, 2, 3 (33.53 is
  // below the start) v_i (1 + k x 0.01 / 2), k = -4..4: 27 speeds.
  EXPECT_EQ(speeds.size(), 8u + 27u);
  for (int i = 1; i <= 3; ++i) {
    const double v_i = kF0Hz * 3.0 * 3.6 / i;
    for (int k = -4; k <= 4; ++k) {
      const double v = v_i * (1.0 + 0.005 * k);
      // The study takes f0 from the FE model (10 elements of 1 m): 12.41831 Hz,
      // 6.1e-6 above the closed form (measured with vsi inspect).
      const bool found =
          std::any_of(speeds.begin(), speeds.end(), [&](double s) { return std::abs(s / v - 1.0) < 1e-5; });
      EXPECT_TRUE(found) << "v_" << i << " (1 + " << 0.005 * k << ") = " << v << " km/h is missing";
    }
  }
  const double v_4 = kF0Hz * 3.0 * 3.6 / 4.0;
  EXPECT_LT(v_4 * 1.02, 40.0) << "v_4 and its neighbours lie below the start";
}

TEST(LineSpeedRange, AStartAboveTheMaximumDesignSpeedIsAnErrorAtItsPath) {
  json doc = tiny_study();
  doc.erase("speeds_kmh");
  doc["line_speed_kmh"] = 100;
  doc["speed_min_kmh"] = 130;  // above 120
  try {
    expand(doc);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/speed_min_kmh");
    EXPECT_EQ(e.file(), "study.json");
  }
  doc.erase("line_speed_kmh");
  doc.erase("speed_min_kmh");
  try {
    expand(doc);
    ADD_FAILURE() << "a study without speeds was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/speeds_kmh");
  }
}

TEST(LineSpeedRange, ResonanceSpeedsAreF0TimesDOverIWithinTheRange) {
  // 5 Hz x 18 m = 90 m/s = 324 km/h; /2 = 162, /3 = 108, /4 = 81.
  EXPECT_EQ(scheduler::resonance_speeds_kmh(5.0, 18.0, 100.0, 400.0), (std::vector<double>{324.0, 162.0, 108.0}));
  EXPECT_TRUE(scheduler::resonance_speeds_kmh(0.0, 18.0, 0.0, 400.0).empty());
  EXPECT_TRUE(scheduler::resonance_speeds_kmh(5.0, 0.0, 0.0, 400.0).empty());
}

}  // namespace
}  // namespace railvsi::test
