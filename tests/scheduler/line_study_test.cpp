// A whole line in one study: "structures" (a list of named structures or a
// CSV of a line's bridges) as a dimension beside trains x speeds x
// profiles. A bridge's jobs are the jobs of a study of it alone, so its
// values equal that study's to the bit; a structure listed twice is one
// set of jobs; the query and the report read the study per bridge; and a
// shard keeps the planned rung of its jobs.
#include <stdlib.h>

#include <bit>
#include <cstdint>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <tuple>

#include "core/input_error.hpp"
#include "analysis/static_influence.hpp"
#include "query/bridge_results.hpp"
#include "query/study_report.hpp"
#include "query/stored_statics.hpp"
#include "simulation/static_equilibrium.hpp"
#include "scheduler_test_support.hpp"
#include "study/study_plan.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

// tiny_study()'s 10 m span, and a 12 m one.
json span(double length_m) {
  json s = tiny_study()["structure"];
  s["spans_m"] = {length_m};
  return s;
}

// Bridges A (10 m), B (12 m) and C (10 m again, under another name).
json line_study() {
  json doc = tiny_study();
  doc.erase("structure");
  doc["name"] = "tiny line";
  doc["structures"] = json::array({{{"name", "A"}, {"structure", span(10)}},
                                   {{"name", "B"}, {"structure", span(12)}},
                                   {{"name", "C"}, {"structure", span(10)}}});
  return doc;
}

json one_bridge_study(double length_m) {
  json doc = tiny_study();
  doc["structure"] = span(length_m);
  return doc;
}

scheduler::StudyPlan expand(const json& doc, const std::filesystem::path& dir = std::filesystem::temp_directory_path()) {
  return scheduler::expand_study(doc, dir, "line.json");
}

TEST(LineStudy, StructuresAreADimensionAndABridgeListedTwiceSharesItsJobs) {
  const scheduler::StudyPlan plan = expand(line_study());
  EXPECT_EQ(plan.structures, (std::vector<std::string>{"A", "B", "C"}));
  // 2 distinct structures x 2 trains x 5 speeds: A and C are one structure.
  ASSERT_EQ(plan.jobs.size(), 20u);
  std::map<std::vector<int>, int> on;
  for (const auto& j : plan.jobs) ++on[j.structures];
  EXPECT_EQ(on, (std::map<std::vector<int>, int>{{{0, 2}, 10}, {{1}, 10}}));
  // Each bridge's jobs are the jobs (the ids) of a study of it alone.
  for (const auto& [length_m, index] : {std::pair{10.0, 0}, std::pair{12.0, 1}}) {
    std::set<std::string> alone, in_line;
    for (const auto& j : expand(one_bridge_study(length_m)).jobs) alone.insert(j.id);
    for (const auto& j : plan.jobs)
      if (j.structures.front() == index) in_line.insert(j.id);
    EXPECT_EQ(in_line, alone) << length_m << " m";
  }
}

TEST(LineStudy, StructureAndStructuresTogetherOrNeitherAreRefused) {
  json both = line_study();
  both["structure"] = span(10);
  try {
    expand(both);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/structures");
    EXPECT_EQ(e.file(), "line.json");
  }
  json neither = line_study();
  neither.erase("structures");
  EXPECT_THROW(expand(neither), InputError);
  json twice = line_study();
  twice["structures"][2]["name"] = "A";
  try {
    expand(twice);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/structures/2/name");
  }
  // A bad value inside a bridge is reported at the bridge.
  json bad = line_study();
  bad["structures"][1]["structure"]["deck"]["EI_Nm2"] = -1.0;
  try {
    expand(bad);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/structures/1/structure/deck/EI_Nm2") << e.what();
  }
}

