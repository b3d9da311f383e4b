// A study's accuracy.verify: its governing cases (and a sample) re-run one
// rung up leave the stored envelope values as they were and add an error
// estimate beside them, equal to the difference of independent vsi
// simulate runs of the original and the verification configuration.
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <tuple>

#include "scheduler_test_support.hpp"
#include "query/study_verification.hpp"
#include "store/sqlite.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using scheduler::Database;
using scheduler::OpenMode;
using scheduler::Statement;

// job, quantity, location -> the value's bits (empty for NULL).
using EnvelopeBits = std::map<std::tuple<std::string, std::string, std::string>, std::string>;

EnvelopeBits envelope_bits(const std::string& db_file) {
  Database db(db_file, OpenMode::kExisting);
  EnvelopeBits out;
  Statement s = db.prepare("SELECT job_id, quantity, location, value FROM envelopes");
  while (s.step()) {
    std::string bits;
    if (const auto v = s.optional_real(3)) bits.assign(reinterpret_cast<const char*>(&*v), sizeof(double));
    out[{s.text(0), s.text(1), s.text(2)}] = bits;
  }
  return out;
}

// The tiny study at three speeds: moving forces, planned on the exact
// modal rung at the given dt of 1 ms.
json verified_study(const json& verify) {
  json doc = tiny_study();
  doc["speeds_kmh"] = json::array({120, 200, 280});
  doc["accuracy"] = {{"verify", verify}};
  return doc;
}

// The key quantities verification covers (docs/accuracy-and-price.md "Error estimates"), with
// whether the largest value governs.
const std::pair<const char*, bool> kKeyQuantities[] = {
    {"deck_displacement_m", true}, {"deck_acceleration_mps2", true}, {"deck_acceleration_unfiltered_mps2", true},
    {"min_contact_force_N", false}, {"unloading_ratio", true},      {"contact_loss_s", true},
    {"carbody_acceleration_mps2", true}};

// Per train and key quantity, the job of the governing value (the whole
// job's), read from vsi query's json: train + quantity -> job id.
std::map<std::string, std::string> governing_jobs(const json& query) {
  std::map<std::string, std::pair<double, std::string>> best;
  for (const json& job : query.at("jobs"))
    for (const auto& [quantity, largest] : kKeyQuantities) {
      const json& e = job.at("envelopes");
      if (!e.contains(quantity) || !e.at(quantity).contains("all") || e.at(quantity).at("all").is_null()) continue;
      const double v = e.at(quantity).at("all").get<double>();
      const std::string key = job.at("train").get<std::string>() + " " + quantity;
      auto [it, fresh] = best.try_emplace(key, v, job.at("id").get<std::string>());
      if (!fresh && (largest ? v > it->second.first : v < it->second.first)) it->second = {v, job.at("id").get<std::string>()};
    }
  std::map<std::string, std::string> out;
  for (const auto& [q, b] : best) out[q] = b.second;
  return out;
}

class StudyVerification : public ServiceTest {
 protected:
  // Submits the study and works its jobs in this process (the worker pool
  // alone: no verification, which vsi work and vsi run add).
  std::string submit_and_work(const json& doc) {
    const auto file = write_json("study.json", doc);
    db_ = (dir_ / "v.sqlite").string();
    const VsiResult submitted = vsi({"submit", file.string(), "--db", db_});
    EXPECT_EQ(submitted.exit_code, 0) << submitted.err;
    scheduler::WorkOptions options;
    options.db_file = db_;
    const scheduler::WorkSummary s = scheduler::run_workers(options);
    EXPECT_TRUE(s.error.empty()) << s.error;
    return submitted.out.substr(6, 64);
  }
  std::int64_t count(const std::string& sql) {
    Database db(db_, OpenMode::kExisting);
    return count_rows(db, sql);
  }
  std::string db_;
};

