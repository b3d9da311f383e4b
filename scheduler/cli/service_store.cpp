#include "cli/service_store.hpp"

#include <filesystem>
#include <iostream>

#include <spdlog/spdlog.h>

#include "core/terminal_text.hpp"
#include "query/stored_statics.hpp"
#include "queue/job_queue.hpp"
#include "store/store_check.hpp"
#include "store/store_schema.hpp"

namespace railvsi::cli {

void fill_static_envelopes(scheduler::Database& db, const std::optional<std::string>& study_id) {
  const std::string what = study_id ? "study " + study_id->substr(0, 12) : std::string("the upgraded store");
  // A scene that no longer loads (a train file moved) leaves its envelopes to
  // the report, which says why it cannot compute them.
  try {
    const std::size_t n = study_id ? scheduler::store_static_envelopes(db, *study_id)
                                   : scheduler::store_missing_static_envelopes(db);
    if (n > 0) spdlog::info("{}: the static envelopes of {} trains stored", what, n);
  } catch (const std::exception& e) {
    spdlog::warn("{}: static envelopes not stored: {}; vsi query --line and vsi report compute them", what, e.what());
  }
}

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
    const std::int64_t version = [&] {
      scheduler::Statement v = db->prepare("PRAGMA user_version");
      return v.step() ? v.int64(0) : 0;
    }();
    scheduler::migrate(*db);
    // Schema 14 keeps the trains' static envelopes: a store of an older vsi
    // gets those of its line studies once, here (then read, never computed).
    if (version > 0 && version < 14) fill_static_envelopes(*db, std::nullopt);
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
