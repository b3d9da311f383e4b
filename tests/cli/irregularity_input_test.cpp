// Track irregularities in scenes and profile documents: a spectrum by name
// and seed, isolated defects, and bad input refused with exit 2 and the JSON
// path by the real vsi binary.
#include "io/scene_loader.hpp"
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class IrregularityInput : public VsiCliTest {
 protected:
  std::filesystem::path scene_with_irregularity(const json& irregularity) const {
    json scene = small_scene();
    scene["irregularity"] = irregularity;
    return write_json("scene.json", scene);
  }
  void expect_irregularity_rejected(const json& irregularity, const std::string& json_path) const {
    expect_rejected(scene_with_irregularity(irregularity), json_path);
  }
};

TEST_F(IrregularityInput, SpectrumAndSeedAreEnoughAndTheSourceIsOnRecord) {
  const auto file = scene_with_irregularity({{"spectrum", "german-high"}, {"seed", 7}});
  const VsiRun run = vsi("validate '" + file.string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const Scene scene = load_scene(file);
  ASSERT_TRUE(scene.irregularity);
  const std::string& source = scene.irregularity->source();
  for (const char* part : {"german-high", "A_v = 1.080e-06 m*rad", "seed 7", "3-70 m", "2000 components"})
    EXPECT_NE(source.find(part), std::string::npos) << part << " in " << source;
}

TEST_F(IrregularityInput, SpectrumCoversTheTrackAndTheTrainBehindAndPastIt) {
  // One force (train length 0) on a 10 m beam without track: the rail line
  // is the beam, 0-10 m; 10 m of reach each side plus the 10 m evaluation
  // margin, plus the free vibration's travel: 3 s (the default rule
  // max(1 s, 3 periods of f0) for any f0 >= 1 Hz) at the scene's speed.
  const Scene scene = load_scene(scene_with_irregularity({{"spectrum", "fra-6"}, {"seed", 1}}));
  ASSERT_TRUE(scene.irregularity);
  const double free_m = 3.0 * scene.speed_mps;
  EXPECT_LE(scene.irregularity->x_m().front(), -10.0);
  EXPECT_GE(scene.irregularity->x_m().back(), 30.0 + free_m);
  EXPECT_LT(scene.irregularity->x_m().back(), 31.0 + free_m);
}

TEST_F(IrregularityInput, DefectsAloneOrOnAMeasuredProfileAreAccepted) {
  EXPECT_EQ(vsi("validate '" +
                scene_with_irregularity({{"defects", {{{"type", "dip"}, {"x_m", 4.0}, {"length_m", 1.0}, {"depth_m", 0.003}}}}})
                    .string() +
                "'")
                .exit_code,
            0);
  write("profile.csv", "x_m,r_m\n0,0\n10,0.001\n");
  const auto file = scene_with_irregularity(
      {{"csv", "profile.csv"}, {"defects", {{{"type", "bump"}, {"x_m", 4.0}, {"length_m", 1.0}, {"depth_m", 0.002}}}}});
  const Scene scene = load_scene(file);
  EXPECT_NEAR(scene.irregularity->at(4.5), 0.00045 + 0.002, 1e-12);
}

TEST_F(IrregularityInput, AProfileDocumentOfItsOwnMayNameASpectrum) {
  const auto profile = write_json("profile.json", {{"spectrum", "fra-6"}, {"seed", 3}, {"components", 500}});
  EXPECT_EQ(vsi("validate '" + profile.string() + "'").out, profile.string() + ": ok (irregularity)\n");
}

TEST_F(IrregularityInput, RejectsUnknownSpectrumNamingThePath) {
  const auto scene = scene_with_irregularity({{"spectrum", "german-medium"}, {"seed", 7}});
  expect_rejected(scene, "/irregularity/spectrum");
  EXPECT_NE(vsi("validate '" + scene.string() + "'").err.find("german-high"), std::string::npos)
      << "the message should list the known spectra";
}

TEST_F(IrregularityInput, RejectsNegativeSeed) {
  expect_irregularity_rejected({{"spectrum", "german-low"}, {"seed", -1}}, "/irregularity/seed");
}

TEST_F(IrregularityInput, RejectsSpectrumWithoutSeed) {
  const auto scene = scene_with_irregularity({{"spectrum", "german-low"}});
  expect_rejected(scene, "/irregularity");
  EXPECT_NE(vsi("validate '" + scene.string() + "'").err.find("'seed'"), std::string::npos);
}

TEST_F(IrregularityInput, RejectsEmptyWavelengthBand) {
  expect_irregularity_rejected({{"spectrum", "german-low"}, {"seed", 1}, {"wavelength_min_m", 25}, {"wavelength_max_m", 25}},
                               "/irregularity/wavelength_min_m");
}

TEST_F(IrregularityInput, RejectsBandOutsideTheFraSpectrumValidity) {
  expect_irregularity_rejected({{"spectrum", "fra-2"}, {"seed", 1}, {"wavelength_max_m", 500}},
                               "/irregularity/wavelength_max_m");
}

TEST_F(IrregularityInput, RejectsSampleSpacingThatWouldAlias) {
  expect_irregularity_rejected({{"spectrum", "fra-2"}, {"seed", 1}, {"sample_spacing_m", 2.0}},
                               "/irregularity/sample_spacing_m");
}

TEST_F(IrregularityInput, RejectsTwoBaseProfiles) {
  write("profile.csv", "x_m,r_m\n0,0\n10,0.001\n");
  expect_irregularity_rejected({{"csv", "profile.csv"}, {"spectrum", "fra-2"}, {"seed", 1}}, "/irregularity/spectrum");
}

TEST_F(IrregularityInput, RejectsDefectDepthNotPositiveOrAboveAMetre) {
  for (double depth : {-0.002, 0.0, 1e308}) {  // 1e308: a defect (issue 35) accepted before
    SCOPED_TRACE(depth);
    expect_irregularity_rejected(
        {{"defects", {{{"type", "dip"}, {"x_m", 4.0}, {"length_m", 1.0}, {"depth_m", depth}}}}},
        "/irregularity/defects/0/depth_m");
  }
}

TEST_F(IrregularityInput, RejectsUnknownDefectType) {
  expect_irregularity_rejected({{"defects", {{{"type", "step"}, {"x_m", 4.0}, {"length_m", 1.0}, {"depth_m", 0.001}}}}},
                               "/irregularity/defects/0/type");
}

TEST_F(IrregularityInput, RejectsDefectOutsideTheMeasuredProfile) {
  write("profile.csv", "x_m,r_m\n0,0\n10,0.001\n");
  expect_irregularity_rejected(
      {{"csv", "profile.csv"},
       {"defects", {{{"type", "dip"}, {"x_m", 2.0}, {"length_m", 1.0}, {"depth_m", 0.001}},
                    {{"type", "dip"}, {"x_m", 9.5}, {"length_m", 1.0}, {"depth_m", 0.001}}}}},
      "/irregularity/defects/1/x_m");
}

TEST_F(IrregularityInput, RejectsEmptyProfileCsvWithDefects) {
  write("profile.csv", "x_m,r_m\n");
  expect_irregularity_rejected(
      {{"csv", "profile.csv"}, {"defects", {{{"type", "dip"}, {"x_m", 2.0}, {"length_m", 1.0}, {"depth_m", 0.001}}}}},
      "/irregularity/csv");
}

}  // namespace
}  // namespace railvsi::test
