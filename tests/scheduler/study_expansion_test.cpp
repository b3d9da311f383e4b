// A study expands into trains x speeds x profiles (x seeds) jobs with ids
// that depend only on what each scene means; a study with any error
// produces no job and names the JSON path of the error.
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "core/sha256.hpp"
#include "scheduler_test_support.hpp"
#include "study/canonical_json.hpp"
#include "study/study_plan.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using scheduler::expand_study;
using scheduler::StudyPlan;

StudyPlan expand(const json& doc, const scheduler::ExpandOptions& options = {}) {
  return expand_study(doc, std::filesystem::temp_directory_path(), "study.json", options);
}

// The InputError of expanding `doc`, or a failure when there is none.
InputError expansion_error(const json& doc, const scheduler::ExpandOptions& options = {}) {
  try {
    expand(doc, options);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "the study was accepted";
  return InputError("", "");
}

TEST(StudyExpansion, JobCountIsTrainsTimesSpeedsTimesProfilesAndSeeds) {
  json doc = tiny_study();  // 2 trains, speeds 100..300 step 50: 5 speeds
  doc["irregularities"] = json::parse(R"([null,
      {"irregularity": {"spectrum": "german-low", "seed": 0}, "seeds": [1, 2, 3]},
      {"x_m": [0, 5, 10], "r_m": [0, 0.001, 0]}])");
  const StudyPlan plan = expand(doc);
  EXPECT_EQ(plan.jobs.size(), 2u * 5u * 5u);
  std::set<std::string> ids, labels;
  for (const auto& j : plan.jobs) {
    ids.insert(j.id);
    labels.insert(j.irregularity);
  }
  EXPECT_EQ(ids.size(), plan.jobs.size()) << "job ids must be distinct";
  EXPECT_EQ(labels, (std::set<std::string>{"none", "german-low seed 1", "german-low seed 2", "german-low seed 3",
                                            "profile 3"}));
}

TEST(StudyExpansion, SpeedRangeIncludesBothEndsWithoutRoundOff) {
  json doc = tiny_study();
  doc["trains"] = json::array({doc["trains"][0]});
  doc["speeds_kmh"] = {{"from", 100}, {"to", 100.3}, {"step", 0.1}};
  const StudyPlan plan = expand(doc);
  ASSERT_EQ(plan.jobs.size(), 4u);
  EXPECT_EQ(plan.jobs[3].speed_kmh, 100.3);  // 100 + 3 * 0.1 = 100.30000000000001 before rounding
  doc["speeds_kmh"] = json::array({120, 180.5});
  const StudyPlan listed = expand(doc);
  ASSERT_EQ(listed.jobs.size(), 2u);
  EXPECT_EQ(listed.jobs[1].speed_kmh, 180.5);
}

TEST(StudyExpansion, SpeedRangeWhoseEndIsOffTheStepKeepsItsEnd) {
  // 200, 250, 300, 350 on the step, then the range's end 380: the top of a
  // range is the maximum design speed, never dropped.
  json doc = tiny_study();
  doc["trains"] = json::array({doc["trains"][0]});
  doc["speeds_kmh"] = {{"from", 200}, {"to", 380}, {"step", 50}};
  const StudyPlan plan = expand(doc);
  std::vector<double> speeds;
  for (const scheduler::JobSpec& j : plan.jobs) speeds.push_back(j.speed_kmh);
  EXPECT_EQ(speeds, (std::vector<double>{200, 250, 300, 350, 380}));
}

TEST(StudyExpansion, AStudyWithoutAnalysisRunsItsDefaults) {
  // A user had to write "analysis": {} for a study to be accepted.
  json with = tiny_study();
  with["analysis"] = json::object();
  json without = with;
  without.erase("analysis");
  const StudyPlan a = expand(with), b = expand(without);
  ASSERT_EQ(a.jobs.size(), b.jobs.size());
  for (std::size_t i = 0; i < a.jobs.size(); ++i) EXPECT_EQ(a.jobs[i].id, b.jobs[i].id) << i;
}

TEST(StudyExpansion, IdsAreHashesOfCanonicalScenesAndStableUnderReformatting) {
  const StudyPlan a = expand(tiny_study());
  // The same study written differently: keys in another order, 1.0e-3 as
  // 0.001, 10 as 10.0.
  json b_doc = json::parse(tiny_study().dump());
  b_doc["analysis"] = json::parse(R"({"dt_s": 0.001})");
  b_doc["structure"]["spans_m"] = json::array({10.0});
  const StudyPlan b = expand(b_doc);
  ASSERT_EQ(a.jobs.size(), b.jobs.size());
  EXPECT_EQ(a.id, b.id);
  for (std::size_t k = 0; k < a.jobs.size(); ++k) {
    EXPECT_EQ(a.jobs[k].id, b.jobs[k].id);
    EXPECT_EQ(a.jobs[k].id, scheduler::sha256_hex(a.jobs[k].scene));
    EXPECT_EQ(a.jobs[k].scene, scheduler::canonical_text(json::parse(a.jobs[k].scene)));
  }
  // A different study has a different id.
  json c_doc = tiny_study();
  c_doc["name"] = "other";
  EXPECT_NE(expand(c_doc).id, a.id);
}