class LineStudyFiles : public ServiceTest {
 protected:
  std::filesystem::path write_text(const std::string& name, const std::string& text) const {
    const auto file = dir_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  std::string study_id(const std::string& db) const {
    scheduler::Database d(db);
    scheduler::Statement s = d.prepare("SELECT id FROM studies");
    EXPECT_TRUE(s.step());
    return s.text(0);
  }
};

TEST_F(LineStudyFiles, ACsvOfBridgesIsOneStructurePerLineAndABadLineNamesFileAndLine) {
  write_text("line.csv",
             "# two bridges\nname,spans_m,EI_Nm2,mass_kg_per_m,damping,output_points_m,continuous\n"
             "P1,10,5.0e9,8000,0.01,2.5;5,\n"
             "P2,8 8,4.0e9,7000,prestressed-concrete,,true\n");
  json doc = tiny_study();
  doc.erase("structure");
  doc.erase("outputs");
  doc["structures"] = {{"csv", "line.csv"}};
  const scheduler::StudyPlan plan = expand(doc, dir_);
  ASSERT_EQ(plan.structures, (std::vector<std::string>{"P1", "P2"}));
  std::map<int, json> scenes;
  for (const auto& j : plan.jobs) scenes.emplace(j.structures.front(), json::parse(j.scene));
  const json& p1 = scenes.at(0);
  EXPECT_EQ(p1["structure"]["spans_m"], json::array({10.0}));
  EXPECT_EQ(p1["structure"]["deck"]["EI_Nm2"], 5.0e9);
  EXPECT_EQ(p1["structure"]["damping"]["ratio"], 0.01);
  EXPECT_EQ(p1["outputs"]["points"][1]["x_m"], 5.0);
  const json& p2 = scenes.at(1);
  EXPECT_EQ(p2["structure"]["spans_m"], json::array({8.0, 8.0}));
  EXPECT_EQ(p2["structure"]["continuous"], true);
  EXPECT_EQ(p2["structure"]["damping"]["en1991"]["bridge_type"], "prestressed-concrete");
  EXPECT_FALSE(p2.contains("outputs"));  // the midspans by default

  write_text("line.csv", "name,spans_m,EI_Nm2,mass_kg_per_m,damping\nP1,10,5.0e9,8000,0.01\nP2,10,stiff,8000,0.01\n");
  try {
    expand(doc, dir_);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/structures/csv");
    EXPECT_EQ(e.file(), "line.json");
    EXPECT_NE(std::string(e.what()).find("line.csv:3: EI_Nm2"), std::string::npos) << e.what();
  }
  // vsi submit: exit 2, the file and the path named, nothing written.
  const auto study = write_json("line.json", doc);
  const std::string db = (dir_ / "l.sqlite").string();
  const VsiResult r = vsi({"submit", study.string(), "--db", db}, "submit");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("/structures/csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("line.csv:3"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(db));
}

TEST_F(LineStudyFiles, ABridgeOfALineHasTheValuesOfItsOwnStudyToTheBitAndTheLineTableOneRowPerBridge) {
  const std::string line_db = (dir_ / "line.sqlite").string(), alone_db = (dir_ / "alone.sqlite").string();
  ASSERT_EQ(vsi({"run", write_json("line.json", line_study()).string(), "--db", line_db, "--threads", "2"}, "l").exit_code, 0);
  ASSERT_EQ(vsi({"run", write_json("b.json", one_bridge_study(12)).string(), "--db", alone_db}, "b").exit_code, 0);
  const std::string line = study_id(line_db), alone = study_id(alone_db);
  {
    scheduler::Database d(line_db);
    EXPECT_EQ(count_rows(d, "SELECT count(*) FROM jobs"), 20);  // A and C computed once
    EXPECT_EQ(count_rows(d, "SELECT count(*) FROM study_structures"), 30);
  }
  const VsiResult in_line = vsi({"query", "--db", line_db, "--study", line, "--structure", "B", "--format", "csv"}, "q1");
  const VsiResult own = vsi({"query", "--db", alone_db, "--study", alone, "--format", "csv"}, "q2");
  ASSERT_EQ(in_line.exit_code, 0) << in_line.err;
  ASSERT_EQ(own.exit_code, 0) << own.err;
  // Every value printed with the shortest text that reads back to the same
  // double: equal text is equal bits. Drop the line's structure column.
  const std::string without_column = std::regex_replace(in_line.out, std::regex("^[^,\n]*,", std::regex::multiline), "");
  EXPECT_EQ(without_column, own.out);
  // Guards against two empty outputs comparing equal: 10 jobs, each with values.
  EXPECT_GT(std::count(own.out.begin(), own.out.end(), '\n'), 10 * 4) << own.out;

  const VsiResult unknown = vsi({"query", "--db", line_db, "--study", line, "--structure", "Z"}, "q3");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("'A', 'B', 'C'"), std::string::npos) << unknown.err;

  const VsiResult table = vsi({"query", "--db", line_db, "--study", line, "--line", "--format", "json"}, "q4");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  const json rows = json::parse(table.out);
  ASSERT_EQ(rows.size(), 3u);
  std::vector<std::string> names;
  for (const json& r : rows) names.push_back(r["structure"]);
  EXPECT_EQ(names, (std::vector<std::string>{"A", "B", "C"}));
  // B's governing deck acceleration is the largest value of its own study.
  double largest = -1.0;
  std::string at;
  const VsiResult own_json = vsi({"query", "--db", alone_db, "--study", alone, "--format", "json"}, "q5");
  ASSERT_EQ(own_json.exit_code, 0) << own_json.err;
  const json own_jobs = json::parse(own_json.out)["jobs"];
  ASSERT_EQ(own_jobs.size(), 10u);
  for (const json& j : own_jobs) {
    const double a = j["envelopes"]["deck_acceleration_mps2"]["all"].get<double>();
    if (a > largest) largest = a, at = j["train"].get<std::string>();
  }
  bool seen = false;
  for (const json& c : rows[1]["checks"])
    if (c["id"] == "deck_acceleration") {
      seen = true;
      EXPECT_EQ(c["value"].get<double>(), largest);
      EXPECT_EQ(c["train"], at);
    }
  EXPECT_TRUE(seen) << rows.dump();

  const auto html = dir_ / "line.html";
  ASSERT_EQ(vsi({"report", "--db", line_db, "--study", line, "--no-histories", "--out", html.string()}, "r").exit_code, 0);
  const std::string text = read_text(html);
  EXPECT_NE(text.find("Line summary"), std::string::npos);
  for (const char* name : {"2.1 A", "2.2 B", "2.3 C"}) EXPECT_NE(text.find(name), std::string::npos) << name;

  // The JSON report has, like the HTML, the checks of each bridge with a
  // table per train: B's deck acceleration per train is the largest value
  // of that train in B's own study (read with vsi query).
  const VsiResult report_json = vsi({"report", "--db", line_db, "--study", line, "--no-histories", "--format", "json"}, "rj");
  ASSERT_EQ(report_json.exit_code, 0) << report_json.err;
  const json structures = json::parse(report_json.out).at("structures");
  ASSERT_EQ(structures.size(), 3u);
  EXPECT_EQ(structures[0]["name"], "A");
  EXPECT_EQ(structures[2]["name"], "C");
  const json& b = structures[1];
  EXPECT_EQ(b["name"], "B");
  std::map<std::string, double> largest_of_train;
  for (const json& j : own_jobs) {
    double& m = largest_of_train[j["train"].get<std::string>()];
    m = std::max(m, j["envelopes"]["deck_acceleration_mps2"]["all"].get<double>());
  }
  ASSERT_EQ(largest_of_train.size(), 2u);
  int tables = 0;
  for (const json& c : b["checks"]) {
    if (c["id"] != "deck_acceleration") continue;
    EXPECT_EQ(c["governing"]["value"].get<double>(), largest);
    for (const json& t : c["per_train"]) {
      ++tables;
      EXPECT_EQ(t["governing"]["value"].get<double>(), largest_of_train.at(t["train"].get<std::string>())) << t.dump();
      EXPECT_EQ(t["cases"], 5);  // 5 speeds
    }
  }
  EXPECT_EQ(tables, 2) << b.dump();
}

TEST_F(LineStudyFiles, AShardedLineMergesIntoTheAnswersOfAnUnshardedRun) {
  const auto study = write_json("line.json", line_study());
  const std::string whole = (dir_ / "whole.sqlite").string(), merged = (dir_ / "merged.sqlite").string();
  ASSERT_EQ(vsi({"run", study.string(), "--db", whole}, "run").exit_code, 0);
  const auto out = dir_ / "shards";
  ASSERT_EQ(vsi({"shard", study.string(), "--shards", "2", "--out", out.string()}, "shard").exit_code, 0);
  for (int k = 0; k < 2; ++k)
    ASSERT_EQ(vsi({"work", "--db", (out / ("shard-" + std::to_string(k) + ".sqlite")).string()}, "work").exit_code, 0);
  ASSERT_EQ(vsi({"merge", (out / "shard-0.sqlite").string(), (out / "shard-1.sqlite").string(), "--into", merged},
                "merge").exit_code, 0);
  const std::string id = study_id(whole);
  for (const char* what : {"--line", "--wide"}) {
    std::vector<std::string> args{"query", "--db", whole, "--study", id, "--format", "csv", what};
    const VsiResult a = vsi(args, "a");
    args[2] = merged;
    const VsiResult b = vsi(args, "b");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_NE(a.out.find("\nC,"), std::string::npos) << what << "\n" << a.out;  // every bridge, by name
    EXPECT_EQ(a.out, b.out) << what;
  }
}

// The line table reads the study bridge by bridge (BridgeReader), each
// bridge's jobs as `--structure NAME` reads them with study_results; a
// filter that keeps every job judges them through study_results instead.
TEST_F(LineStudyFiles, ReadBridgeByBridgeTheLineIsWhatTheWholeStudyReadAtOnceGives) {
  const std::string db = (dir_ / "line.sqlite").string();
  ASSERT_EQ(vsi({"run", write_json("line.json", line_study()).string(), "--db", db}, "run").exit_code, 0);
  const std::string id = study_id(db);
  for (const char* format : {"table", "csv", "json"}) {
    const VsiResult bridge_by_bridge = vsi({"query", "--db", db, "--study", id, "--line", "--format", format}, "a");
    // --speed-min at the study's lowest speed keeps every job.
    const VsiResult at_once =
        vsi({"query", "--db", db, "--study", id, "--line", "--format", format, "--speed-min", "0.1"}, "b");
    ASSERT_EQ(bridge_by_bridge.exit_code, 0) << bridge_by_bridge.err;
    ASSERT_EQ(at_once.exit_code, 0) << at_once.err;
    EXPECT_NE(bridge_by_bridge.out.find("C"), std::string::npos) << bridge_by_bridge.out;
    EXPECT_EQ(bridge_by_bridge.out, at_once.out) << format;
  }

  scheduler::Database d(db, scheduler::OpenMode::kReadOnly);
  const std::vector<std::string> names = scheduler::study_structure_names(d, id);
  ASSERT_EQ(names, (std::vector<std::string>{"A", "B", "C"}));
  for (const auto fields : {scheduler::BridgeFields::kAll, scheduler::BridgeFields::kVerdicts}) {
    scheduler::BridgeReader reader(d, id, fields);
    std::string name;
    std::vector<scheduler::JobResult> jobs;
    for (const std::string& expected : names) {
      ASSERT_TRUE(reader.next(name, jobs));
      EXPECT_EQ(name, expected);
      const auto own = scheduler::study_results(d, {id, {}, {}, {}, {}, expected});
      ASSERT_EQ(jobs.size(), own.size()) << name;
      ASSERT_EQ(jobs.size(), 10u) << name;  // 2 trains x 5 speeds; C shares A's jobs
      for (std::size_t k = 0; k < jobs.size(); ++k) {
        const auto& a = jobs[k];
        const auto& b = own[k];
        EXPECT_EQ(a.id, b.id);
        EXPECT_EQ(a.structure, b.structure);
        EXPECT_EQ(std::tie(a.train, a.speed_kmh, a.irregularity, a.variant, a.state, a.status, a.error),
                  std::tie(b.train, b.speed_kmh, b.irregularity, b.variant, b.state, b.status, b.error));
        ASSERT_TRUE(a.axle_forces.has_value());
        EXPECT_EQ(a.axle_forces, b.axle_forces);
        EXPECT_EQ(a.dt_s, b.dt_s);
        EXPECT_EQ(a.cutoff_hz, b.cutoff_hz);
        if (fields == scheduler::BridgeFields::kAll) {
          EXPECT_EQ(a.envelopes, b.envelopes);
          EXPECT_EQ(a.error_estimates, b.error_estimates);
          EXPECT_EQ(std::tie(a.fidelity, a.warnings, a.ran_dt_s, a.wall_s, a.loop_s, a.dt_reason),
                    std::tie(b.fidelity, b.warnings, b.ran_dt_s, b.wall_s, b.loop_s, b.dt_reason));
          EXPECT_FALSE(a.fidelity.empty());
        } else {
          // Only the quantities the checks judge, each with the stored value.
          EXPECT_FALSE(a.envelopes.empty());
          for (const auto& [quantity, at] : a.envelopes) {
            EXPECT_TRUE(quantity == "deck_displacement_m" || quantity == "deck_acceleration_mps2" ||
                        quantity == "bending_moment_Nm")
                << quantity;
            EXPECT_EQ(at, b.envelopes.at(quantity)) << quantity;
          }
          EXPECT_TRUE(a.envelopes.count("deck_acceleration_mps2"));
          EXPECT_FALSE(a.envelopes.count("shear_force_N"));
        }
      }
    }
    EXPECT_FALSE(reader.next(name, jobs));
    EXPECT_TRUE(jobs.empty());
  }
}

// The bits of a value (nullopt stays nullopt: a missing value never equals one).
std::optional<std::uint64_t> bits(std::optional<double> v) {
  return v ? std::optional(std::bit_cast<std::uint64_t>(*v)) : std::nullopt;
}

// Schema 14: the submission stores each bridge's static envelopes of each
// train (the deflection at each output point, the section forces and
// support values of the beam deck), and what the store gives back is what
// the static influence lines give, to the bit: the expected values here
// are StaticInfluence's own, not the stored path's. With the rows gone the
// line table and the report compute them, to the same bytes.
// A whole line's table and CSV are written bridge by bridge (one bridge's
// jobs in memory): the CSV is the bytes of one read of every job, each
// bridge's table is what --structure prints, and vsi run ends with the line
// table rather than a row per job.
TEST_F(LineStudyFiles, AWholeLinesTableAndCsvAreWrittenBridgeByBridgeAndVsiRunEndsWithTheLineTable) {
  const std::string db = (dir_ / "line.sqlite").string();
  const VsiResult run = vsi({"run", write_json("line.json", line_study()).string(), "--db", db}, "run");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string id = study_id(db);
  const VsiResult line = vsi({"query", "--db", db, "--study", id, "--line"}, "line");
  ASSERT_EQ(line.exit_code, 0) << line.err;
  EXPECT_EQ(run.out, line.out + "a bridge's jobs: vsi query --study " + id.substr(0, 12) +
                         " --structure NAME; every job: without --structure\n");
  EXPECT_NE(line.out.find("\nC "), std::string::npos) << line.out;  // a row per bridge

  const VsiResult csv = vsi({"query", "--db", db, "--study", id, "--format", "csv"}, "csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  {
    scheduler::Database d(db, scheduler::OpenMode::kReadOnly);
    EXPECT_EQ(csv.out, scheduler::format_csv(scheduler::study_results(d, {id, {}, {}, {}, {}, {}})));
  }
  EXPECT_GT(std::count(csv.out.begin(), csv.out.end(), '\n'), 30 * 4) << csv.out;  // 3 bridges x 10 jobs

  const VsiResult table = vsi({"query", "--db", db, "--study", id}, "table");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  const std::string& t = table.out;
  // 20 jobs: C is A under another name and shares its jobs.
  EXPECT_EQ(t.rfind("study " + id.substr(0, 12) + " (tiny line): 20 jobs in 3 bridges", 0), 0u) << t;
  const std::vector<std::string> names{"A", "B", "C"};
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string head = "\nbridge " + names[k] + "\n";
    const std::size_t from = t.find(head);
    ASSERT_NE(from, std::string::npos) << names[k];
    const std::size_t to = k + 1 < names.size() ? t.find("\nbridge " + names[k + 1] + "\n") : t.size();
    ASSERT_NE(to, std::string::npos);
    const VsiResult own = vsi({"query", "--db", db, "--study", id, "--structure", names[k]}, "own" + names[k]);
    ASSERT_EQ(own.exit_code, 0) << own.err;
    EXPECT_NE(own.out.find("10 jobs shown"), std::string::npos) << own.out;
    EXPECT_EQ(t.substr(from + head.size(), to - from - head.size()), own.out) << names[k];
  }

