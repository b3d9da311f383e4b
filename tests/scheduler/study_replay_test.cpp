// The histories of a study case reconcile with its envelopes: vsi replay
// runs a stored job again from job_scenes.scene and writes deck.csv with the
// first axle's x, the evaluation window and the filtered deck acceleration,
// whose maximum inside the window is the envelope the study stored. vsi
// simulate reports where each maximum happened and reads a scene from
// stdin.
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/sampled_peak.hpp"
#include "scheduler_test_support.hpp"
#include "../support/worst_of.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) return c;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

Csv read_csv(const std::filesystem::path& file) {
  Csv csv;
  std::istringstream in(read_text(file));
  std::string line;
  std::getline(in, line);
  std::istringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');) csv.header.push_back(cell);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    csv.rows.push_back(row);
  }
  return csv;
}

class Replay : public ServiceTest {};

TEST_F(Replay, HistoriesOfAStoredJobGiveItsEnvelopeInsideTheEvaluationWindow) {
  // 0.1 s of free vibration after the train has left the window: the
  // window column then has both values.
  json doc = tiny_study();
  doc["analysis"]["extra_time_s"] = 0.1;
  const auto study = write_json("study.json", doc);
  const std::string db = (dir_ / "r.sqlite").string();
  ASSERT_EQ(vsi({"run", study.string(), "--db", db, "--threads", "1"}).exit_code, 0);

  // The stored envelopes, read straight from the database.
  std::string job_id;
  double speed_kmh = 0.0;
  std::map<std::string, double> stored;  // location -> filtered deck acceleration
  {
    scheduler::Database d(db);
    scheduler::Statement s = d.prepare(
        "SELECT j.id, j.speed_kmh FROM jobs j WHERE j.train = 'two axles' AND j.speed_kmh = 250");
    ASSERT_TRUE(s.step());
    job_id = s.text(0);
    speed_kmh = s.real(1);
    scheduler::Statement e = d.prepare(
        "SELECT location, value FROM envelopes WHERE job_id = ? AND quantity = 'deck_acceleration_mps2'");
    e.bind(1, job_id);
    while (e.step()) stored[e.text(0)] = e.real(1);
  }
  ASSERT_EQ(stored.size(), 3u);  // quarter, midspan, overall

  const auto histories = dir_ / "histories";
  const VsiResult replay = vsi({"replay", job_id.substr(0, 10), "--db", db, "--histories", histories.string()});
  ASSERT_EQ(replay.exit_code, 0) << replay.err;
  const json summary = json::parse(replay.out);
  const Csv deck = read_csv(histories / "deck.csv");
  const std::size_t t = deck.column("t_s"), x = deck.column("first_axle_x_m"), w = deck.column("in_window");
  ASSERT_GT(deck.rows.size(), 100u);
  // The first axle moves at the job's speed.
  const double v = speed_kmh / 3.6;
  for (const auto& row : deck.rows) EXPECT_NEAR(row[x] - deck.rows[0][x], v * row[t], 1e-9 * (1.0 + std::abs(row[x])));
  double overall = 0.0;
  int inside = 0;
  for (const char* point : {"quarter", "midspan"}) {
    const std::size_t a = deck.column(std::string(point) + "_acceleration_filtered_mps2");
    std::vector<double> in_window;
    for (const auto& row : deck.rows)
      if (row[w] == 1.0) {
        in_window.push_back(row[a]);
        ++inside;
      }
    // The stored envelope refines each peak between its samples.
    const double max_in_window = refined_max_abs(in_window.data(), in_window.size());
    // Round-off: the CSV prints the shortest text that reads back to the
    // same double, and the replay runs the same code on the same scene.
    EXPECT_NEAR(max_in_window, stored.at(point), 1e-12 * stored.at(point)) << point;
    EXPECT_NEAR(summary["deck"]["points"][point == std::string("quarter") ? 0 : 1]["max_abs_acceleration_filtered_mps2"]
                    .get<double>(),
                stored.at(point), 1e-12 * stored.at(point));
    overall = railvsi::testing::worst_of(overall, max_in_window);
  }
  EXPECT_GT(inside, 0);
  EXPECT_NEAR(overall, stored.at(""), 1e-12 * stored.at(""));
  EXPECT_NEAR(summary["deck"]["max_abs_acceleration_filtered_mps2"].get<double>(), stored.at(""), 1e-12 * stored.at(""));
  // The window: an axle within 10 m (evaluation_margin_m) of the 10 m
  // bridge; the free vibration after it is outside.
  EXPECT_LT(inside, static_cast<int>(2 * deck.rows.size()));
  for (const auto& row : deck.rows) {
    const bool expected = row[x] >= -10.0 && row[x] - 3.0 <= 20.0;
    EXPECT_EQ(row[w] == 1.0, expected) << "t = " << row[t];
  }
}

