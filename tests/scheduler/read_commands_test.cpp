// The read commands (status, query, check) as users run them: they open the
// database read-only, never create one, fail whole (exit 1, nothing on
// stdout) on a damaged file, show jobs of dead workers as such, measure
// throughput over recent work, and refuse filters that cannot match.
#include <sys/stat.h>

#include <regex>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/unix_time.hpp"
#include "queue/job_queue.hpp"
#include "scheduler_test_support.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using namespace railvsi::scheduler;

class ReadCommands : public ServiceTest {
 protected:
  // 2 trains x 21 speeds of the tiny study, submitted and worked by the
  // real binary.
  void run_sweep() {
    json doc = tiny_study();
    doc["speeds_kmh"] = {{"from", 100}, {"to", 300}, {"step", 10}};
    const auto study = write_json("sweep.json", doc);
    db_file_ = (dir_ / "r.sqlite").string();
    const VsiResult submitted = vsi({"submit", study.string(), "--db", db_file_});
    ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
    study_id_ = submitted.out.substr(6, 64);
    const VsiResult worked = vsi({"work", "--db", db_file_, "--threads", "2"});
    ASSERT_EQ(worked.exit_code, 0) << worked.err;
  }
  // Submitted only (42 queued jobs), for tests that set the job rows.
  void submit_sweep() {
    json doc = tiny_study();
    doc["speeds_kmh"] = {{"from", 100}, {"to", 300}, {"step", 10}};
    db_file_ = (dir_ / "r.sqlite").string();
    Database db(db_file_);
    migrate(db);
    study_id_ = submit_study(db, expand_study(doc, dir_, (dir_ / "s.json").string())).study_id;
  }
  std::string db_file_, study_id_;
};

std::size_t lines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

// Defect: status and query on a 0444 file exited 1 ("PRAGMA
// journal_mode=WAL: attempt to write a readonly database"). Run as nobody
// when the tests run as root (root ignores file modes), in a directory it
// may write (SQLite creates the -shm) and in one it may not (as on a
// read-only mount: the read falls back to immutable=1).
TEST_F(ReadCommands, StatusAndQueryReadA0444FileWithAndWithoutAWritableDirectory) {
  run_sweep();
  for (const bool writable_dir : {true, false}) {
    SCOPED_TRACE(writable_dir ? "writable directory" : "read-only directory");
    const auto ro = dir_ / (writable_dir ? "rw-dir" : "ro-dir");
    std::filesystem::create_directories(ro);
    const auto file = ro / "r.sqlite";
    std::filesystem::copy_file(db_file_, file);
    ::chmod(file.c_str(), 0444);
    ::chmod(ro.c_str(), writable_dir ? 0777 : 0555);
    const std::string before = read_text(file);
    const ChildSetup nobody{{}, true};
    const VsiResult status = vsi({"status", "--db", file.string()}, "status", nobody);
    EXPECT_EQ(status.exit_code, 0) << status.err;
    EXPECT_NE(status.out.find("42 total, 0 queued, 0 running, 42 done"), std::string::npos) << status.out;
    const VsiResult csv = vsi({"query", "--db", file.string(), "--study", study_id_, "--format", "csv"}, "query", nobody);
    EXPECT_EQ(csv.exit_code, 0) << csv.err;
    // Per job: 11 rows, and on this beam deck 6 of moment and shear (2
    // points and overall) and 6 of the 2 supports (and overall).
    EXPECT_EQ(lines(csv.out), 1u + 42u * 23u);
    const VsiResult check = vsi({"check", "--db", file.string()}, "check", nobody);
    EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
    EXPECT_EQ(read_text(file), before) << "a read command changed the file";
    ::chmod(ro.c_str(), 0755);
  }
}

// Defect: `vsi status --db typo.sqlite`, `vsi work --db nothing.sqlite` and
// `vsi query` without --db created empty databases and exited 0.
TEST_F(ReadCommands, CommandsThatDoNotSubmitNeverCreateADatabase) {
  const std::string missing = (dir_ / "typo.sqlite").string();
  const std::vector<std::vector<std::string>> commands = {
      {"status", "--db", missing},
      {"query", "--db", missing, "--study", "abcdef"},
      {"work", "--db", missing},
      {"cancel", "--db", missing, "--study", "abcdef"},
      {"retry", "--db", missing, "--study", "abcdef"},
      {"check", "--db", missing}};
  for (const auto& args : commands) {
    SCOPED_TRACE(args.front());
    const VsiResult r = vsi(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "error: no such database: " + missing + "\n");
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(std::filesystem::exists(missing));
  }
  // The default database, ./vsi-results.sqlite, is not created either.
  const VsiResult r = vsi({"query", "--study", "abcdef"}, "default", ChildSetup{dir_, false});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: no such database: vsi-results.sqlite\n");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "vsi-results.sqlite"));
}

