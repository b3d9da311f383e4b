// Trains as the input layer builds them: placement of the cars, shared
// models, and the moving-force view of a multibody train.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/input_error.hpp"
#include "core/types.hpp"
#include "io/train_loader.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

json car(double length_m) {
  return {{"template", "car-2d"},
          {"name", "coach"},
          {"car_body", {{"mass_kg", 40000}, {"pitch_inertia_kgm2", 2.0e6}}},
          {"bogie", {{"mass_kg", 3000}, {"pitch_inertia_kgm2", 2000}}},
          {"wheelset", {{"mass_kg", 1500}}},
          {"bogie_spacing_m", 17.5},
          {"axle_spacing_m", 2.5},
          {"primary", {{"k_N_per_m", 1.0e6}, {"c_Ns_per_m", 1.0e4}}},
          {"secondary", {{"k_N_per_m", 5.0e5}, {"c_Ns_per_m", 3.0e4}}},
          {"length_m", length_m}};
}

TEST(TrainLoader, RepeatedAndIdenticalCarsShareOneModelAndFollowEachOther) {
  json first = car(25.0);
  first["count"] = 2;
  const Train t = parse_train({{"name", "t"}, {"vehicles", {first, car(25.0)}}});
  ASSERT_EQ(t.vehicles.size(), 3u);
  EXPECT_EQ(t.vehicles[0].model, t.vehicles[1].model);
  EXPECT_EQ(t.vehicles[0].model, t.vehicles[2].model) << "an identical definition reuses the model";
  EXPECT_DOUBLE_EQ(t.vehicles[1].offset_m, 25.0);
  EXPECT_DOUBLE_EQ(t.vehicles[2].offset_m, 50.0);
}

TEST(TrainLoader, GivenOffsetPlacesTheCarAndTheNextOneFollowsIt) {
  json second = car(20.0);
  second["offset_m"] = 30.0;
  const Train t = parse_train({{"name", "t"}, {"vehicles", {car(25.0), second, car(25.0)}}});
  EXPECT_DOUBLE_EQ(t.vehicles[1].offset_m, 30.0);
  EXPECT_DOUBLE_EQ(t.vehicles[2].offset_m, 50.0);
  EXPECT_NE(t.vehicles[0].model, nullptr);
}

TEST(TrainLoader, CarTemplateErrorsGetTheCarsPath) {
  json bad = car(25.0);
  bad["primary"]["k_N_per_m"] = 0.0;
  try {
    parse_train({{"name", "t"}, {"vehicles", {car(25.0), bad}}});
    FAIL() << "a zero primary stiffness must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/vehicles/1/primary/k_N_per_m");
  }
}

TEST(TrainLoader, MovingForceViewPutsEachWheelsStaticLoadAtItsAxle) {
  json two = car(25.0);
  two["count"] = 2;
  const Train multibody = parse_train({{"name", "t"}, {"vehicles", {two}}});
  const Train forces = parse_train({{"name", "t"}, {"vehicles", {two}}, {"as", "moving_forces"}});
  ASSERT_TRUE(forces.is_moving_forces());
  ASSERT_EQ(forces.moving_forces.size(), 8u);
  // The car is symmetric: each wheel carries a quarter of its weight.
  const double weight_N = (40000 + 2 * 3000 + 4 * 1500) * kGravity_mps2;
  for (const MovingForce& f : forces.moving_forces) EXPECT_NEAR(f.load_N, weight_N / 4, 1e-9 * weight_N);
  EXPECT_DOUBLE_EQ(forces.moving_forces[4].offset_m, 25.0);
  EXPECT_DOUBLE_EQ(forces.length_m(), multibody.length_m());
}

TEST(TrainLoader, LibraryNamesAreListedFromTheTrainsFolder) {
  const auto names = library_train_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "ICE3"), names.end());
  EXPECT_THROW(load_library_train("../trains/ICE3"), InputError) << "a name is never a path";
}

}  // namespace
}  // namespace railvsi::test