  // --fail-on-exceeded judges each bridge as the line table does.
  const VsiResult judged = vsi({"query", "--db", db, "--study", id, "--fail-on-exceeded"}, "judged");
  const VsiResult line_judged = vsi({"query", "--db", db, "--study", id, "--line", "--fail-on-exceeded"}, "lj");
  EXPECT_EQ(judged.exit_code, line_judged.exit_code) << judged.err << line_judged.err;
  EXPECT_NE(judged.exit_code, -1);
}

TEST_F(LineStudyFiles, TheStoredStaticEnvelopesAreTheInfluenceLinesOwnToTheBit) {
  const std::string db = (dir_ / "line.sqlite").string();
  ASSERT_EQ(vsi({"run", write_json("line.json", line_study()).string(), "--db", db}, "run").exit_code, 0);
  const std::string id = study_id(db);
  std::size_t pairs = 0, expected_rows = 0;
  {
    scheduler::Database d(db, scheduler::OpenMode::kReadOnly);
    scheduler::BridgeReader reader(d, id, scheduler::BridgeFields::kLabels);
    std::string name;
    std::vector<scheduler::JobResult> jobs;
    std::set<std::pair<std::string, std::string>> seen;
    while (reader.next(name, jobs)) {
      SCOPED_TRACE(name);
      const scheduler::StaticSceneJobs picked = scheduler::static_scene_jobs(jobs);
      ASSERT_EQ(picked.train_job.size(), 2u);  // two trains
      const Scene structure_scene = scheduler::load_job_scene(d, picked.structure_job);
      const StaticInfluence influence(*structure_scene.structure, structure_scene.analysis.contact.rail_lines);
      const std::size_t points = structure_scene.structure->outputs().size();
      const std::size_t supports = influence.section_forms().supports.size();
      ASSERT_EQ(points, 2u);
      ASSERT_TRUE(influence.section_forms().available());
      for (const auto& [train, job] : picked.train_job) {
        SCOPED_TRACE(train);
        const std::optional<scheduler::TrainStatics> stored =
            scheduler::read_train_statics(d, picked.structure_job, job, influence);
        ASSERT_TRUE(stored.has_value());
        const std::vector<MovingForce> axles = axle_loads(scheduler::load_job_scene(d, job).train);
        const StaticSectionEnvelope sections = influence.section_envelope(axles);
        ASSERT_EQ(stored->max_deflection_m.size(), points);
        for (std::size_t k = 0; k < points; ++k) {
          const double computed = influence.train_envelope(static_cast<int>(k), axles).max_deflection_m;
          EXPECT_GT(computed, 0.0);  // a train of downward loads bends the span down
          EXPECT_EQ(bits(stored->max_deflection_m[k]), bits(computed)) << k;
        }
        EXPECT_EQ(stored->sections.unavailable, sections.unavailable);
        ASSERT_EQ(stored->sections.max_abs_bending_moment_Nm.size(), points);
        ASSERT_EQ(stored->sections.max_reaction_N.size(), supports);
        for (std::size_t k = 0; k < points; ++k) {
          ASSERT_TRUE(sections.max_abs_bending_moment_Nm[k].has_value());
          EXPECT_EQ(bits(stored->sections.max_abs_bending_moment_Nm[k]), bits(sections.max_abs_bending_moment_Nm[k]));
          EXPECT_EQ(bits(stored->sections.max_abs_shear_force_N[k]), bits(sections.max_abs_shear_force_N[k]));
        }
        for (std::size_t i = 0; i < supports; ++i) {
          EXPECT_EQ(bits(stored->sections.max_reaction_N[i]), bits(sections.max_reaction_N[i]));
          EXPECT_EQ(bits(stored->sections.max_abs_rotation_rad[i]), bits(sections.max_abs_rotation_rad[i]));
        }
        // Bridges A and C are one structure (one set of jobs): one set of rows.
        if (seen.insert({picked.structure_job, job}).second) {
          ++pairs;
          expected_rows += 3 * points + 2 * supports;
        }
      }
    }
    EXPECT_EQ(pairs, 4u);  // 2 distinct spans x 2 trains
    EXPECT_EQ(count_rows(d, "SELECT count(*) FROM static_envelopes"), static_cast<std::int64_t>(expected_rows));
  }
  // Read, then computed: the same bytes.
  const auto outputs = [&](const std::string& tag) {
    std::vector<std::string> out;
    for (const char* format : {"table", "csv", "json"}) {
      const VsiResult r = vsi({"query", "--db", db, "--study", id, "--line", "--format", format}, tag);
      EXPECT_EQ(r.exit_code, 0) << r.err;
      out.push_back(r.out);
    }
    // The report's one changing line, the date, fixed (the child inherits it).
    ::setenv("SOURCE_DATE_EPOCH", "1800000000", 1);
    const VsiResult report = vsi({"report", "--db", db, "--study", id, "--no-histories", "--format", "json"}, tag);
    ::unsetenv("SOURCE_DATE_EPOCH");
    EXPECT_EQ(report.exit_code, 0) << report.err;
    out.push_back(report.out);
    return out;
  };
  const std::vector<std::string> read = outputs("read");
  {
    scheduler::Database d(db);
    d.exec("DELETE FROM static_envelopes");
  }
  EXPECT_EQ(outputs("computed"), read);
}

