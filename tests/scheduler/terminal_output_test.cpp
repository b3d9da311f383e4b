// What vsi prints to a terminal fits it and cannot drive it: the progress
// line of vsi run is one line redrawn with \r, no wider than the terminal
// (TIOCGWINSZ of a real pseudo-terminal from script(1), else $COLUMNS);
// without a terminal there is no \r; the query table fits 80 columns;
// control characters and ANSI escapes of user strings are escaped.
#include <algorithm>

#include <fmt/format.h>

#include "scheduler_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

constexpr char kEsc = '\x1b';

class TerminalOutputFixture : public ServiceTest {
 public:
  // The transcript of `vsi run` of long_study() in a pseudo-terminal.
  std::string run_in_terminal(const std::string& terminal_setup) const {
    const auto study = write_json("study.json", long_study());
    return in_terminal(fmt::format("{} {} run '{}' --db '{}' --threads 1 >/dev/null", terminal_setup, VSI_BINARY,
                                   study.string(), (dir_ / "r.sqlite").string()));
  }

 protected:
  // Runs `command` in a pseudo-terminal (script -q -e -c); the transcript
  // of the terminal is returned.
  std::string in_terminal(const std::string& command) const {
    const auto transcript = dir_ / "transcript.txt";
    const std::string line = "script -qfec \"" + command + "\" '" + transcript.string() + "' >/dev/null 2>&1 </dev/null";
    EXPECT_EQ(std::system(line.c_str()), 0) << line;
    return read_text(transcript);
  }
  json long_study() const {
    json study = tiny_study();
    study["speeds_kmh"] = {{"from", 100}, {"to", 300}, {"step", 25}};
    return study;
  }
};

using TerminalOutput = TerminalOutputFixture;

bool has_script() { return std::system("command -v script >/dev/null 2>&1") == 0; }

// The redraws of the progress line: the pieces between \r and the next \r
// or \n, where a redraw starts.
std::vector<std::string> redraws(const std::string& transcript) {
  std::vector<std::string> out;
  for (std::size_t r = transcript.find('\r'); r != std::string::npos; r = transcript.find('\r', r + 1)) {
    const std::size_t end = transcript.find_first_of("\r\n", r + 1);
    const std::string piece = transcript.substr(r + 1, end == std::string::npos ? std::string::npos : end - r - 1);
    if (piece.find("done") != std::string::npos) out.push_back(piece);
  }
  return out;
}

// Every redraw of the progress line of `vsi run` in a pseudo-terminal set
// up by `terminal_setup` (shell commands and environment before vsi) has
// `width` characters.
void expect_redraws_of_width(const TerminalOutputFixture& test, const std::string& terminal_setup, std::size_t width) {
  const std::string transcript = test.run_in_terminal(terminal_setup);
  const auto lines = redraws(transcript);
  ASSERT_FALSE(lines.empty()) << transcript;
  for (const auto& l : lines) EXPECT_EQ(l.size(), width) << "'" << l << "'";
}

TEST_F(TerminalOutput, ProgressLineFitsTheTerminalWidthFromTheTerminalItself) {
  if (!has_script()) GTEST_SKIP() << "script(1) missing";
  expect_redraws_of_width(*this, "stty cols 50 rows 20;", 49);  // 50 columns less one: no wrap
}

TEST_F(TerminalOutput, ProgressLineFollowsColumnsWhenTheTerminalHasNoSize) {
  if (!has_script()) GTEST_SKIP() << "script(1) missing";
  // stty cols 0: the terminal reports no width; COLUMNS says 62.
  expect_redraws_of_width(*this, "stty cols 0 rows 0; COLUMNS=62", 61);
}

TEST_F(TerminalOutput, WithoutATerminalProgressIsPlainLinesWithoutCarriageReturns) {
  const auto study = write_json("study.json", long_study());
  const VsiResult run = vsi({"run", study.string(), "--db", (dir_ / "r.sqlite").string(), "--threads", "1"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err.find('\r'), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("jobs done"), std::string::npos) << run.err;
}

TEST_F(TerminalOutput, QueryTableFitsEightyColumnsAndEscapesNames) {
  json study = long_study();
  study["name"] = std::string("study \x1b[2J cleared");
  study["trains"][0]["name"] = std::string("a train with a very long name indeed, longer than any table column \x1b[31mred");
  const auto file = write_json("study.json", study);
  const auto db = (dir_ / "r.sqlite").string();
  ASSERT_EQ(vsi({"submit", file.string(), "--db", db}).exit_code, 0);
  ASSERT_EQ(vsi({"work", "--db", db, "--threads", "1"}).exit_code, 0);
  const VsiResult status = vsi({"status", "--db", db});
  const std::string id = status.out.substr(6, 12);
  const VsiResult query = vsi({"query", "--db", db, "--study", id});
  ASSERT_EQ(query.exit_code, 0) << query.err;
  std::istringstream lines(query.out);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) EXPECT_LE(line.size(), 80u) << line;
  EXPECT_GT(count, 10);
  for (const auto* out : {&query.out, &status.out}) {
    EXPECT_EQ(out->find(kEsc), std::string::npos) << *out;
    EXPECT_NE(out->find("\\x1b["), std::string::npos) << *out;
  }
}

TEST_F(TerminalOutput, ErrorMessagesEscapeControlCharactersOfFileNames) {
  const std::string name = (dir_ / "evil\x1b]0;title\x07\x1b[31m.json").string();
  std::ofstream(name) << "{ \"structure\": 1 }";
  const VsiResult run = vsi({"validate", name});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err.find(kEsc), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find('\x07'), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("evil\\x1b]0;title\\x07\\x1b[31m.json"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace railvsi::test