// Defect: a damaged file gave partial results with exit 0. Pages in the
// middle of a real database are overwritten (zeros, then a copy of another
// page); whatever status and query read, they either print everything
// (exit 0) or nothing (exit 1 with the SQLite message), and `vsi check`
// finds the damage (exit 1) where it reports a sound file with exit 0.
TEST_F(ReadCommands, DamagedDatabaseIsReportedByCheckAndNeverReadInPart) {
  run_sweep();
  const VsiResult sound = vsi({"check", "--db", db_file_});
  EXPECT_EQ(sound.exit_code, 0) << sound.out << sound.err;
  EXPECT_NE(sound.out.find("ok: "), std::string::npos) << sound.out;
  const auto size = std::filesystem::file_size(db_file_);
  const std::size_t page = 4096, pages = size / page;
  ASSERT_GE(pages, 30u);
  int damage_found_by_reads = 0, damage_refused_by_work = 0;
  for (const bool zeros : {true, false})
    for (const std::size_t first : {pages / 4, pages / 2, 3 * pages / 4}) {
      SCOPED_TRACE(fmt::format("{} at page {}", zeros ? "zeros" : "copy", first));
      const auto damaged = dir_ / "damaged.sqlite";
      std::filesystem::copy_file(db_file_, damaged, std::filesystem::copy_options::overwrite_existing);
      {
        std::fstream f(damaged, std::ios::in | std::ios::out | std::ios::binary);
        std::string bytes(2 * page, '\0');
        if (!zeros) {
          f.seekg(static_cast<std::streamoff>((first + 5) * page));
          f.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        }
        f.seekp(static_cast<std::streamoff>(first * page));
        f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      }
      const VsiResult check = vsi({"check", "--db", damaged.string()});
      EXPECT_EQ(check.exit_code, 1) << check.out;
      EXPECT_NE(check.out.find("problem: "), std::string::npos) << check.out;
      const VsiResult status = vsi({"status", "--db", damaged.string()});
      if (status.exit_code == 0) {
        EXPECT_NE(status.out.find("42 total, 0 queued, 0 running, 42 done"), std::string::npos) << status.out;
      } else {
        ++damage_found_by_reads;
        EXPECT_EQ(status.exit_code, 1);
        EXPECT_EQ(status.out, "") << "partial output";
        EXPECT_TRUE(status.err.find("malformed") != std::string::npos || status.err.find("is damaged") != std::string::npos)
            << status.err;
      }
      // A store that status finds damaged is not written to either (vsi
      // work, submit and run had added to such a file and exited 0).
      if (status.err.find("is damaged") != std::string::npos) {
        ++damage_refused_by_work;
        const VsiResult work = vsi({"work", "--db", damaged.string(), "--threads", "1"});
        EXPECT_EQ(work.exit_code, 1) << work.err;
        EXPECT_NE(work.err.find(damaged.string() + " is damaged"), std::string::npos) << work.err;
      }
      const VsiResult csv = vsi({"query", "--db", damaged.string(), "--study", study_id_, "--format", "csv"});
      if (csv.exit_code == 0) {
        EXPECT_EQ(lines(csv.out), 1u + 42u * 23u);
      } else {
        ++damage_found_by_reads;
        EXPECT_EQ(csv.exit_code, 1);
        EXPECT_EQ(csv.out, "") << "partial output";
      }
    }
  EXPECT_GT(damage_found_by_reads, 0) << "no damage reached the reads: the test proves nothing about them";
  EXPECT_GT(damage_refused_by_work, 0) << "no damage found by quick_check: the test proves nothing about work";
}

TEST_F(ReadCommands, CheckReportsARunningJobWithoutALease) {
  run_sweep();
  {
    Database db(db_file_);
    db.exec("UPDATE jobs SET state = 'running', lease_expires = NULL WHERE rowid = (SELECT min(rowid) FROM jobs)");
  }
  const VsiResult check = vsi({"check", "--db", db_file_});
  EXPECT_EQ(check.exit_code, 1);
  EXPECT_NE(check.out.find("problem: 1 running jobs without a lease"), std::string::npos) << check.out;
}

