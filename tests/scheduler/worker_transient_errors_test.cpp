// A transient store error while a worker asks whether any work is left
// (after a claim that found nothing queued) is retried like a failed
// claim: it must neither end the worker with an error nor leave behind a
// job that another, dead worker still holds.
//
// The error is injected into SQLite itself: an auto-extension hooks every
// connection this process opens, and the first run of the "anything left?"
// count (state_counts over all studies) is interrupted (SQLITE_INTERRUPT),
// as a locked or failing store would make it fail.
#include <sqlite3.h>

#include <atomic>

#include <gtest/gtest.h>

#include "queue/job_queue.hpp"
#include "scheduler_test_support.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using namespace railvsi::scheduler;

// The count that decides whether a worker with nothing to claim is finished.
constexpr const char* kAnythingLeftSql = "SELECT state, count(*) FROM jobs GROUP BY state";

std::atomic<int> faults_left{0}, faults_made{0};
thread_local bool interrupt_this_statement = false;

int on_trace(unsigned event, void*, void* statement, void*) {
  if (event == SQLITE_TRACE_STMT) {
    const char* sql = sqlite3_sql(static_cast<sqlite3_stmt*>(statement));
    if (sql != nullptr && std::string(sql) == kAnythingLeftSql && faults_left.fetch_sub(1) > 0) {
      interrupt_this_statement = true;
      ++faults_made;
    }
  } else if (event == SQLITE_TRACE_PROFILE) {
    interrupt_this_statement = false;
  }
  return 0;
}

int on_progress(void*) { return interrupt_this_statement ? 1 : 0; }

int hook_connection(sqlite3* db, const char**, const sqlite3_api_routines*) {
  sqlite3_trace_v2(db, SQLITE_TRACE_STMT | SQLITE_TRACE_PROFILE, on_trace, nullptr);
  sqlite3_progress_handler(db, 1, on_progress, nullptr);
  return SQLITE_OK;
}

using AutoExtension = void (*)();

// Connections opened while it lives are hooked; `faults` runs of the count fail.
class InjectedCountFaults {
 public:
  explicit InjectedCountFaults(int faults) {
    faults_left = faults;
    faults_made = 0;
    sqlite3_auto_extension(reinterpret_cast<AutoExtension>(hook_connection));
  }
  ~InjectedCountFaults() {
    sqlite3_cancel_auto_extension(reinterpret_cast<AutoExtension>(hook_connection));
    faults_left = 0;
  }
  InjectedCountFaults(const InjectedCountFaults&) = delete;
  InjectedCountFaults& operator=(const InjectedCountFaults&) = delete;
};

class WorkerTransientErrors : public ServiceTest {};

// Defect (issue 35): the "anything left?" read ran outside the claim's retry
// path, so one failed read ended the worker thread with the error. Here a
// dead worker holds one of the two jobs with a 1 s lease: the live worker
// runs the other, finds nothing to claim, and its read fails once. It must
// retry, wait for the lease to expire, and run the dead worker's job.
TEST_F(WorkerTransientErrors, AFailedReadOfTheRemainingWorkIsRetriedAndTheDeadWorkersJobStillRuns) {
  json doc = tiny_study();
  doc["trains"] = json::array({doc["trains"][0]});
  doc["speeds_kmh"] = json::array({100, 200});
  const std::string db_file = (dir_ / "w.sqlite").string();
  {
    Database db(db_file);
    migrate(db);
    submit_study(db, expand_study(doc, dir_, (dir_ / "s.json").string()));
    ASSERT_TRUE(JobQueue(db, "dead-host:1:0-00000000:t0", 1.0).claim().has_value());
  }
  WorkSummary summary;
  {
    const InjectedCountFaults faults(1);
    WorkOptions options;
    options.db_file = db_file;
    options.threads = 1;
    options.lease_s = 1.0;
    options.db_retry_s = 30.0;
    summary = run_workers(options);
  }
  ASSERT_EQ(faults_made.load(), 1) << "no read of the remaining work failed: the test tests nothing";
  EXPECT_EQ(summary.error, "") << "the worker ended on a transient error instead of retrying";
  EXPECT_EQ(summary.jobs_done, 2);
  Database db(db_file);
  EXPECT_EQ(count_rows(db, "SELECT count(*) FROM jobs WHERE state = 'done'"), 2);
}

}  // namespace
}  // namespace railvsi::test