TEST(StudyExpansion, CanonicalTextSortsKeysAndNormalizesNumbers) {
  EXPECT_EQ(scheduler::canonical_text(json::parse(R"({"b": 1.0, "a": [2.50, -0.0, 1e2, 0.1]})")),
            R"({"a":[2.5,0,100,0.1],"b":1})");
}

TEST(StudyExpansion, NumberSlotWritesTheCanonicalTextOfTheDocumentWithThatNumber) {
  const json doc = json::parse(R"({"z": {"speed_kmh": [1, "x"]}, "speed_kmh": 0, "a": 0.25, "m": null})");
  const auto slot = scheduler::CanonicalNumberSlot::make(doc, "speed_kmh");
  ASSERT_TRUE(slot.has_value());
  for (double x : {100.0, 100.30000000000001, 180.5, -0.0, 1e-7, 1e21, 123.456, 400.0 / 3.0}) {
    json with = doc;
    with["speed_kmh"] = x;
    EXPECT_EQ(slot->text(x), scheduler::canonical_text(with)) << x;
  }
  // The slot's mark met elsewhere in the document: no slot.
  json marked = doc;
  marked["m"] = "\x01railvsi number slot\x01";
  EXPECT_FALSE(scheduler::CanonicalNumberSlot::make(marked, "speed_kmh").has_value());
  EXPECT_FALSE(scheduler::CanonicalNumberSlot::make(json::array({1}), "speed_kmh").has_value());
}

TEST(StudyExpansion, ScenesOfOneTrainDifferInTheirSpeedAloneAndAreCanonical) {
  // Non-integral speeds and two profiles: each scene is written from its
  // train's text around the speed, and reads back as the scene of its job.
  json doc = tiny_study();
  doc["speeds_kmh"] = {{"from", 100.5}, {"to", 103.2}, {"step", 0.9}};
  doc["irregularities"] = json::parse(R"([null, {"x_m": [0, 5, 10], "r_m": [0, 0.001, 0]}])");
  const StudyPlan plan = expand(doc);
  ASSERT_EQ(plan.jobs.size(), 2u * 4u * 2u);
  std::map<std::string, json> without_speed;
  for (const scheduler::JobSpec& j : plan.jobs) {
    json scene = json::parse(j.scene);
    EXPECT_EQ(j.scene, scheduler::canonical_text(scene));
    EXPECT_EQ(j.id, scheduler::sha256_hex(j.scene));
    EXPECT_EQ(scene.at("speed_kmh").get<double>(), j.speed_kmh);
    scene.erase("speed_kmh");
    const auto [it, first] = without_speed.try_emplace(j.train + "/" + j.irregularity, scene);
    if (!first) {
      EXPECT_EQ(it->second, scene) << j.train;
    }
  }
}

TEST(StudyExpansion, ScenesCarryTheirOwnTimeStepWhereItChangesWithTheSpeed) {
  // The FE rung with the time step left to the policy, 0.1 m rail
  // elements: a wheel's travel per step bounds dt, so it shrinks with the
  // speed, and the scene text around the speed is made again for each dt.
  json doc = tiny_study();
  doc["analysis"].erase("dt_s");
  doc["structure"]["deck"]["EI_Nm2"] = 5.0e8;
  doc["structure"]["element_length_m"] = 0.1;
  doc["fidelity"] = {{"model", "moving_forces"}, {"structure", "fe"}};
  doc["speeds_kmh"] = {{"from", 100}, {"to", 400}, {"step", 50}};
  const StudyPlan plan = expand(doc);
  std::map<std::string, std::set<double>> steps_of_train;
  for (const scheduler::JobSpec& j : plan.jobs) {
    const json scene = json::parse(j.scene);
    EXPECT_EQ(j.scene, scheduler::canonical_text(scene));
    EXPECT_EQ(j.id, scheduler::sha256_hex(j.scene));
    EXPECT_EQ(scene.at("speed_kmh").get<double>(), j.speed_kmh);
    EXPECT_EQ(scene.at("analysis").at("dt_s").get<double>(), j.dt_s) << j.train << " at " << j.speed_kmh;
    steps_of_train[j.train].insert(j.dt_s);
  }
  for (const auto& [train, steps] : steps_of_train) EXPECT_GE(steps.size(), 2u) << train << ": one dt for all speeds";
}