TEST_F(StudyVerification, LeavesTheEnvelopesUntouchedAndAddsEstimatesEqualToIndependentRuns) {
  const std::string id = submit_and_work(verified_study("governing"));
  const EnvelopeBits before = envelope_bits(db_);
  ASSERT_EQ(count("SELECT count(*) FROM envelopes WHERE error_estimate IS NOT NULL"), 0);
  const std::int64_t study_jobs = count("SELECT count(*) FROM jobs");
  ASSERT_EQ(study_jobs, 6);

  const VsiResult worked = vsi({"work", "--db", db_});
  ASSERT_EQ(worked.exit_code, 0) << worked.err;

  // Every value the study stored has the same bits; the verification runs
  // added rows of their own jobs only.
  const EnvelopeBits after = envelope_bits(db_);
  for (const auto& [key, bits] : before) {
    const auto it = after.find(key);
    ASSERT_NE(it, after.end());
    EXPECT_EQ(it->second, bits) << std::get<0>(key) << " " << std::get<1>(key) << " " << std::get<2>(key);
  }
  // The governing jobs of the tiny study's quantities; each re-run at dt/2
  // on its rung and at dt/2 on FE (the planner chose the modal rung).
  const VsiResult query = vsi({"query", "--db", db_, "--study", id, "--format", "json"});
  ASSERT_EQ(query.exit_code, 0) << query.err;
  const json q = json::parse(query.out);
  std::set<std::string> governing;
  for (const auto& [quantity, job] : governing_jobs(q)) governing.insert(job);
  EXPECT_EQ(count("SELECT count(DISTINCT job_id) FROM verification_jobs"), static_cast<std::int64_t>(governing.size()));
  EXPECT_EQ(count("SELECT count(*) FROM verification_jobs"), 2 * static_cast<std::int64_t>(governing.size()));
  EXPECT_EQ(count("SELECT count(*) FROM jobs"), study_jobs + 2 * static_cast<std::int64_t>(governing.size()));
  for (const json& job : q.at("jobs")) {
    const bool verified = governing.count(job.at("id").get<std::string>()) > 0;
    EXPECT_EQ(job.at("error_estimates").contains("deck_acceleration_mps2"), verified) << job.dump();
  }

  // The deck-acceleration governing job, recomputed here: its stored scene
  // as it is and as docs/accuracy-and-price.md says verification changes it (dt halved,
  // moving forces on FE), each run by vsi simulate.
  const std::string gov = governing_jobs(q).at("two axles deck_acceleration_mps2");
  json scene;
  {
    Database db(db_, OpenMode::kExisting);
    Statement s = db.prepare("SELECT scene FROM job_records WHERE id = ?");
    ASSERT_TRUE(s.bind(1, gov).step());
    scene = json::parse(s.text(0));
  }
  ASSERT_EQ(scene.at("fidelity").at("structure"), "modal");
  json up = scene;
  up["analysis"]["dt_s"] = scene.at("analysis").at("dt_s").get<double>() / 2.0;
  up["fidelity"] = {{"model", "moving_forces"}, {"structure", "fe"}};
  const VsiResult original = vsi({"simulate", write_json("original.json", scene).string()}, "original");
  const VsiResult verification = vsi({"simulate", write_json("up.json", up).string()}, "up");
  ASSERT_EQ(original.exit_code, 0) << original.err;
  ASSERT_EQ(verification.exit_code, 0) << verification.err;
  const json a = json::parse(original.out), b = json::parse(verification.out);
  json estimates;
  for (const json& job : q.at("jobs"))
    if (job.at("id") == gov) estimates = job.at("error_estimates");
  const std::pair<const char*, const char*> pairs[] = {{"deck_displacement_m", "max_abs_displacement_m"},
                                                        {"deck_acceleration_mps2", "max_abs_acceleration_filtered_mps2"}};
  for (const auto& [quantity, key] : pairs) {
    const double v = a.at("deck").at(key).get<double>(), v_up = b.at("deck").at(key).get<double>();
    const double expected = (v - v_up) / v_up;
    const double stored = estimates.at(quantity).at("all").get<double>();
    // The job ran on the batched modal sweep, vsi simulate on the single
    // modal run: the same recurrence, measured equal to the bit here (4 ulp
    // allowed).
    EXPECT_DOUBLE_EQ(stored, expected) << quantity;
    // A real difference: dt/2 and FE move the values.
    EXPECT_NE(stored, 0.0) << quantity;
  }

  // Again: nothing is queued twice, the estimates are rewritten the same.
  const EnvelopeBits once = envelope_bits(db_);
  ASSERT_EQ(vsi({"work", "--db", db_}).exit_code, 0);
  EXPECT_EQ(count("SELECT count(*) FROM jobs"), study_jobs + 2 * static_cast<std::int64_t>(governing.size()));
  EXPECT_EQ(envelope_bits(db_), once);
  EXPECT_EQ(vsi({"check", "--db", db_}).exit_code, 0);
}

