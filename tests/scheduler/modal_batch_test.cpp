// Batched sweeps on the modal moving-force rung: the planner puts HSLM-like
// studies on it, a worker claims the jobs of one structure (all its trains) as a
// batch and stores them in one transaction, and every job's envelopes are
// the same bits as when it runs alone, or through `vsi simulate`'s path
// (histories, then the filter). A worker killed in the middle of a batched
// sweep loses nothing.
#include <algorithm>
#include <csignal>
#include <fstream>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "analysis/modal_moving_forces.hpp"
#include "envelopes/code_filter.hpp"
#include "envelopes/job_envelopes.hpp"
#include "io/scene_loader.hpp"
#include "queue/job_queue.hpp"
#include "scheduler_test_support.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using scheduler::Database;
using scheduler::Statement;

// 2 trains x 13 speeds on the tiny span, time step left to the planner.
json modal_study() {
  json doc = tiny_study();
  doc["analysis"].erase("dt_s");
  doc["speeds_kmh"] = {{"from", 100}, {"to", 340}, {"step", 20}};
  return doc;
}

class ModalBatches : public ServiceTest {
 protected:
  // Submits `doc` into a new store and works it with batches of max_batch.
  std::string run_study(const json& doc, const std::string& db_name, std::size_t max_batch) {
    const std::string db_file = (dir_ / db_name).string();
    {
      Database db(db_file);
      scheduler::migrate(db);
      scheduler::submit_study(db, scheduler::expand_study(doc, dir_, (dir_ / "s.json").string()));
    }
    scheduler::WorkOptions o;
    o.db_file = db_file;
    o.max_batch_jobs = max_batch;
    const scheduler::WorkSummary w = scheduler::run_workers(o);
    EXPECT_EQ(w.jobs_failed, 0);
    EXPECT_TRUE(w.error.empty()) << w.error;
    return db_file;
  }
  // The warning codes of each stored job, all on the modal rung.
  static std::vector<std::set<std::string>> modal_warning_codes(const std::string& db_file) {
    Database db(db_file);
    Statement s = db.prepare("SELECT warnings, rung FROM job_records");
    std::vector<std::set<std::string>> out;
    while (s.step()) {
      EXPECT_EQ(s.text(1), "moving_forces/modal");
      std::set<std::string>& codes = out.emplace_back();
      for (const json& w : json::parse(s.text(0))) codes.insert(w.at("code").get<std::string>());
    }
    return out;
  }
  // Every stored envelope value and run record, as text with exact (hex) doubles.
  static std::string stored(const std::string& db_file) {
    Database db(db_file);
    std::string out;
    Statement e = db.prepare("SELECT job_id, quantity, location, value FROM envelopes ORDER BY job_id, quantity, location");
    while (e.step()) out += fmt::format("{}|{}|{}|{:a}\n", e.text(0), e.text(1), e.text(2), e.is_null(3) ? -1.0 : e.real(3));
    Statement j = db.prepare("SELECT id, state, status, fidelity, steps, warnings, rung FROM job_records ORDER BY id");
    while (j.step())
      out += fmt::format("{}|{}|{}|{}|{}|{}|{}\n", j.text(0), j.text(1), j.text(2), j.text(3), j.int64(4), j.text(5),
                         j.text(6));
    return out;
  }
};

// A study that asks the deck alone skips the section forces on the modal
// sweep (11 rows per job instead of 23), and at the same step its deck
// values are the same bits as those of the study that asks everything: the
// section forces only read the sweep's state.
TEST_F(ModalBatches, AskingTheDeckAloneSkipsSectionForcesAndLeavesTheDeckBitsAlone) {
  json all = modal_study();
  all["analysis"]["dt_s"] = 1e-3;
  json deck_only = all;
  deck_only["asks"] = {"deck"};
  const std::string a = run_study(deck_only, "deck.sqlite", 256);
  const std::string b = run_study(all, "all.sqlite", 256);
  const auto deck_rows = [](const std::string& file) {
    Database db(file);
    std::string out;
    Statement e = db.prepare(
        "SELECT j.train, j.speed_kmh, e.quantity, e.location, e.value FROM envelopes e JOIN jobs j ON j.id = e.job_id "
        "WHERE e.quantity LIKE 'deck_%' ORDER BY 1, 2, 3, 4");
    while (e.step()) out += fmt::format("{}|{}|{}|{}|{:a}\n", e.text(0), e.real(1), e.text(2), e.text(3), e.real(4));
    return out;
  };
  Database db(a);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes"), 26 * 11);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes WHERE quantity LIKE 'bending%' OR quantity LIKE 'support%'"), 0);
  const std::string da = deck_rows(a);
  EXPECT_FALSE(da.empty());
  EXPECT_EQ(da, deck_rows(b));
}