TEST(StudyExpansion, BadTrainStiffnessIsReportedAtItsPathInTheStudy) {
  json doc = tiny_study();
  doc["trains"].push_back({{"name", "bad"}, {"vehicles", json::array({car(-1.0)})}});
  const InputError e = expansion_error(doc);
  EXPECT_EQ(e.json_path(), "/trains/2/vehicles/0/primary/k_N_per_m");
  EXPECT_EQ(e.file(), "study.json");
}

TEST(StudyExpansion, ModalRunBeyondTheStepLimitIsRefusedAtSubmission) {
  // A very stiff, light deck: its code frequency sets a modal dt of about
  // 1e-7 s, tens of millions of steps. The workers kept every step's deck
  // response (3.9 GB) or failed with bad_alloc; now the submission refuses
  // it as it does on the FE rungs.
  json doc = tiny_study();
  doc["analysis"].erase("dt_s");
  doc["structure"]["deck"] = {{"EI_Nm2", 1.0e16}, {"mass_kg_per_m", 100}};
  doc["speeds_kmh"] = json::array({300, 200});  // judged at its slowest speed, whatever the order
  const InputError e = expansion_error(doc);
  EXPECT_EQ(e.json_path(), "/analysis/dt_s");
  EXPECT_NE(std::string(e.what()).find("steps (limit 2e+06)"), std::string::npos) << e.what();
  EXPECT_EQ(e.file(), "study.json");
  // A step planned from a tolerance far below any need is the tolerance's fault.
  json strict = tiny_study();
  strict["analysis"].erase("dt_s");
  strict["speeds_kmh"] = json::array({200});
  strict["accuracy"] = {{"tolerance", 1e-12}};
  const InputError t = expansion_error(strict);
  EXPECT_EQ(t.json_path(), "/accuracy/tolerance");
  EXPECT_NE(std::string(t.what()).find("planned from this tolerance"), std::string::npos) << t.what();
}

TEST(StudyExpansion, TheSameTrainTwiceIsRefusedAtItsSecondIndex) {
  json doc = tiny_study();
  doc["trains"].push_back(doc["trains"][0]);
  const InputError e = expansion_error(doc);
  EXPECT_EQ(e.json_path(), "/trains/2");
  EXPECT_NE(std::string(e.what()).find("the same train as /trains/0"), std::string::npos) << e.what();
  // Two trains that differ but share a name are two trains.
  json renamed = tiny_study();
  json other = renamed["trains"][0];
  other["moving_forces"][0]["load_N"] = 2.0e5;
  renamed["trains"].push_back(other);
  EXPECT_EQ(expand(renamed).jobs.size(), 3u * 5u);
}

TEST(StudyExpansion, UnknownLibraryTrainIsReportedAtItsIndex) {
  json doc = tiny_study();
  doc["trains"].push_back("NO-SUCH-TRAIN");
  const InputError e = expansion_error(doc);
  EXPECT_EQ(e.json_path(), "/trains/2");
  EXPECT_NE(std::string(e.what()).find("NO-SUCH-TRAIN"), std::string::npos) << e.what();
}

TEST(StudyExpansion, BadProfileIsReportedAtItsIndex) {
  json doc = tiny_study();
  doc["irregularities"] = json::parse(R"([null, {"x_m": [0, 5, 4], "r_m": [0, 0.001, 0]}])");
  const InputError e = expansion_error(doc);
  EXPECT_TRUE(e.json_path().starts_with("/irregularities/1")) << e.json_path() << ": " << e.what();
}

TEST(StudyExpansion, SeedsNeedASpectrum) {
  json doc = tiny_study();
  doc["irregularities"] = json::parse(R"([{"irregularity": {"x_m": [0, 5], "r_m": [0, 0]}, "seeds": [1]}])");
  EXPECT_EQ(expansion_error(doc).json_path(), "/irregularities/0/irregularity");
}

TEST(StudyExpansion, EmptySpeedRangeIsRefused) {
  json doc = tiny_study();
  doc["speeds_kmh"] = {{"from", 300}, {"to", 200}, {"step", 10}};
  EXPECT_EQ(expansion_error(doc).json_path(), "/speeds_kmh/to");
}

TEST(StudyExpansion, MoreThanTheJobLimitIsRefusedUnlessAllowed) {
  json doc = tiny_study();  // 2 trains x 5 speeds = 10 jobs
  scheduler::ExpandOptions small;
  small.max_jobs = 9;
  const InputError e = expansion_error(doc, small);
  EXPECT_NE(std::string(e.what()).find("--allow-large"), std::string::npos) << e.what();
  small.allow_large = true;
  EXPECT_EQ(expand(doc, small).jobs.size(), 10u);
  // The default limit is 100,000: refused before anything is expanded.
  doc["speeds_kmh"] = {{"from", 1}, {"to", 50001}, {"step", 1}};
  EXPECT_EQ(expansion_error(doc).json_path(), "/speeds_kmh");
}