TEST_F(StudyVerification, AFractionVerifiesTheGoverningCasesAndAnEvenSample) {
  const std::string id = submit_and_work(verified_study(0.5));
  ASSERT_EQ(vsi({"work", "--db", db_}).exit_code, 0);
  const VsiResult query = vsi({"query", "--db", db_, "--study", id, "--format", "json"});
  ASSERT_EQ(query.exit_code, 0) << query.err;
  const json q = json::parse(query.out);
  std::set<std::string> governing;
  for (const auto& [quantity, job] : governing_jobs(q)) governing.insert(job);
  // Half of the 6 jobs, the governing ones (of both trains) among them.
  const std::size_t expected = std::max<std::size_t>(3, governing.size());
  std::set<std::string> verified;
  {
    Database db(db_, OpenMode::kExisting);
    Statement s = db.prepare("SELECT DISTINCT job_id FROM verification_jobs WHERE study_id = ?");
    s.bind(1, id);
    while (s.step()) verified.insert(s.text(0));
  }
  EXPECT_EQ(verified.size(), expected);
  for (const std::string& g : governing) EXPECT_EQ(verified.count(g), 1u) << g;
  std::size_t with_estimates = 0;
  for (const json& job : q.at("jobs")) with_estimates += job.at("error_estimates").empty() ? 0 : 1;
  EXPECT_EQ(with_estimates, expected);
}

// A deck-alone study left to the planner runs on the step of refined deck
// peaks (8 samples a period of the code frequency); its verification one
// rung up (FE, which takes the largest sample) runs at half the sampled
// rule's step (23 samples a period), not at half the job's.
TEST_F(StudyVerification, NextRungOfARefinedPeakJobRunsAtHalfTheSampledStep) {
  json doc = verified_study("governing");
  doc["analysis"].erase("dt_s");
  doc["asks"] = {"deck"};
  submit_and_work(doc);
  const VsiResult worked = vsi({"work", "--db", db_});
  ASSERT_EQ(worked.exit_code, 0) << worked.err;
  Database db(db_, OpenMode::kExisting);
  Statement s = db.prepare(
      "SELECT j.dt_s, j.cutoff_hz, v.refinement, r.dt_s, r.state FROM verification_jobs v JOIN jobs j ON j.id = v.job_id "
      "JOIN jobs r ON r.id = v.verify_job_id ORDER BY v.job_id, v.refinement");
  int rows = 0;
  while (s.step()) {
    ++rows;
    const double job_dt = s.real(0), code_hz = s.real(1), verify_dt = s.real(3);
    EXPECT_EQ(s.text(4), "done");
    // The job's step: 16 samples a period of the code frequency (the
    // recurrence's floor at 1 %), 3 significant digits.
    EXPECT_LE(job_dt * code_hz, 1.0 / 16.0);
    EXPECT_GT(job_dt * code_hz, 0.99 / 16.0);
    if (s.int64(2) == 1) {
      EXPECT_EQ(verify_dt, job_dt / 2.0) << "on its own rung: dt halved";
    } else {
      EXPECT_LE(verify_dt * code_hz, 0.5 / 23.0) << "one rung up: half of 23 samples a period";
      EXPECT_GT(verify_dt * code_hz, 0.99 * 0.5 / 23.0);
    }
  }
  EXPECT_GT(rows, 0);
  EXPECT_EQ(rows % 2, 0);
}

