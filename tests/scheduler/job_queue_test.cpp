// The durable queue: idempotent submission, leases that expire when their
// worker stops renewing them, attempts that end in 'failed', a result that
// is stored only by the worker holding the job, and user text kept intact.
#include <gtest/gtest.h>

#include <map>
#include <optional>

#include <fmt/format.h>

#include "query/study_results.hpp"
#include "queue/job_queue.hpp"
#include "scheduler_test_support.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using namespace railvsi::scheduler;

class JobQueueTest : public ServiceTest {
 protected:
  void SetUp() override {
    ServiceTest::SetUp();
    db_ = std::make_unique<Database>((dir_ / "q.sqlite").string());
    migrate(*db_);
  }
  StudyPlan plan(const json& doc) const { return expand_study(doc, dir_, (dir_ / "s.json").string()); }
  std::unique_ptr<Database> db_;
};

JobOutcome outcome_with(double value) {
  JobOutcome o;
  o.status = "ok";
  o.fidelity = "{}";
  o.envelopes = {{"deck_acceleration_mps2", "", value}, {"deck_acceleration_mps2", "midspan", value}};
  return o;
}

TEST_F(JobQueueTest, ResubmittingAddsNothing) {
  const StudyPlan p = plan(tiny_study());
  const SubmitResult first = submit_study(*db_, p);
  EXPECT_TRUE(first.new_study);
  EXPECT_EQ(first.new_jobs, 10u);
  const SubmitResult again = submit_study(*db_, plan(tiny_study()));
  EXPECT_FALSE(again.new_study);
  EXPECT_EQ(again.new_jobs, 0u);
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM jobs"), 10);
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM study_jobs"), 10);
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM studies"), 1);
  // Another study sharing some jobs links them without copies.
  json other = tiny_study();
  other["name"] = "one train";
  other["trains"] = json::array({other["trains"][0]});
  const SubmitResult shared = submit_study(*db_, plan(other));
  EXPECT_EQ(shared.jobs, 5u);
  EXPECT_EQ(shared.new_jobs, 0u);
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM jobs"), 10);
}

// The same study document planned into other jobs (as another vsi's
// planner would): the stored study keeps its jobs, none is added, and the
// result says how many differ.
TEST_F(JobQueueTest, AnotherExpansionOfAStoredStudyAddsNothingAndIsCounted) {
  const StudyPlan p = plan(tiny_study());
  submit_study(*db_, p);
  StudyPlan other = p;
  for (std::size_t i = 0; i < 3; ++i) other.jobs[i].id = std::string(64, static_cast<char>('a' + i));
  const SubmitResult again = submit_study(*db_, other);
  EXPECT_FALSE(again.new_study);
  EXPECT_EQ(again.differing_jobs, 3u);
  EXPECT_EQ(again.stored_jobs, 10u);
  EXPECT_EQ(again.new_jobs, 0u);
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM jobs"), 10);
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM study_jobs"), 10);
  // The same expansion again is no conflict.
  EXPECT_EQ(submit_study(*db_, p).differing_jobs, 0u);
}

// A store with some of the study's jobs (as a shard or a partial merge
// holds them, at their positions in the whole study) is completed.
TEST_F(JobQueueTest, AStoreWithPartOfAStudyIsCompletedBySubmittingIt) {
  const StudyPlan p = plan(tiny_study());
  submit_study(*db_, p);
  db_->exec("DELETE FROM study_jobs WHERE position < 4");
  const SubmitResult again = submit_study(*db_, p);
  EXPECT_EQ(again.differing_jobs, 0u);
  EXPECT_EQ(again.stored_jobs, 6u);
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM study_jobs"), 10);
}

TEST_F(JobQueueTest, ExpiredLeaseReturnsTheJobAndCountsAttempts) {
  json doc = tiny_study();
  doc["trains"] = json::array({doc["trains"][0]});
  doc["speeds_kmh"] = json::array({100});
  submit_study(*db_, plan(doc), /*max_attempts=*/2);
  JobQueue dead(*db_, "dead", /*lease_s=*/1.0);
  const auto first = dead.claim();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->attempt, 1);
  JobQueue live(*db_, "live", 60.0);
  EXPECT_FALSE(live.claim()) << "a job under a valid lease is not claimable";
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  const auto second = live.claim();
  ASSERT_TRUE(second) << "the expired lease returns the job";
  EXPECT_EQ(second->id, first->id);
  EXPECT_EQ(second->attempt, 2);
  // The dead worker's late result is not stored.
  EXPECT_FALSE(dead.complete(*first, outcome_with(1.0)));
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM envelopes"), 0);
  EXPECT_TRUE(live.complete(*second, outcome_with(2.0)));
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM envelopes"), 2);
  EXPECT_EQ(state_counts(*db_).done, 1);
}

