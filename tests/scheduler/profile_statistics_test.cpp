// Values over random profiles: a study with several seeds of one spectrum
// gets from vsi query, per train x speed and quantity, the mean, the
// standard deviation (divisor n - 1) and the extreme over the seeds, and
// over speeds where each governs. The reference is computed here from the
// stored envelope rows, read with SQL.
#include <cmath>
#include <map>

#include "scheduler_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class ProfileStatistics : public ServiceTest {};

TEST_F(ProfileStatistics, QueryReportsMeanStandardDeviationAndExtremeOverSeeds) {
  json doc = tiny_study();
  doc["trains"] = json::array({one_car_train()});
  doc["speeds_kmh"] = json::array({150, 250});
  doc["irregularities"] = json::parse(
      R"([{"irregularity": {"spectrum": "german-high", "seed": 0}, "seeds": [1, 2, 3]}, null])");
  const auto file = write_json("study.json", doc);
  const std::string db = (dir_ / "r.sqlite").string();
  const VsiResult run = vsi({"run", file.string(), "--db", db, "--threads", "1"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("over random profiles"), std::string::npos) << run.out;

  // Reference: the rows of the seeded profiles, grouped here.
  struct Samples {
    std::vector<double> values;
  };
  std::map<std::tuple<std::string, double, std::string>, Samples> groups;
  std::string study_id;
  {
    scheduler::Database d(db);
    scheduler::Statement id = d.prepare("SELECT id FROM studies");
    ASSERT_TRUE(id.step());
    study_id = id.text(0);
    // The study's jobs: an interaction study over profiles also has its
    // governing cases' dt/2 re-runs (accuracy.verify's default), which
    // carry the same labels and are no sample of the profiles.
    scheduler::Statement s = d.prepare(
        "SELECT j.train, j.speed_kmh, e.quantity, e.value FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id "
        "JOIN envelopes e ON e.job_id = j.id "
        "WHERE e.location = '' AND j.irregularity LIKE 'german-high seed %' AND e.value IS NOT NULL");
    while (s.step()) groups[{s.text(0), s.real(1), s.text(2)}].values.push_back(s.real(3));
  }
  const VsiResult query = vsi({"query", "--db", db, "--study", study_id.substr(0, 12), "--format", "json"});
  ASSERT_EQ(query.exit_code, 0) << query.err;
  const json stats = json::parse(query.out)["profile_statistics"];
  int compared = 0;
  bool some_spread = false;
  for (const json& g : stats) {
    EXPECT_EQ(g["profile"], "german-high");
    EXPECT_EQ(g["samples"], 3);
    const auto it = groups.find({g["train"], g["speed_kmh"].get<double>(), g["quantity"]});
    ASSERT_NE(it, groups.end()) << g.dump();
    const std::vector<double>& v = it->second.values;
    ASSERT_EQ(v.size(), 3u) << g.dump();
    double mean = 0.0;
    for (double x : v) mean += x / 3.0;
    double var = 0.0;
    for (double x : v) var += (x - mean) * (x - mean) / 2.0;
    const bool is_min = g.contains("min");
    const double extreme = is_min ? std::min({v[0], v[1], v[2]}) : std::max({v[0], v[1], v[2]});
    const double scale = std::max(std::abs(mean), 1e-300);
    // Summation order differs: round-off only.
    EXPECT_NEAR(g["mean"].get<double>(), mean, 1e-13 * scale) << g.dump();
    EXPECT_NEAR(g["std_dev"].get<double>(), std::sqrt(var), 1e-12 * scale + 1e-300) << g.dump();
    EXPECT_EQ(g[is_min ? "min" : "max"].get<double>(), extreme) << g.dump();
    some_spread = some_spread || std::sqrt(var) > 1e-6 * scale;
    ++compared;
  }
  // Every quantity with values, at both speeds, for the one train.
  EXPECT_EQ(compared, static_cast<int>(groups.size()));
  EXPECT_GE(compared, 2 * 4);
  EXPECT_TRUE(some_spread) << "the seeds should give different values";
}

}  // namespace
}  // namespace railvsi::test
