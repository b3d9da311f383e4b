// What vsi accepts: the examples and the train library validate, a scene
// runs and reports the summary of the contract, histories are written.
#include <cstdio>

#include "exported_beam.hpp"
#include "vsi_test_support.hpp"
#include "../support/worst_of.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

const std::filesystem::path kJobs = std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs";

class Documents : public VsiCliTest {};

TEST_F(Documents, EveryExampleAndLibraryTrainValidates) {
  int checked = 0;
  for (const char* folder : {"examples", "trains"})
    for (const auto& entry : std::filesystem::directory_iterator(kJobs / folder)) {
      if (entry.path().extension() != ".json") continue;
      const VsiRun run = vsi("validate '" + entry.path().string() + "'");
      EXPECT_EQ(run.exit_code, 0) << run.err;
      EXPECT_EQ(run.out.find(entry.path().string() + ": ok ("), 0u) << run.out;
      ++checked;
    }
  EXPECT_GE(checked, 4);
}

TEST_F(Documents, ValidateNamesTheKindOfDocument) {
  EXPECT_EQ(vsi("validate '" + (kJobs / "examples/viaduct-ice3.json").string() + "'").out,
            (kJobs / "examples/viaduct-ice3.json").string() + ": ok (scene)\n");
  EXPECT_EQ(vsi("validate '" + (kJobs / "trains/ICE3.json").string() + "'").out,
            (kJobs / "trains/ICE3.json").string() + ": ok (train)\n");
  const auto profile = write_json("profile.json", {{"x_m", {0.0, 1.0}}, {"r_m", {0.0, 0.001}}});
  EXPECT_EQ(vsi("validate '" + profile.string() + "'").out, profile.string() + ": ok (irregularity)\n");
}

