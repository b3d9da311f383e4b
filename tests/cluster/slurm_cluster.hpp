#pragma once
// A real single-node Slurm for tests and benchmarks: Debian's munged,
// slurmctld and slurmd started in a directory of their own (own ports, own
// munge socket, SLURM_CONF set for the clients), stopped by pid.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "../scheduler/scheduler_test_support.hpp"

namespace railvsi::test {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

inline std::string which(const std::string& program) {
  for (const char* dir : {"/usr/sbin", "/usr/bin", "/sbin", "/bin", "/usr/local/bin", "/usr/local/sbin"}) {
    const fs::path p = fs::path(dir) / program;
    if (::access(p.c_str(), X_OK) == 0) return p.string();
  }
  return {};
}

// A shell command's standard output (stderr joined); the exit status in *status.
inline std::string sh(const std::string& command, int* status = nullptr) {
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return {};
  std::string out;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int st = ::pclose(pipe);
  if (status != nullptr) *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}

// A daemon in the foreground, stopped by its pid: SIGTERM, then SIGKILL
// after 10 s.
class Daemon {
 public:
  Daemon(const std::vector<std::string>& args, const fs::path& log) {
    pid_ = ::fork();
    if (pid_ == 0) {
      std::FILE* o = std::freopen(log.c_str(), "w", stdout);
      if (o == nullptr || ::dup2(STDOUT_FILENO, STDERR_FILENO) < 0) ::_exit(127);
      ::setpgid(0, 0);
      std::vector<char*> argv;
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  ~Daemon() { stop(); }
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;
  bool running() {
    if (pid_ <= 0) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) pid_ = -1;
    return pid_ > 0;
  }
  void stop() {
    if (!running()) return;
    ::kill(pid_, SIGTERM);
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    while (Clock::now() < deadline) {
      if (::waitpid(pid_, nullptr, WNOHANG) == pid_) {
        pid_ = -1;
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};

// waits until ready() or the deadline; true when ready.
template <class Ready>
inline bool wait_until(Ready ready, std::chrono::seconds limit, std::chrono::milliseconds poll = std::chrono::milliseconds(200)) {
  const auto deadline = Clock::now() + limit;
  while (Clock::now() < deadline) {
    if (ready()) return true;
    std::this_thread::sleep_for(poll);
  }
  return ready();
}

class SlurmCluster {
 public:
  // Empty when the cluster runs; otherwise why it cannot. Its directory is
  // short (/tmp/vsi-slurm-PID): slurmstepd's socket paths must fit 108 bytes.
  std::string start() {
    const fs::path dir = fs::path("/tmp") / ("vsi-slurm-" + std::to_string(::getpid()));
    if (::geteuid() != 0) return "the Slurm test runs as root (as CI does): slurmd must start jobs";
    for (const char* p : {"munged", "slurmctld", "slurmd", "sbatch", "squeue", "scontrol", "sinfo"})
      if (which(p).empty())
        return std::string(p) + " is not installed (Debian packages munge slurmctld slurmd slurm-client; tests/setup "
                                "installs them)";
    dir_ = dir;
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "state");
    fs::create_directories(dir_ / "spool");
    // munged wants a private key file and a socket directory others can enter.
    ::chmod(dir_.c_str(), 0755);
    {
      std::ifstream random("/dev/urandom", std::ios::binary);
      std::string key(1024, '\0');
      random.read(key.data(), static_cast<std::streamsize>(key.size()));
      std::ofstream(dir_ / "munge.key", std::ios::binary) << key;
      ::chmod((dir_ / "munge.key").c_str(), 0400);
    }
    const std::string socket = (dir_ / "munge.socket").string();
    munged_ = std::make_unique<Daemon>(
        std::vector<std::string>{which("munged"), "-F", "--force", "--socket=" + socket,
                                 "--key-file=" + (dir_ / "munge.key").string(),
                                 "--pid-file=" + (dir_ / "munged.pid").string(),
                                 "--log-file=" + (dir_ / "munged.log").string(),
                                 "--seed-file=" + (dir_ / "munged.seed").string()},
        dir_ / "munged.out");
    if (!wait_until([&] { return fs::exists(socket); }, std::chrono::seconds(20)))
      return "munged did not start: " + read_text(dir_ / "munged.out");

    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    const int port = 20000 + static_cast<int>(::getpid() % 20000) * 2;
    const std::string d = dir_.string();
    std::ofstream(dir_ / "slurm.conf")
        << "ClusterName=vsitest\n"
        << "SlurmctldHost=" << host << "(127.0.0.1)\n"
        << "SlurmUser=root\nSlurmdUser=root\n"
        << "SlurmctldPort=" << port << "\nSlurmdPort=" << port + 1 << "\n"
        << "AuthType=auth/munge\nAuthInfo=socket=" << socket << "\nCredType=cred/munge\n"
        << "StateSaveLocation=" << d << "/state\nSlurmdSpoolDir=" << d << "/spool\n"
        << "SlurmctldPidFile=" << d << "/slurmctld.pid\nSlurmdPidFile=" << d << "/slurmd.pid\n"
        << "SlurmctldLogFile=" << d << "/slurmctld.log\nSlurmdLogFile=" << d << "/slurmd.log\n"
        << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
        << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
        << "SchedulerType=sched/backfill\nSelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
        << "MpiDefault=none\nReturnToService=2\nSlurmdParameters=config_overrides\n"
        // Finished jobs stay visible to scontrol for the checks.
        << "MinJobAge=600\n"
        << "NodeName=vsinode NodeHostname=" << host << " NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN\n"
        << "PartitionName=debug Nodes=vsinode Default=YES MaxTime=INFINITE State=UP\n";
    ::setenv("SLURM_CONF", (dir_ / "slurm.conf").c_str(), 1);
    const std::string conf = (dir_ / "slurm.conf").string();
    slurmctld_ = std::make_unique<Daemon>(std::vector<std::string>{which("slurmctld"), "-D", "-f", conf},
                                          dir_ / "slurmctld.out");
    slurmd_ = std::make_unique<Daemon>(std::vector<std::string>{which("slurmd"), "-D", "-f", conf, "-N", "vsinode"},
                                       dir_ / "slurmd.out");
    if (!wait_until([] { return sh("sinfo -h -o %t").find("idle") != std::string::npos; }, std::chrono::seconds(60),
                    std::chrono::milliseconds(500)))
      return "the Slurm node did not become idle: " + sh("sinfo") + read_text(dir_ / "slurmctld.log") +
             read_text(dir_ / "slurmd.log");
    return {};
  }

  ~SlurmCluster() {
    if (slurmctld_ && slurmctld_->running()) sh("scancel --full --user=root");
    slurmd_.reset();
    slurmctld_.reset();
    munged_.reset();
    ::unsetenv("SLURM_CONF");
    if (!dir_.empty()) {
      std::error_code ignored;
      fs::remove_all(dir_, ignored);
    }
  }

  const fs::path& dir() const { return dir_; }

  // "Key=Value" of scontrol show job, "" when absent.
  static std::string job_field(const std::string& job, const std::string& key) {
    const std::string text = sh("scontrol show job " + job);
    std::smatch m;
    if (std::regex_search(text, m, std::regex("(^|\\s)" + key + "=(\\S+)"))) return m[2].str();
    return {};
  }

 private:
  fs::path dir_;
  std::unique_ptr<Daemon> munged_, slurmctld_, slurmd_;
};

// Pids of processes whose command line holds every word.
inline std::vector<pid_t> processes_with(const std::vector<std::string>& words) {
  std::vector<pid_t> pids;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = read_text(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (std::all_of(words.begin(), words.end(), [&](const auto& w) { return cmdline.find(w) != std::string::npos; }))
      pids.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return pids;
}

}  // namespace railvsi::test
