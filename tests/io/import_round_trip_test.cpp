// Structures exported in each matrix format and imported back run to the
// same result, to the bit, through the real vsi binary: the TTB-2D-like
// bridge (simply supported 50.1 m span, EI 1.7955e12 N*m^2, 69 t/m, with
// track) and the 3D deck at about 5,000 DOFs. And vsi inspect tells the
// track's modes from the deck's when the map names the track.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli/vsi_test_support.hpp"
#include "generators/bridge_2d.hpp"
#include "generators/deck_3d.hpp"
#include "../engine/test_scenes.hpp"
#include "io/file_set_writer.hpp"
#include "io/structure_export.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

constexpr ExportFormat kAllFormats[] = {ExportFormat::kMatrixMarket, ExportFormat::kHarwellBoeing,
                                        ExportFormat::kAbaqus};
const char* name_of(ExportFormat f) {
  return f == ExportFormat::kMatrixMarket ? "mtx" : f == ExportFormat::kHarwellBoeing ? "hb" : "abaqus";
}

// The TTB-2D-like bridge: the paper's Trans-European-type span as a plane
// girder with Zhai's ballasted track (defaults) on it and 10 m embankments.
Bridge2dOptions ttb_like() {
  Bridge2dOptions o;
  o.spans_m = {50.1};
  o.deck_EI_Nm2 = 1.7955e12;
  o.deck_mass_kg_per_m = 69000.0;
  o.damping_ratio = 0.02;
  o.element_length_m = 0.6;
  o.track = TrackOptions{};
  o.track->approach_m = 10.0;
  o.track->exit_m = 10.0;
  return o;
}

// Two 195 kN axles 3 m apart at 300 km/h, a short run.
json two_axles(json structure, double duration_s, bool both_rails) {
  json scene = {{"structure", std::move(structure)},
                {"train", {{"name", "two axles"},
                           {"moving_forces", {{{"offset_m", 0.0}, {"load_N", 195e3}},
                                              {{"offset_m", 3.0}, {"load_N", 195e3}}}}}},
                {"speed_kmh", 300},
                {"irregularity", nullptr},
                {"analysis", {{"dt_s", 1e-3}, {"duration_s", duration_s}}}};
  if (both_rails) scene["analysis"]["contact"] = {{"rail_lines", {0, 1}}};
  return scene;
}

class ImportRoundTrip : public VsiCliTest {
 protected:
  // Writes the model in `format` with a scene beside it; returns the scene.
  std::filesystem::path export_scene(const StructureModel& model, ExportFormat format, double duration_s,
                                     bool both_rails) const {
    const auto dir = dir_ / name_of(format);
    write_files_together(dir, structure_files(model, format));
    const auto scene = dir / "scene.json";
    std::ofstream(scene) << two_axles({{"import", structure_import_json(model, format)}}, duration_s, both_rails).dump(2);
    return scene;
  }
  // The summary without its wall-clock time.
  json simulate(const std::filesystem::path& scene) const {
    const VsiRun run = vsi("simulate '" + scene.string() + "'");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    json summary = json::parse(run.out);
    summary["run"].erase("wall_s");
    return summary;
  }
  void expect_formats_agree(const StructureModel& model, double duration_s, bool both_rails) const {
    const json reference = simulate(export_scene(model, ExportFormat::kMatrixMarket, duration_s, both_rails));
    EXPECT_EQ(reference["status"], "ok");
    EXPECT_GT(reference["deck"]["max_abs_displacement_m"].get<double>(), 0.0);
    for (const ExportFormat f : {ExportFormat::kHarwellBoeing, ExportFormat::kAbaqus}) {
      SCOPED_TRACE(name_of(f));
      // Bit-identical: the dump prints every double to round-trip precision.
      EXPECT_EQ(simulate(export_scene(model, f, duration_s, both_rails)).dump(), reference.dump());
    }
  }
};

TEST_F(ImportRoundTrip, TtbLikeBridgeWithTrackRunsBitIdenticallyInEveryFormat) {
  const auto model = make_bridge_2d(ttb_like());
  expect_formats_agree(*model, 0.8, false);
}

TEST_F(ImportRoundTrip, Deck3dRunsBitIdenticallyInEveryFormat) {
  Deck3dOptions o;
  o.spans_m = {25.0};
  o.target_dofs = 5000;
  o.approach_m = 10.0;
  o.exit_m = 10.0;
  const auto model = make_deck_3d(o).model;
  ASSERT_NEAR(model->num_dofs(), 5000, 250);
  expect_formats_agree(*model, 0.3, true);
}

