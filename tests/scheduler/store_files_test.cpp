// What --db and --out name must be a store file and a report file: a FIFO
// is refused at once (status, check, query, replay, work blocked on it
// forever), an empty file is not turned into a store by vsi work, and
// report --out "" does not write into the current folder. Exit 2 with the
// file named; nothing written.
#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "scheduler_test_support.hpp"

namespace railvsi::test {
namespace {

class StoreFiles : public ServiceTest {
 protected:
  // The command's result, or exit -1000 when it still ran after 20 s (killed).
  VsiResult vsi_within_20_s(const std::vector<std::string>& args, const std::string& tag) const {
    auto child = start_vsi(args, tag);
    VsiResult r;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    int status = 0;
    while (::waitpid(child->pid(), &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        child->kill9();
        ::waitpid(child->pid(), &status, 0);
        child->mark_waited();
        r.exit_code = -1000;
        return r;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    child->mark_waited();
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
    r.out = read_text(dir_ / (tag + ".out"));
    r.err = read_text(dir_ / (tag + ".err"));
    return r;
  }
};

TEST_F(StoreFiles, AFifoIsRefusedAtOnceNotWaitedOn) {
  const std::string fifo = (dir_ / "pipe").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::vector<std::vector<std::string>> commands{
      {"status", "--db", fifo},           {"check", "--db", fifo},
      {"query", "--db", fifo, "--study", "abcdef"}, {"replay", "abcdef", "--db", fifo},
      {"work", "--db", fifo, "--threads", "1"},     {"cancel", "--db", fifo, "--study", "abcdef"}};
  for (const auto& args : commands) {
    const VsiResult r = vsi_within_20_s(args, args[0]);
    EXPECT_EQ(r.exit_code, 2) << args[0] << " (-1000: still blocked after 20 s)\n" << r.err;
    EXPECT_NE(r.err.find(fifo + ": is not a regular file (a FIFO)"), std::string::npos) << args[0] << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(fifo + "-wal"));
}

TEST_F(StoreFiles, WorkDoesNotTurnAnEmptyFileIntoAStore) {
  const auto empty = dir_ / "empty.sqlite";
  std::ofstream{empty};
  for (const char* command : {"work", "status", "cancel"}) {
    std::vector<std::string> args{command, "--db", empty.string()};
    if (std::string(command) == "cancel") args.insert(args.end(), {"--study", "abcdef"});
    const VsiResult r = vsi_within_20_s(args, command);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
    EXPECT_NE(r.err.find(empty.string() + ": is empty, not a vsi study database"), std::string::npos)
        << command << "\n" << r.err;
  }
  EXPECT_EQ(std::filesystem::file_size(empty), 0u);
  EXPECT_FALSE(std::filesystem::exists(empty.string() + "-wal"));
  // vsi submit creates the store in an empty file (as from mktemp).
  const auto study = write_json("tiny.json", tiny_study());
  EXPECT_EQ(vsi({"submit", study.string(), "--db", empty.string()}).exit_code, 0);
}

TEST_F(StoreFiles, ReportOutEmptyIsRefusedAndWritesNothing) {
  const auto study = write_json("tiny.json", tiny_study());
  const std::string db = (dir_ / "r.sqlite").string();
  const VsiResult ran = vsi({"run", study.string(), "--db", db, "--threads", "1"});
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  const auto cwd = dir_ / "cwd";
  std::filesystem::create_directories(cwd);
  const VsiResult r = vsi({"report", "--db", db, "--study", ran.out.substr(ran.out.find("study ") + 6, 12), "--out", ""},
                          "report", ChildSetup{cwd});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_empty(cwd)) << "the report went into the current folder";
}

}  // namespace
}  // namespace railvsi::test