// Left to the planner, the deck alone takes a longer step than the study
// with section forces: its peaks are refined between samples (8 samples a
// period of the code frequency for 1 %), a section force's are not (23).
TEST_F(ModalBatches, DeckAloneAndTheDefaultAsksTakeTheStepOfRefinedPeaks) {
  json deck_only = modal_study();
  deck_only["asks"] = {"deck"};
  const auto step = [&](const json& doc, const char* file) {
    Database db(run_study(doc, file, 256));
    Statement s = db.prepare("SELECT min(dt_s), max(dt_s), min(cutoff_hz) FROM jobs");
    s.step();
    EXPECT_EQ(s.real(0), s.real(1));
    return std::make_pair(s.real(0), s.real(2));
  };
  const auto [dt_deck, code_hz] = step(deck_only, "deck-step.sqlite");
  const auto [dt_all, code_hz_all] = step(modal_study(), "all-step.sqlite");
  EXPECT_EQ(code_hz, code_hz_all);
  // The largest step with 16 samples a period of the code frequency, 3
  // significant digits: the section forces' peaks are refined too, and
  // both take the recurrence's floor (at 1 %: n >= 16).
  EXPECT_LE(dt_deck * code_hz, 1.0 / 16.0);
  EXPECT_GT(dt_deck * code_hz, 0.99 / 16.0);
  EXPECT_EQ(dt_all, dt_deck);
}

TEST_F(ModalBatches, PlannerPutsMovingForceStudiesOnTheModalRungAndRecordsWhy) {
  const std::string db_file = run_study(modal_study(), "modal.sqlite", 256);
  Database db(db_file);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done'"), 26);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE rung = 'moving_forces/modal'"), 26);
  // One basis for the structure: built once, every other job a cache hit.
  EXPECT_EQ(count_rows(db, "SELECT factorizations FROM cache_stats"), 1);
  EXPECT_EQ(count_rows(db, "SELECT hits FROM cache_stats"), 25);
  EXPECT_EQ(count_rows(db, "SELECT jobs FROM cache_stats"), 26);  // the hits counted once per batch
  Statement s = db.prepare("SELECT fidelity, dt_s, dt_reason FROM job_records LIMIT 1");
  ASSERT_TRUE(s.step());
  const json f = json::parse(s.text(0));
  EXPECT_EQ(f["rung"], "moving_forces/modal");
  EXPECT_EQ(f["chosen_by"], "planner");
  EXPECT_GE(f["modes"].get<int>(), 1);
  // The submission stored the count the workers' basis starts from, and
  // the basis kept that many.
  EXPECT_EQ(count_rows(db, fmt::format("SELECT count(*) FROM jobs WHERE planned_modes = {}", f["modes"].get<int>())),
            26);
  EXPECT_GT(f["modal_cutoff_hz"].get<double>(), 30.0);
  EXPECT_EQ(f["dt_s"].get<double>(), s.real(1));
  EXPECT_NE(s.text(2).find("modal rung"), std::string::npos) << s.text(2);
  ASSERT_GE(f["ignores"].size(), 2u);
  EXPECT_NE(f["ignores"][0]["what"].get<std::string>().find("modes above"), std::string::npos);
  EXPECT_FALSE(f["ignores"][0]["why"].get<std::string>().empty());
  EXPECT_NE(f["reasons"][0].get<std::string>().find("load model"), std::string::npos);
  // 23 rows per job, as on the FE rung: displacement, filtered and unfiltered
  // acceleration at 2 points and overall, Newton iterations (0) and the most
  // in a step; moment and shear (2 points and overall) and reaction and end
  // rotation (2 supports and overall) by mode acceleration.
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes"), 26 * 23);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes WHERE quantity = 'deck_acceleration_mps2' AND value IS NULL"), 0);
}

TEST_F(ModalBatches, BatchedResultsAreBitIdenticalToUnbatched) {
  const json doc = modal_study();
  const std::string batched = run_study(doc, "batched.sqlite", 256);
  const std::string single = run_study(doc, "single.sqlite", 1);
  const std::string a = stored(batched), b = stored(single);
  ASSERT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
}

