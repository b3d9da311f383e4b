// The hybrid structure's reduction (the bridge's modes and constraint modes)
// does not depend on dt: jobs of one structure at two steps (a study's
// speeds, its dt/2 verification runs) compute it once in a worker, and
// each job's envelopes are the same bits as when it runs on a cache of its
// own.
#include <gtest/gtest.h>

#include "scheduler_test_support.hpp"
#include "study/structure_key.hpp"
#include "study/study_plan.hpp"
#include "workers/factorization_cache.hpp"
#include "workers/job_runner.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

// One coach over a 10 m span with track, pinned on the hybrid structure,
// at the given step.
json hybrid_study(double dt_s) {
  json doc = tiny_study();
  doc["structure"]["track"] = {{"approach_m", 24}, {"exit_m", 6}};
  doc["trains"] = json::array({one_car_train()});
  doc["speeds_kmh"] = json::array({200});
  doc["analysis"] = {{"dt_s", dt_s}, {"contact", {{"law", "hertz"}}}};
  doc["fidelity"] = {{"model", "interaction"}, {"structure", "hybrid"}};
  return doc;
}

class HybridReductionSharing : public ServiceTest {
 protected:
  scheduler::ClaimedJob job_at(double dt_s) {
    const scheduler::StudyPlan plan = scheduler::expand_study(hybrid_study(dt_s), dir_, (dir_ / "s.json").string());
    EXPECT_EQ(plan.jobs.size(), 1u);
    const scheduler::JobSpec& p = plan.jobs.front();
    scheduler::ClaimedJob j;
    j.id = p.id;
    j.scene = p.scene;
    j.operator_key = p.operator_key;
    j.train = p.train;
    j.irregularity = p.irregularity;
    j.speed_kmh = p.speed_kmh;
    j.dt_s = p.dt_s;
    j.cutoff_hz = p.cutoff_hz;
    j.rung = p.rung;
    return j;
  }
};

TEST_F(HybridReductionSharing, TwoStepsOfOneStructureComputeTheReductionOnce) {
  const scheduler::ClaimedJob coarse = job_at(1.0e-3), fine = job_at(5.0e-4);
  ASSERT_NE(coarse.operator_key, fine.operator_key);
  ASSERT_EQ(scheduler::structure_part(coarse.operator_key), scheduler::structure_part(fine.operator_key));

  scheduler::FactorizationCache shared;
  const scheduler::JobOutcome a = scheduler::run_job(coarse, shared);
  const scheduler::JobOutcome b = scheduler::run_job(fine, shared);
  ASSERT_TRUE(a.ok) << a.error;
  ASSERT_TRUE(b.ok) << b.error;
  // One reduction and two operators (K_bar differs with dt); before, each
  // operator computed its own reduction: four builds.
  EXPECT_EQ(shared.stats().factorizations, 3);
  EXPECT_EQ(shared.stats().hits, 1);

  scheduler::FactorizationCache own;
  const scheduler::JobOutcome alone = scheduler::run_job(fine, own);
  ASSERT_TRUE(alone.ok) << alone.error;
  EXPECT_EQ(own.stats().factorizations, 2);
  ASSERT_FALSE(b.envelopes.empty());
  ASSERT_EQ(b.envelopes.size(), alone.envelopes.size());
  for (std::size_t i = 0; i < b.envelopes.size(); ++i) {
    SCOPED_TRACE(b.envelopes[i].quantity + " " + b.envelopes[i].location);
    EXPECT_EQ(b.envelopes[i].quantity, alone.envelopes[i].quantity);
    EXPECT_EQ(b.envelopes[i].location, alone.envelopes[i].location);
    ASSERT_EQ(b.envelopes[i].value.has_value(), alone.envelopes[i].value.has_value());
    if (b.envelopes[i].value) {
      EXPECT_EQ(*b.envelopes[i].value, *alone.envelopes[i].value);  // the same bits
    }
  }
}

TEST(StructurePart, OfAKeyWithoutOneIsTheWholeKey) {
  // Keys stored before operator keys began with the structure hash.
  EXPECT_EQ(scheduler::structure_part("0123abcd"), "0123abcd");
  EXPECT_EQ(scheduler::structure_part("s/op"), "s");
}

}  // namespace
}  // namespace railvsi::test