TEST_F(StudyVerification, QueryAndReportShowTheEstimateAndFlagOneAboveTheTolerance) {
  json doc = verified_study("governing");
  // Far below what dt/2 and FE change: every estimate is flagged.
  doc["accuracy"]["tolerance"] = 1e-9;
  const auto file = write_json("study.json", doc);
  db_ = (dir_ / "v.sqlite").string();
  const VsiResult run = vsi({"run", file.string(), "--db", db_});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  Database db(db_, OpenMode::kExisting);
  Statement s = db.prepare("SELECT id FROM studies");
  ASSERT_TRUE(s.step());
  const std::string id = s.text(0);

  const VsiResult table = vsi({"query", "--db", db_, "--study", id});
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("\u00b1"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("above the study's tolerance"), std::string::npos) << table.out;

  const VsiResult csv = vsi({"query", "--db", db_, "--study", id, "--format", "csv"});
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(csv.out.substr(0, csv.out.find('\n')),
            "train,irregularity,speed_kmh,quantity,location,value,state,error_estimate");

  const VsiResult js = vsi({"query", "--db", db_, "--study", id, "--format", "json"});
  const json q = json::parse(js.out);
  // Every train's governing value is verified, and flagged.
  int shown = 0;
  for (const json& e : q.at("envelope_over_speeds"))
    if (e.at("quantity") == "deck_acceleration_mps2") {
      ++shown;
      EXPECT_TRUE(e.at("error_estimate").is_number()) << e.dump();
      EXPECT_TRUE(e.at("error_estimate_above_tolerance").get<bool>()) << e.dump();
    }
  EXPECT_EQ(shown, 2);

  const auto html = dir_ / "report.html";
  const VsiResult report = vsi({"report", "--db", db_, "--study", id, "--out", html.string(), "--no-histories"});
  ASSERT_EQ(report.exit_code, 0) << report.err;
  const std::string text = read_text(html);
  EXPECT_NE(text.find("<th>error estimate</th>"), std::string::npos);
  EXPECT_NE(text.find("estimate-warning"), std::string::npos);
}

TEST_F(StudyVerification, RunsQueuedByAProcessThatDiedAreFinishedByTheNextWork) {
  const std::string id = submit_and_work(verified_study("governing"));
  std::size_t queued = 0;
  {
    // What a vsi work killed after queueing the verification leaves.
    Database db(db_, OpenMode::kExisting);
    queued = scheduler::enqueue_verification(db, id);
    ASSERT_GT(queued, 0u);
    EXPECT_EQ(scheduler::enqueue_verification(db, id), 0u);  // queued once
  }
  EXPECT_EQ(count("SELECT count(*) FROM jobs WHERE state = 'queued'"), static_cast<std::int64_t>(queued));
  EXPECT_EQ(count("SELECT count(*) FROM envelopes WHERE error_estimate IS NOT NULL"), 0);
  ASSERT_EQ(vsi({"work", "--db", db_}).exit_code, 0);
  EXPECT_EQ(count("SELECT count(*) FROM jobs"), 6 + static_cast<std::int64_t>(queued));
  EXPECT_EQ(count("SELECT count(*) FROM jobs WHERE state != 'done'"), 0);
  EXPECT_GT(count("SELECT count(*) FROM envelopes WHERE error_estimate IS NOT NULL"), 0);
}

