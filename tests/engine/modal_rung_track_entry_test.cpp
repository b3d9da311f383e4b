// The modal moving-force rung records what the FE rung records about the
// rail-end entry: axles that start behind a short approach track enter it
// while the first axle is already inside the evaluation window, and the
// entry transient is part of the results on either rung.
#include <gtest/gtest.h>

#include <algorithm>

#include "analysis/modal_moving_forces.hpp"
#include "simulation/simulation.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

// Two 10 m spans, four 170 kN axles over 23 m at 200 km/h: with a 5 m
// approach the last axles start behind the rail end and enter it
// when the first is on the bridge; with 40 m the whole train starts on the
// modelled track.
Scene four_axles(double approach_m) {
  Bridge2dOptions b = testing::small_viaduct_options();
  b.track->approach_m = approach_m;
  Scene s;
  s.structure = make_bridge_2d(b);
  s.train.name = "four axles";
  for (const double offset_m : {0.0, 3.0, 20.0, 23.0}) s.train.moving_forces.push_back({offset_m, 170e3});
  s.speed_mps = 200.0 / 3.6;
  s.analysis.dt_s = 5e-4;
  return s;
}

const RunWarning* find_warning(const Result& r, const std::string& code) {
  const auto it = std::find_if(r.summary.warnings.begin(), r.summary.warnings.end(),
                               [&](const RunWarning& w) { return w.code == code; });
  return it == r.summary.warnings.end() ? nullptr : &*it;
}

TEST(ModalRungTrackEntry, AxlesEnteringAShortApproachInsideTheWindowWarnAsOnTheFeRung) {
  const Scene scene = four_axles(5.0);
  const Result fe = Simulation(scene).run();
  const Result modal = run_modal_moving_forces(scene);
  ASSERT_TRUE(fe.status.ok()) << fe.status.message();
  ASSERT_TRUE(modal.status.ok()) << modal.status.message();
  const RunWarning* fe_entry = find_warning(fe, "entry_inside_window");
  const RunWarning* modal_entry = find_warning(modal, "entry_inside_window");
  ASSERT_NE(fe_entry, nullptr) << "the FE rung does not see the entry: the scene tests nothing";
  ASSERT_NE(modal_entry, nullptr) << "the modal rung's record lacks entry_inside_window";
  // Both start the first axle at the same place: the same sentence and time.
  EXPECT_EQ(modal_entry->message, fe_entry->message);
  ASSERT_TRUE(fe_entry->t_s.has_value());
  ASSERT_TRUE(modal_entry->t_s.has_value());
  EXPECT_EQ(*modal_entry->t_s, *fe_entry->t_s);
  // The last axle (23 m behind the first) enters at the rail's first node
  // (the 5 m approach on the 0.6 m sleeper grid: x = -5.4 m) when the first
  // is at 17.6 m: that distance at 200 km/h from the start at the bridge
  // (x = 0, the whole train not fitting on the approach).
  const double rail_start_m = scene.structure->rails().front().start_m();
  ASSERT_NEAR(rail_start_m, -5.4, 1e-12);
  EXPECT_NEAR(*modal_entry->t_s, (rail_start_m + 23.0) / (200.0 / 3.6), 1e-12);  // closed form; rounding only
}

TEST(ModalRungTrackEntry, ATrainStartingWhollyOnTheApproachRecordsNoEntry) {
  const Result modal = run_modal_moving_forces(four_axles(40.0));
  ASSERT_TRUE(modal.status.ok()) << modal.status.message();
  EXPECT_EQ(find_warning(modal, "entry_inside_window"), nullptr);
}

}  // namespace
}  // namespace railvsi
