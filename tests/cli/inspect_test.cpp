// vsi inspect: natural frequencies against closed forms, damping from
// EN 1991-2, axles and profile statistics worked out by hand.
#include <cmath>
#include <numbers>

#include "vsi_test_support.hpp"
#include "../support/worst_of.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

const std::filesystem::path kJobs = std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs";

// f1 = pi / (2 L^2) sqrt(EI / m).
double ss_first_frequency_hz(double L, double EI, double m) {
  return std::numbers::pi / (2.0 * L * L) * std::sqrt(EI / m);
}

class Inspect : public VsiCliTest {
 protected:
  json inspect_json(const std::filesystem::path& file, const std::string& options = "") const {
    const VsiRun run = vsi("inspect '" + file.string() + "' --format json " + options);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return json::parse(run.out);
  }
};

TEST_F(Inspect, ReportsTheFirstBendingFrequencyOfASimplySupportedBeamAtTheDefaultMesh) {
  json scene = small_scene();
  scene["structure"].erase("element_length_m");
  const json report = inspect_json(write_json("scene.json", scene));
  const double f1 = ss_first_frequency_hz(10.0, 5.0e9, 8000.0);
  const json& modes = report["modal_analysis"]["modes"];
  ASSERT_EQ(modes.size(), 6u) << "six modes by default";
  EXPECT_NEAR(modes[0]["frequency_hz"].get<double>() / f1, 1.0, 1e-3);
  EXPECT_NEAR(modes[1]["frequency_hz"].get<double>() / (4.0 * f1), 1.0, 5e-3);
  EXPECT_EQ(modes[0]["type"], "deck bending, 1 half-wave in span 1");
  EXPECT_EQ(modes[2]["half_waves_per_span"], json::array({3}));
  EXPECT_EQ(report["modal_analysis"]["solver"], "Lanczos") << "a small model";
  const json& s = report["structure"];
  EXPECT_EQ(s["source"], "bridge-2d");
  EXPECT_EQ(s["track_dofs"], 0);
  EXPECT_EQ(s["dofs"], s["deck_dofs"]);
  EXPECT_EQ(s["supports_m"], json::array({0.0, 10.0}));
  EXPECT_EQ(s["damping_ratio"], 0.01);
  EXPECT_EQ(s["damping_source"], "given");
}

TEST_F(Inspect, DeckFromItsFirstFrequencyAndEn1991DampingAreReported) {
  json scene = small_scene();
  scene["structure"]["spans_m"] = {15.0};
  scene["structure"]["deck"] = {{"mass_kg_per_m", 9000.0}, {"first_frequency_hz", 7.5}};
  scene["structure"]["damping"] = {{"en1991", {{"bridge_type", "steel-composite"}}}};
  const json report = inspect_json(write_json("scene.json", scene), "--modes 2");
  ASSERT_EQ(report["modal_analysis"]["modes"].size(), 2u);
  EXPECT_NEAR(report["modal_analysis"]["modes"][0]["frequency_hz"].get<double>() / 7.5, 1.0, 1e-3);
  // Table 6.6, steel and composite, L = 15 m: 0.5 + 0.125 (20 - 15) = 1.125 %.
  EXPECT_NEAR(report["structure"]["damping_ratio"].get<double>(), 0.01125, 1e-12);
  EXPECT_NE(report["structure"]["damping_source"].get<std::string>().find("Table 6.6"), std::string::npos);
}

TEST_F(Inspect, ContinuousTwoSpanGirderHasTheSingleSpanFirstFrequency) {
  json scene = small_scene();
  scene["structure"]["spans_m"] = {10.0, 10.0};
  scene["structure"]["continuous"] = true;
  scene["structure"].erase("element_length_m");
  const json report = inspect_json(write_json("scene.json", scene), "--modes 2");
  EXPECT_NEAR(report["modal_analysis"]["modes"][0]["frequency_hz"].get<double>() /
                  ss_first_frequency_hz(10.0, 5.0e9, 8000.0),
              1.0, 5e-3);
  EXPECT_EQ(report["modal_analysis"]["modes"][0]["half_waves_per_span"], json::array({1, 1}));
  EXPECT_EQ(report["structure"]["supports_m"], json::array({0.0, 10.0, 20.0}));
}

