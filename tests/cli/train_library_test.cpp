// Every train of the library, referenced by name from a scene, runs over a
// small bridge: multibody trains both as vehicles and as moving forces.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "generators/bridge_2d.hpp"
#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"
#include "simulation/simulation.hpp"
#include "simulation/static_equilibrium.hpp"
#include "solver/structure_backend.hpp"
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
      expect_finite_ok_run(name, "moving_forces");
      continue;
    }
    ++multibody;
    expect_finite_ok_run(name, "interaction");
    expect_finite_ok_run(json{{"library", name}, {"as", "moving_forces"}}, "moving_forces");
  }
  EXPECT_GE(multibody, 4) << "ICE3, Eurostar, Shinkansen300, KHST";
}

// A multibody train standing on a bridge loads the deck with its static
// wheel loads: each body rests on two suspensions and each bogie on two
// wheelsets, so the loads do not depend on the deck's deflection, and the
// static deck deflection equals that of the train as its axle loads.
TEST(TrainLibraryStatics, MultibodyTrainsDeflectTheDeckAsTheirAxleLoads) {
  Bridge2dOptions o;
  o.spans_m = {40.0};
  o.deck_EI_Nm2 = 5.0e10;
  o.deck_mass_kg_per_m = 15000.0;
  o.element_length_m = 1.0;
  int checked = 0;
  for (const std::string& name : library_train_names()) {
    const Train train = load_library_train(name);
    if (train.is_moving_forces()) continue;
    SCOPED_TRACE(name);
    Scene multibody;
    multibody.structure = make_bridge_2d(o);
    multibody.train = train;
    Scene forces = multibody;
    forces.train.vehicles.clear();
    forces.train.moving_forces = axle_loads(train);
    StructureOperatorOptions options;
    options.rail_flexibility = false;
    const auto statics = make_structure_operator(multibody.structure, {0.0, 0.0, 1.0}, options);
    const auto coords = statics->coordinates(*multibody.structure);
    const int mid = multibody.structure->outputs().front().dof;
    // First axle at the far support (the front cars on the span), and 60 m
    // beyond it (the middle cars, which differ in AVE-S103).
    for (const double front_x_m : {40.0, 100.0}) {
      const TrainLayout mb_layout(multibody.train, multibody.analysis.contact);
      const TrainLayout mf_layout(forces.train, forces.analysis.contact);
      const double u_mb = coords.at(mid, static_equilibrium(multibody, mb_layout, front_x_m, *statics).u_s);
      const double u_mf = coords.at(mid, static_equilibrium(forces, mf_layout, front_x_m, *statics).u_s);
      ASSERT_LT(u_mf, 0.0) << "axles on the span at " << front_x_m;
      std::printf("[statics] %s, first axle at %g m: %.6e m multibody, %.6e m forces, ratio - 1 = %.1e\n", name.c_str(),
                  front_x_m, u_mb, u_mf, u_mb / u_mf - 1.0);
      // Measured |ratio - 1| <= 4.4e-16 (KHST); tolerance 3x that.
      EXPECT_NEAR(u_mb / u_mf, 1.0, 1.3e-15) << front_x_m;
    }
    ++checked;
  }
  EXPECT_GE(checked, 5) << "AVE-S103, ICE3, Eurostar, KHST, Shinkansen300";
}

}  // namespace
}  // namespace railvsi::test
