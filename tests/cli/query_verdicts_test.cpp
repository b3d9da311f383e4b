// Machine-readable verdicts of vsi query and vsi run, through the real binary
// on real study databases: the checks' verdicts in --format json, every job
// in --format csv (cancelled ones too, with their state), the wide csv, and
// the exit codes of --fail-on-exceeded.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "vsi_test_support.hpp"
#include "../support/worst_of.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

// Two HSLM trains over the 25 m span of the README example, two output
// points; quick jobs (about a second each).
json study(double speed_from_kmh, double speed_to_kmh, double step_kmh, double limit_mps2) {
  json s = railvsi::testing::two_hslm_trains_without_speeds("query verdicts");
  s["speeds_kmh"] = {{"from", speed_from_kmh}, {"to", speed_to_kmh}, {"step", step_kmh}};
  s["checks"] = {{"deck_acceleration_limit_mps2", limit_mps2}};
  return s;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (char c : line) {
    if (c == ',') cells.push_back(cell), cell.clear();
    else cell += c;
  }
  cells.push_back(cell);
  return cells;
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

Csv parse_csv(const std::string& text) {
  Csv csv;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  csv.header = split(line);
  while (std::getline(in, line)) csv.rows.push_back(split(line));
  return csv;
}

const json& check_of(const json& out, const std::string& id) {
  for (const json& c : out.at("checks"))
    if (c.at("id") == id) return c;
  throw std::runtime_error("no check " + id);
}

class QueryVerdictsTest : public VsiCliTest {
 protected:
  std::filesystem::path db() const { return dir_ / "study.sqlite"; }
  std::string db_arg() const { return " --db '" + db().string() + "'"; }
  std::string submit(const json& doc, const std::string& name) {
    const VsiRun s = vsi("submit '" + write_json(name, doc).string() + "'" + db_arg());
    EXPECT_EQ(s.exit_code, 0) << s.err;
    return study_id_of(s.out);
  }
  int report_exit_code(const std::string& id) const {
    return vsi("report" + db_arg() + " --study " + id + " --no-histories --out '" + (dir_ / "r.html").string() +
               "' --fail-on-exceeded")
        .exit_code;
  }
  VsiRun query(const std::string& id, const std::string& extra) const {
    return vsi("query" + db_arg() + " --study " + id + " " + extra);
  }
};

// Study A (100 and 120 km/h) runs; study B (100 to 160 km/h) shares A's
// jobs and is cancelled before its own two speeds per train run: 8 cases,
// 4 of them without a value.
TEST_F(QueryVerdictsTest, CancelledJobsMakeTheChecksIncompleteAndStayInTheCsv) {
  submit(study(100, 120, 20, 100.0), "a.json");
  ASSERT_EQ(vsi("work" + db_arg() + " --threads 2").exit_code, 0);
  const json doc_b = study(100, 160, 20, 100.0);
  const std::string b = submit(doc_b, "b.json");
  ASSERT_EQ(vsi("cancel" + db_arg() + " --study " + b).exit_code, 0);

  const VsiRun q = query(b, "--format json");
  ASSERT_EQ(q.exit_code, 0) << q.err;
  const json out = json::parse(q.out);
  std::map<std::string, std::string> state_of;
  std::map<std::string, int> states;
  for (const json& j : out.at("jobs")) {
    state_of[j.at("id")] = j.at("state");
    ++states[j.at("state").get<std::string>()];
  }
  ASSERT_EQ(states["done"], 4) << q.out;
  ASSERT_EQ(states["cancelled"], 4) << q.out;

  EXPECT_EQ(out.at("verdict"), "INCOMPLETE");
  const json& acc = check_of(out, "deck_acceleration");
  EXPECT_EQ(acc.at("verdict"), "INCOMPLETE");
  EXPECT_EQ(acc.at("cases"), 8);
  EXPECT_EQ(acc.at("missing"), 4);
  EXPECT_EQ(acc.at("missing_by_state"), json({{"cancelled", 4}}));
  EXPECT_EQ(acc.at("limit"), 100.0);
  EXPECT_EQ(acc.at("clause"), "EN 1990 A2.4.4.2.1(4)P");
  EXPECT_TRUE(acc.at("limit_verified").is_boolean());
  // A plane model has no cross level: the twist check is not applicable, never 0.
  const json& twist = check_of(out, "deck_twist");
  EXPECT_EQ(twist.at("verdict"), "NOT EVALUATED");
  EXPECT_TRUE(twist.at("limit").is_null());
  EXPECT_TRUE(twist.at("value").is_null());
  EXPECT_NE(twist.at("note").get<std::string>().find("Not applicable: a plane model has one rail line"),
            std::string::npos)
      << twist.dump();
  // The governing value is the largest of the done jobs, and its case names
  // that job.
  double largest = -1.0;
  std::string largest_job;
  for (const json& j : out.at("jobs"))
    if (j.at("state") == "done" && j.at("envelopes").at("deck_acceleration_mps2").at("all").get<double>() > largest)
      largest = j.at("envelopes").at("deck_acceleration_mps2").at("all").get<double>(), largest_job = j.at("id");
  EXPECT_EQ(acc.at("value").get<double>(), largest);
  EXPECT_EQ(acc.at("governing").at("job_id"), largest_job);
  EXPECT_LE(acc.at("governing").at("speed_kmh").get<double>(), 120.0);
  // Per train: 4 cases, 2 cancelled, each INCOMPLETE.
  ASSERT_EQ(acc.at("trains").size(), 2u);
  for (const json& t : acc.at("trains")) {
    EXPECT_EQ(t.at("verdict"), "INCOMPLETE") << t;
    EXPECT_EQ(t.at("cases"), 4);
    EXPECT_EQ(t.at("missing"), 2);
    EXPECT_EQ(state_of.at(t.at("governing").at("job_id")), "done");
    EXPECT_EQ(t.at("governing").at("train"), t.at("train"));
  }
  // The dynamic-enhancement check, one case per train, is incomplete too.
  EXPECT_EQ(check_of(out, "dynamic_enhancement").at("verdict"), "INCOMPLETE");
  // The existing fields are still there.
  for (const char* key : {"study", "jobs", "envelope_over_speeds", "profile_statistics"})
    EXPECT_TRUE(out.contains(key)) << key;

  // csv: the cancelled jobs are there, one line each, state cancelled and
  // empty value cells; every line of a done job says done.
  const VsiRun c = query(b, "--format csv");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const Csv csv = parse_csv(c.out);
  EXPECT_EQ(csv.header, (std::vector<std::string>{"train", "irregularity", "speed_kmh", "quantity", "location", "value",
                                                  "state", "error_estimate"}));
  std::set<std::string> cancelled, done;
  for (const auto& row : csv.rows) {
    ASSERT_EQ(row.size(), 8u);
    EXPECT_EQ(row[7], "");  // the study asks no verification
    const std::string key = row[0] + "@" + row[2];
    if (row[6] == "cancelled") {
      EXPECT_TRUE(cancelled.insert(key).second) << "two lines for a cancelled job " << key;
      EXPECT_EQ(row[3] + row[4] + row[5], "") << key;
      EXPECT_GT(std::stod(row[2]), 120.0);
    } else {
      EXPECT_EQ(row[6], "done");
      done.insert(key);
    }
  }
  EXPECT_EQ(cancelled.size(), 4u);
  EXPECT_EQ(done.size(), 4u);

  // --fail-on-exceeded: incomplete is 5 for query, report and run alike.
  EXPECT_EQ(query(b, "--format csv --fail-on-exceeded").exit_code, 5);
  EXPECT_EQ(query(b, "--fail-on-exceeded").exit_code, 5);
  EXPECT_EQ(report_exit_code(b), 5);
  const VsiRun run = vsi("run '" + (dir_ / "b.json").string() + "'" + db_arg() + " --threads 2 --fail-on-exceeded");
  EXPECT_EQ(run.exit_code, 5) << run.out << run.err;
  EXPECT_NE(run.out.find("checks: INCOMPLETE"), std::string::npos) << run.out;
  EXPECT_EQ(vsi("run '" + (dir_ / "b.json").string() + "'" + db_arg() + " --threads 2").exit_code, 0);
  // A filter to the speeds that ran: the checks over those jobs pass.
  EXPECT_EQ(query(b, "--speed-max 120 --fail-on-exceeded").exit_code, 0);
}

// A limit of 0.01 m/s2 is exceeded by every job: exit 4 with
// --fail-on-exceeded (query, run, report), 0 without.
TEST_F(QueryVerdictsTest, ExceededCheckExitsFourOnlyWhenAsked) {
  const auto file = write_json("fail.json", study(200, 300, 50, 0.01));
  const VsiRun plain = vsi("run '" + file.string() + "'" + db_arg() + " --threads 2");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const std::string id = study_id_of(plain.err + plain.out);
  const VsiRun run = vsi("run '" + file.string() + "'" + db_arg() + " --threads 2 --fail-on-exceeded");
  EXPECT_EQ(run.exit_code, 4) << run.out << run.err;
  EXPECT_NE(run.out.find("checks: FAIL"), std::string::npos) << run.out;
  ASSERT_FALSE(id.empty()) << plain.err;
  EXPECT_EQ(query(id, "").exit_code, 0);
  EXPECT_EQ(query(id, "--format json").exit_code, 0);
  EXPECT_EQ(query(id, "--fail-on-exceeded").exit_code, 4);
  EXPECT_EQ(query(id, "--format json --fail-on-exceeded").exit_code, 4);
  EXPECT_EQ(report_exit_code(id), 4);
  const json out = json::parse(query(id, "--format json").out);
  EXPECT_EQ(out.at("verdict"), "FAIL");
  const json& acc = check_of(out, "deck_acceleration");
  EXPECT_EQ(acc.at("verdict"), "FAIL");
  EXPECT_EQ(acc.at("missing"), 0);
  EXPECT_EQ(acc.at("limit"), 0.01);
  for (const json& t : acc.at("trains")) {
    EXPECT_EQ(t.at("verdict"), "FAIL");
    // The train's value is the largest of its jobs.
    double largest = -1.0;
    for (const json& j : out.at("jobs"))
      if (j.at("train") == t.at("train"))
        largest = railvsi::testing::worst_of(largest, j.at("envelopes").at("deck_acceleration_mps2").at("all").get<double>());
    EXPECT_EQ(t.at("value").get<double>(), largest);
  }
}

// HSLM trains are axle forces: a wheel-unloading or comfort limit in the
// checks does not make every case "without a value" (the verdict could never
// be PASS); those checks are not evaluated, and the deck's verdict decides.
TEST_F(QueryVerdictsTest, WheelAndComfortChecksOfLoadModelTrainsAreNotEvaluatedNotIncomplete) {
  json doc = study(200, 300, 50, 100.0);
  doc["checks"]["max_unloading_ratio"] = 0.6;
  doc["checks"]["carbody_acceleration_limit_mps2"] = 1.0;
  const auto file = write_json("forces.json", doc);
  const VsiRun run = vsi("run '" + file.string() + "'" + db_arg() + " --threads 2 --fail-on-exceeded");
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("checks: PASS"), std::string::npos) << run.out;
  const std::string id = study_id_of(run.err + run.out);
  ASSERT_FALSE(id.empty()) << run.err;
  const json out = json::parse(query(id, "--format json").out);
  EXPECT_EQ(out.at("verdict"), "PASS");
  EXPECT_EQ(check_of(out, "deck_acceleration").at("verdict"), "PASS");
  for (const char* id_of_check : {"wheel_unloading", "passenger_comfort"}) {
    const json& c = check_of(out, id_of_check);
    EXPECT_EQ(c.at("verdict"), "NOT EVALUATED") << id_of_check;
    EXPECT_EQ(c.at("cases"), 0) << id_of_check;
    EXPECT_EQ(c.at("missing"), 0) << id_of_check;
    EXPECT_NE(c.at("note").get<std::string>().find("every train of the study is given as axle forces"),
              std::string::npos)
        << c.at("note");
  }
}

