// A real single-node Slurm: Debian's munged, slurmctld and slurmd started by
// the test in a temporary directory (own ports, own munge socket), stopped
// by pid at the end. A study is submitted with vsi slurm --submit as a
// 4-task job array plus the dependent merge job; the worker of one task is
// killed with SIGKILL in the middle of its shard; the task requeues itself
// and resumes its shard. Checks: every job done exactly once, the merged
// CSV byte-identical to a single-process run. Skipped (with the reason)
// only when not root or when the Slurm packages are not installed.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "slurm_cluster.hpp"

namespace railvsi::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using scheduler::Database;

// 4 shards of 4 to 5 jobs, each a few tenths of a second: long enough to
// kill a worker in the middle of its shard, short enough for CI. The rung is
// pinned to moving forces on the FE structure: the planner would take the
// exact modal rung, where these jobs take 1 to 10 ms (measured) and a
// shard can finish between the test's polls (it did once under load).
json slurm_study() {
  json doc = tiny_study();
  doc["speeds_kmh"] = {{"from", 120}, {"to", 300}, {"step", 20}};
  doc["structure"]["element_length_m"] = 0.1;
  doc["analysis"]["dt_s"] = 1.5e-5;
  doc["fidelity"] = {{"model", "moving_forces"}, {"structure", "fe"}};
  return doc;
}

std::int64_t count_in(const fs::path& db_file, const std::string& sql) {
  Database db(db_file.string());
  return count_rows(db, sql);
}

class Slurm : public ServiceTest {};

TEST_F(Slurm, ArrayOfFourShardsWithAKilledWorkerMergesToTheSingleRun) {
  SlurmCluster cluster;
  if (const std::string why = cluster.start(); !why.empty()) GTEST_SKIP() << why;

  const auto study = write_json("study.json", slurm_study());
  const auto out = dir_ / "shards";
  const VsiResult submitted = vsi({"slurm", study.string(), "--shards", "4", "--out", out.string(), "--lease-s", "2",
                                   "--submit"},
                                  "slurm");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.out << submitted.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(submitted.out, m, std::regex("submitted array job ([0-9]+) \\(4 tasks\\) and merge "
                                                             "job ([0-9]+) \\(afterok:([0-9]+)\\)")))
      << submitted.out;
  const std::string array = m[1].str(), merge = m[2].str();
  EXPECT_EQ(m[3].str(), array);
  ASSERT_TRUE(std::regex_search(submitted.out, m, std::regex("study ([0-9a-f]{64})")));
  const std::string id = m[1].str();
  std::int64_t jobs = 0;
  for (int k = 0; k < 4; ++k) jobs += count_in(out / ("shard-" + std::to_string(k) + ".sqlite"), "SELECT count(*) FROM jobs");
  ASSERT_EQ(jobs, 20);

  // Kill the worker of task 1 once it has finished a job and has more queued.
  const auto shard1 = out / "shard-1.sqlite";
  const std::string victim_task = array + "_1";
  std::int64_t done_at_kill = -1, total1 = count_in(shard1, "SELECT count(*) FROM jobs");
  ASSERT_GE(total1, 3);
  ASSERT_TRUE(wait_until([&] { return count_in(shard1, "SELECT count(*) FROM jobs WHERE state = 'done'") >= 1; },
                         std::chrono::seconds(90), std::chrono::milliseconds(20)))
      << read_text(out / "logs" / "shard-1.log") << sh("squeue; scontrol show job " + array)
      << read_text(cluster.dir() / "slurmctld.log") << read_text(cluster.dir() / "slurmd.log");
  const auto workers = processes_with({"vsi", "work", "--db", shard1.string()});
  ASSERT_EQ(workers.size(), 1u) << "the worker of task 1 is not running";
  ::kill(workers.front(), SIGKILL);
  done_at_kill = count_in(shard1, "SELECT count(*) FROM jobs WHERE state = 'done'");
  ASSERT_LT(done_at_kill, total1) << "task 1 finished its shard before the kill: make the jobs longer";

  // The task requeues itself; Slurm holds a requeued job about two minutes
  // before it is eligible again (BeginTime): release it at once.
  ASSERT_TRUE(wait_until([&] { return SlurmCluster::job_field(victim_task, "Restarts") == "1"; },
                         std::chrono::seconds(30)))
      << sh("scontrol show job " + victim_task) << read_text(out / "logs" / "shard-1.log");
  sh("scontrol update JobId=" + victim_task + " StartTime=now");

  // Under load the requeue may set its BeginTime after that update: release
  // the task again while it still waits for it.
  ASSERT_TRUE(wait_until(
                  [&] {
                    if (SlurmCluster::job_field(victim_task, "Reason") == "BeginTime")
                      sh("scontrol update JobId=" + victim_task + " StartTime=now");
                    return SlurmCluster::job_field(merge, "JobState") == "COMPLETED";
                  },
                  std::chrono::seconds(150), std::chrono::milliseconds(500)))
      << sh("squeue") << sh("scontrol show job " + merge) << read_text(out / "logs" / "merge.log")
      << read_text(out / "logs" / "shard-1.log");
  EXPECT_EQ(SlurmCluster::job_field(merge, "ExitCode"), "0:0");
  for (int k = 0; k < 4; ++k) {
    const std::string task = array + "_" + std::to_string(k);
    EXPECT_EQ(SlurmCluster::job_field(task, "JobState"), "COMPLETED") << task;
    EXPECT_EQ(SlurmCluster::job_field(task, "Restarts"), k == 1 ? "1" : "0") << task;
  }
  const std::string log1 = read_text(out / "logs" / "shard-1.log");
  EXPECT_NE(log1.find("requeueing the task"), std::string::npos) << log1;
  EXPECT_NE(log1.find("restart 1:"), std::string::npos) << log1;
  const std::string merge_log = read_text(out / "logs" / "merge.log");
  EXPECT_NE(merge_log.find("merged 4 of 4 shards"), std::string::npos) << merge_log;

  // Every job done exactly once: one row each, 11 envelope values each; a
  // second attempt only for the job the killed worker held.
  const auto results = out / "results.sqlite";
  EXPECT_EQ(count_in(results, "SELECT count(*) FROM jobs WHERE state = 'done'"), 20);
  EXPECT_EQ(count_in(results, "SELECT count(*) FROM envelopes"), 20 * 23);
  EXPECT_LE(count_in(results, "SELECT count(*) FROM jobs WHERE attempts > 1"), 1);
  EXPECT_EQ(count_in(shard1, "SELECT count(*) FROM jobs WHERE attempts > 1"),
            count_in(results, "SELECT count(*) FROM jobs WHERE attempts > 1"));

  const auto reference = dir_ / "reference.sqlite";
  ASSERT_EQ(vsi({"run", study.string(), "--db", reference.string(), "--threads", "1"}, "reference").exit_code, 0);
  const VsiResult a = vsi({"query", "--db", results.string(), "--study", id, "--format", "csv"}, "qa");
  const VsiResult b = vsi({"query", "--db", reference.string(), "--study", id, "--format", "csv"}, "qb");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(std::count(a.out.begin(), a.out.end(), '\n'), 1 + 20 * 23);
  EXPECT_EQ(a.out, b.out) << "the merged Slurm run differs from a single-process run";
}

}  // namespace
}  // namespace railvsi::test