TEST_F(ModalBatches, BatchedJobEqualsTheHistoriesPathOfSimulate) {
  // The batch keeps no histories and filters a workspace; `vsi simulate`
  // runs run_modal_moving_forces (histories) and the envelopes filter
  // those: the same bits.
  const std::string db_file = run_study(modal_study(), "one.sqlite", 256);
  Database db(db_file);
  Statement s = db.prepare("SELECT id, scene, cutoff_hz FROM job_records WHERE speed_kmh = 260 AND train = 'two axles'");
  ASSERT_TRUE(s.step());
  const Scene scene = parse_scene(json::parse(s.text(1)), "/", "job");
  ModalBasisOptions o;
  o.max_frequency_hz = scene.fidelity.modal_cutoff_hz.value();
  const Result r = run_modal_moving_forces(scene, ModalBasis(scene.structure, o));
  const JobEnvelopes e = compute_envelopes(r, scene.analysis.dt_s, 1, s.real(2));
  Statement v = db.prepare("SELECT quantity, value FROM envelopes WHERE job_id = ? AND location = ''");
  v.bind(1, s.text(0));
  int compared = 0;
  while (v.step()) {
    if (v.text(0) == "deck_acceleration_mps2") {
      EXPECT_EQ(v.real(1), e.max_abs_acceleration_mps2.value());
      ++compared;
    } else if (v.text(0) == "deck_displacement_m") {
      EXPECT_EQ(v.real(1), e.max_abs_displacement_m.value());
      ++compared;
    }
  }
  EXPECT_EQ(compared, 2);
}

// Moving forces do not feel a profile: a batched job with one says so in
// its warnings, as the single-run path (and the FE monitor) does.
TEST_F(ModalBatches, BatchedJobsWithAProfileCarryIrregularityIgnored) {
  json doc = modal_study();
  doc["speeds_kmh"] = json::array({200, 220});
  doc["irregularities"] = json::parse(R"([null, {"x_m": [0, 5, 10], "r_m": [0, 0.001, 0]}])");
  const std::string db_file = run_study(doc, "profile.sqlite", 256);
  Database db(db_file);
  Statement s = db.prepare("SELECT irregularity, warnings, scene FROM job_records");
  int with_profile = 0, without = 0;
  while (s.step()) {
    const bool profile = s.text(0) != "none";
    const json warnings = json::parse(s.text(1));
    const bool ignored = std::any_of(warnings.begin(), warnings.end(),
                                     [](const json& w) { return w.at("code") == "irregularity_ignored"; });
    EXPECT_EQ(ignored, profile) << s.text(0) << " " << s.text(1);
    (profile ? with_profile : without) += 1;
    // The single-run path of the same scene gives the same warning.
    const Scene scene = parse_scene(json::parse(s.text(2)), "/", "job");
    ModalBasisOptions o;
    o.max_frequency_hz = scene.fidelity.modal_cutoff_hz.value();
    const Result r = run_modal_moving_forces(scene, ModalBasis(scene.structure, o));
    ASSERT_EQ(r.summary.warnings.size(), profile ? 1u : 0u);
    if (profile) {
      EXPECT_EQ(r.summary.warnings[0].code, "irregularity_ignored");
    }
  }
  EXPECT_EQ(with_profile, 4);  // 2 trains x 2 speeds
  EXPECT_EQ(without, 4);
}

// Axles that start behind a short approach track enter it while the first
// is inside the evaluation window: the batched modal jobs record
// entry_inside_window, as the single-run path and the FE rungs' monitor do
// (issue 35: the modal rung's record lacked it).
TEST_F(ModalBatches, BatchedJobsRecordTheRailEndEntryInsideTheWindow) {
  json doc = modal_study();
  doc["speeds_kmh"] = json::array({200, 250});
  doc["structure"]["track"] = {{"approach_m", 5.0}, {"exit_m", 5.0}};
  doc["trains"] = json::parse(R"([{ "name": "four axles", "moving_forces": [
      { "offset_m": 0, "load_N": 1.0e5 }, { "offset_m": 3, "load_N": 1.0e5 },
      { "offset_m": 20, "load_N": 1.0e5 }, { "offset_m": 23, "load_N": 1.0e5 }] }])");
  const auto jobs = modal_warning_codes(run_study(doc, "entry.sqlite", 256));
  EXPECT_EQ(jobs.size(), 2u);
  for (const std::set<std::string>& codes : jobs) EXPECT_EQ(codes.count("entry_inside_window"), 1u);
}

