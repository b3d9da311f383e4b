#include "cli/serve_command.hpp"

#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <thread>

#include <httplib.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "cli/commands.hpp"
#include "cli/interrupt_release.hpp"
#include "cli/service_store.hpp"
#include "http/bearer_token.hpp"
#include "http/study_api.hpp"
#include "queue/job_queue.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::cli {

ServeCommand::ServeCommand(CLI::App& app) {
  serve_ = app.add_subcommand(
      "serve", "Serve a study store over HTTP: a JSON API (schemas/http-api.openapi.json), a dashboard at /, and a "
               "worker pool that runs the queue as vsi work does");
  ServiceArgs& s = args_.service;
  serve_->add_option("--db", s.db, "Study database (SQLite file; created if needed)")->capture_default_str();
  serve_->add_option("--port", args_.port, "TCP port (0: any free port, printed at start)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  serve_->add_option("--bind", args_.bind,
                     "Address to listen on; another than loopback needs a token (--token or RAILVSI_TOKEN)")
      ->capture_default_str();
  s.threads = 1;
  serve_->add_option("--threads", s.threads,
                     "Worker threads running the queue (0: only accept studies, leaving the work to vsi work "
                     "processes on the same store)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  serve_->add_option("--token", args_.token,
                     "Token every /api request must carry (Authorization: Bearer <token>); default: the "
                     "environment variable RAILVSI_TOKEN");
  serve_->add_option("--max-body-mb", args_.max_body_mb, "Largest request body, MB (larger: 413)")
      ->check(CLI::Range(0.001, 1024.0))
      ->capture_default_str();
  serve_->add_option("--lease-s", s.lease_s, "Lease of a claimed job in s (as vsi work)")->check(CLI::Range(1.0, 1e6));
  serve_->add_option("--max-attempts", s.max_attempts, "Attempts per job before it fails (as vsi submit)")
      ->check(CLI::Range(1, 100));
}

std::optional<int> ServeCommand::run_parsed() const {
  if (!serve_->parsed()) return std::nullopt;
  spdlog::set_default_logger(spdlog::stderr_color_mt("vsi"));
  scheduler::single_threaded_blas();
  ServeArgs args = args_;
  if (args.token.empty())
    if (const char* env = std::getenv("RAILVSI_TOKEN")) args.token = env;
  return serve_command(args);
}

namespace {

// The pool's thread: runs the queue whenever it holds work, as vsi work does
// (refinement passes and verification included); idle, it looks every 0.5 s.
void run_queue(const ServiceArgs& args, const WorkerIdentity& identity, const std::atomic<bool>& server_done) {
  const auto db = open_store(args.db, scheduler::OpenMode::kExisting);
  bool first = true;  // a refinement left pending by a previous server is taken up at once
  while (!identity.stopping->load() && !server_done.load()) {
    if (first || scheduler::state_counts(*db).unfinished() > 0) {
      const scheduler::WorkSummary s = work_and_refine(args, *db, scheduler::study_ids(*db), &identity);
      if (!s.error.empty()) spdlog::error("workers stopped: {}; retrying in 5 s", s.error);
      if (!s.error.empty()) std::this_thread::sleep_for(std::chrono::seconds(5));
    }
    first = false;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
}

}  // namespace

int serve_command(const ServeArgs& args) {
  if (!scheduler::is_loopback_address(args.bind) && args.token.empty()) {
    std::cerr << "error: --bind " << args.bind
              << " is reachable from other hosts: give a token (--token or RAILVSI_TOKEN) that every API request "
                 "must carry\n";
    return kExitInvalidInput;
  }
  open_store(args.service.db, scheduler::OpenMode::kCreate);  // created and migrated before any request
  // Before any thread starts: they all inherit its signal mask, and its
  // thread gives this process's running jobs back on SIGINT or SIGTERM.
  const WorkerIdentity identity{scheduler::worker_name_prefix(), nullptr};
  const InterruptRelease interrupts(args.service.db, identity.prefix);
  const WorkerIdentity workers{identity.prefix, interrupts.stopping()};

  scheduler::StudyApiOptions options;
  options.service = args.service;
  options.token = args.token;
  options.max_body_bytes = static_cast<std::size_t>(args.max_body_mb * 1024.0 * 1024.0);
  scheduler::StudyApi api(options);
  httplib::Server server;
  // The library owns its task queue (a raw pointer by its API): 16 request threads.
  server.new_task_queue = [] { return new httplib::ThreadPool(16); };
  api.mount(server);
  // The library listens with a backlog of 5, compiled into Debian's build:
  // a burst of clients (100 status polls at once) overflowed it, and the
  // dropped connections waited for SYN retries (p99 55 s, 87 of 500 failed).
  // Listening again on the bound socket raises the backlog (Linux).
  int listening_socket = -1;
  server.set_socket_options([&listening_socket](int sock) {
    httplib::default_socket_options(sock);
    listening_socket = sock;
  });
  // An idle keep-alive connection holds a request thread: 1 s, not 5.
  server.set_keep_alive_timeout(1);
  const int port = args.port == 0 ? server.bind_to_any_port(args.bind) : (server.bind_to_port(args.bind, args.port) ? args.port : -1);
  if (port < 0) {
    std::cerr << "error: cannot listen on " << args.bind << ":" << args.port << '\n';
    return kExitRuntimeFailure;
  }
  if (listening_socket >= 0) ::listen(listening_socket, SOMAXCONN);
  std::atomic<bool> server_done{false};
  std::jthread pool;
  if (args.service.threads > 0) pool = std::jthread([&] { run_queue(args.service, workers, server_done); });
  std::cout << "listening on http://" << args.bind << ":" << port << "/ (store " << args.service.db << ", "
            << args.service.threads << " worker threads" << (args.token.empty() ? "" : ", token required") << ")"
            << std::endl;
  server.listen_after_bind();  // returns only when the server fails
  std::cerr << "error: the server stopped listening\n";
  server_done = true;
  return kExitRuntimeFailure;
}

}  // namespace railvsi::cli