TEST_F(JobQueueTest, EveryEnvelopeRowIsStoredWithItsValueWhateverTheirNumber) {
  // Rows go in multi-row statements of up to 64: 1, 64, 65 and 150 rows,
  // with missing values among them, in one batch.
  json doc = tiny_study();
  doc["trains"] = json::array({doc["trains"][0]});
  doc["speeds_kmh"] = json::array({100, 150, 200, 250});
  submit_study(*db_, plan(doc));
  JobQueue queue(*db_, "w", 60.0);
  std::vector<ClaimedJob> jobs;
  std::vector<JobOutcome> outcomes;
  for (const std::size_t rows : {1, 64, 65, 150}) {
    const auto job = queue.claim();
    ASSERT_TRUE(job);
    JobOutcome o = outcome_with(0.0);
    o.envelopes.clear();
    for (std::size_t r = 0; r < rows; ++r)
      o.envelopes.push_back({fmt::format("q{}", r), fmt::format("w{}", rows),
                             r % 7 == 3 ? std::nullopt : std::optional<double>(0.5 * static_cast<double>(r))});
    jobs.push_back(*job);
    outcomes.push_back(std::move(o));
  }
  const std::vector<bool> stored = queue.complete_batch(jobs, outcomes);
  EXPECT_EQ(stored, std::vector<bool>(4, true));
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    Statement s = db_->prepare("SELECT quantity, location, value FROM envelopes WHERE job_id = ? ORDER BY rowid");
    s.bind(1, jobs[j].id);
    std::size_t n = 0;
    std::map<std::string, std::optional<double>> read;
    while (s.step()) {
      EXPECT_EQ(s.text(1), outcomes[j].envelopes.front().location);
      read[s.text(0)] = s.optional_real(2);
      ++n;
    }
    ASSERT_EQ(n, outcomes[j].envelopes.size());
    for (const EnvelopeRow& e : outcomes[j].envelopes) EXPECT_EQ(read.at(e.quantity), e.value) << e.quantity;
  }
}