// Defect: jobs of killed workers showed as running until the queue
// drained, and throughput ran from the first start: 11 jobs over an hour
// read 0.003 jobs/s where the last 10 had finished at about 1 per second;
// cancelled jobs counted too. Here: one job an hour ago, ten finishing one
// per second up to now (each started 1 s before it finished), 20 cancelled
// just now, one running under an expired lease and one under a valid one.
TEST_F(ReadCommands, StatusShowsExpiredLeasesAndTheRecentThroughput) {
  submit_sweep();
  {
    Database db(db_file_);
    const double now = unix_now_s();
    Statement ids = db.prepare("SELECT job_id FROM study_jobs ORDER BY position");
    std::vector<std::string> id;
    while (ids.step()) id.push_back(ids.text(0));
    ASSERT_EQ(id.size(), 42u);
    const auto set = [&](std::size_t k, const char* state, double started, double finished) {
      db.prepare("UPDATE jobs SET state = ?, started_at = ?, finished_at = ?, attempts = 1 WHERE id = ?")
          .bind(1, state).bind(2, started).bind(3, finished).bind(4, id[k]).run();
      // A done job has its envelopes (status checks that the store is consistent).
      if (std::string(state) == "done")
        db.prepare("INSERT INTO job_envelopes (job_seq, quantity, location, value) "
                   "SELECT seq, 'deck_displacement_m', '', 0.001 FROM jobs WHERE id = ?")
            .bind(1, id[k]).run();
    };
    set(0, "done", now - 3601, now - 3600);
    for (std::size_t k = 0; k < 10; ++k) set(1 + k, "done", now - 11.0 + static_cast<double>(k), now - 10.0 + static_cast<double>(k));
    for (std::size_t k = 11; k < 31; ++k) set(k, "cancelled", now - 2, now - 1);
    db.prepare("UPDATE jobs SET state = 'running', worker = 'dead', lease_expires = ?, attempts = 1 WHERE id = ?")
        .bind(1, now - 5).bind(2, id[31]).run();
    db.prepare("UPDATE jobs SET state = 'running', worker = 'alive', lease_expires = ?, attempts = 1 WHERE id = ?")
        .bind(1, now + 600).bind(2, id[32]).run();
  }
  const VsiResult status = vsi({"status", "--db", db_file_});
  ASSERT_EQ(status.exit_code, 0) << status.err;
  EXPECT_NE(status.out.find("42 total, 9 queued, 1 running, 1 running (lease expired), 11 done, 0 failed, 20 cancelled"),
            std::string::npos)
      << status.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(status.out, m, std::regex("throughput: ([0-9.]+) jobs/s"))) << status.out;
  // 10 jobs over the 11 s since the first of them started: 0.91 jobs/s.
  EXPECT_NEAR(std::stod(m[1].str()), 10.0 / 11.0, 0.05) << status.out;
  EXPECT_NE(status.out.find("ETA"), std::string::npos) << status.out;
}

// Defect: an unknown or mis-cased train, --speed-min above --speed-max, or
// a speed range between two of the study's speeds printed "0 jobs shown"
// with exit 0.
TEST_F(ReadCommands, QueryRefusesFiltersThatCannotMatchAndListsWhatExists) {
  submit_sweep();
  const auto query = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"query", "--db", db_file_, "--study", study_id_};
    args.insert(args.end(), extra.begin(), extra.end());
    return vsi(args);
  };
  const VsiResult unknown = query({"--train", "HSLM-A33"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(unknown.out, "");
  EXPECT_NE(unknown.err.find("--train 'HSLM-A33'"), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("'two axles', 'one axle'"), std::string::npos) << unknown.err;
  const VsiResult cased = query({"--train", "ONE AXLE"});
  EXPECT_EQ(cased.exit_code, 2);
  EXPECT_NE(cased.err.find("case-sensitive: 'one axle'"), std::string::npos) << cased.err;
  const VsiResult reversed = query({"--speed-min", "500", "--speed-max", "100"});
  EXPECT_EQ(reversed.exit_code, 2);
  EXPECT_NE(reversed.err.find("--speed-min 500 is above --speed-max 100"), std::string::npos) << reversed.err;
  const VsiResult beyond = query({"--speed-min", "400"});
  EXPECT_EQ(beyond.exit_code, 2);
  EXPECT_NE(beyond.err.find("from 100 to 300 km/h"), std::string::npos) << beyond.err;
  // Inside the study's speeds but between two of them: no speed either.
  const VsiResult between = query({"--speed-min", "155", "--speed-max", "158"});
  EXPECT_EQ(between.exit_code, 2);
  EXPECT_EQ(between.out, "");
  EXPECT_NE(between.err.find("[155, 158] km/h holds no speed of the study: it lies between two of its speeds, 150 and "
                             "160 km/h"),
            std::string::npos)
      << between.err;
  const VsiResult profile = query({"--irregularity", "fra-6"});
  EXPECT_EQ(profile.exit_code, 2);
  EXPECT_NE(profile.err.find("it has: 'none'"), std::string::npos) << profile.err;
  const VsiResult fine = query({"--train", "one axle", "--speed-min", "150", "--speed-max", "200"});
  EXPECT_EQ(fine.exit_code, 0) << fine.err;
  EXPECT_NE(fine.out.find("6 jobs shown"), std::string::npos) << fine.out;
}

}  // namespace
}  // namespace railvsi::test
