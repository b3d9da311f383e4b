// The real vsi binary as users run it: several worker processes on one
// database, a worker killed with SIGKILL in the middle of a study, the
// factorization cache, and the exit codes of the service commands.
#include <csignal>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "scheduler_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using scheduler::Database;

// 2 trains x 21 speeds, a few thousand steps each, one job per claim: the
// FE rung pinned (the planner would batch them on the modal rung, whose
// kill test is in modal_batch_test).
json sweep_study() {
  json doc = tiny_study();
  doc["speeds_kmh"] = {{"from", 100}, {"to", 300}, {"step", 10}};
  doc["analysis"]["dt_s"] = 2.0e-4;
  doc["fidelity"] = {{"model", "moving_forces"}, {"structure", "fe"}};
  return doc;
}

std::string study_id_of(const VsiResult& submit) {
  std::smatch m;
  const std::regex id("study ([0-9a-f]{64}): ([0-9]+) jobs");
  EXPECT_TRUE(std::regex_search(submit.out, m, id)) << submit.out << submit.err;
  return m.size() > 1 ? m[1].str() : std::string();
}

std::int64_t done_jobs(const std::filesystem::path& db_file) {
  Database db(db_file.string());
  return count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done'");
}

class WorkerProcesses : public ServiceTest {};

TEST_F(WorkerProcesses, TwoProcessesWithTwoThreadsRunEveryJobExactlyOnce) {
  const auto study = write_json("sweep.json", sweep_study());
  const std::string db_file = (dir_ / "shared.sqlite").string();
  const VsiResult submitted = vsi({"submit", study.string(), "--db", db_file});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  auto a = start_vsi({"work", "--db", db_file, "--threads", "2"}, "a");
  auto b = start_vsi({"work", "--db", db_file, "--threads", "2"}, "b");
  EXPECT_EQ(a->wait(), 0) << read_text(dir_ / "a.err");
  EXPECT_EQ(b->wait(), 0) << read_text(dir_ / "b.err");

  Database db(db_file);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs"), 42);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done'"), 42);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE attempts != 1"), 0) << "a job was claimed twice";
  // Per job: displacement, filtered and unfiltered acceleration at 2 points
  // and overall (3 x 3), Newton iterations and the most in a step; moment and
  // shear (2 points and overall), reaction and rotation (2 supports and overall).
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes"), 42 * 23);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM (SELECT job_id FROM envelopes GROUP BY job_id HAVING count(*) != 23)"),
            0);
  // Each process says how many jobs it finished: together, every job once.
  std::int64_t reported = 0;
  for (const char* tag : {"a", "b"}) {
    std::smatch m;
    const std::string err = read_text(dir_ / (std::string(tag) + ".err"));
    ASSERT_TRUE(std::regex_search(err, m, std::regex("this worker: ([0-9]+) jobs done"))) << err;
    reported += std::stoll(m[1].str());
  }
  EXPECT_EQ(reported, 42);
}