// A step given in the study above the modal rung's sampling rule is
// flagged as on the FE rungs: dt_above_policy, and filter_above_nyquist
// where it cannot resolve the code frequency (the filtered value is left
// out). The planner's own step raises neither (the test above).
TEST_F(ModalBatches, AGivenStepAboveTheSamplingRuleIsFlagged) {
  json doc = modal_study();
  doc["speeds_kmh"] = json::array({200});
  doc["analysis"]["dt_s"] = 0.05;
  const std::string db_file = run_study(doc, "coarse.sqlite", 256);
  const auto jobs = modal_warning_codes(db_file);
  EXPECT_EQ(jobs.size(), 2u);
  for (const std::set<std::string>& codes : jobs)
    EXPECT_EQ(codes, (std::set<std::string>{"dt_above_policy", "filter_above_nyquist"}));
  Database db(db_file);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes WHERE quantity = 'deck_acceleration_mps2' AND value IS NOT NULL"), 0);
  // vsi simulate of a job's scene warns alike.
  Statement scene = db.prepare("SELECT scene FROM job_records LIMIT 1");
  ASSERT_TRUE(scene.step());
  const auto file = dir_ / "coarse-scene.json";
  { std::ofstream(file) << scene.text(0); }
  const VsiResult simulated = vsi({"simulate", file.string()});
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const json run = json::parse(simulated.out).at("run");
  EXPECT_EQ(run.at("fidelity").at("solver_path"), "modal-exact");
  std::set<std::string> codes;
  for (const json& w : run.at("warnings")) codes.insert(w.at("code").get<std::string>());
  EXPECT_EQ(codes, (std::set<std::string>{"dt_above_policy", "filter_above_nyquist"}));
}

// Trains that share the structure and time step share the operator key:
// one claim takes them together, each train's speeds together and in order
// (the runner makes one pass per train and runs neighbouring speeds side by side).
TEST_F(ModalBatches, ClaimTakesTrainsOfOneOperatorKeyInOrderOfTrainAndSpeed) {
  const std::string db_file = (dir_ / "shared-key.sqlite").string();
  const json doc = modal_study();  // its trains share the structure and dt: one operator key
  Database db(db_file);
  scheduler::migrate(db);
  scheduler::submit_study(db, scheduler::expand_study(doc, dir_, (dir_ / "s.json").string()));
  scheduler::JobQueue queue(db, "w", 60.0);
  const auto batch = queue.claim_batch({}, 256);
  ASSERT_EQ(batch.size(), 26u) << "both trains' 13 speeds";
  for (std::size_t i = 1; i < batch.size(); ++i) {
    EXPECT_EQ(batch[i].operator_key, batch.front().operator_key);
    const bool ordered = batch[i - 1].train < batch[i].train ||
                         (batch[i - 1].train == batch[i].train && batch[i - 1].speed_kmh < batch[i].speed_kmh);
    EXPECT_TRUE(ordered) << i << ": " << batch[i - 1].train << " " << batch[i - 1].speed_kmh << " then "
                         << batch[i].train << " " << batch[i].speed_kmh;
  }
  EXPECT_NE(batch.front().train, batch.back().train);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'running'"), 26);
  EXPECT_EQ(queue.renew(std::vector<std::string>{batch[0].id, batch[1].id, "no such job"}), 2u);
}

// A batch's scenes are joined from their stored parts once per part: each
// must be the text the store's view job_scenes gives for the job, byte for byte.
TEST_F(ModalBatches, EveryJobOfABatchClaimCarriesItsStoredSceneText) {
  Database db((dir_ / "scenes.sqlite").string());
  scheduler::migrate(db);
  scheduler::submit_study(db, scheduler::expand_study(modal_study(), dir_, (dir_ / "s.json").string()));
  scheduler::JobQueue queue(db, "w", 60.0);
  const auto batch = queue.claim_batch({}, 256);
  ASSERT_EQ(batch.size(), 26u);
  Statement view = db.prepare("SELECT scene FROM job_scenes WHERE job_id = ?");
  for (const auto& job : batch) {
    view.reset();
    ASSERT_TRUE(view.bind(1, job.id).step()) << job.id;
    EXPECT_FALSE(job.scene.empty()) << job.id;
    EXPECT_EQ(job.scene, view.text(0)) << job.id;
  }
}

