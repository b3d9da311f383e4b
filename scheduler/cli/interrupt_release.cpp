#include "cli/interrupt_release.hpp"

#include <pthread.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>

#include <fmt/format.h>

#include "core/terminal_text.hpp"
#include "queue/job_queue.hpp"
#include "store/sqlite.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::cli {

InterruptRelease::InterruptRelease(std::string db_file) : db_file_(std::move(db_file)) {
  sigemptyset(&signals_);
  sigaddset(&signals_, SIGINT);
  sigaddset(&signals_, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals_, &previous_mask_);
  watcher_ = std::thread([this] { watch(); });
}

InterruptRelease::~InterruptRelease() {
  stop_ = true;
  watcher_.join();
  pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

void InterruptRelease::watch() {
  const timespec poll{0, 100'000'000};  // 0.1 s: how soon the destructor's stop is seen
  while (!stop_) {
    const int signal = sigtimedwait(&signals_, nullptr, &poll);
    if (signal <= 0) continue;
    std::string what;
    try {
      scheduler::Database db(db_file_, scheduler::OpenMode::kExisting, 5000);
      const std::int64_t n = scheduler::release_running_jobs(db, scheduler::process_worker_stem());
      what = fmt::format("{} running jobs of this process went back to the queue; vsi work --db {} resumes them", n,
                         db_file_);
    } catch (const std::exception& e) {
      what = fmt::format("its running jobs could not be given back ({}): they are taken over when their lease "
                         "expires",
                         e.what());
    }
    std::fprintf(stderr, "\ninterrupted (%s): %s\n", signal == SIGINT ? "SIGINT" : "SIGTERM",
                 scheduler::terminal_safe(what).c_str());
    std::fflush(stderr);
    // The workers' transactions in progress are not committed: SQLite rolls
    // them back when the store is next opened.
    std::_Exit(128 + signal);
  }
}

}  // namespace railvsi::cli