// accuracy.verify left out: "governing" only for an interaction study on a
// track with irregularities (docs/accuracy-and-price.md "Error estimates").
// The decision reads the submitted jobs' rungs and profiles; nothing runs.
TEST_F(StudyVerification, DefaultVerifiesOnlyAnInteractionStudyOnAProfileOrDefects) {
  const json dip = {{"defects", json::array({{{"type", "dip"}, {"x_m", 4.0}, {"length_m", 1.0}, {"depth_m", 0.01}}})}};
  const auto by_default = [&](const json& doc, const std::string& name) {
    const auto file = write_json(name + ".json", doc);
    const std::string db_file = (dir_ / (name + ".sqlite")).string();
    const VsiResult submitted = vsi({"submit", file.string(), "--db", db_file});
    EXPECT_EQ(submitted.exit_code, 0) << name << ": " << submitted.err;
    Database db(db_file, OpenMode::kExisting);
    const std::string id = submitted.out.substr(6, 64);
    EXPECT_EQ(count_rows(db, "SELECT count(*) FROM studies"), 1) << name;
    const bool verifies = scheduler::verifies_by_default(db, id);
    Statement s = db.prepare("SELECT document FROM studies WHERE id = ?");
    EXPECT_TRUE(s.bind(1, id).step()) << name;
    const auto request = scheduler::verify_request(json::parse(s.text(0)), verifies);
    // verifies by default, verifies, only at dt/2 on the job's own rung
    return std::tuple{verifies, request.has_value(), request && request->dt_only};
  };
  json interaction = tiny_study();
  interaction["trains"] = json::array({one_car_train()});
  interaction["speeds_kmh"] = json::array({200});
  interaction["asks"] = {"deck", "wheel_unloading"};
  interaction["irregularities"] = json::array({dip});
  // The default re-runs at dt/2 on the job's rung only (the time-step self-check).
  EXPECT_EQ(by_default(interaction, "interaction-dip"), std::tuple(true, true, true));
  // The same on a perfect track: no default verification.
  json perfect = interaction;
  perfect["irregularities"] = json::array({nullptr});
  EXPECT_EQ(by_default(perfect, "interaction-perfect"), std::tuple(false, false, false));
  // Moving forces over the dip (the load model ignores the profile).
  json forces = tiny_study();
  forces["speeds_kmh"] = json::array({200});
  forces["irregularities"] = json::array({dip});
  EXPECT_EQ(by_default(forces, "forces-dip"), std::tuple(false, false, false));
  // "verify": false turns the default off; a value given is kept.
  json off = interaction;
  off["accuracy"] = {{"verify", false}};
  EXPECT_EQ(by_default(off, "interaction-off"), std::tuple(true, false, false));
  json forces_asked = forces;
  forces_asked["accuracy"] = {{"verify", "governing"}};
  // Asked: the next rung as well.
  EXPECT_EQ(by_default(forces_asked, "forces-asked"), std::tuple(false, true, false));
}

// The default at work: the one-coach study over a dip, worked, queues its
// governing job's re-run at dt/2 on its own rung and nothing else.
TEST_F(StudyVerification, DefaultQueuesTheGoverningJobAtHalfItsStepOnItsOwnRung) {
  json doc = tiny_study();
  doc["trains"] = json::array({one_car_train()});
  doc["speeds_kmh"] = json::array({200});
  doc["asks"] = {"deck", "wheel_unloading"};
  doc["irregularities"] = json::array(
      {{{"defects", json::array({{{"type", "dip"}, {"x_m", 4.0}, {"length_m", 1.0}, {"depth_m", 0.01}}})}}});
  submit_and_work(doc);
  ASSERT_EQ(count("SELECT count(*) FROM jobs WHERE state = 'done'"), 1);
  const VsiResult worked = vsi({"work", "--db", db_});
  ASSERT_EQ(worked.exit_code, 0) << worked.err;
  EXPECT_EQ(count("SELECT count(*) FROM verification_jobs"), 1);
  EXPECT_EQ(count("SELECT count(*) FROM verification_jobs WHERE refinement = 1"), 1);
  // Its step halved exactly, the same rung, done; and estimates stored.
  EXPECT_EQ(count("SELECT count(*) FROM verification_jobs v JOIN jobs j ON j.id = v.job_id JOIN jobs r ON "
                  "r.id = v.verify_job_id WHERE r.dt_s = j.dt_s / 2 AND r.rung = j.rung AND r.state = 'done'"),
            1);
  EXPECT_GT(count("SELECT count(*) FROM envelopes WHERE error_estimate IS NOT NULL"), 0);
  EXPECT_EQ(vsi({"check", "--db", db_}).exit_code, 0);
}

TEST_F(StudyVerification, BadVerifyValuesExit2NamingFileAndPath) {
  for (const json& bad : {json(0), json(1.5), json(-0.1), json("all"), json(true)}) {
    const auto file = write_json("bad.json", verified_study(bad));
    const VsiResult r = vsi({"submit", file.string(), "--db", (dir_ / "bad.sqlite").string()});
    EXPECT_EQ(r.exit_code, 2) << bad.dump() << r.err;
    EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/accuracy/verify"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "bad.sqlite")) << bad.dump();
  }
}

}  // namespace
}  // namespace railvsi::test
