#pragma once
// Shared by the study service tests: a fresh directory per test, tiny
// studies that run in milliseconds, and the real vsi binary (VSI_BINARY)
// started as a child process.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../support/coach_json.hpp"
#include "store/sqlite.hpp"

namespace railvsi::test {

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A study of 10 m spans and a two-axle train of moving forces: each job is
// a few hundred steps.
inline nlohmann::json tiny_study() {
  return nlohmann::json::parse(R"({
    "name": "tiny",
    "structure": {
      "generator": "bridge-2d", "spans_m": [10], "continuous": false,
      "deck": { "EI_Nm2": 5.0e9, "mass_kg_per_m": 8000 },
      "damping": { "ratio": 0.01 }, "element_length_m": 1.0, "track": null
    },
    "trains": [
      { "name": "two axles", "moving_forces": [{ "offset_m": 0, "load_N": 1.0e5 }, { "offset_m": 3, "load_N": 1.0e5 }] },
      { "name": "one axle", "moving_forces": [{ "offset_m": 0, "load_N": 1.5e5 }] }
    ],
    "speeds_kmh": { "from": 100, "to": 300, "step": 50 },
    "analysis": { "dt_s": 1.0e-3 },
    "outputs": { "points": [{ "name": "quarter", "x_m": 2.5 }, { "name": "midspan", "x_m": 5.0 }] }
  })");
}

// One car-2d coach (ICE3-like values), as a train of vehicles of its own
// when wrapped by one_car_train().
inline nlohmann::json car(double primary_k_N_per_m) { return railvsi::testing::coach_json(primary_k_N_per_m); }

inline nlohmann::json one_car_train() {
  return {{"name", "one coach"}, {"vehicles", nlohmann::json::array({car(2.4e6)})}};
}

// How a child process starts: its working directory, and whether it drops
// root privileges (to nobody) so that file permissions apply to it.
struct ChildSetup {
  std::filesystem::path cwd;
  bool unprivileged = false;
};

// A child process with its output in files.
class Child {
 public:
  Child(const std::vector<std::string>& args, const std::filesystem::path& out, const std::filesystem::path& err,
        const ChildSetup& setup = {}) {
    pid_ = ::fork();
    if (pid_ == 0) {
      std::FILE* o = std::freopen(out.c_str(), "w", stdout);
      std::FILE* e = std::freopen(err.c_str(), "w", stderr);
      if (o == nullptr || e == nullptr) ::_exit(127);
      if (!setup.cwd.empty() && ::chdir(setup.cwd.c_str()) != 0) ::_exit(126);
      if (setup.unprivileged && ::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(125);
      std::vector<char*> argv;
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  ~Child() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  // Exit code, or -signal when killed.
  int wait() {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    waited_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
  }
  void kill9() { ::kill(pid_, SIGKILL); }
  // After a waitpid done by the caller.
  void mark_waited() { waited_ = true; }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  bool waited_ = false;
};

struct VsiResult {
  int exit_code = -1;
  std::string out, err;
};

class ServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("vsi-service-") + info->test_suite_name() + "-" + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write_json(const std::string& name, const nlohmann::json& doc) const {
    const auto file = dir_ / name;
    std::ofstream(file, std::ios::binary) << doc.dump(2);
    return file;
  }

  std::unique_ptr<Child> start_vsi(const std::vector<std::string>& args, const std::string& tag,
                                   const ChildSetup& setup = {}) const {
    std::vector<std::string> all{VSI_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    return std::make_unique<Child>(all, dir_ / (tag + ".out"), dir_ / (tag + ".err"), setup);
  }

  VsiResult vsi(const std::vector<std::string>& args, const std::string& tag = "vsi", const ChildSetup& setup = {}) const {
    auto child = start_vsi(args, tag, setup);
    VsiResult r;
    r.exit_code = child->wait();
    r.out = read_text(dir_ / (tag + ".out"));
    r.err = read_text(dir_ / (tag + ".err"));
    return r;
  }

  std::filesystem::path dir_;
};

inline std::int64_t count_rows(scheduler::Database& db, const std::string& sql) {
  scheduler::Statement s = db.prepare(sql);
  s.step();
  return s.int64(0);
}

}  // namespace railvsi::test