// The generated TTB-like bridge, and the same imported with its track
// named by node (Harwell-Boeing + mapping) and by equation (Matrix Market):
// the same modes, typed alike. Without the track in the map every mode
// counts as deck (how vsi inspect read an import before).
// The map carries the supports of a multi-span deck (supports_x_m), so an
// imported deck is read span by span as the generated one: its first modes
// bend each span in one half-wave. Read as one span along the bridge, the
// three spans' first mode looked like a third bending mode.
TEST_F(ImportRoundTrip, Deck3dSupportsTravelWithTheMapAndItsSpansAreReadAsSpans) {
  const auto scene = export_scene(*make_deck_3d(testing::coarse_three_span_deck_3d()).model, ExportFormat::kMatrixMarket, 0.1, true);
  const json map = json::parse(std::ifstream(dir_ / "mtx" / "map.json"));
  EXPECT_EQ(map["supports_x_m"], json({0.0, 25.0, 50.0, 75.0}));
  const VsiRun run = vsi("inspect '" + scene.string() + "' --modes 3 --format json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json report = json::parse(run.out);
  const auto& modes = report["modal_analysis"]["modes"];
  ASSERT_EQ(modes.size(), 3u) << report["modal_analysis"].dump();
  for (const auto& m : modes)
    EXPECT_NE(m["type"].get<std::string>().find("1 half-wave in each of spans"), std::string::npos)
        << m.dump();
}

// The same export with supports_x_m taken out of the map: vsi inspect reads
// the supports from the deck's lowest modes, says so, and reads the modes
// span by span as with the map's.
TEST_F(ImportRoundTrip, Deck3dWithoutSupportsInTheMapHasThemReadFromItsModes) {
  const auto scene = export_scene(*make_deck_3d(testing::coarse_three_span_deck_3d()).model, ExportFormat::kMatrixMarket, 0.1, true);
  const auto map_path = dir_ / "mtx" / "map.json";
  json map = json::parse(std::ifstream(map_path));
  map.erase("supports_x_m");
  std::ofstream(map_path) << map.dump(2);
  const VsiRun run = vsi("inspect '" + scene.string() + "' --modes 3 --format json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json report = json::parse(run.out);
  EXPECT_TRUE(report["structure"]["supports_m"].empty());
  const json& read = report["modal_analysis"]["supports_from_modes"];
  ASSERT_TRUE(read.is_object()) << report["modal_analysis"].dump();
  ASSERT_EQ(read["supports_m"].size(), 4u);
  EXPECT_NEAR(read["supports_m"][1].get<double>(), 25.0, 0.2);
  EXPECT_NEAR(read["supports_m"][2].get<double>(), 50.0, 0.2);
  EXPECT_NE(read["note"].get<std::string>().find("give supports_x_m"), std::string::npos);
  for (const auto& m : report["modal_analysis"]["modes"])
    EXPECT_NE(m["type"].get<std::string>().find("1 half-wave in each of spans"), std::string::npos) << m.dump();
}

TEST_F(ImportRoundTrip, InspectTellsTrackFromDeckOnAnImportedStructure) {
  const auto model = make_bridge_2d(ttb_like());
  const auto inspect = [&](const std::filesystem::path& scene) {
    const VsiRun run = vsi("inspect '" + scene.string() + "' --modes 12 --format json");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return json::parse(run.out);
  };
  json generated_scene = two_axles(json::object(), 0.1, false);
  generated_scene["structure"] = {{"generator", "bridge-2d"},
                                  {"spans_m", {50.1}},
                                  {"deck", {{"EI_Nm2", 1.7955e12}, {"mass_kg_per_m", 69000.0}}},
                                  {"damping", {{"ratio", 0.02}}},
                                  {"element_length_m", 0.6},
                                  {"track", {{"approach_m", 10.0}, {"exit_m", 10.0}}}};
  const json generated = inspect(write_json("generated.json", generated_scene));
  const auto& gen_modes = generated["modal_analysis"]["modes"];
  int track_modes = 0;
  for (const auto& m : gen_modes) track_modes += m["type"] == "track";
  // Modes 4-9 and 11-12: the rail on its pads near 45.7 Hz (mode 4: 45.66 Hz).
  ASSERT_GT(track_modes, 0) << "the first 12 modes of the generated bridge hold a track mode";

  for (const ExportFormat f : {ExportFormat::kHarwellBoeing, ExportFormat::kMatrixMarket}) {
    SCOPED_TRACE(name_of(f));
    const json imported = inspect(export_scene(*model, f, 0.1, false));
    EXPECT_EQ(imported["structure"]["track_dofs"], generated["structure"]["track_dofs"]);
    EXPECT_EQ(imported["structure"]["deck_dofs"], generated["structure"]["deck_dofs"]);
    const auto& modes = imported["modal_analysis"]["modes"];
    ASSERT_EQ(modes.size(), gen_modes.size());
    // The same matrices in the same equation order: the same numbers to the
    // bit (measured). Deck modes are worded differently (the import knows
    // no supports: "along the bridge" rather than "in span 1").
    for (std::size_t k = 0; k < modes.size(); ++k) {
      EXPECT_EQ(modes[k]["frequency_hz"], gen_modes[k]["frequency_hz"]);
      EXPECT_EQ(modes[k]["deck_energy_fraction"], gen_modes[k]["deck_energy_fraction"]);
      EXPECT_EQ(modes[k]["type"] == "track", gen_modes[k]["type"] == "track") << "mode " << k + 1;
    }
    EXPECT_FALSE(imported["structure"]["import"]["matched"].empty());
  }

  // The same Matrix Market files with the track left out of the map.
  const auto dir = dir_ / name_of(ExportFormat::kMatrixMarket);
  json map = json::parse(read_text(dir / "map.json"));
  map.erase("track_dofs");
  std::ofstream(dir / "map.json") << map.dump(1);
  const json lumped = inspect(dir / "scene.json");
  EXPECT_EQ(lumped["structure"]["track_dofs"], 0);
  for (const auto& m : lumped["modal_analysis"]["modes"]) EXPECT_NE(m["type"], "track");
}

}  // namespace
}  // namespace railvsi::test
