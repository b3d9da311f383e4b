// Bridges from designer inputs: what the scene loader accepts and refuses
// for the deck stiffness and the damping.
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class BridgeInputs : public VsiCliTest {};

TEST_F(BridgeInputs, DeckGivenByFirstFrequencyAndDampingByBridgeTypeValidates) {
  json scene = small_scene();
  scene["structure"]["deck"] = {{"mass_kg_per_m", 9000.0}, {"first_frequency_hz", 7.5}};
  scene["structure"]["damping"] = {{"en1991", {{"bridge_type", "filler-beam"}}}, {"f2_hz", 40.0}};
  const auto file = write_json("scene.json", scene);
  const VsiRun run = vsi("validate '" + file.string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.err;
}

TEST_F(BridgeInputs, RejectsStiffnessGivenTwice) {
  json scene = small_scene();
  scene["structure"]["deck"]["first_frequency_hz"] = 5.0;
  expect_rejected(write_json("scene.json", scene), "/structure/deck");
}

TEST_F(BridgeInputs, RejectsDeckWithoutStiffness) {
  json scene = small_scene();
  scene["structure"]["deck"].erase("EI_Nm2");
  expect_rejected(write_json("scene.json", scene), "/structure/deck");
}

TEST_F(BridgeInputs, RejectsFirstFrequencyForAContinuousGirderOfUnequalSpans) {
  json scene = small_scene();
  scene["structure"]["spans_m"] = {8.0, 10.0};
  scene["structure"]["continuous"] = true;
  scene["structure"]["deck"] = {{"mass_kg_per_m", 9000.0}, {"first_frequency_hz", 7.5}};
  expect_rejected(write_json("scene.json", scene), "/structure/deck/first_frequency_hz");
}

TEST_F(BridgeInputs, RejectsDampingGivenBothWays) {
  json scene = small_scene();
  scene["structure"]["damping"]["en1991"] = {{"bridge_type", "steel-composite"}};
  expect_rejected(write_json("scene.json", scene), "/structure/damping");
}

TEST_F(BridgeInputs, RejectsUnknownBridgeTypeNamingIt) {
  json scene = small_scene();
  scene["structure"]["damping"] = {{"en1991", {{"bridge_type", "timber"}}}};
  expect_rejected(write_json("scene.json", scene), "/structure/damping/en1991/bridge_type");
}

}  // namespace
}  // namespace railvsi::test
