// Wheels that run off the exit rail end of the modelled track onto the
// rigid path beyond meet a step in their support. That is the model's end,
// not the bridge: it must neither raise a result warning outside the
// evaluation window nor go unreported when it reaches a car still inside.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "simulation/simulation.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

// Two ICE3 coaches (axle span 19.875 m each, 25 m apart) over two 10 m
// spans, the whole train on the approach at t = 0, smooth track, bilateral
// linear Hertz: the contact law that would show tension as a warning.
Scene two_coaches(double exit_m) {
  Bridge2dOptions b = testing::small_viaduct_options();
  b.track->approach_m = 60.0;
  b.track->exit_m = exit_m;
  Scene s;
  s.structure = make_bridge_2d(b);
  s.train.name = "two coaches";
  const auto coach = make_car_2d(testing::ice3_coach());
  s.train.vehicles.push_back({coach, 0.0});
  s.train.vehicles.push_back({coach, 25.0});
  s.speed_mps = 300.0 / 3.6;
  s.analysis.dt_s = 2.5e-4;
  s.analysis.contact.law = "linear-hertz";
  s.analysis.contact.unilateral = false;
  return s;
}

bool has_warning(const Result& r, const std::string& code) {
  return std::any_of(r.summary.warnings.begin(), r.summary.warnings.end(),
                     [&](const RunWarning& w) { return w.code == code; });
}

double min_force_N(const Result& r) {
  double m = std::numeric_limits<double>::infinity();
  for (const auto& h : r.histories.contact_force_N)
    for (double p : h) m = std::min(m, p);
  return m;
}

// Exit 40 m: the first coach's wheels leave the rail 40 m past the bridge,
// where the bilateral law pulls them (the histories show it), while the
// second coach is still on the bridge. Its wheels and car bodies are
// outside the window then, so nothing is reported and the wheel envelope
// keeps its positive minimum.
TEST(TrackEnds, WheelsRunningOffTheExitRailEndOutsideTheWindowRaiseNoWarning) {
  const Result r = Simulation(two_coaches(40.0)).run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_LT(min_force_N(r), 0.0) << "no wheel ran off the rail end: the case tests nothing";
  for (const RunWarning& w : r.summary.warnings) ADD_FAILURE() << w.code << ": " << w.message;
  EXPECT_GT(r.summary.min_contact_force_N, 0.0);
}

// The window ends 10 m past the bridge (x = 30 m). The first wheel leaves at
// 20 + exit: with exit 29 m (the rail end at 49.2 m, on a sleeper) its
// car's last wheel is at 29.3 m, inside; with 31 m (rail end 51.0 m) at
// 31.1 m, outside.
TEST(TrackEnds, AnExitTrackShorterThanTheCarPlusTheMarginWarns) {
  const Result short_exit = Simulation(two_coaches(29.0)).run();
  ASSERT_TRUE(short_exit.status.ok()) << short_exit.status.message();
  ASSERT_TRUE(has_warning(short_exit, "exit_inside_window"));
  for (const RunWarning& w : short_exit.summary.warnings)
    if (w.code == "exit_inside_window") {
      EXPECT_EQ(w.wheel, 0) << w.message;  // the first wheel of the first coach
      EXPECT_NE(w.message.find("v1_w4"), std::string::npos) << w.message;
    }
  const Result long_exit = Simulation(two_coaches(31.0)).run();
  ASSERT_TRUE(long_exit.status.ok()) << long_exit.status.message();
  EXPECT_FALSE(has_warning(long_exit, "exit_inside_window"));
}

}  // namespace
}  // namespace railvsi
