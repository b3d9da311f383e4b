// The hybrid structure from a scene document: "structure": "hybrid" runs
// and says so in its fidelity record; interaction on the modes of a
// structure with track is refused (it misses any tolerance there), as is a
// hybrid structure without a track to keep in FE.
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class HybridStructureCli : public VsiCliTest {
 protected:
  // The example viaduct (ballasted track, German low-interference profile).
  static json viaduct() {
    json doc =
        json::parse(read_text(std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs/examples/viaduct-ice3-german.json"));
    doc.erase("$schema");
    return doc;
  }
};

TEST_F(HybridStructureCli, InteractionOnTheModesOfATrackIsRefusedNamingTheHybridStructure) {
  json doc = viaduct();
  doc["analysis"]["structure"] = "modal";
  const auto scene = write_json("modal.json", doc);
  expect_rejected(scene, "/analysis/structure");
  const VsiRun run = vsi("simulate '" + scene.string() + "'");
  EXPECT_NE(run.err.find("use \"hybrid\""), std::string::npos) << run.err;
}

TEST_F(HybridStructureCli, APinnedModalInteractionRungOnATrackIsRefusedAtTheFidelity) {
  json doc = viaduct();
  doc["fidelity"] = {{"model", "interaction"}, {"structure", "modal"}};
  expect_rejected(write_json("pinned.json", doc), "/fidelity/structure");
}

TEST_F(HybridStructureCli, TheHybridStructureWithoutTrackIsRefused) {
  json doc = small_scene();
  doc["analysis"]["structure"] = "hybrid";
  const auto scene = write_json("hybrid.json", doc);
  const VsiRun run = vsi("simulate '" + scene.string() + "'");
  expect_input_error(run, scene, "/analysis/structure");
  EXPECT_NE(run.err.find("no track DOFs"), std::string::npos) << run.err;
}

TEST_F(HybridStructureCli, SimulateOnTheHybridStructureRecordsItsModesAndCutoff) {
  json doc = viaduct();
  doc["analysis"]["structure"] = "hybrid";
  doc["analysis"]["cutoff_hz"] = 60;
  const VsiRun run = vsi("simulate '" + write_json("hybrid.json", doc).string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(run.out);
  EXPECT_EQ(s.at("status"), "ok");
  const json& f = s.at("run").at("fidelity");
  EXPECT_EQ(f.at("rung"), "interaction/hybrid");
  // The plane viaduct's deck DOFs nearly all carry the ballast: 9 interior
  // DOFs against 291 on the interface, so the bridge's 3 own modes below
  // 60 Hz leave 3 directions inside it and the reduced model is nearly the
  // FE model reordered. Its deck displacement equals FE's.
  EXPECT_EQ(f.at("structure_backend").get<std::string>().rfind("hybrid (", 0), 0u) << f.dump();
  EXPECT_NE(f.at("structure_backend").get<std::string>().find("3 free-interface modes up to 60 Hz and 291 interface DOFs"),
            std::string::npos)
      << f.dump();
  EXPECT_EQ(f.at("modes"), 3);
  doc["analysis"].erase("structure");
  doc["analysis"].erase("cutoff_hz");
  const VsiRun fe = vsi("simulate '" + write_json("fe.json", doc).string() + "'");
  ASSERT_EQ(fe.exit_code, 0) << fe.err;
  const double u_fe = json::parse(fe.out).at("deck").at("max_abs_displacement_m");
  const double u_hy = s.at("deck").at("max_abs_displacement_m");
  EXPECT_GT(u_fe, 1e-4);
  // Measured 2.9e-11 relative (2026-11-28; 6.2e-11 with the fixed-interface
  // modes, none below 60 Hz): a reordered factor and the contact Newton's
  // tolerance.
  EXPECT_NEAR(u_hy, u_fe, 8.7e-11 * u_fe);
}

// A study of a multibody train over a 3D deck with "fidelity": "auto": the
// planner puts interaction on the hybrid structure (the deck's interior is
// many times the DOFs the rails bear on) and the job records it.
TEST_F(HybridStructureCli, TheAutomaticStudyOverA3dDeckRunsOnTheHybridStructure) {
  const VsiRun g = vsi("generate deck-3d --dofs 3000 --spans 25 --approach 30 --out '" + (dir_ / "deck").string() + "'");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  json coach = json::parse(read_text(std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs/trains/ICE3.json")).at("vehicles").at(0);
  coach.erase("count");
  const json study = {
      {"name", "one coach over a 3D deck"},
      {"structure", {{"import", {{"K", "deck/K.mtx"}, {"M", "deck/M.mtx"}, {"C", "deck/C.mtx"}, {"map", "deck/map.json"}}}}},
      {"trains", {{{"name", "ICE3 coach"}, {"vehicles", json::array({coach})}}}},
      {"speeds_kmh", {250}},
      {"irregularities", {nullptr}},
      {"analysis", {{"contact", {{"law", "hertz"}, {"rail_lines", {0, 1}}}}}}};
  const VsiRun run = vsi("run '" + write_json("study.json", study).string() + "' --db '" + (dir_ / "r.sqlite").string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const std::string sql = "sqlite3 '" + (dir_ / "r.sqlite").string() +
                          "' \"SELECT rung || '|' || json_extract(fidelity, '$.structure_backend') FROM job_records "
                          "WHERE state = 'done'\" > '" + (dir_ / "rung.txt").string() + "'";
  ASSERT_EQ(std::system(sql.c_str()), 0);
  const std::string rung = read_text(dir_ / "rung.txt");
  EXPECT_EQ(rung.rfind("interaction/hybrid|hybrid (track in FE", 0), 0u) << rung;
}

// A wheel that loses contact on the hybrid structure lands with an impact
// whose response the bridge's cut-off leaves out: the run is repeated on FE
// and its record says why.
TEST_F(HybridStructureCli, ALostContactOnTheHybridStructureRepeatsTheRunOnFe) {
  const VsiRun g = vsi("generate deck-3d --dofs 3000 --spans 25 --approach 30 --out '" + (dir_ / "deck").string() + "'");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  json coach = json::parse(read_text(std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs/trains/ICE3.json")).at("vehicles").at(0);
  coach.erase("count");
  json scene = {
      {"structure", {{"import", {{"K", "deck/K.mtx"}, {"M", "deck/M.mtx"}, {"C", "deck/C.mtx"}, {"map", "deck/map.json"}}}}},
      {"train", {{"name", "ICE3 coach"}, {"vehicles", json::array({coach})}}},
      {"speed_kmh", 350},
      {"irregularity", nullptr},
      {"analysis", {{"dt_s", 2.5e-4}, {"contact", {{"law", "hertz"}, {"rail_lines", {0, 1}}}}}},
      {"fidelity", {{"model", "interaction"}, {"structure", "hybrid"}, {"modal_cutoff_hz", 100}}}};
  const VsiRun smooth = vsi("simulate '" + write_json("smooth.json", scene).string() + "'");
  ASSERT_EQ(smooth.exit_code, 0) << smooth.err;
  EXPECT_EQ(json::parse(smooth.out).at("run").at("fidelity").at("rung"), "interaction/hybrid");
  scene["irregularity"] = {{"defects", {{{"type", "dip"}, {"x_m", 12.0}, {"length_m", 1.0}, {"depth_m", 0.03}}}}};
  const VsiRun dip = vsi("simulate '" + write_json("dip.json", scene).string() + "'");
  ASSERT_EQ(dip.exit_code, 0) << dip.err;
  const json s = json::parse(dip.out);
  EXPECT_GT(s.at("wheels").at("contact_loss_s").get<double>(), 0.0);
  const json& f = s.at("run").at("fidelity");
  EXPECT_EQ(f.at("rung"), "interaction/fe");
  EXPECT_EQ(f.at("structure_backend"), "cholmod");
  EXPECT_NE(f.at("escalation").get<std::string>().find("lost contact"), std::string::npos) << f.dump();
  EXPECT_NE(f.at("escalation").get<std::string>().find("repeated on the FE structure"), std::string::npos) << f.dump();
}

}  // namespace
}  // namespace railvsi::test
