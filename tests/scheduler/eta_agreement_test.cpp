// `vsi status` and the progress of `vsi work` read the same store at the
// same second and show the same throughput and ETA: one function computes
// them (recent_throughput).
#include <gtest/gtest.h>

#include "cli/progress_display.hpp"
#include "query/study_status.hpp"
#include "scheduler_test_support.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using namespace railvsi::scheduler;

class EtaAgreement : public ServiceTest {};

// Defect (issue 35): the worker's line divided the unfinished jobs by its
// own session's average rate (none yet at its start: "ETA ?"), while status
// used the store's last 60 s: a minute apart in the same second.
//
// Eight jobs of one study; at t = 1000 s four finished 40, 30, 20 and 10 s
// before (the earliest started 45 s before) and one 1,000 s before, outside
// the 60 s window. Closed form: 4 jobs over 45 s, 3 unfinished, so
// 3 / (4 / 45) = 33.75 s.
TEST_F(EtaAgreement, StatusAndTheWorkersProgressShowTheSameEtaAtTheSameSecond) {
  json doc = tiny_study();
  doc["trains"] = json::array({doc["trains"][0]});
  doc["speeds_kmh"] = json::array({100, 120, 140, 160, 180, 200, 220, 240});
  Database db((dir_ / "w.sqlite").string());
  migrate(db);
  const std::string study = submit_study(db, expand_study(doc, dir_, (dir_ / "s.json").string())).study_id;
  const double now_s = 1000.0;
  const std::vector<std::pair<double, double>> started_finished{
      {now_s - 2000.0, now_s - 1000.0}, {now_s - 45.0, now_s - 40.0}, {now_s - 35.0, now_s - 30.0},
      {now_s - 25.0, now_s - 20.0},     {now_s - 15.0, now_s - 10.0}};
  std::vector<std::string> ids;
  {
    Statement s = db.prepare("SELECT id FROM jobs ORDER BY id");
    while (s.step()) ids.push_back(s.text(0));
  }
  ASSERT_EQ(ids.size(), 8u);
  for (std::size_t i = 0; i < started_finished.size(); ++i)
    db.prepare("UPDATE jobs SET state = 'done', started_at = ?, finished_at = ? WHERE id = ?")
        .bind(1, started_finished[i].first)
        .bind(2, started_finished[i].second)
        .bind(3, ids[i])
        .step();

  const StudyStatus status = study_status(db, study, now_s);
  const WorkProgress worker = work_progress(db, now_s, 0.0);
  ASSERT_TRUE(status.eta_s.has_value());
  ASSERT_TRUE(worker.throughput.eta_s.has_value()) << "the worker shows no ETA where status shows one";
  // Closed form above; the only error is the rounding of two divisions.
  EXPECT_NEAR(*status.eta_s, 33.75, 1e-12);
  EXPECT_EQ(*worker.throughput.eta_s, *status.eta_s);
  EXPECT_EQ(*worker.throughput.jobs_per_s, *status.jobs_per_s);
  // The text both print.
  EXPECT_EQ(cli::eta_text(worker.throughput), "0:34");
  EXPECT_EQ(cli::eta_text({status.jobs_per_s, status.eta_s}), "0:34");
  EXPECT_NE(cli::progress_line(worker.counts, *worker.throughput.jobs_per_s, cli::eta_text(worker.throughput), 200)
                .find("ETA 0:34"),
            std::string::npos);
}

}  // namespace
}  // namespace railvsi::test
