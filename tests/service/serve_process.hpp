#pragma once
// A real `vsi serve` process on a free loopback port (--port 0: the server
// prints the port it took), and an HTTP client to it (cpp-httplib's, the
// library the server uses, but a separate process and a real socket).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <httplib.h>

namespace railvsi::test {

class ServeProcess {
 public:
  // Starts VSI_BINARY serve --port 0 with `args` (with `whole_command`,
  // VSI_BINARY with `args` alone), its output in log_dir/serve-<n>.log;
  // waits (up to 60 s) for the line naming its port.
  ServeProcess(const std::vector<std::string>& args, const std::filesystem::path& log_dir,
               const std::vector<std::string>& env = {}, bool whole_command = false) {
    static int serial = 0;
    log_ = log_dir / ("serve-" + std::to_string(serial++) + ".log");
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      std::vector<std::string> argv_text = {VSI_BINARY};
      if (!whole_command) argv_text.insert(argv_text.end(), {"serve", "--port", "0"});
      argv_text.insert(argv_text.end(), args.begin(), args.end());
      std::vector<char*> argv;
      for (std::string& a : argv_text) argv.push_back(a.data());
      argv.push_back(nullptr);
      for (const std::string& e : env) ::putenv(const_cast<char*>(e.c_str()));
      const std::string log = log_.string();
      std::FILE* out = std::freopen(log.c_str(), "w", stdout);
      if (out == nullptr || ::dup2(STDOUT_FILENO, STDERR_FILENO) < 0) ::_exit(126);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    const std::regex listening("listening on http://[^:]+:([0-9]+)/");
    while (std::chrono::steady_clock::now() < deadline) {
      std::smatch m;
      const std::string text = log();
      if (std::regex_search(text, m, listening)) {
        port_ = std::stoi(m[1].str());
        return;
      }
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        pid_ = -1;
        return;  // it refused to start: exit_code() and log() say why
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    throw std::runtime_error("vsi serve did not start in 60 s: " + log());
  }
  ~ServeProcess() { stop(SIGKILL); }
  ServeProcess(const ServeProcess&) = delete;
  ServeProcess& operator=(const ServeProcess&) = delete;

  // Sends `signal` and waits for the process; its exit code (128 + the
  // signal when it died of it).
  int stop(int signal) {
    if (pid_ > 0) {
      ::kill(pid_, signal);
      int status = 0;
      ::waitpid(pid_, &status, 0);
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      pid_ = -1;
    }
    return exit_code_;
  }

  int port() const { return port_; }
  bool running() const { return pid_ > 0; }
  int exit_code() const { return exit_code_; }
  std::string log() const {
    std::ifstream in(log_);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", port_);
    c->set_read_timeout(std::chrono::seconds(120));
    return c;
  }

 private:
  std::filesystem::path log_;
  pid_t pid_ = -1;
  int port_ = 0;
  int exit_code_ = -1;
};

// GET /api/studies without a token, with `token` altered, and with `token`:
// the three statuses (-1: no answer). The client keeps the token.
inline std::vector<int> token_statuses(httplib::Client& c, const std::string& token) {
  std::vector<int> statuses;
  const auto status = [&c] {
    const auto r = c.Get("/api/studies");
    return r ? r->status : -1;
  };
  statuses.push_back(status());
  c.set_bearer_token_auth(token + "x");
  statuses.push_back(status());
  c.set_bearer_token_auth(token);
  statuses.push_back(status());
  return statuses;
}

}  // namespace railvsi::test
