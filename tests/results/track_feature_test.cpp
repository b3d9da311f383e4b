// The shortest feature of a track profile (results/planning/track_feature.hpp)
// and the time-step policy's track bound, against profiles whose feature
// length is known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/test_scenes.hpp"
#include "generators/bridge_2d.hpp"
#include "planning/time_step_policy.hpp"
#include "planning/track_feature.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;

Irregularity sampled(double x0, double x1, double h, double (*r)(double)) {
  std::vector<double> x, v;
  for (double xi = x0; xi <= x1 + 1e-9; xi += h) {
    x.push_back(xi);
    v.push_back(r(xi));
  }
  return Irregularity(x, v);
}

TEST(TrackFeature, ASampledSineIsItsWavelength) {
  // 2 mm amplitude, 1.5 m wavelength, 0.02 m samples. Over whole periods
  // sum dr^2 / sum ds^2 is 1 / k^2 up to (k h)^2 / 24 = 2.9e-4; the 2 m
  // window centred on a crest holds 1.33 periods, which makes it shorter:
  // measured 0.894 of the wavelength (conservative: a smaller dt);
  // tolerance 0.12.
  const Irregularity p = sampled(0.0, 30.0, 0.02, [](double x) { return 0.002 * std::sin(2.0 * kPi * x / 1.5); });
  const TrackFeature f = shortest_track_feature(p);
  EXPECT_NEAR(f.wavelength_m / 1.5, 1.0, 0.12);
  EXPECT_NEAR(f.height_m, 0.004, 1e-5);
}

TEST(TrackFeature, ACosineDipIsItsLength) {
  // The generators' cosine dip: 30 mm deep, 0.5 m long, samples 0.01 m.
  const auto dip = testing::cosine_dip(10.0, 0.5, 0.030);
  const TrackFeature f = shortest_track_feature(*dip);
  // Measured 1.0108 (the linear interpolation of the samples); tolerance 2e-2.
  EXPECT_NEAR(f.wavelength_m / 0.5, 1.0, 2e-2);
  EXPECT_NEAR(f.height_m, 0.030, 1e-4);
  EXPECT_NEAR(f.x_m, 10.25, 1.0);
}

TEST(TrackFeature, AStepIsItsRiseInterval) {
  // A 5 mm rise over h = 1 mm between long flat intervals: two kinks of
  // slope 5 and one rise of 5 mm, lambda = 2 pi sqrt(h^2 / 2) = 4.44 h.
  const Irregularity p({-400.0, 10.0, 10.001, 400.0}, {0.0, 0.0, 0.005, 0.005});
  const TrackFeature f = shortest_track_feature(p);
  EXPECT_NEAR(f.wavelength_m, 2.0 * kPi * 0.001 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(f.height_m, 0.005, 1e-15);
}

TEST(TrackFeature, AFlatOrLinearProfileHasNone) {
  EXPECT_EQ(shortest_track_feature(Irregularity({0.0, 1.0, 2.0, 3.0}, {0.0, 0.0, 0.0, 0.0})).wavelength_m, 0.0);
  EXPECT_EQ(shortest_track_feature(Irregularity({0.0, 1.0, 2.0, 3.0}, {0.0, 0.1, 0.2, 0.3})).wavelength_m, 0.0);
}

std::shared_ptr<const StructureModel> two_spans() {
  return make_bridge_2d(testing::two_fifteen_metre_spans(TrackOptions{}));
}

Train one_coach() { return testing::one_ice3_coach(); }

TEST(TimeStepPolicyTrack, ADipBindsAtItsCrossingTime) {
  // 30 mm x 0.5 m at 400 km/h lifts the wheel (v^2 r'' = 111.1^2 x 0.015 x
  // (2 pi / 0.5)^2 = 29,000 m/s^2 > 500): 0.5 m / (150 x 111.1 m/s) = 3.0e-5 s,
  // the ladder's 1.5625e-5 s; the structure and the contact need more.
  ContactOptions hertz;
  hertz.law = "hertz";
  const auto dip = testing::cosine_dip(10.0, 0.5, 0.030);
  const TimeStepChoice c = choose_time_step(*two_spans(), one_coach(), 400.0 / 3.6, hertz, 6.2, 56.0, {}, dip.get());
  EXPECT_EQ(c.binding, "track profile");
  // The sampled dip's lambda is 0.5 m to 2e-2 (TrackFeature above: 1.0108).
  EXPECT_NEAR(c.required_dt_s / (0.5 / (150.0 * 400.0 / 3.6)), 1.0, 2e-2);
  EXPECT_DOUBLE_EQ(c.dt_s, 1.5625e-5);
  EXPECT_NE(c.reason.find("the wheel lifts and lands"), std::string::npos) << c.reason;
  EXPECT_NE(c.reason.find("30 mm peak to peak"), std::string::npos) << c.reason;
  // Moving forces do not feel the profile: no track bound.
  Train forces;
  forces.moving_forces = {{0.0, 170e3}};
  const TimeStepChoice m = choose_time_step(*two_spans(), forces, 400.0 / 3.6, hertz, 6.2, 56.0, {}, dip.get());
  EXPECT_NE(m.binding, "track profile");
}

TEST(TimeStepPolicyTrack, AStepStopsAtTheLaddersFloorAndSaysSo) {
  // 5 mm over 1 mm at 300 km/h needs 4.44 mm / (150 x 83.3 m/s) = 3.6e-7 s:
  // below the floor 2 ms / 2^7 = 15.6 us, which the policy takes.
  ContactOptions hertz;
  hertz.law = "hertz";
  const Irregularity step({-400.0, 10.0, 10.001, 400.0}, {0.0, 0.0, 0.005, 0.005});
  const TimeStepChoice c = choose_time_step(*two_spans(), one_coach(), 300.0 / 3.6, hertz, 6.2, 56.0, {}, &step);
  EXPECT_EQ(c.binding, "track profile");
  EXPECT_DOUBLE_EQ(c.dt_s, 2e-3 / 128.0);
  EXPECT_NEAR(c.required_dt_s, 2.0 * kPi * 0.001 / std::sqrt(2.0) / (150.0 * 300.0 / 3.6), 1e-12);
  EXPECT_NE(c.reason.find("the ladder's floor"), std::string::npos) << c.reason;
}

}  // namespace
}  // namespace railvsi
