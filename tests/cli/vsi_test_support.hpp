#pragma once
// Runs the real vsi binary (VSI_BINARY) on documents written to a fresh
// temporary directory, capturing its exit code, stdout and stderr.
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../support/two_hslm_study.hpp"

namespace railvsi::test {

struct VsiRun {
  int exit_code = -1;
  std::string out, err;
};

// The study id a `vsi submit` printed ("study <64 hex>"), or the 12-digit
// prefix `vsi run` logs and tables show (a prefix vsi accepts as --study).
inline std::string study_id_of(const std::string& output) {
  std::smatch m;
  const std::regex re("study ([0-9a-f]{12,64})");
  return std::regex_search(output, m, re) ? m[1].str() : std::string();
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Two HSLM trains over the 25 m span of the README example (light deck:
// its resonances exceed the ballasted limit), five speeds: 10 quick jobs.
inline nlohmann::json two_hslm_trains_study(const std::string& name) {
  nlohmann::json doc = railvsi::testing::two_hslm_trains_without_speeds(name);
  doc["speeds_kmh"] = {{"from", 200}, {"to", 400}, {"step", 50}};
  return doc;
}

class VsiCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("vsi-cli-") + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto file = dir_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  std::filesystem::path write_json(const std::string& name, const nlohmann::json& doc) const {
    return write(name, doc.dump(2));
  }

  // The scene every case starts from: small, valid and quick to run.
  static nlohmann::json small_scene() {
    return nlohmann::json::parse(read_text(std::filesystem::path(RAILVSI_TEST_DATA) / "small-scene.json"));
  }

  VsiRun vsi(const std::string& args) const {
    const auto out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    // Under a timeout: an input that makes vsi hang fails the test (124)
    // instead of hanging the suite.
    const std::string command =
        "timeout 120 " + std::string(VSI_BINARY) + " " + args + " >'" + out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    VsiRun run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out = read_text(out);
    run.err = read_text(err);
    return run;
  }

  // The contract for bad input: exit 2, nothing on stdout (nothing ran), and
  // "error: <file>: <json path>: ..." on stderr.
  static void expect_input_error(const VsiRun& run, const std::filesystem::path& file, const std::string& json_path) {
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(run.out, "");
    EXPECT_NE(run.err.find("error: " + file.string() + ": " + json_path + ": "), std::string::npos)
        << "expected " << file.string() << ": " << json_path << " in: " << run.err;
  }

  // Both commands must refuse the scene the same way.
  void expect_rejected(const std::filesystem::path& scene, const std::string& json_path,
                       const std::filesystem::path& file_in_error = {}) const {
    const auto file = file_in_error.empty() ? scene : file_in_error;
    SCOPED_TRACE(scene.string());
    for (const char* command : {"validate", "simulate"}) {
      SCOPED_TRACE(command);
      expect_input_error(vsi(std::string(command) + " '" + scene.string() + "'"), file, json_path);
    }
  }

  std::filesystem::path dir_;
};

}  // namespace railvsi::test