TEST(StudyExpansion, SchemaErrorsNameTheirPath) {
  json doc = tiny_study();
  doc["speeds_kmh"] = {{"from", 100}, {"to", 200}, {"step", 0}};
  EXPECT_EQ(expansion_error(doc).json_path(), "/speeds_kmh/step");
  doc = tiny_study();
  doc["checks"] = {{"max_unloading_ratio", 1.5}};
  EXPECT_EQ(expansion_error(doc).json_path(), "/checks/max_unloading_ratio");
}

TEST(StudyExpansion, JobsWithoutDtGetTheTimeStepPolicysRungAndReason) {
  json doc = tiny_study();
  doc["analysis"].erase("dt_s");
  doc["fidelity"] = {{"model", "moving_forces"}, {"structure", "fe"}};  // the policy is the FE rung's
  const StudyPlan plan = expand(doc);
  for (const auto& j : plan.jobs) {
    // A rung of the ladder 2 ms / 2^k.
    const double k = std::log2(2.0e-3 / j.dt_s);
    EXPECT_NEAR(k, std::round(k), 1e-9) << j.dt_s;
    EXPECT_NE(j.dt_reason.find("ladder"), std::string::npos) << j.dt_reason;
    EXPECT_EQ(json::parse(j.scene)["analysis"]["dt_s"].get<double>(), j.dt_s);
  }
}

TEST(StudyExpansion, PlannerPinsTheModalRungWithItsSamplingStepInEveryJob) {
  json doc = tiny_study();
  doc["analysis"].erase("dt_s");
  doc["accuracy"] = {{"tolerance", 0.01}};
  const StudyPlan plan = expand(doc);
  ASSERT_FALSE(plan.jobs.empty());
  for (const auto& j : plan.jobs) {
    EXPECT_EQ(j.rung, "moving_forces/modal");
    const json scene = json::parse(j.scene);
    EXPECT_EQ(scene["fidelity"]["model"], "moving_forces");
    EXPECT_EQ(scene["fidelity"]["structure"], "modal");
    // 1.2 x the code frequency, and 16 samples per period of it (peaks
    // refined: 1 - cos(pi/8) (1 + sin^2(pi/8) / 2) < 1 % at 8, and the
    // recurrence's floor 16 sqrt(0.01 / 0.01) = 16).
    EXPECT_NEAR(scene["fidelity"]["modal_cutoff_hz"].get<double>(), 1.2 * j.cutoff_hz, 1e-9);
    EXPECT_LE(j.dt_s, 1.0 / (16.0 * j.cutoff_hz));
    EXPECT_GT(j.dt_s, 0.99 / (16.0 * j.cutoff_hz));
    EXPECT_NE(j.dt_reason.find("modal rung"), std::string::npos) << j.dt_reason;
    EXPECT_EQ(j.operator_key, plan.jobs.front().operator_key) << "one basis and pass for the whole structure";
  }
}

TEST(StudyExpansion, WheelUnloadingAskedPinsTheEscalationAtHalfTheTimeStep) {
  json doc = tiny_study();
  doc["trains"] = json::array({one_car_train()});
  doc["speeds_kmh"] = json::array({200});
  doc["asks"] = {"deck", "wheel_unloading"};
  const StudyPlan wheels = expand(doc);
  ASSERT_EQ(wheels.jobs.size(), 1u);
  const json pinned = json::parse(wheels.jobs[0].scene)["fidelity"];
  EXPECT_EQ(pinned["contact_law"], "linear-hertz");
  EXPECT_EQ(pinned["escalate_below_fraction"].get<double>(), 0.7);
  EXPECT_EQ(pinned["escalation_dt_factor"].get<double>(), 0.5);
  doc["asks"] = {"deck", "comfort"};
  const json deck_and_comfort = json::parse(expand(doc).jobs[0].scene)["fidelity"];
  EXPECT_EQ(deck_and_comfort["escalate_below_fraction"].get<double>(), 0.5);
  EXPECT_FALSE(deck_and_comfort.contains("escalation_dt_factor"));
}

TEST(StudyExpansion, PinnedInteractionForALoadModelIsRefusedAtItsPath) {
  json doc = tiny_study();
  doc["fidelity"] = {{"model", "interaction"}, {"structure", "fe"}};
  try {
    expand(doc);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/fidelity/model") << e.describe();
  }
}

}  // namespace
}  // namespace railvsi::test