TEST_F(Replay, UnknownJobIsAnInputError) {
  const auto study = write_json("study.json", tiny_study());
  const std::string db = (dir_ / "r.sqlite").string();
  ASSERT_EQ(vsi({"submit", study.string(), "--db", db}).exit_code, 0);
  const VsiResult r = vsi({"replay", "abcdef0123", "--db", db});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no job abcdef0123"), std::string::npos) << r.err;
}

TEST_F(Replay, SimulateReportsWhereEachMaximumHappensAndReadsStdin) {
  json study = tiny_study();
  json scene = {{"structure", study["structure"]}, {"train", study["trains"][1]}, {"speed_kmh", 200},
                {"irregularity", nullptr}, {"analysis", study["analysis"]}, {"outputs", study["outputs"]}};
  const auto file = write_json("scene.json", scene);
  const auto histories = dir_ / "h";
  const VsiResult run = vsi({"simulate", file.string(), "--histories", histories.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(run.out);
  const Csv deck = read_csv(histories / "deck.csv");
  const std::size_t t = deck.column("t_s"), x = deck.column("first_axle_x_m");
  for (const auto& [quantity, column] : {std::pair{"at_max_displacement", "midspan_displacement_m"},
                                         std::pair{"at_max_acceleration", "midspan_acceleration_mps2"},
                                         std::pair{"at_max_acceleration_filtered", "midspan_acceleration_filtered_mps2"}}) {
    // The row of the largest |value|, found here from the CSV.
    const std::size_t c = deck.column(column);
    std::size_t best = 0;
    for (std::size_t k = 1; k < deck.rows.size(); ++k)
      if (std::abs(deck.rows[k][c]) > std::abs(deck.rows[best][c])) best = k;
    const json& at = s["deck"]["points"][1][quantity];
    EXPECT_EQ(at["t_s"].get<double>(), deck.rows[best][t]) << quantity;
    EXPECT_EQ(at["first_axle_x_m"].get<double>(), deck.rows[best][x]) << quantity;
    EXPECT_EQ(at["value"].get<double>(), std::abs(deck.rows[best][c])) << quantity;
  }
  EXPECT_EQ(s["deck"]["points"][1]["max_abs_displacement_m"], s["deck"]["points"][1]["at_max_displacement"]["value"]);
  EXPECT_GT(s["deck"]["cutoff_hz"].get<double>(), 29.9);

  // The same scene on stdin gives the same summary (wall time aside).
  const std::string piped = fmt::format("'{}' simulate - < '{}' > '{}'", VSI_BINARY, file.string(),
                                        (dir_ / "piped.json").string());
  ASSERT_EQ(std::system(piped.c_str()), 0);
  json from_stdin = json::parse(read_text(dir_ / "piped.json")), from_file = s;
  from_stdin["run"].erase("wall_s");
  from_file["run"].erase("wall_s");
  EXPECT_EQ(from_stdin, from_file);
}

}  // namespace
}  // namespace railvsi::test