// Ctrl-C gives the running jobs back at once: nothing waits for a lease to
// expire (the default lease is 60 s), and the interrupted attempt is not
// counted.
TEST_F(WorkerProcesses, InterruptedWorkerGivesItsRunningJobsBackAtOnce) {
  const auto study = write_json("sweep.json", sweep_study());
  const auto db_file = dir_ / "interrupted.sqlite";
  ASSERT_EQ(vsi({"submit", study.string(), "--db", db_file.string()}).exit_code, 0);
  auto worker = start_vsi({"work", "--db", db_file.string(), "--threads", "2"}, "interrupted");
  const auto running = [&] {
    Database db(db_file.string());
    return count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'running'");
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while ((done_jobs(db_file) < 2 || running() == 0) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(worker->pid(), SIGINT);
  EXPECT_EQ(worker->wait(), 128 + SIGINT);
  const std::int64_t done_before = done_jobs(db_file);
  ASSERT_LT(done_before, 42) << "the worker finished before it was interrupted: make the jobs longer";
  const std::string err = read_text(dir_ / "interrupted.err");
  EXPECT_NE(err.find("interrupted (SIGINT): "), std::string::npos) << err;
  EXPECT_NE(err.find("running jobs of this process went back to the queue"), std::string::npos) << err;
  {
    Database db(db_file.string());
    EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'running'"), 0);
    EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'queued' AND (attempts != 0 OR worker IS NOT NULL)"), 0);
  }
  // Resumed at once, with the default lease: every job done, each claimed once by its finishing run.
  const VsiResult resumed = vsi({"work", "--db", db_file.string(), "--threads", "2"}, "resumed");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  Database db(db_file.string());
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done'"), 42);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE attempts != 1"), 0);
}

TEST_F(WorkerProcesses, KilledWorkerIsReplacedAndTheEnvelopesEqualAnUninterruptedRun) {
  const auto study = write_json("sweep.json", sweep_study());
  const auto interrupted = dir_ / "interrupted.sqlite", reference = dir_ / "reference.sqlite";
  const VsiResult submitted = vsi({"submit", study.string(), "--db", interrupted.string()});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  const std::string id = study_id_of(submitted);

  auto victim = start_vsi({"work", "--db", interrupted.string(), "--threads", "1", "--lease-s", "1"}, "victim");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (done_jobs(interrupted) < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  victim->kill9();
  EXPECT_EQ(victim->wait(), -SIGKILL);
  const std::int64_t done_before = done_jobs(interrupted);
  ASSERT_GE(done_before, 3);
  ASSERT_LT(done_before, 42) << "the worker finished before it was killed: make the jobs longer";

  const VsiResult resumed = vsi({"work", "--db", interrupted.string(), "--threads", "2", "--lease-s", "1"}, "resumed");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(done_jobs(interrupted), 42);

  ASSERT_EQ(vsi({"run", study.string(), "--db", reference.string(), "--threads", "1"}, "reference").exit_code, 0);
  const VsiResult a = vsi({"query", "--db", interrupted.string(), "--study", id, "--format", "csv"}, "qa");
  const VsiResult b = vsi({"query", "--db", reference.string(), "--study", id, "--format", "csv"}, "qb");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(std::count(a.out.begin(), a.out.end(), '\n'), 1 + 42 * 23);
  EXPECT_EQ(a.out, b.out) << "envelopes of the resumed study differ from an uninterrupted run";

  Database db(interrupted.string());
  scheduler::Statement check = db.prepare("PRAGMA integrity_check");
  ASSERT_TRUE(check.step());
  EXPECT_EQ(check.text(0), "ok");
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM (SELECT job_id FROM envelopes GROUP BY job_id HAVING count(*) != 23)"),
            0);
}

TEST_F(WorkerProcesses, FactorizationsEqualTheDistinctStructureStepKeys) {
  json doc = tiny_study();
  doc["analysis"].erase("dt_s");  // the time-step policy chooses per train and speed
  doc["trains"].push_back(one_car_train());
  doc["speeds_kmh"] = json::array({150, 250});
  const auto study = write_json("mixed.json", doc);
  // Submitted, then worked by another process: the workers factorize.
  const std::string db_file = (dir_ / "mixed.sqlite").string();
  const VsiResult submitted = vsi({"submit", study.string(), "--db", db_file});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  const std::string id = study_id_of(submitted);
  const VsiResult work = vsi({"work", "--db", db_file, "--threads", "2"});
  ASSERT_EQ(work.exit_code, 0) << work.err;

  Database db(db_file);
  // One structure: a key is a time step and whether the train has wheels
  // (they need the rail flexibility block).
  std::set<std::pair<double, bool>> keys;
  scheduler::Statement s = db.prepare("SELECT dt_s, train FROM jobs");
  while (s.step()) keys.insert({s.real(0), s.text(1) == "one coach"});
  EXPECT_GE(keys.size(), 2u);
  const auto n_keys = static_cast<std::int64_t>(keys.size());
  EXPECT_EQ(count_rows(db, "SELECT count(DISTINCT operator_key) FROM jobs"), n_keys);
  EXPECT_EQ(count_rows(db, "SELECT factorizations FROM cache_stats"), n_keys);
  EXPECT_EQ(count_rows(db, "SELECT hits FROM cache_stats"), 6 - n_keys);

  // vsi run: its workers take the operators its submission's dry run built
  // (each train's first key) instead of factorizing them again, and store
  // the same envelopes.
  const std::string run_file = (dir_ / "mixed-run.sqlite").string();
  const VsiResult run = vsi({"run", study.string(), "--db", run_file, "--threads", "2"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  Database run_db(run_file);
  const std::int64_t run_factorizations = count_rows(run_db, "SELECT factorizations FROM cache_stats");
  EXPECT_LT(run_factorizations, n_keys);
  EXPECT_EQ(count_rows(run_db, "SELECT hits FROM cache_stats"), 6 - run_factorizations);
  const VsiResult a = vsi({"query", "--db", db_file, "--study", id, "--format", "csv"});
  const VsiResult b = vsi({"query", "--db", run_file, "--study", id, "--format", "csv"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.out, b.out) << "vsi run's envelopes differ from submit + work's";
}

TEST_F(WorkerProcesses, InvalidStudyEnqueuesNothingAndNamesThePath) {
  json doc = tiny_study();
  doc["trains"].push_back({{"name", "bad"}, {"vehicles", json::array({car(2.4e6), car(-5.0)})}});
  const auto study = write_json("bad.json", doc);
  const auto db_file = dir_ / "bad.sqlite";
  for (const char* command : {"submit", "run"}) {
    const VsiResult r = vsi({command, study.string(), "--db", db_file.string()});
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find("error: " + study.string() + ": /trains/2/vehicles/1/primary/k_N_per_m: "), std::string::npos)
        << r.err;
  }
  if (std::filesystem::exists(db_file)) {
    Database db(db_file.string());
    EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs"), 0);
  }
}

TEST_F(WorkerProcesses, RunExitsWithThreeWhenJobsFailAndShowsWhy) {
  json doc = tiny_study();
  doc["trains"] = json::array({one_car_train()});
  doc["speeds_kmh"] = json::array({200});
  doc["analysis"]["max_newton_iterations"] = 1;  // the Hertz contact needs more: no_convergence
  doc["analysis"]["dt_s"] = 5.0e-4;
  // Nonlinear Hertz pinned: the planner would start with linear Hertz, which converges in one iteration.
  doc["fidelity"] = {{"model", "interaction"}, {"structure", "fe"}, {"contact_law", "hertz"}};
  const auto study = write_json("failing.json", doc);
  const std::string db_file = (dir_ / "f.sqlite").string();
  const VsiResult run = vsi({"run", study.string(), "--db", db_file});
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_NE(run.out.find("failed (no_convergence)"), std::string::npos) << run.out;
  Database db(db_file);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'failed' AND error != ''"), 1);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes"), 0) << "a failed run is not a result";
}

// The 4 mm dip of rung_runner_test lifts the coach's leading wheelset: the
// planner's linear Hertz run escalates, and wheel unloading is asked.
json dip_study() {
  json doc = tiny_study();
  doc["structure"]["spans_m"] = {10, 10};
  doc["structure"]["deck"] = {{"EI_Nm2", 1.0e10}, {"mass_kg_per_m", 10000}};
  doc["structure"]["damping"] = {{"ratio", 0.02}};
  doc["structure"]["track"] = {{"approach_m", 24}, {"exit_m", 6}};
  doc["trains"] = json::array({one_car_train()});
  doc["speeds_kmh"] = json::array({300});
  doc["irregularities"] = json::parse(R"([{"defects": [{"type": "dip", "x_m": 4, "length_m": 1, "depth_m": 0.004}]}])");
  doc["asks"] = {"deck", "wheel_unloading"};
  doc["analysis"] = {{"dt_s", 1.0e-4}, {"duration_s", 0.25}};
  doc["outputs"] = json::parse(R"({"points": [{"name": "midspan", "x_m": 5}]})");
  return doc;
}

TEST_F(WorkerProcesses, WheelEscalationRunsAtHalfTheStepAndTheJobRecordSaysSo) {
  const json doc = dip_study();
  const auto study = write_json("dip.json", doc);
  const std::string db_file = (dir_ / "dip.sqlite").string();
  const VsiResult run = vsi({"run", study.string(), "--db", db_file});
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("interaction/fe, dt 5e-05 s, chosen by planner, escalated to unilateral Hertz"),
            std::string::npos)
      << run.out;
  const std::string id = study_id_of(vsi({"submit", study.string(), "--db", db_file}));
  const json jobs = json::parse(vsi({"query", "--db", db_file, "--study", id, "--format", "json"}).out)["jobs"];
  ASSERT_EQ(jobs.size(), 1u);
  const json& fidelity = jobs[0]["fidelity"];
  EXPECT_EQ(fidelity["contact_law"], "hertz");
  EXPECT_EQ(fidelity["dt_s"].get<double>(), 5.0e-5);
  EXPECT_NE(fidelity["escalation"].get<std::string>().find("at dt = 5e-05 s (0.5 x 0.0001 s)"), std::string::npos)
      << fidelity["escalation"];
  EXPECT_EQ(jobs[0]["dt_s"].get<double>(), 1.0e-4) << "the job's planned step stays in the jobs table";
  // The table and the report show the step the answer ran at, not the planned one.
  const VsiResult table = vsi({"query", "--db", db_file, "--study", id});
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("   5e-05  "), std::string::npos) << table.out;
  EXPECT_EQ(table.out.find("0.0001"), std::string::npos) << table.out;
  const auto html = dir_ / "dip.html";
  const VsiResult report = vsi({"report", "--db", db_file, "--study", id, "--no-histories", "--out", html.string()});
  ASSERT_EQ(report.exit_code, 0) << report.err;
  std::ifstream in(html);
  const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("5e-05 s (first job: escalated from its planned 0.0001 s: "), std::string::npos);
  EXPECT_EQ(page.find("0.0001 s (first job:"), std::string::npos);
  // The job's envelopes are those of vsi simulate of its scene (filtered at
  // the step the answer ran at in both).
  json scene = {{"structure", doc["structure"]}, {"train", doc["trains"][0]}, {"speed_kmh", 300},
                {"irregularity", doc["irregularities"][0]}, {"fidelity", "auto"}, {"asks", doc["asks"]},
                {"analysis", doc["analysis"]}, {"outputs", doc["outputs"]}};
  const VsiResult simulated = vsi({"simulate", write_json("dip-scene.json", scene).string()});
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const json summary = json::parse(simulated.out);
  EXPECT_EQ(summary["run"]["dt_s"].get<double>(), 5.0e-5);
  const json& point = summary["deck"]["points"][0];
  EXPECT_DOUBLE_EQ(jobs[0]["envelopes"]["deck_acceleration_mps2"]["midspan"].get<double>(),
                   point["max_abs_acceleration_filtered_mps2"].get<double>());
  EXPECT_GT(summary["wheels"]["contact_loss_s"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(jobs[0]["envelopes"]["contact_loss_s"]["all"].get<double>(),
                   summary["wheels"]["contact_loss_s"].get<double>());
}

// Defect (issue 35): an escalated job's time-step warnings were judged at
// its planned step: planned 2e-4 s, run at 1e-4 s, it stored dt_above_policy
// for 2e-4 s, which vsi simulate of its scene (judged at the step it ran)
// does not give.
TEST_F(WorkerProcesses, AnEscalatedJobsStepWarningsAreJudgedAtTheStepItRan) {
  json doc = dip_study();
  doc["analysis"]["dt_s"] = 2.0e-4;
  const std::string db_file = (dir_ / "dip.sqlite").string();
  const auto study = write_json("dip.json", doc);
  ASSERT_EQ(vsi({"run", study.string(), "--db", db_file}).exit_code, 0);
  const std::string id = study_id_of(vsi({"submit", study.string(), "--db", db_file}, "again"));
  const json jobs = json::parse(vsi({"query", "--db", db_file, "--study", id, "--format", "json"}, "q").out)["jobs"];
  ASSERT_EQ(jobs.size(), 1u);
  ASSERT_EQ(jobs[0]["fidelity"]["dt_s"].get<double>(), 1.0e-4) << "escalated at half the step";
  json scene = {{"structure", doc["structure"]}, {"train", doc["trains"][0]}, {"speed_kmh", 300},
                {"irregularity", doc["irregularities"][0]}, {"fidelity", "auto"}, {"asks", doc["asks"]},
                {"analysis", doc["analysis"]}, {"outputs", doc["outputs"]}};
  const VsiResult simulated = vsi({"simulate", write_json("dip-scene.json", scene).string()}, "sim");
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const json summary = json::parse(simulated.out);
  ASSERT_EQ(summary["run"]["dt_s"].get<double>(), 1.0e-4);
  const auto step_warnings = [](const json& warnings) {
    std::set<std::string> messages;
    for (const json& w : warnings)
      if (w["code"] == "dt_above_policy" || w["code"] == "filter_above_nyquist")
        messages.insert(w["message"].get<std::string>());
    return messages;
  };
  const std::set<std::string> from_job = step_warnings(jobs[0]["warnings"]);
  EXPECT_EQ(from_job, step_warnings(summary["run"]["warnings"]));
  for (const std::string& m : from_job) EXPECT_EQ(m.find("dt = 0.0002 s"), std::string::npos) << m;
}

TEST_F(WorkerProcesses, StatusQueryCancelAndRetryFromTheCommandLine) {
  const auto study = write_json("tiny.json", tiny_study());
  const std::string db_file = (dir_ / "t.sqlite").string();
  const VsiResult submitted = vsi({"submit", study.string(), "--db", db_file});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  const std::string id = study_id_of(submitted);
  EXPECT_NE(submitted.out.find(": 10 jobs, 10 new"), std::string::npos) << submitted.out;
  EXPECT_NE(vsi({"submit", study.string(), "--db", db_file}).out.find(": 10 jobs, 0 new"), std::string::npos);

  const VsiResult cancel = vsi({"cancel", "--db", db_file, "--study", id.substr(0, 10)});
  EXPECT_EQ(cancel.exit_code, 0) << cancel.err;
  EXPECT_NE(cancel.out.find("10 jobs cancelled"), std::string::npos) << cancel.out;
  EXPECT_EQ(vsi({"work", "--db", db_file}).exit_code, 0);
  EXPECT_EQ(done_jobs(db_file), 0);
  EXPECT_NE(vsi({"retry", "--db", db_file, "--study", id}).out.find("10 jobs queued again"), std::string::npos);
  EXPECT_EQ(vsi({"work", "--db", db_file, "--threads", "2"}).exit_code, 0);
  EXPECT_EQ(done_jobs(db_file), 10);

  const VsiResult validated = vsi({"validate", study.string()});
  EXPECT_EQ(validated.exit_code, 0) << validated.err;
  EXPECT_NE(validated.out.find("ok (study, 10 jobs)"), std::string::npos) << validated.out;
  const VsiResult status = vsi({"status", "--db", db_file});
  EXPECT_NE(status.out.find("10 done, 0 failed"), std::string::npos) << status.out;
  const VsiResult table = vsi({"query", "--db", db_file, "--study", id, "--train", "one axle", "--speed-min", "150"});
  EXPECT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("4 jobs shown"), std::string::npos) << table.out;
  const VsiResult json_out = vsi({"query", "--db", db_file, "--study", id, "--format", "json"});
  const json parsed = json::parse(json_out.out);
  EXPECT_EQ(parsed["jobs"].size(), 10u);
  EXPECT_EQ(vsi({"query", "--db", db_file, "--study", "ffffffffff"}).exit_code, 2);
}

}  // namespace
}  // namespace railvsi::test
