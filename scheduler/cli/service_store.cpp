#include "cli/service_store.hpp"

#include <filesystem>
#include <iostream>

#include "core/terminal_text.hpp"
#include "queue/job_queue.hpp"
#include "store/store_check.hpp"
#include "store/store_schema.hpp"

namespace railvsi::cli {

std::unique_ptr<scheduler::Database> open_store(const std::string& file, scheduler::OpenMode mode) {
  std::error_code ec;
  if (mode != scheduler::OpenMode::kReadOnly && std::filesystem::file_size(file, ec) > 0 && !ec) {
    // Read-only first: a writable connection would switch another
    // program's database to WAL before migrate() refuses it.
    scheduler::Database probe(file, scheduler::OpenMode::kReadOnly);
    scheduler::require_vsi_or_empty(probe);
  }
  auto db = std::make_unique<scheduler::Database>(file, mode);
  if (mode == scheduler::OpenMode::kReadOnly) {
    scheduler::require_current_schema(*db);
    scheduler::require_sound(*db);
  } else {
    // A damaged store is reported, never written to (submit, work and run
    // had added jobs to a file that status and query refuse).
    scheduler::require_sound(*db);
    scheduler::migrate(*db);
    // A process killed mid-run (or stopped by a full disk) leaves its WAL
    // unfolded: fold it in now, as a clean close does, so that this run's
    // WAL starts over instead of growing past it. PASSIVE waits for no
    // other process; a failure (disk still full) is left to the first write.
    try {
      db->exec("PRAGMA wal_checkpoint(PASSIVE)");
    } catch (const scheduler::SqliteError&) {
    }
  }
  return db;
}

std::optional<std::string> find_study(scheduler::Database& db, const std::string& id_or_prefix) {
  const std::string id = scheduler::resolve_study_id(db, id_or_prefix);
  if (id.empty()) {
    std::cerr << "error: no study " << scheduler::terminal_safe(id_or_prefix) << " in "
              << scheduler::terminal_safe(db.file())
              << (id_or_prefix.size() < 6 ? " (give at least 6 digits of the id)" : "") << '\n';
    return std::nullopt;
  }
  return id;
}

std::optional<OpenedStudy> open_study(const std::string& file, const std::string& id_or_prefix,
                                      scheduler::OpenMode mode) {
  if (!std::filesystem::is_regular_file(file)) {
    std::cerr << "error: no such database: " << file << '\n';
    return std::nullopt;
  }
  OpenedStudy s{open_store(file, mode), {}};
  const auto id = find_study(*s.db, id_or_prefix);
  if (!id) return std::nullopt;
  s.id = *id;
  return s;
}

}  // namespace railvsi::cli