// The line table and the line report check the study's links alone before
// reading (StudyCheck::kLinks) and refuse, as they read, a done job without
// envelopes (a damaged page reads as fewer rows): nothing printed, exit 1,
// the message of the whole check.
TEST_F(LineStudyFiles, TheLineRefusesADoneJobWithoutEnvelopesFoundAsItReads) {
  const std::string db = (dir_ / "line.sqlite").string();
  ASSERT_EQ(vsi({"run", write_json("line.json", line_study()).string(), "--db", db}, "run").exit_code, 0);
  const std::string id = study_id(db);
  ASSERT_EQ(vsi({"query", "--db", db, "--study", id, "--line"}, "sound").exit_code, 0);
  {
    scheduler::Database d(db);
    // A job of bridge A, which C shares: read twice, one job.
    d.exec("DELETE FROM envelope_values WHERE job_seq = (SELECT min(j.seq) FROM jobs j JOIN study_structures ss "
           "ON ss.job_id = j.id WHERE ss.structure = 'C')");
    EXPECT_EQ(count_rows(d, "SELECT count(*) FROM study_structures ss JOIN jobs j ON j.id = ss.job_id WHERE j.seq = "
                            "(SELECT min(j.seq) FROM jobs j JOIN study_structures ss ON ss.job_id = j.id "
                            "WHERE ss.structure = 'C')"),
              2);
  }
  const std::string expected = "study " + id.substr(0, 12) + ": 1 done jobs have no envelopes";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"query", "--db", db, "--study", id, "--line"},
        std::vector<std::string>{"query", "--db", db, "--study", id, "--line", "--train", "one axle"},
        std::vector<std::string>{"query", "--db", db, "--study", id, "--format", "csv"},
        std::vector<std::string>{"report", "--db", db, "--study", id, "--no-histories", "--format", "json"}}) {
    SCOPED_TRACE(args.back());
    const VsiResult r = vsi(args, "damaged");
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
  }
}

