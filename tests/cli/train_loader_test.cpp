// Trains as the input layer builds them: placement of the cars, shared
// models, the moving-force view of a multibody train, and the library
// (HSLM-A1 to A10 and the multibody trains).
#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/input_error.hpp"
#include "core/types.hpp"
#include "io/train_loader.hpp"
#include "simulation/static_equilibrium.hpp"

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
  for (const char* name : {"", ".", "..", "./ICE3", "ICE3/", "ICE3\\x", "NoSuchTrain"}) {
    try {
      load_library_train(name);
      ADD_FAILURE() << "'" << name << "' was loaded";
    } catch (const InputError& e) {
      // The message lists what the library has.
      EXPECT_NE(std::string(e.what()).find("ICE3"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(load_library_train("ICE3").name, "ICE3");
}

// EN 1991-2 Annex E, HSLM-A table (N, D, d, P), and two
// axle positions per train from the public CALDINTAV files
// caldintav/trains/aNN.def (GitHub SoftwareImpacts/SIMPAC-2024-175): the
// first axle of the first articulated bogie and the first axle of the rear
// end coach.
struct HslmRow {
  int number, N;
  double D_m, d_m, P_kN, first_articulated_m, rear_end_coach_m;
};
constexpr HslmRow kHslmA[] = {
    {1, 18, 18, 2.0, 170, 35.7625, 375.0},  {2, 17, 19, 3.5, 200, 36.0125, 374.5},
    {3, 16, 20, 2.0, 180, 37.7625, 375.0},  {4, 15, 21, 3.0, 190, 38.2625, 371.0},
    {5, 14, 22, 2.0, 170, 39.7625, 367.0},  {6, 13, 23, 2.0, 180, 40.7625, 360.0},
    {7, 13, 24, 2.0, 190, 41.7625, 375.0},  {8, 12, 25, 2.5, 190, 42.5125, 364.5},
    {9, 11, 26, 2.0, 210, 43.7625, 353.0},  {10, 11, 27, 2.0, 210, 44.7625, 366.0},
};

TEST(TrainLibrary, HslmATrainsHaveTheAxlesOfTheRuleForAllTen) {
  for (const HslmRow& r : kHslmA) {
    SCOPED_TRACE("HSLM-A" + std::to_string(r.number));
    const Train t = load_library_train("HSLM-A" + std::to_string(r.number));
    ASSERT_TRUE(t.is_moving_forces());
    // The EN 1991-2 Annex E layout, segment by segment: power car (4 axles, 17 m),
    // 3.525 m, end coach (2 axles, d), gap g, N + 1 articulated bogies D
    // apart (2 axles each, d), gap g, end coach, 3.525 m, power car.
    const double g = r.D_m - 1.5 * r.d_m - 1.7625;
    const int axles = 4 + 2 + 2 * (r.N + 1) + 2 + 4;
    const double length_m = 17 + 3.525 + r.d_m + g + r.N * r.D_m + r.d_m + g + r.d_m + 3.525 + 17;
    EXPECT_EQ(t.num_axles(), axles);
    EXPECT_NEAR(t.length_m(), length_m, 1e-9);
    ASSERT_EQ(t.moving_forces.size(), static_cast<std::size_t>(axles));
    EXPECT_NEAR(t.moving_forces[6].offset_m, r.first_articulated_m, 1e-9);
    EXPECT_NEAR(t.moving_forces[static_cast<std::size_t>(axles - 6)].offset_m, r.rear_end_coach_m, 1e-9);
    for (std::size_t i = 0; i < t.moving_forces.size(); ++i) {
      EXPECT_DOUBLE_EQ(t.moving_forces[i].load_N, r.P_kN * 1000.0);
      if (i > 0) {
        EXPECT_GT(t.moving_forces[i].offset_m, t.moving_forces[i - 1].offset_m);
      }
    }
  }
  // The numbers.
  EXPECT_EQ(load_library_train("HSLM-A1").num_axles(), 50);
  EXPECT_NEAR(load_library_train("HSLM-A1").length_m(), 397.525, 1e-9);
  EXPECT_EQ(load_library_train("HSLM-A2").num_axles(), 48);
  EXPECT_NEAR(load_library_train("HSLM-A2").length_m(), 398.525, 1e-9);
  EXPECT_EQ(load_library_train("HSLM-A10").num_axles(), 36);
  EXPECT_NEAR(load_library_train("HSLM-A10").length_m(), 388.525, 1e-9);
}

TEST(TrainLoader, HslmAObjectIsCheckedAtItsPathAndExcludesOtherForms) {
  const json h = {{"intermediate_coaches", 10}, {"coach_length_m", 4.0}, {"bogie_axle_spacing_m", 2.0},
                  {"axle_load_N", 1.7e5}};
  try {
    parse_train({{"name", "t"}, {"hslm_a", h}});
    FAIL() << "a coach shorter than 1.5 d + 1.7625 m must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/hslm_a/coach_length_m");
  }
  try {
    parse_train({{"name", "t"}, {"moving_forces", {{{"offset_m", 0.0}, {"load_N", 1.0}}}}, {"hslm_a", h}});
    FAIL() << "two forms of train must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/hslm_a");
  }
}

// Car bodies of interest: one per car or articulated body.
std::size_t car_bodies(const Train& t) {
  std::size_t n = 0;
  for (const TrainVehicle& v : t.vehicles) n += v.model->body_dofs().size();
  return n;
}

TEST(TrainLibrary, KhstLikeTrainMeetsThePapersCountsLengthAndAxleLoad) {
  const Train t = load_library_train("KHST");
  EXPECT_EQ(t.num_axles(), 46);  // 23 two-axle bogies
  EXPECT_EQ(car_bodies(t), 20u) << "2 power cars, 2 motorized trailers, 16 passenger cars";
  EXPECT_NEAR(t.length_m(), 380.15, 0.01);
  double total_N = 0.0;
  for (const TrainVehicle& v : t.vehicles) total_N += static_wheel_loads_on_rigid_track(*v.model).sum();
  const double mean_axle_t = total_N / kGravity_mps2 / 46 / 1000.0;
  EXPECT_NEAR(mean_axle_t, 17.0, 0.05 * 17.0);
}

TEST(TrainLibrary, EurostarAndShinkansenHaveTheirCompositions) {
  const Train eurostar = load_library_train("Eurostar");
  EXPECT_EQ(eurostar.num_axles(), 48);  // 24 bogies: Bo'Bo' + Bo'2'x9 + 2'x9 Bo' + Bo'Bo'
  EXPECT_EQ(car_bodies(eurostar), 20u);
  const Train shinkansen = load_library_train("Shinkansen300");
  EXPECT_EQ(shinkansen.num_axles(), 64);
  EXPECT_EQ(car_bodies(shinkansen), 16u);
  EXPECT_NEAR(shinkansen.length_m(), 15 * 25.0 + 17.5 + 2.5, 1e-9);
}

TEST(TrainLoader, LibraryReferenceChoosesMovingForcesKeepingTheWeight) {
  const Train multibody = parse_train_reference("KHST");
  const Train forces = parse_train_reference(json{{"library", "KHST"}, {"as", "moving_forces"}});
  ASSERT_FALSE(multibody.is_moving_forces());
  ASSERT_TRUE(forces.is_moving_forces());
  EXPECT_EQ(forces.num_axles(), 46);
  double mass_kg = 0.0;
  for (const TrainVehicle& v : multibody.vehicles) mass_kg += v.model->total_mass_kg();
  const double load_N = std::accumulate(forces.moving_forces.begin(), forces.moving_forces.end(), 0.0,
                                        [](double sum, const MovingForce& f) { return sum + f.load_N; });
  EXPECT_NEAR(load_N, mass_kg * kGravity_mps2, 1e-9 * load_N);
  EXPECT_NEAR(forces.length_m(), multibody.length_m(), 1e-9);
}

TEST(TrainLoader, LibraryReferenceErrorsAreAtTheReferencesPaths) {
  for (const auto& [reference, path] :
       {std::pair{json{{"library", "HSLM-A11"}}, "/library"},
        std::pair{json{{"library", "HSLM-A1"}, {"as", "multibody"}}, "/as"}}) {
    try {
      parse_train_reference(reference);
      ADD_FAILURE() << reference.dump() << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), path) << reference.dump();
    }
  }
  EXPECT_TRUE(parse_train_reference(json{{"library", "HSLM-A1"}, {"as", "moving_forces"}}).is_moving_forces());
}

}  // namespace
}  // namespace railvsi::test