// Defect: after a kill (or a full disk) the jobs a dead worker held came
// back one claim each, each stored in its own transaction: resuming the
// 602-job sweep of docs/cluster-and-service.md wrote 12.2 MB of WAL against
// 1.9 MB for a fresh run. Jobs whose lease expired are claimed in one
// batch with the queued ones, as a fresh run claims them.
TEST_F(ModalBatches, JobsOfADeadWorkerComeBackInOneBatch) {
  Database db((dir_ / "resumed.sqlite").string());
  scheduler::migrate(db);
  scheduler::submit_study(db, scheduler::expand_study(modal_study(), dir_, (dir_ / "s.json").string()));
  {
    scheduler::JobQueue dying(db, "dying", 0.01);
    ASSERT_EQ(dying.claim_batch({}, 10).size(), 10u);  // 10 of 26 held, then the worker dies
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(30));  // past their 0.01 s lease
  scheduler::JobQueue next(db, "next", 60.0);
  const auto batch = next.claim_batch({}, 256);
  EXPECT_EQ(batch.size(), 26u) << "the 10 expired and the 16 queued, in one claim";
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'running' AND worker = 'next'"), 26);
  EXPECT_EQ(count_rows(db, "SELECT max(attempts) FROM jobs"), 2) << "the dead worker's attempt counts";
}

TEST_F(ModalBatches, KilledWorkerInABatchedSweepLosesNothing) {
  // 3 trains x 21 speeds with 20 s of free vibration each (about 50,000
  // steps): a batch of 21 jobs takes long enough to be interrupted.
  json doc = modal_study();
  doc["speeds_kmh"] = {{"from", 100}, {"to", 300}, {"step", 10}};
  doc["analysis"]["extra_time_s"] = 20.0;
  doc["trains"].push_back({{"name", "three axles"},
                           {"moving_forces", json::array({{{"offset_m", 0}, {"load_N", 1.0e5}},
                                                          {{"offset_m", 2.5}, {"load_N", 1.0e5}},
                                                          {{"offset_m", 5.0}, {"load_N", 1.0e5}}})}});
  const auto study = write_json("sweep.json", doc);
  const auto interrupted = dir_ / "interrupted.sqlite", reference = dir_ / "reference.sqlite";
  const VsiResult submitted = vsi({"submit", study.string(), "--db", interrupted.string()});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  const std::int64_t total = 3 * 21;

  // Batches of 21, so that one is stored before the kill.
  auto victim = start_vsi({"work", "--db", interrupted.string(), "--threads", "1", "--lease-s", "1", "--batch", "21"},
                          "victim");
  const auto done = [&] {
    Database db(interrupted.string());
    return count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done'");
  };
  const auto running = [&] {
    Database db(interrupted.string());
    return count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'running'");
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  // Killed while it holds a batch, after at least one batch was stored.
  while ((done() < 21 || running() < 2) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  victim->kill9();
  EXPECT_EQ(victim->wait(), -SIGKILL);
  const std::int64_t done_before = done();
  const std::int64_t held_at_kill = running();  // the batch the victim held
  EXPECT_GE(held_at_kill, 2);
  ASSERT_GE(done_before, 21);
  ASSERT_LT(done_before, total) << "the worker finished before it was killed: make the jobs longer";
  // A batch is stored in one transaction: whole batches only.
  EXPECT_EQ(done_before % 21, 0) << done_before;

  const VsiResult resumed = vsi({"work", "--db", interrupted.string(), "--threads", "2", "--lease-s", "1"}, "resumed");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(done(), total);
  ASSERT_EQ(vsi({"run", study.string(), "--db", reference.string(), "--threads", "1", "--batch", "1"}, "reference")
                .exit_code,
            0);
  Database a(interrupted.string()), b(reference.string());
  const auto envelopes = [](Database& db) {
    std::string out;
    Statement e = db.prepare("SELECT job_id, quantity, location, value FROM envelopes ORDER BY job_id, quantity, location");
    while (e.step()) out += fmt::format("{}|{}|{}|{:a}\n", e.text(0), e.text(1), e.text(2), e.is_null(3) ? -1.0 : e.real(3));
    return out;
  };
  const std::string ea = envelopes(a);
  EXPECT_EQ(std::count(ea.begin(), ea.end(), '\n'), total * 23);
  EXPECT_EQ(ea, envelopes(b)) << "the resumed sweep differs from an uninterrupted unbatched run";
  // Only the killed batch ran twice.
  EXPECT_EQ(count_rows(a, "SELECT count(*) FROM jobs WHERE attempts > 1"), held_at_kill);
}

}  // namespace
}  // namespace railvsi::test
