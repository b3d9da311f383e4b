// Numeric options of the study service are checked before anything runs:
// nan, inf, zero, negative or absurd values exit 2 naming the option.
// Defect: `--lease-s nan` was accepted; the lease was stored NULL, the
// heartbeat spun at 126 % CPU and the job never returned to the queue.
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

class ServiceOptions : public VsiCliTest {};

TEST_F(ServiceOptions, BadNumericOptionsExitTwoNamingTheOption) {
  const std::string db = (dir_ / "o.sqlite").string();
  const auto study = write_json("study.json", {{"name", "unused"}});
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"work", "--lease-s nan"},       {"work", "--lease-s inf"},        {"work", "--lease-s 0"},
      {"work", "--lease-s -5"},        {"work", "--threads -1"},         {"work", "--threads 100000"},
      {"work", "--threads nan"},       {"work", "--cache-mb nan"},       {"work", "--cache-mb 0"},
      {"work", "--cache-mb -1"},       {"work", "--cache-mb inf"},       {"work", "--db-retry-s nan"},
      {"work", "--db-retry-s 0"},      {"run", "--lease-s nan"},         {"submit", "--max-attempts 0"},
      {"submit", "--max-attempts -3"}, {"submit", "--max-attempts 1e9"}, {"query", "--speed-min nan"},
      {"query", "--speed-max inf"},    {"query", "--speed-min -10"}};
  for (const auto& [command, option] : cases) {
    SCOPED_TRACE(command + " " + option);
    std::string args = command + " --db '" + db + "' " + option;
    if (command == "submit" || command == "run") args += " '" + study.string() + "'";
    if (command == "query") args += " --study abcdef";
    const VsiRun run = vsi(args);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(run.out, "");
    const std::string name = option.substr(0, option.find(' '));
    EXPECT_NE(run.err.find(name), std::string::npos) << "the message names " << name << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(db)) << "nothing runs after a bad option";
  }
}

}  // namespace
}  // namespace railvsi::test