TEST_F(JobQueueTest, JobWhoseWorkersKeepDyingEndsFailedWithItsError) {
  json doc = tiny_study();
  doc["trains"] = json::array({doc["trains"][0]});
  doc["speeds_kmh"] = json::array({100});
  submit_study(*db_, plan(doc), /*max_attempts=*/2);
  for (int k = 0; k < 2; ++k) {
    JobQueue dying(*db_, "dying", 0.01);
    ASSERT_TRUE(dying.claim());
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  JobQueue next(*db_, "next", 60.0);
  EXPECT_FALSE(next.claim());
  const StateCounts c = state_counts(*db_);
  EXPECT_EQ(c.failed, 1);
  Statement s = db_->prepare("SELECT error FROM jobs");
  ASSERT_TRUE(s.step());
  EXPECT_NE(s.text(0).find("lease expired 2 times"), std::string::npos) << s.text(0);
}

TEST_F(JobQueueTest, TransientErrorsRequeueUntilAttemptsRunOut) {
  json doc = tiny_study();
  doc["trains"] = json::array({doc["trains"][0]});
  doc["speeds_kmh"] = json::array({100});
  submit_study(*db_, plan(doc), /*max_attempts=*/2);
  JobQueue w(*db_, "w", 60.0);
  auto job = w.claim();
  ASSERT_TRUE(job);
  EXPECT_TRUE(w.release_after_error(*job, "out of memory"));
  EXPECT_EQ(state_counts(*db_).queued, 1);
  job = w.claim();
  ASSERT_TRUE(job);
  EXPECT_TRUE(w.release_after_error(*job, "out of memory again"));
  EXPECT_EQ(state_counts(*db_).failed, 1);
  EXPECT_FALSE(w.claim());
}

TEST_F(JobQueueTest, CancelAndRetry) {
  const StudyPlan p = plan(tiny_study());
  submit_study(*db_, p);
  JobQueue w(*db_, "w", 60.0);
  const auto running = w.claim();
  ASSERT_TRUE(running);
  EXPECT_EQ(cancel_study(*db_, p.id).cancelled, 10);
  EXPECT_FALSE(w.complete(*running, outcome_with(1.0))) << "a cancelled job's result is dropped";
  EXPECT_FALSE(w.claim());
  EXPECT_EQ(state_counts(*db_, p.id).cancelled, 10);
  EXPECT_EQ(retry_study(*db_, p.id), 10);
  EXPECT_EQ(state_counts(*db_, p.id).queued, 10);
  EXPECT_EQ(resolve_study_id(*db_, p.id.substr(0, 8)), p.id);
  EXPECT_EQ(resolve_study_id(*db_, "00000000"), "");
}

// Two unfinished studies share the jobs of one train: cancelling one leaves
// the shared jobs queued for the other and says how many it left; once the
// other is cancelled too, nothing keeps them.
TEST_F(JobQueueTest, CancelLeavesJobsAnotherUnfinishedStudyNeeds) {
  const StudyPlan both = plan(tiny_study());  // 2 trains x 5 speeds
  json one_doc = tiny_study();
  one_doc["name"] = "one train";
  one_doc["trains"] = json::array({one_doc["trains"][0]});
  const StudyPlan one = plan(one_doc);  // its 5 jobs are 5 of both's 10
  submit_study(*db_, both);
  submit_study(*db_, one);
  const CancelResult first = cancel_study(*db_, both.id);
  EXPECT_EQ(first.cancelled, 5);
  EXPECT_EQ(first.left_for_other_studies, 5);
  EXPECT_EQ(state_counts(*db_, one.id).queued, 5) << "the other study's jobs still run";
  EXPECT_EQ(state_counts(*db_, both.id).cancelled, 5);
  const CancelResult second = cancel_study(*db_, one.id);
  EXPECT_EQ(second.cancelled, 5);
  EXPECT_EQ(second.left_for_other_studies, 0);
  EXPECT_EQ(state_counts(*db_).cancelled, 10);
}

TEST_F(JobQueueTest, ClaimsPreferTheKeyWhoseFactorIsCached) {
  json doc = tiny_study();
  doc["trains"].push_back(one_car_train());  // needs the rail flexibility: another key
  const StudyPlan p = plan(doc);
  std::set<std::string> keys;
  for (const auto& j : p.jobs) keys.insert(j.operator_key);
  ASSERT_EQ(keys.size(), 2u);
  submit_study(*db_, p);
  JobQueue w(*db_, "w", 60.0);
  const auto first = w.claim();
  ASSERT_TRUE(first);
  const std::string other_key = *keys.begin() == first->operator_key ? *keys.rbegin() : *keys.begin();
  // The first key still has queued jobs; the preferred one comes first.
  const auto second = w.claim(other_key);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->operator_key, other_key);
  const auto third = w.claim(other_key);
  ASSERT_TRUE(third);
  EXPECT_EQ(third->operator_key, other_key);
}

TEST_F(JobQueueTest, UserTextIsStoredAndQueriedBackIntact) {
  const std::string study_name = "O'Neil \"fast\" study'); DROP TABLE jobs; --";
  const std::string train_name = "O'Neil \"fast\"";
  json doc = tiny_study();
  doc["name"] = study_name;
  doc["trains"][0]["name"] = train_name;
  const StudyPlan p = plan(doc);
  submit_study(*db_, p);
  EXPECT_EQ(study_info(*db_, p.id).name, study_name);
  JobQueue w(*db_, "w", 60.0);
  for (auto job = w.claim(); job; job = w.claim()) ASSERT_TRUE(w.complete(*job, outcome_with(job->speed_kmh)));
  QueryFilter f{p.id, train_name, std::nullopt, std::nullopt, std::nullopt, std::nullopt};
  const auto jobs = study_results(*db_, f);
  ASSERT_EQ(jobs.size(), 5u);
  for (const auto& j : jobs) {
    EXPECT_EQ(j.train, train_name);
    EXPECT_EQ(j.overall("deck_acceleration_mps2"), j.speed_kmh);
  }
  f.speed_min_kmh = 150;
  f.speed_max_kmh = 250;
  EXPECT_EQ(study_results(*db_, f).size(), 3u);
  EXPECT_EQ(count_rows(*db_, "SELECT count(*) FROM jobs"), 10) << "the table is still there";
}

}  // namespace
}  // namespace railvsi::test
