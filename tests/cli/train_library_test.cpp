// Every train of the library, referenced by name from a scene, runs over a
// small bridge: multibody trains both as vehicles and as moving forces.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"
#include "simulation/simulation.hpp"
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

// The small scene of the command-line tests (a 10 m simply supported deck,
// no track) with the train replaced: 200 km/h, dt = 1 ms, 0.2 s.
Scene short_run_scene(const json& train) {
  const auto data = std::filesystem::path(RAILVSI_TEST_DATA);
  json doc = json::parse(read_text(data / "small-scene.json"));
  doc["train"] = train;
  doc["speed_kmh"] = 200;
  doc["analysis"]["dt_s"] = 1.0e-3;
  doc["analysis"]["duration_s"] = 0.2;
  return parse_scene(doc, data, "small-scene.json");
}

void expect_finite_ok_run(const json& train, const std::string& model) {
  SCOPED_TRACE(train.dump());
  const Result r = Simulation(short_run_scene(train)).run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_EQ(r.summary.fidelity.model, model);
  EXPECT_EQ(r.summary.steps, 200);
  EXPECT_TRUE(std::isfinite(r.summary.max_abs_displacement_m));
  EXPECT_GT(r.summary.max_abs_displacement_m, 0.0) << "the first axles are on the deck";
  EXPECT_TRUE(std::isfinite(r.summary.max_abs_acceleration_mps2));
  if (model == "interaction") {
    EXPECT_TRUE(std::isfinite(r.summary.max_abs_carbody_acceleration_mps2));
    EXPECT_GT(r.summary.min_contact_force_N, 0.0);
  }
}

TEST(TrainLibraryRuns, EveryLibraryTrainRunsOnASmallBridgeAsVehiclesAndAsForces) {
  const std::vector<std::string> names = library_train_names();
  for (int n = 1; n <= 10; ++n)
    EXPECT_NE(std::find(names.begin(), names.end(), "HSLM-A" + std::to_string(n)), names.end()) << n;
  int multibody = 0;
  for (const std::string& name : names) {
    if (load_library_train(name).is_moving_forces()) {
      expect_finite_ok_run(name, "moving-forces");
      continue;
    }
    ++multibody;
    expect_finite_ok_run(name, "interaction");
    expect_finite_ok_run(json{{"library", name}, {"as", "moving_forces"}}, "moving-forces");
  }
  EXPECT_GE(multibody, 4) << "ICE3, Eurostar, Shinkansen300, KHST";
}

}  // namespace
}  // namespace railvsi::test