TEST_F(Documents, SimulatePrintsTheSummaryOfTheContractWithNullWheelsForMovingForces) {
  const auto scene = write_json("scene.json", small_scene());
  const VsiRun run = vsi("simulate '" + scene.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json summary = json::parse(run.out);
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_FALSE(summary.contains("message"));
  EXPECT_EQ(summary["deck"]["points"].size(), 2u);
  EXPECT_EQ(summary["deck"]["points"][1]["name"], "midspan");
  EXPECT_GT(summary["deck"]["max_abs_displacement_m"].get<double>(), 0.0);
  // A beam deck: section forces per point, reaction and end rotation per support.
  EXPECT_GT(summary["deck"]["points"][1]["max_abs_bending_moment_Nm"].get<double>(), 0.0);
  EXPECT_GT(summary["deck"]["points"][1]["max_abs_shear_force_N"].get<double>(), 0.0);
  ASSERT_EQ(summary["supports"].size(), 2u);
  EXPECT_GT(summary["supports"][0]["max_reaction_N"].get<double>(), 0.0);
  EXPECT_GT(summary["supports"][1]["max_abs_rotation_rad"].get<double>(), 0.0);
  for (const char* key : {"min_contact_force_N", "max_unloading_ratio", "contact_loss_s"})
    EXPECT_TRUE(summary["wheels"][key].is_null()) << key;
  EXPECT_TRUE(summary["vehicles"]["max_abs_carbody_acceleration_mps2"].is_null());
  EXPECT_GT(summary["run"]["steps"].get<long>(), 0);
  EXPECT_EQ(summary["run"]["dt_s"], 2.0e-3);
  for (const char* key : {"model", "contact_law", "unilateral", "solver_path", "structure_backend", "structure_dofs",
                          "vehicle_dofs", "contacts", "hht_alpha", "hht_beta", "hht_gamma"})
    EXPECT_TRUE(summary["run"]["fidelity"].contains(key)) << key;
  EXPECT_EQ(summary["run"]["fidelity"]["model"], "moving_forces");
}

// The modal interaction rung prints the same section keys (mode
// acceleration, engine/simulation/modal_section_forces), close to the FE
// rung's on this scene.
TEST_F(Documents, SimulateOnTheModalStructurePrintsTheSectionForces) {
  json doc = small_scene();
  const json fe = json::parse(vsi("simulate '" + write_json("fe.json", doc).string() + "'").out);
  doc["analysis"]["structure"] = "modal";
  doc["analysis"]["modes"] = 6;
  const VsiRun run = vsi("simulate '" + write_json("modal.json", doc).string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json modal = json::parse(run.out);
  EXPECT_EQ(modal["run"]["fidelity"]["modes"], 6);
  EXPECT_FALSE(modal["deck"].contains("section_forces_note"));
  const auto rel = [](const json& a, const json& b) { return std::abs(a.get<double>() / b.get<double>() - 1); };
  double worst = 0.0;
  for (int p = 0; p < 2; ++p)
    for (const char* key : {"max_abs_bending_moment_Nm", "max_abs_shear_force_N"})
      worst = railvsi::testing::worst_of(worst, rel(modal["deck"]["points"][p][key], fe["deck"]["points"][p][key]));
  ASSERT_EQ(modal["supports"].size(), 2u);
  for (int i = 0; i < 2; ++i)
    for (const char* key : {"max_reaction_N", "max_abs_rotation_rad"})
      worst = railvsi::testing::worst_of(worst, rel(modal["supports"][i][key], fe["supports"][i][key]));
  std::printf("[modal sections] vsi simulate, 6 modes vs FE: worst %.2e\n", worst);
  // Measured 5.4e-5 (6 modes, a moving force: no contact dynamics).
  EXPECT_LT(worst, 1e-4);
}

TEST_F(Documents, HistoriesAreWrittenAsCsvWithOneColumnPerPointQuantity) {
  const auto scene = write_json("scene.json", small_scene());
  const auto out = dir_ / "histories";
  const VsiRun run = vsi("simulate '" + scene.string() + "' --histories '" + out.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string deck = read_text(out / "deck.csv");
  EXPECT_EQ(deck.substr(0, deck.find('\n')),
            "t_s,first_axle_x_m,in_window,quarter_displacement_m,quarter_acceleration_mps2,"
            "quarter_acceleration_filtered_mps2,midspan_displacement_m,midspan_acceleration_mps2,"
            "midspan_acceleration_filtered_mps2");
  const auto rows = std::count(deck.begin(), deck.end(), '\n');
  EXPECT_EQ(rows, json::parse(run.out)["run"]["steps"].get<long>() + 2) << "header, t = 0 and every step";
  EXPECT_FALSE(std::filesystem::exists(out / "contact_forces.csv")) << "moving forces have no contact";
  for (const auto& entry : std::filesystem::directory_iterator(out))
    EXPECT_EQ(entry.path().extension(), ".csv") << "no temporary file left behind";
}

TEST_F(Documents, MultibodyTrainReportsWheelsAndWritesContactAndCarbodyHistories) {
  json scene = small_scene();
  scene["train"] = json::parse(read_text(kJobs / "trains/ICE3.json"));
  scene["train"]["vehicles"][0]["count"] = 1;
  scene["analysis"]["dt_s"] = 1.0e-3;
  const auto out = dir_ / "histories";
  const VsiRun run = vsi("simulate '" + write_json("scene.json", scene).string() + "' --histories '" + out.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json summary = json::parse(run.out);
  EXPECT_GT(summary["wheels"]["min_contact_force_N"].get<double>(), 0.0);
  EXPECT_EQ(summary["run"]["fidelity"]["contacts"], 4);
  EXPECT_TRUE(std::filesystem::exists(out / "contact_forces.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "carbody.csv"));
}

TEST_F(Documents, VehiclesAsMovingForcesRunAsAMovingForceModelWithoutWheelValues) {
  json scene = small_scene();
  scene["train"] = json::parse(read_text(kJobs / "trains/ICE3.json"));
  scene["train"]["as"] = "moving_forces";
  const VsiRun run = vsi("simulate '" + write_json("scene.json", scene).string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json summary = json::parse(run.out);
  EXPECT_EQ(summary["run"]["fidelity"]["model"], "moving_forces");
  EXPECT_TRUE(summary["wheels"]["min_contact_force_N"].is_null());
}

TEST_F(Documents, ImportedSimplySupportedBeamValidatesAndRuns) {
  const ExportedBeam beam = exported_beam(8, 10.0, true);
  write("K.mtx", matrix_market(beam.K, true));
  write("M.mtx", matrix_market(beam.M, false));
  write_json("map.json", beam.map);
  const auto scene = write_json("scene.json", imported_scene(small_scene()));
  EXPECT_EQ(vsi("validate '" + scene.string() + "'").exit_code, 0);
  const VsiRun run = vsi("simulate '" + scene.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json summary = json::parse(run.out);
  EXPECT_EQ(summary["deck"]["points"][0]["name"], "mid");
  EXPECT_EQ(summary["run"]["fidelity"]["structure_dofs"], beam.K.rows());
}

TEST_F(Documents, RunThatDoesNotConvergePrintsItsSummaryAndExitsWithOne) {
  json scene = small_scene();
  scene["train"] = json::parse(read_text(kJobs / "trains/ICE3.json"));
  scene["train"]["vehicles"][0]["count"] = 1;
  scene["analysis"]["max_newton_iterations"] = 1;  // nonlinear Hertz needs more
  const VsiRun run = vsi("simulate '" + write_json("scene.json", scene).string() + "'");
  EXPECT_EQ(run.exit_code, 1) << run.err;
  const json summary = json::parse(run.out);
  EXPECT_EQ(summary["status"], "no_convergence");
  EXPECT_TRUE(summary["message"].is_string());
}

TEST_F(Documents, VersionIsPrinted) {
  const VsiRun run = vsi("--version");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_EQ(run.out.find("vsi "), 0u) << run.out;
}

}  // namespace
}  // namespace railvsi::test