// Names a spreadsheet would take for formulas stay text in both CSVs.
TEST_F(QueryVerdictsTest, CsvWritesFormulaLikeNamesAsText) {
  json doc = study(200, 200, 50, 100.0);
  doc["trains"] = json::parse(R"j([{"name": "=1+1", "moving_forces": [{"offset_m": 0, "load_N": 1e5}]},
                                  {"name": "@SUM(A1)", "moving_forces": [{"offset_m": 0, "load_N": 2e5}]}])j");
  const auto file = write_json("formula.json", doc);
  const VsiRun run = vsi("run '" + file.string() + "'" + db_arg() + " --threads 1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string id = study_id_of(run.err + run.out);
  for (const char* format : {"--format csv", "--format csv --wide"}) {
    const Csv csv = parse_csv(query(id, format).out);
    ASSERT_FALSE(csv.rows.empty()) << format;
    std::set<std::string> trains;
    for (const auto& row : csv.rows) trains.insert(row.at(0));
    EXPECT_EQ(trains, (std::set<std::string>{"'=1+1", "'@SUM(A1)"})) << format;
  }
}

// --wide: one line per train x speed x profile, one column per quantity
// (x location), each value that of the long csv.
TEST_F(QueryVerdictsTest, WideCsvHasOneLinePerCaseAndTheLongCsvValues) {
  const auto file = write_json("wide.json", study(200, 300, 50, 3.5));
  const VsiRun r = vsi("run '" + file.string() + "'" + db_arg() + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string id = study_id_of(r.err + r.out);
  const VsiRun l = query(id, "--format csv"), w = query(id, "--format csv --wide");
  ASSERT_EQ(l.exit_code, 0) << l.err;
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const Csv long_csv = parse_csv(l.out), wide = parse_csv(w.out);

  // The long csv, pivoted here: (train, profile, speed) -> column -> value.
  std::map<std::string, std::map<std::string, std::string>> expected;
  std::set<std::string> columns;
  for (const auto& row : long_csv.rows) {
    const std::string column = row[4].empty() ? row[3] : row[3] + "@" + row[4];
    expected[row[0] + "|" + row[1] + "|" + row[2]][column] = row[5];
    columns.insert(column);
  }
  ASSERT_GE(wide.header.size(), 4u);
  EXPECT_EQ(std::vector<std::string>(wide.header.begin(), wide.header.begin() + 4),
            (std::vector<std::string>{"train", "irregularity", "speed_kmh", "state"}));
  const std::set<std::string> wide_columns(wide.header.begin() + 4, wide.header.end());
  EXPECT_EQ(wide_columns.size(), wide.header.size() - 4) << "a column twice";
  EXPECT_EQ(wide_columns, columns);
  for (const char* c : {"deck_acceleration_mps2", "deck_acceleration_mps2@midspan", "deck_acceleration_mps2@quarter",
                        "deck_displacement_m@midspan", "deck_acceleration_unfiltered_mps2"})
    EXPECT_TRUE(wide_columns.count(c)) << c;

  // 2 trains x 3 speeds x 1 profile.
  ASSERT_EQ(wide.rows.size(), 6u);
  std::set<std::string> keys;
  for (const auto& row : wide.rows) {
    ASSERT_EQ(row.size(), wide.header.size());
    const std::string key = row[0] + "|" + row[1] + "|" + row[2];
    EXPECT_TRUE(keys.insert(key).second) << "two lines for " << key;
    EXPECT_EQ(row[3], "done");
    ASSERT_TRUE(expected.count(key)) << key;
    for (std::size_t k = 4; k < row.size(); ++k) {
      const auto it = expected.at(key).find(wide.header[k]);
      const std::string want = it == expected.at(key).end() ? std::string() : it->second;
      if (want.empty()) EXPECT_EQ(row[k], "") << key << " " << wide.header[k];
      else EXPECT_EQ(std::stod(row[k]), std::stod(want)) << key << " " << wide.header[k];
    }
  }
  EXPECT_EQ(keys.size(), expected.size());

  // --wide belongs to csv.
  const VsiRun bad = query(id, "--format json --wide");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.out, "");
  EXPECT_NE(bad.err.find("--wide"), std::string::npos);
}

TEST_F(QueryVerdictsTest, HelpListsTheExitCodesOfFailOnExceeded) {
  for (const char* command : {"query", "run", "report"}) {
    const VsiRun h = vsi(std::string(command) + " --help");
    EXPECT_EQ(h.exit_code, 0);
    EXPECT_NE(h.out.find("--fail-on-exceeded"), std::string::npos) << command;
    EXPECT_NE(h.out.find("4 a check fails"), std::string::npos) << command << h.out;
    EXPECT_NE(h.out.find("5 a check is incomplete"), std::string::npos) << command;
  }
}

}  // namespace
}  // namespace railvsi::test
