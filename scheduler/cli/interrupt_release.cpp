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

InterruptRelease::InterruptRelease(std::string db_file, std::string worker_prefix)
    : db_file_(std::move(db_file)), worker_prefix_(std::move(worker_prefix)) {
  sigemptyset(&signals_);
  sigaddset(&signals_, SIGINT);
  sigaddset(&signals_, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals_, &previous_mask_);
  watcher_ = std::thread([this] { watch(); });
}

InterruptRelease::~InterruptRelease() {
  done_ = true;
  watcher_.join();
  pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

void InterruptRelease::watch() {
  const timespec poll{0, 100'000'000};  // 0.1 s: how soon the destructor's stop is seen
  while (!done_) {
    const int signal = sigtimedwait(&signals_, nullptr, &poll);
    if (signal <= 0) continue;
    // First no new claim (workers read the flag inside their claim's write
    // transaction), then the release: no job is claimed after it.
    stopping_ = true;
    std::string what;
    try {
      scheduler::Database db(db_file_, scheduler::OpenMode::kExisting, 5000);
      // The run's names are prefix:tN; the colon keeps another nonce out.
      const std::int64_t n = scheduler::release_running_jobs(db, worker_prefix_ + ":");
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