TEST_F(Inspect, ViaductWithTrackSplitsDeckAndTrackDofs) {
  json scene = small_scene();
  scene["structure"]["track"] = json::object();
  const json report = inspect_json(write_json("scene.json", scene), "--modes 1");
  const json& s = report["structure"];
  EXPECT_GT(s["track_dofs"].get<int>(), 0);
  EXPECT_EQ(s["dofs"].get<int>(), s["deck_dofs"].get<int>() + s["track_dofs"].get<int>());
  EXPECT_EQ(s["rail_lines"][0]["name"], "rail");
  EXPECT_GT(report["modal_analysis"]["modes"][0]["deck_energy_fraction"].get<double>(), 0.5);
}

// A track on an almost free subballast (5 N/m) has modes far below the
// deck's, with no deck motion: inspect names them track modes, never deck
// bending (a 0.016 Hz track mode was once reported as "deck bending").
TEST_F(Inspect, AVeryLowTrackModeIsATrackModeNotDeckBending) {
  json scene = json::parse(read_text(kJobs / "examples" / "viaduct-ice3-german.json"));
  scene["structure"]["track"] = {{"subballast_k_N_per_m", 5.0}};
  const json report = inspect_json(write_json("soft.json", scene), "--modes 3");
  const json& modes = report["modal_analysis"]["modes"];
  ASSERT_EQ(modes.size(), 3u);
  for (const json& m : modes) {
    ASSERT_LT(m["frequency_hz"].get<double>(), 1.0) << m.dump();  // far below the deck's 5 Hz
    EXPECT_EQ(m["type"].get<std::string>().rfind("track", 0), 0u) << m.dump();
    EXPECT_LT(m["deck_energy_fraction"].get<double>(), 0.02) << m.dump();
  }
}

TEST_F(Inspect, MultibodyTrainAxleLoadsAddUpToItsWeight) {
  const json report = inspect_json(kJobs / "trains/ICE3.json");
  EXPECT_EQ(report["document"], "train");
  const json& t = report["train"];
  EXPECT_EQ(t["model"], "multibody");
  ASSERT_EQ(t["axle_list"].size(), t["axles"].get<std::size_t>());
  double sum_N = 0.0, last_m = 0.0;
  for (const json& a : t["axle_list"]) {
    sum_N += a["static_load_N"].get<double>();
    last_m = railvsi::testing::worst_of(last_m, a["offset_m"].get<double>());
  }
  // Static equilibrium on a rigid track: the wheels carry the weight.
  EXPECT_NEAR(sum_N / (t["total_mass_kg"].get<double>() * 9.81), 1.0, 1e-9);
  EXPECT_NEAR(t["length_m"].get<double>(), last_m, 1e-9);
  EXPECT_GT(t["vehicle_dofs"].get<int>(), 0);
}

TEST_F(Inspect, ProfileStatisticsAreTrapezoidalOverX) {
  // r: 0, 2, 0, -2, 0 mm at 1 m steps: integral of r^2 = 4 * (0 + 4e-6)/2 = 8e-6 m^3
  // over 4 m: RMS = sqrt(2e-6) m; mean 0.
  const auto file = write_json("profile.json", {{"x_m", {0.0, 1.0, 2.0, 3.0, 4.0}},
                                                {"r_m", {0.0, 0.002, 0.0, -0.002, 0.0}}});
  const json r = inspect_json(file)["irregularity"];
  EXPECT_EQ(r["samples"], 5);
  EXPECT_EQ(r["x_start_m"], 0.0);
  EXPECT_EQ(r["x_end_m"], 4.0);
  EXPECT_EQ(r["min_m"], -0.002);
  EXPECT_EQ(r["max_m"], 0.002);
  EXPECT_NEAR(r["mean_m"].get<double>(), 0.0, 1e-15);
  EXPECT_NEAR(r["rms_m"].get<double>(), std::sqrt(2e-6), 1e-12);
}

TEST_F(Inspect, TextReportListsFrequenciesAxlesAndDamping) {
  const VsiRun run = vsi("inspect '" + write_json("scene.json", small_scene()).string() + "' --modes 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* text : {"structure (bridge-2d)", "damping: 1.000 % (given)", "natural frequencies",
                           "deck bending, 1 half-wave in span 1", "train 'one force' (moving_forces): 1 axles",
                           "irregularity: none"})
    EXPECT_NE(run.out.find(text), std::string::npos) << text << " in:\n" << run.out;
}

TEST_F(Inspect, InvalidSceneIsAnInputErrorAsForValidate) {
  json scene = small_scene();
  scene["structure"]["deck"]["first_frequency_hz"] = 5.0;  // and EI_Nm2
  const auto file = write_json("scene.json", scene);
  expect_input_error(vsi("inspect '" + file.string() + "'"), file, "/structure/deck");
}

}  // namespace
}  // namespace railvsi::test
