// Speed sweeps that miss peaks: a study with "refine": true adds speeds
// around each peak of the deck acceleration until its neighbours are within
// 1 km/h; a governing value at the edge of the speed range is flagged.
#include <cmath>

#include "scheduler_test_support.hpp"
#include "study/speed_refinement.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using scheduler::refinement_speeds;
using scheduler::SpeedValue;

TEST(RefinementSpeeds, MidpointsAroundAnInteriorPeakOnly) {
  const std::vector<SpeedValue> curve{{100, 1.0}, {110, 3.0}, {120, 2.0}, {130, 0.5}, {140, 0.6}, {150, 0.4}};
  // 140 is a local maximum below half the largest value: not refined.
  EXPECT_EQ(refinement_speeds(curve), (std::vector<double>{105, 115}));
}

TEST(RefinementSpeeds, NothingWhenTheNeighboursAreWithinTheTolerance) {
  const std::vector<SpeedValue> curve{{183, 1.0}, {184, 3.0}, {185, 2.0}};
  EXPECT_TRUE(refinement_speeds(curve).empty());
  EXPECT_EQ(refinement_speeds({{183, 1.0}, {184, 3.0}, {186, 2.0}}), (std::vector<double>{185}));
}

TEST(RefinementSpeeds, AnEdgeMaximumIsRefinedInwardsAndAHoleBlocksRefinement) {
  EXPECT_EQ(refinement_speeds({{100, 3.0}, {110, 2.0}, {120, 1.0}}), (std::vector<double>{105}));
  EXPECT_TRUE(refinement_speeds({{100, 1.0}, {110, 3.0}, {120, std::nullopt}}).empty());
}

class SpeedRefinement : public ServiceTest {
 protected:
  // HSLM-A1 over the quick start example's 25 m span (jobs/examples/hslm-sweep.json).
  json hslm_a1_study(const json& speeds, bool refine) const {
    json doc = json::parse(read_text(std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs/examples/hslm-sweep.json"));
    doc.erase("$schema");
    doc["trains"] = json::array({"HSLM-A1"});
    doc["speeds_kmh"] = speeds;
    doc["outputs"] = {{"points", json::array({{{"name", "midspan"}, {"x_m", 12.5}}})}};
    if (refine) doc["refine"] = true;
    return doc;
  }
  // The governing deck acceleration and its speed, from vsi query --format json.
  struct Peak {
    double value = 0.0, speed_kmh = 0.0;
    bool at_edge = false;
    std::size_t jobs = 0;
  };
  Peak run(const std::string& name, const json& study) const {
    const auto file = write_json(name + ".json", study);
    const std::string db = (dir_ / (name + ".sqlite")).string();
    const VsiResult r = vsi({"run", file.string(), "--db", db, "--threads", "2"}, name);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    scheduler::Database d(db);
    scheduler::Statement s = d.prepare("SELECT id FROM studies");
    EXPECT_TRUE(s.step());
    const VsiResult q = vsi({"query", "--db", db, "--study", s.text(0).substr(0, 12), "--format", "json"}, name + "-q");
    const json out = json::parse(q.out);
    Peak p;
    p.jobs = out["jobs"].size();
    for (const json& e : out["envelope_over_speeds"])
      if (e["quantity"] == "deck_acceleration_mps2") {
        p.value = e["value"].get<double>();
        p.speed_kmh = e["governing_speed_kmh"].get<double>();
        p.at_edge = e["at_edge_of_speed_range"].get<bool>();
      }
    return p;
  }
};

TEST_F(SpeedRefinement, RefineFindsThePeakATenKmhSweepMisses) {
  const json coarse_speeds = {{"from", 150}, {"to", 250}, {"step", 10}};
  const Peak coarse = run("coarse", hslm_a1_study(coarse_speeds, false));
  const Peak refined = run("refined", hslm_a1_study(coarse_speeds, true));
  const Peak fine = run("fine", hslm_a1_study({{"from", 175}, {"to", 195}, {"step", 1}}, false));
  std::printf("coarse %.4f m/s2 at %g km/h (%zu jobs); refined %.4f at %g (%zu jobs); 1 km/h sweep %.4f at %g\n",
              coarse.value, coarse.speed_kmh, coarse.jobs, refined.value, refined.speed_kmh, refined.jobs, fine.value,
              fine.speed_kmh);
  std::fflush(stdout);  // before the next fork copies the buffer
  // The 10 km/h sweep misses the resonance peak (v = f0 D / 2, about 184 km/h).
  EXPECT_LT(coarse.value, 0.8 * fine.value);
  // Refined: the speed to within the stated 1 km/h of the 1 km/h sweep's
  // (measured: 183.75 against 184 km/h), the value within 0.2 % of it
  // (measured: 2.9760 against 2.9785 m/s2, -0.08 %; the two sweeps sample
  // the same peak at different speeds, 0.25 km/h apart).
  EXPECT_NEAR(refined.speed_kmh, fine.speed_kmh, 1.0);
  EXPECT_NEAR(refined.value, fine.value, 0.002 * fine.value);
  EXPECT_GT(refined.jobs, coarse.jobs);
  EXPECT_FALSE(refined.at_edge);

  // A second run of the refined study adds nothing: the peaks are resolved.
  const Peak again = run("refined", hslm_a1_study(coarse_speeds, true));
  EXPECT_EQ(again.jobs, refined.jobs);
}

TEST_F(SpeedRefinement, AGoverningValueAtTheEdgeOfTheSpeedRangeIsFlagged) {
  const Peak p = run("edge", hslm_a1_study({{"from", 150}, {"to", 180}, {"step", 10}}, false));
  EXPECT_TRUE(p.at_edge);
  EXPECT_EQ(p.speed_kmh, 180.0);
  const auto db = (dir_ / "edge.sqlite").string();
  scheduler::Database d(db);
  scheduler::Statement s = d.prepare("SELECT id FROM studies");
  ASSERT_TRUE(s.step());
  const VsiResult table = vsi({"query", "--db", db, "--study", s.text(0).substr(0, 12)});
  EXPECT_NE(table.out.find("EDGE"), std::string::npos) << table.out;
}

}  // namespace
}  // namespace railvsi::test
