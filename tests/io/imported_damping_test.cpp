// Damping of an imported structure: EN 1991-2 Table 6.6 by bridge type (as
// bridge-2d takes it), at the longest span of the map's supports; and a
// model left undamped runs with a warning saying so (undamped overstates
// the resonant deck acceleration about twice; the norm prescribes the
// table's lower bound).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli/vsi_test_support.hpp"
#include "beam_files.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class ImportedDamping : public VsiCliTest {
 protected:
  void SetUp() override {
    VsiCliTest::SetUp();
    copy_beam_files(dir_);
  }
  // The deck's peak acceleration of the small scene on the 20 m beam.
  double peak_acceleration(const json& damping, const std::string& map, const std::string& name) const {
    json s = small_scene();
    s["structure"] = {{"import", {{"K", "beam_K_sym.mtx"}, {"M", "beam_M_sym.mtx"}, {"map", map}}}};
    if (!damping.is_null()) s["structure"]["damping"] = damping;
    s.erase("outputs");
    const VsiRun run = vsi("simulate '" + write_json(name, s).string() + "'");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    if (run.exit_code != 0) return std::numeric_limits<double>::quiet_NaN();
    return json::parse(run.out)["deck"]["max_abs_acceleration_mps2"].get<double>();
  }
  // map_index.json with supports (the spans Table 6.6 reads).
  std::string map_with_supports(const std::vector<double>& supports_x_m) const {
    json map = json::parse(read_text(dir_ / "map_index.json"));
    map["supports_x_m"] = supports_x_m;
    write_json("map_supports.json", map);
    return "map_supports.json";
  }
};

TEST_F(ImportedDamping, En1991TableGivesTheRatioOfTheBridgeTypeAtTheLongestSpan) {
  const json rayleigh = {{"f1_hz", 2.0}, {"f2_hz", 30.0}};
  auto with = [&](json extra) {
    json d = rayleigh;
    d.update(extra);
    return d;
  };
  // One 20 m span (no supports: the bridge's length): prestressed concrete
  // 1.0 % (Table 6.6, L >= 20 m). Same C, same run: equal bits.
  const double table_20 = peak_acceleration(with({{"en1991", {{"bridge_type", "prestressed-concrete"}}}}),
                                            "map_index.json", "table20.json");
  const double given_20 = peak_acceleration(with({{"ratio", 0.01}}), "map_index.json", "given20.json");
  EXPECT_EQ(table_20, given_20);
  // Spans 8 m and 12 m: the longest 12 m, steel-composite
  // 0.5 + 0.125 (20 - 12) = 1.5 %.
  const std::string map = map_with_supports({0.0, 8.0, 20.0});
  const double table_12 = peak_acceleration(with({{"en1991", {{"bridge_type", "steel-composite"}}}}), map, "t12.json");
  const double given_12 = peak_acceleration(with({{"ratio", 0.015}}), map, "g12.json");
  EXPECT_EQ(table_12, given_12);
  EXPECT_GT(given_20, 0.0);
}

TEST_F(ImportedDamping, BothOrNeitherOfRatioAndEn1991IsRefused) {
  json s = small_scene();
  s.erase("outputs");
  s["structure"] = {{"import", {{"K", "beam_K_sym.mtx"}, {"M", "beam_M_sym.mtx"}, {"map", "map_index.json"}}},
                    {"damping", {{"ratio", 0.01}, {"en1991", {{"bridge_type", "filler-beam"}}}, {"f1_hz", 2.0},
                                 {"f2_hz", 30.0}}}};
  const auto both = write_json("both.json", s);
  expect_input_error(vsi("validate '" + both.string() + "'"), both, "/structure/damping");
  s["structure"]["damping"] = {{"f1_hz", 2.0}, {"f2_hz", 30.0}};
  const auto neither = write_json("neither.json", s);
  expect_input_error(vsi("validate '" + neither.string() + "'"), neither, "/structure/damping");
}

TEST_F(ImportedDamping, AnUndampedModelRunsWithAWarning) {
  json s = small_scene();
  s.erase("outputs");
  s["structure"] = {{"import", {{"K", "beam_K_sym.mtx"}, {"M", "beam_M_sym.mtx"}, {"map", "map_index.json"}}}};
  const auto scene = write_json("undamped.json", s);
  const VsiRun checked = vsi("validate '" + scene.string() + "'");
  EXPECT_EQ(checked.exit_code, 0) << checked.err;
  EXPECT_NE(checked.err.find("warning: " + scene.string() + ": /structure/damping: no damping"), std::string::npos)
      << checked.err;
  for (const char* structure : {"fe", "modal"}) {  // the modal moving-force path has warnings of its own
    SCOPED_TRACE(structure);
    s["analysis"]["structure"] = structure;
    const VsiRun run = vsi("simulate '" + write_json("undamped-run.json", s).string() + "'");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const json summary = json::parse(run.out);
    bool warned = false;
    for (const json& w : summary["run"]["warnings"]) warned = warned || w["code"] == "structure_undamped";
    EXPECT_TRUE(warned) << run.out.substr(0, 4000);
  }
}

}  // namespace
}  // namespace railvsi::test
