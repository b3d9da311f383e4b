// vsi price --db F --study ID: the sample holds the study's governing
// cases (as vsi query shows them), and vsi submit / run state the
// predicted CPU time.
#include <algorithm>

#include "scheduler_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class PriceStudy : public ServiceTest {};

TEST_F(PriceStudy, SamplesTheGoverningCasesAndPricesThem) {
  json doc = tiny_study();
  doc["speeds_kmh"] = json::array({120, 200, 280});
  const auto study = write_json("study.json", doc);
  const std::string db = (dir_ / "s.sqlite").string();
  const VsiResult submitted = vsi({"submit", study.string(), "--db", db});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  EXPECT_NE(submitted.err.find("estimated CPU time"), std::string::npos) << submitted.err;
  const std::string id = submitted.out.substr(6, 64);
  ASSERT_EQ(vsi({"work", "--db", db}).exit_code, 0);

  // The governing case of deck acceleration, from the stored envelopes.
  const VsiResult query = vsi({"query", "--db", db, "--study", id, "--format", "json"});
  ASSERT_EQ(query.exit_code, 0) << query.err;
  std::string governing;
  double best = -1.0;
  const json query_json = json::parse(query.out);
  for (const json& job : query_json.at("jobs")) {
    const double a = job.at("envelopes").at("deck_acceleration_mps2").at("all").get<double>();
    if (a > best) {
      best = a;
      governing = job.at("id").get<std::string>();
    }
  }
  ASSERT_FALSE(governing.empty()) << query.out;

  const VsiResult price = vsi({"price", "--db", db, "--study", id.substr(0, 12), "--jobs", "2", "--format", "json"});
  ASSERT_EQ(price.exit_code, 0) << price.err;
  const json p = json::parse(price.out);
  const json& jobs = p.at("jobs");
  ASSERT_GE(jobs.size(), 2u);
  const auto it = std::find_if(jobs.begin(), jobs.end(), [&](const json& j) { return j.at("job") == governing; });
  ASSERT_NE(it, jobs.end()) << "the governing job " << governing << " is not in the sample";
  const auto& why = it->at("why");
  EXPECT_NE(std::find(why.begin(), why.end(), "governing deck_acceleration_mps2"), why.end()) << why.dump();
  // Each sampled job priced: two moving-force rungs x five steps, the
  // reference's acceleration the FE rung's at the finest step.
  const json& rows = it->at("price").at("rows");
  EXPECT_EQ(rows.size(), 10u);
  for (const json& r : rows) {
    EXPECT_EQ(r.at("status"), "ok");
    EXPECT_GT(r.at("cpu_s").get<double>(), 0.0);
    EXPECT_GT(r.at("cpu_predicted_s").get<double>(), 0.0);
  }
  EXPECT_EQ(it->at("price").at("reference").at("structure"), "fe");
}

}  // namespace
}  // namespace railvsi::test
