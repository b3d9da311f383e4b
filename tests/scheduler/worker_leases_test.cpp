// Leases as workers hold them in real processes: a container restarted as
// PID 1 on the same host name must not renew its dead predecessor's lease,
// a job the database refuses to take back must not hang its worker, and a
// full disk ends `vsi work` with exit 1 after a bounded time, losing nothing.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <regex>

#include <gtest/gtest.h>

#include "core/unix_time.hpp"
#include "queue/job_queue.hpp"
#include "scheduler_test_support.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using namespace railvsi::scheduler;

std::string host_name() {
  char name[256] = {};
  ::gethostname(name, sizeof name - 1);
  return name;
}

bool command_works(const std::string& command) { return std::system((command + " >/dev/null 2>&1").c_str()) == 0; }

// Waits for the child at most timeout_s; kills it (and returns -1) after.
int wait_at_most(Child& child, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    int status = 0;
    const pid_t r = ::waitpid(child.pid(), &status, WNOHANG);
    if (r == child.pid()) {
      child.mark_waited();
      return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return -1;
}

class WorkerLeases : public ServiceTest {
 protected:
  // The tiny study, submitted: `trains` of its two, at `speeds`.
  std::string submit(const json& speeds, std::size_t trains = 2) {
    json doc = tiny_study();
    doc["speeds_kmh"] = speeds;
    if (trains == 1) doc["trains"] = json::array({doc["trains"][0]});
    db_file_ = (dir_ / "w.sqlite").string();
    Database db(db_file_);
    migrate(db);
    return submit_study(db, expand_study(doc, dir_, (dir_ / "s.json").string())).study_id;
  }
  std::string db_file_;
};

// Defect: workers were named host:pid:tN. A worker restarted in a container
// is PID 1 on the same host name again: its heartbeat renewed the dead
// worker's job forever and `vsi work` never ended. Reproduced with a real
// PID namespace (unshare -Upfr), the dead worker's row written as the old
// vsi named it.
TEST_F(WorkerLeases, RestartedWorkerWithTheSamePidDoesNotRenewItsPredecessorsLease) {
  if (!command_works("unshare -Upfr true")) GTEST_SKIP() << "unshare -Upfr (user and PID namespaces) is not available";
  submit(json::array({100}), 1);
  {
    Database db(db_file_);
    db.prepare("UPDATE jobs SET state = 'running', attempts = 1, worker = ?, lease_expires = ?, started_at = ?")
        .bind(1, host_name() + ":1:t0")
        .bind(2, unix_now_s() + 1.0)
        .bind(3, unix_now_s())
        .run();
  }
  auto worker = std::make_unique<Child>(
      std::vector<std::string>{"/usr/bin/env", "unshare", "--kill-child", "-Upfr", VSI_BINARY, "work", "--db", db_file_, "--threads",
                               "1", "--lease-s", "1"},
      dir_ / "w.out", dir_ / "w.err");
  const int code = wait_at_most(*worker, 30.0);
  EXPECT_EQ(code, 0) << "vsi work as PID 1 did not finish: it renews the dead worker's lease\n"
                     << read_text(dir_ / "w.err");
  Database db(db_file_);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done' AND attempts = 2"), 1)
      << "the dead worker's job is taken over once its lease expires";
}

// The same collision built directly: two holders with one name. Each
// renews only the job it holds, by job id.
TEST_F(WorkerLeases, RenewingTouchesOnlyTheHeldJobEvenUnderASharedName) {
  submit(json::array({100, 150}), 1);
  Database db(db_file_);
  JobQueue dead(db, "host:1:t0", 1.0), reborn(db, "host:1:t0", 60.0);
  const auto old_job = dead.claim();
  const auto new_job = reborn.claim();
  ASSERT_TRUE(old_job && new_job);
  EXPECT_TRUE(reborn.renew(new_job->id));
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  EXPECT_TRUE(reborn.renew(new_job->id));
  JobQueue other(db, "other", 60.0);
  const auto taken = other.claim();
  ASSERT_TRUE(taken) << "the dead holder's lease was renewed by the live one";
  EXPECT_EQ(taken->id, old_job->id);
  EXPECT_FALSE(dead.renew(old_job->id)) << "a job taken over is no longer the old holder's";
}

TEST_F(WorkerLeases, WorkerNamesAreNewAtEveryStartOfTheSameProcess) {
  const std::string a = worker_name_prefix(), b = worker_name_prefix();
  EXPECT_NE(a, b);
  EXPECT_TRUE(std::regex_match(a, std::regex(".+:" + std::to_string(::getpid()) + ":[0-9]+-[0-9a-f]{8}"))) << a;
}

TEST_F(WorkerLeases, NonFiniteOrNonPositiveLeaseIsRefused) {
  submit(json::array({100}), 1);
  Database db(db_file_);
  for (const double lease_s : {std::nan(""), 0.0, -1.0, HUGE_VAL})
    EXPECT_THROW(JobQueue(db, "w", lease_s), std::invalid_argument) << lease_s;
}

// Defect: when the job could not be put back (the database refused the
// change), the heartbeat renewed its lease forever and `vsi work` waited on
// it forever. Here a trigger makes SQLite refuse every change of a running
// job's state, so that completing and re-queueing both fail; once the
// worker has given up on the job, the trigger is dropped. The worker must
// let the lease expire, take the job again and finish.
TEST_F(WorkerLeases, JobThatCannotBePutBackIsLeftToExpireAndRunsAgain) {
  submit(json::array({100}), 1);
  {
    Database db(db_file_);
    db.exec("CREATE TRIGGER refuse_put_back BEFORE UPDATE OF state ON jobs "
            "WHEN OLD.state = 'running' AND NEW.state != 'running' "
            "BEGIN SELECT RAISE(ABORT, 'the test refuses to change a running job'); END");
  }
  auto worker = start_vsi({"work", "--db", db_file_, "--threads", "1", "--lease-s", "1"}, "w");
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (read_text(dir_ / "w.err").find("could not") == std::string::npos &&
         std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_NE(read_text(dir_ / "w.err").find("could not"), std::string::npos) << read_text(dir_ / "w.err");
  {
    Database db(db_file_);
    db.exec("DROP TRIGGER refuse_put_back");
  }
  const int code = wait_at_most(*worker, 30.0);
  EXPECT_EQ(code, 0) << "vsi work kept renewing the job it could not put back\n" << read_text(dir_ / "w.err");
  Database db(db_file_);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done' AND attempts = 2"), 1);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes"), 23);
}

// Defect: with the disk full, `vsi work` logged "claim failed, retrying"
// every 0.2 s for as long as the disk stayed full. A real full disk: a
// tmpfs of 8 MiB mounted in a user and mount namespace (unshare -Urm, no
// root needed where user namespaces are enabled), filled to 64 KiB; SQLite
// reports SQLITE_FULL. The worker must back off, exit 1 after --db-retry-s
// with a clear message, and lose nothing: once space is back, a worker
// finishes every job.
TEST_F(WorkerLeases, FullDiskEndsWorkWithExitOneAfterTheRetryTimeAndLosesNothing) {
  if (!command_works("unshare -Urm true")) GTEST_SKIP() << "unshare -Urm (user and mount namespaces) is not available";
  submit(json{{"from", 100}, {"to", 300}, {"step", 10}});  // 42 jobs
  const auto mnt = dir_ / "mnt";
  std::filesystem::create_directories(mnt);
  const std::string vsi = VSI_BINARY, d = dir_.string(), m = mnt.string();
  std::ofstream(dir_ / "full.sh") << "set -u\n"
                                  << "mount -t tmpfs -o size=8m tmpfs '" << m << "' || exit 90\n"
                                  << "cp '" << db_file_ << "' '" << m << "/db.sqlite'\n"
                                  << "dd if=/dev/zero of='" << m << "/fill' bs=4k 2>/dev/null\n"
                                  << "truncate -s -65536 '" << m << "/fill'\n"
                                  << "start=$(date +%s)\n"
                                  << "timeout 60 '" << vsi << "' work --db '" << m << "/db.sqlite' --threads 1 "
                                  << "--lease-s 1 --db-retry-s 3 >'" << d << "/w1.out' 2>'" << d << "/w1.err'\n"
                                  << "echo $? > '" << d << "/rc1'\n"
                                  << "echo $(( $(date +%s) - start )) > '" << d << "/t1'\n"
                                  << "rm '" << m << "/fill'\n"
                                  << "timeout 60 '" << vsi << "' work --db '" << m << "/db.sqlite' --threads 1 "
                                  << "--lease-s 1 >'" << d << "/w2.out' 2>'" << d << "/w2.err'\n"
                                  << "echo $? > '" << d << "/rc2'\n"
                                  << "cp '" << m << "/db.sqlite' '" << d << "/final.sqlite'\n";
  ASSERT_EQ(std::system(("unshare -Urm sh '" + d + "/full.sh'").c_str()), 0);
  const std::string err = read_text(dir_ / "w1.err");
  EXPECT_EQ(read_text(dir_ / "rc1"), "1\n") << err;
  EXPECT_LE(std::stoi(read_text(dir_ / "t1")), 10) << "gave up long after --db-retry-s 3";
  EXPECT_NE(err.find("disk is full"), std::string::npos) << err;
  EXPECT_NE(err.find("error: the database refused claims for"), std::string::npos) << err;
  // Backed off: 0.2, 0.4, 0.8, 1.6 s... not a line every 0.2 s.
  const auto retries = std::count(err.begin(), err.end(), '\n');
  EXPECT_LE(retries, 12) << err;

  EXPECT_EQ(read_text(dir_ / "rc2"), "0\n") << read_text(dir_ / "w2.err");
  Database db((dir_ / "final.sqlite").string());
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done'"), 42);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM envelopes"), 42 * 23);
}

// Defect: under a lock held by another process, each claim waited SQLite's
// 60 s busy timeout before it counted as failed, so --db-retry-s 1 gave up
// after about 120 s. The lock now waits at most --db-retry-s.
TEST_F(WorkerLeases, LockedStoreEndsWorkAfterTheRetryTime) {
  submit(json{{"from", 100}, {"to", 120}, {"step", 10}});
  Database holder(db_file_);
  holder.exec("BEGIN EXCLUSIVE");
  const auto start = std::chrono::steady_clock::now();
  const VsiResult w = vsi({"work", "--db", db_file_, "--threads", "1", "--db-retry-s", "1"});
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  holder.exec("ROLLBACK");
  EXPECT_EQ(w.exit_code, 1) << w.err;
  EXPECT_NE(w.err.find("error: the database refused claims for"), std::string::npos) << w.err;
  EXPECT_NE(w.err.find("locked"), std::string::npos) << w.err;
  EXPECT_LT(took_s, 15.0) << "gave up long after --db-retry-s 1";
  // Nothing is lost: with the lock gone the jobs run.
  EXPECT_EQ(vsi({"work", "--db", db_file_, "--threads", "1"}).exit_code, 0);
  Database db(db_file_);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done'"), 3 * 2);
}

}  // namespace
}  // namespace railvsi::test
