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

// A wheel that loses contact on the hybrid structure lands with an impact;
// with the bridge's free-interface modes to the planner's cut-off (3 x the
// code frequency) the run stays on the hybrid structure and agrees with the
// same scene pinned on FE.
TEST_F(HybridStructureCli, ALostContactOnTheHybridStructureAgreesWithFeWithoutARepeat) {
  const VsiRun g = vsi("generate deck-3d --dofs 3000 --spans 25 --approach 30 --out '" + (dir_ / "deck").string() + "'");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  json coach = json::parse(read_text(std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs/trains/ICE3.json")).at("vehicles").at(0);
  coach.erase("count");
  json scene = {
      {"structure", {{"import", {{"K", "deck/K.mtx"}, {"M", "deck/M.mtx"}, {"C", "deck/C.mtx"}, {"map", "deck/map.json"}}}}},
      {"train", {{"name", "ICE3 coach"}, {"vehicles", json::array({coach})}}},
      {"speed_kmh", 350},
      {"irregularity", {{"defects", {{{"type", "dip"}, {"x_m", 12.0}, {"length_m", 1.0}, {"depth_m", 0.03}}}}}},
      {"analysis", {{"dt_s", 2.5e-4}, {"contact", {{"law", "hertz"}, {"rail_lines", {0, 1}}}}}},
      {"fidelity", {{"model", "interaction"}, {"structure", "hybrid"}}}};
  const VsiRun hybrid = vsi("simulate '" + write_json("hybrid.json", scene).string() + "'");
  ASSERT_EQ(hybrid.exit_code, 0) << hybrid.err;
  scene["fidelity"]["structure"] = "fe";
  const VsiRun fe = vsi("simulate '" + write_json("fe.json", scene).string() + "'");
  ASSERT_EQ(fe.exit_code, 0) << fe.err;
  const json h = json::parse(hybrid.out), f = json::parse(fe.out);
  const json& record = h.at("run").at("fidelity");
  EXPECT_EQ(record.at("rung"), "interaction/hybrid");
  EXPECT_EQ(record.at("structure_backend").get<std::string>().rfind("hybrid (", 0), 0u) << record.dump();
  EXPECT_TRUE(record.at("escalation").is_null()) << record.dump();
  EXPECT_EQ(f.at("run").at("fidelity").at("rung"), "interaction/fe");
  // Both lose contact (FE 36.25 ms over the four wheels).
  const double loss_fe = f.at("wheels").at("contact_loss_s");
  ASSERT_GT(loss_fe, 0.01);
  // Measured 2026-11-28 (17 modes to 109.7 Hz): the same number of steps
  // without contact; half a step is that count.
  EXPECT_NEAR(h.at("wheels").at("contact_loss_s").get<double>(), loss_fe, 0.5 * 2.5e-4);
  const auto near = [&](const std::string& group, const std::string& key, double tolerance) {
    const double hy = h.at(group).at(key), ref = f.at(group).at(key);
    EXPECT_GT(std::abs(ref), 0.0) << key;
    EXPECT_NEAR(hy, ref, tolerance * std::abs(ref)) << key;
  };
  // Measured (hybrid - FE) / FE, 2026-11-28: displacement +0.197 % (the
  // target 0.5 %, 2.5x), filtered deck acceleration +0.024 % (0.07 %),
  // car body -0.020 % (0.06 %).
  near("deck", "max_abs_displacement_m", 5e-3);
  near("deck", "max_abs_acceleration_filtered_mps2", 7e-4);
  near("vehicles", "max_abs_carbody_acceleration_mps2", 6e-4);
  // The unfiltered deck acceleration over the landing is not given on the
  // hybrid structure (measured -8.3 % off FE on this scene), and the run
  // says why; FE gives it.
  EXPECT_TRUE(h.at("deck").at("max_abs_acceleration_mps2").is_null()) << h.at("deck").dump();
  EXPECT_GT(f.at("deck").at("max_abs_acceleration_mps2").get<double>(), 0.0);
  bool warned = false;
  for (const json& w : h.at("run").at("warnings"))
    warned = warned || w.at("code") == "unfiltered_acceleration_after_landing";
  EXPECT_TRUE(warned) << h.at("run").dump();
}

}  // namespace
}  // namespace railvsi::test