TEST_F(LineStudyFiles, AShardsJobsKeepTheirPlannedRungAndModes) {
  json doc = one_bridge_study(10);
  doc["analysis"].erase("dt_s");  // the planner's rung and step
  const auto study = write_json("s.json", doc);
  const std::string db = (dir_ / "s.sqlite").string();
  ASSERT_EQ(vsi({"submit", study.string(), "--db", db}, "submit").exit_code, 0);
  std::map<std::string, std::pair<std::string, std::int64_t>> planned;
  {
    scheduler::Database d(db);
    scheduler::Statement s = d.prepare("SELECT id, rung, planned_modes FROM jobs");
    while (s.step()) planned[s.text(0)] = {s.text(1), s.is_null(2) ? -1 : s.int64(2)};
  }
  ASSERT_EQ(planned.size(), 10u);
  ASSERT_EQ(planned.begin()->second.first, "moving_forces/modal");
  ASSERT_GT(planned.begin()->second.second, 0);
  const auto out = dir_ / "shards";
  ASSERT_EQ(vsi({"shard", study.string(), "--shards", "2", "--out", out.string()}, "shard").exit_code, 0);
  std::size_t seen = 0;
  for (int k = 0; k < 2; ++k) {
    scheduler::Database d((out / ("shard-" + std::to_string(k) + ".sqlite")).string());
    scheduler::Statement s = d.prepare("SELECT id, rung, planned_modes FROM jobs");
    while (s.step()) {
      ++seen;
      ASSERT_TRUE(planned.count(s.text(0)));
      EXPECT_EQ(s.text(1), planned[s.text(0)].first);
      EXPECT_EQ(s.is_null(2) ? -1 : s.int64(2), planned[s.text(0)].second);
    }
  }
  EXPECT_EQ(seen, planned.size());
}

}  // namespace
}  // namespace railvsi::test
