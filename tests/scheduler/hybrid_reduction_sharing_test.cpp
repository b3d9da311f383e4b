// The hybrid structure's reduction (the bridge's modes and constraint modes)
// does not depend on dt: jobs of one structure at two steps (a study's
// speeds, its dt/2 verification runs) compute it once in a worker, and
// each job's envelopes are the same bits as when it runs on a cache of its
// own.
#include <gtest/gtest.h>

#include "scheduler_test_support.hpp"
#include "generators/deck_3d.hpp"
#include "io/file_set_writer.hpp"
#include "io/structure_export.hpp"
#include "study/structure_key.hpp"
#include "study/study_cost.hpp"
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

// The study's cost estimate prices the hybrid reduction once per
// structure, as the workers compute it: a study holding the jobs of both
// steps costs the reduction less than the two studies apart, and each
// job knows the bridge modes its dry run kept. On a small 3D deck: a beam
// deck under a track has no interior for the modes to replace.
TEST_F(HybridReductionSharing, TheStudyEstimateCountsTheReductionOncePerStructure) {
  Deck3dOptions d;
  d.spans_m = {25.0};
  d.target_dofs = 3000;
  d.approach_m = 30.0;
  const Deck3d deck = make_deck_3d(d);
  write_files_together(dir_ / "deck", structure_files(*deck.model));
  const auto study_at = [&](double dt_s) {
    json doc = hybrid_study(dt_s);
    doc["structure"] = {{"import", structure_import_json(*deck.model)}};
    doc.erase("outputs");  // the map lists the deck's
    doc["analysis"]["contact"]["rail_lines"] = {0, 1};
    return scheduler::expand_study(doc, dir_ / "deck", (dir_ / "deck" / "s.json").string());
  };
  const scheduler::StudyPlan coarse = study_at(1.0e-3), fine = study_at(5.0e-4);
  ASSERT_EQ(coarse.jobs.size(), 1u);
  ASSERT_EQ(fine.jobs.size(), 1u);
  EXPECT_EQ(coarse.jobs.front().rung, "interaction/hybrid");
  EXPECT_GT(coarse.jobs.front().hybrid_modes, 0);
  EXPECT_EQ(coarse.jobs.front().hybrid_modes, fine.jobs.front().hybrid_modes);
  scheduler::StudyPlan both = coarse;
  both.jobs.push_back(fine.jobs.front());
  const scheduler::StudyCostEstimate a = scheduler::estimate_study_cost(coarse),
                                     b = scheduler::estimate_study_cost(fine),
                                     ab = scheduler::estimate_study_cost(both);
  EXPECT_EQ(ab.setups, 2u);
  ASSERT_GT(a.setup_cpu_s, 0.0);
  ASSERT_GT(b.setup_cpu_s, 0.0);
  // What the second step adds is only its operator's setup: a whole
  // setup less the reduction, which is most of it on a 3D deck.
  const double added_s = ab.setup_cpu_s - a.setup_cpu_s;
  EXPECT_GT(added_s, 0.0);
  EXPECT_LT(added_s, 0.5 * b.setup_cpu_s) << added_s << " s against a whole setup of " << b.setup_cpu_s << " s";
  EXPECT_NEAR(ab.cpu_s, a.cpu_s + b.cpu_s - (b.setup_cpu_s - added_s), 1e-12 * ab.cpu_s);
}

TEST(StructurePart, OfAKeyWithoutOneIsTheWholeKey) {
  // Keys stored before operator keys began with the structure hash.
  EXPECT_EQ(scheduler::structure_part("0123abcd"), "0123abcd");
  EXPECT_EQ(scheduler::structure_part("s/op"), "s");
}

}  // namespace
}  // namespace railvsi::test
