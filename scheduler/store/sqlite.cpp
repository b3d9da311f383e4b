#include "store/sqlite.hpp"

#include <sqlite3.h>

#include <filesystem>

#include <fmt/format.h>

namespace railvsi::scheduler {
namespace {

// The message names the database file: "database is locked" alone left a
// user guessing which of several stores.
[[noreturn]] void fail(sqlite3* db, int code, std::string_view what) {
  const char* file = db != nullptr ? sqlite3_db_filename(db, "main") : nullptr;
  throw SqliteError(code, fmt::format("sqlite: {}{}: {}", file != nullptr && *file != '\0' ? std::string(file) + ": " : "",
                                      what, db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(code)));
}

}  // namespace

void Database::Closer::operator()(sqlite3* db) const { sqlite3_close_v2(db); }

namespace {

// file: URI of a path: '%', '?' and '#' are the characters SQLite decodes.
std::string file_uri(const std::string& path) {
  std::string uri = "file:";
  for (const char c : path) {
    if (c == '%' || c == '?' || c == '#') uri += fmt::format("%{:02X}", static_cast<unsigned char>(c));
    else uri += c;
  }
  return uri;
}

// SQLITE_ROW when the schema can be read, else the error code.
int read_schema(sqlite3* db) {
  sqlite3_stmt* raw = nullptr;
  int rc = sqlite3_prepare_v2(db, "SELECT count(*) FROM sqlite_schema", -1, &raw, nullptr);
  if (rc == SQLITE_OK) rc = sqlite3_step(raw);
  sqlite3_finalize(raw);
  return rc;
}

// A FIFO would block the open forever and a directory or device is no
// store; an empty file opened as an existing store would silently become
// one (SQLite treats it as a new database). In-memory names are not files.
void refuse_what_is_no_store(const std::string& file, OpenMode mode) {
  if (file.empty() || file == ":memory:") return;
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || status.type() == std::filesystem::file_type::not_found) return;
  if (status.type() != std::filesystem::file_type::regular)
    throw NoSuchDatabase(file, fmt::format("is not a regular file ({}); give a vsi study database file",
                                           status.type() == std::filesystem::file_type::fifo        ? "a FIFO"
                                           : status.type() == std::filesystem::file_type::directory ? "a directory"
                                                                                                     : "a special file"));
  if (mode == OpenMode::kCreate) return;
  const auto bytes = std::filesystem::file_size(file, ec);
  // A database whose pages are all still in its -wal has an empty main file.
  const auto wal_bytes = std::filesystem::file_size(file + "-wal", ec);
  if (bytes == 0 && (ec || wal_bytes == 0))
    throw NoSuchDatabase(file, "is empty, not a vsi study database (vsi submit creates one)");
}

}  // namespace

void Database::open(const std::string& name, int flags) {
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(name.c_str(), &raw, flags | SQLITE_OPEN_NOMUTEX, nullptr);
  db_.reset(raw);  // closed even when the open failed
  if (rc != SQLITE_OK) fail(raw, rc, fmt::format("cannot open {}", file_));
}

Database::Database(const std::string& file, OpenMode mode, int busy_timeout_ms) : file_(file) {
  if (mode != OpenMode::kCreate && !std::filesystem::exists(file)) throw NoSuchDatabase(file);
  refuse_what_is_no_store(file, mode);
  if (const auto folder = std::filesystem::path(file).parent_path();
      mode == OpenMode::kCreate && !folder.empty() && !std::filesystem::is_directory(folder))
    throw NoSuchDatabase(fmt::format("{} (its folder {} does not exist)", file, folder.string()));
  if (mode == OpenMode::kReadOnly) {
    read_only_ = true;
    open(file, SQLITE_OPEN_READONLY);
    sqlite3_busy_timeout(db_.get(), busy_timeout_ms);
    sqlite3_extended_result_codes(db_.get(), 1);
    const int rc = read_schema(db_.get());
    if (rc == SQLITE_ROW) return;
    if ((rc & 0xff) != SQLITE_CANTOPEN && (rc & 0xff) != SQLITE_READONLY) fail(db_.get(), rc, "read");
    // A WAL database needs its -shm, which a read-only connection cannot
    // create on a read-only directory or mount. immutable=1 reads the main
    // file alone: right only when no -wal holds commits not yet
    // checkpointed (the last writer to close checkpoints and removes it).
    std::error_code ec;
    const auto wal_bytes = std::filesystem::file_size(file + "-wal", ec);
    if (!ec && wal_bytes > 0)
      throw SqliteError(SQLITE_CANTOPEN,
                        fmt::format("sqlite: cannot read {} read-only: its -wal file holds changes not yet in the "
                                    "database and the -shm file cannot be created here; open it once with write "
                                    "access to checkpoint it (sqlite3 FILE 'PRAGMA wal_checkpoint')",
                                    file));
    open(file_uri(file) + "?immutable=1", SQLITE_OPEN_READONLY | SQLITE_OPEN_URI);
    sqlite3_extended_result_codes(db_.get(), 1);
    immutable_ = true;
    return;
  }
  open(file, mode == OpenMode::kCreate ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE : SQLITE_OPEN_READWRITE);
  sqlite3* raw = db_.get();
  sqlite3_busy_timeout(raw, busy_timeout_ms);
  sqlite3_extended_result_codes(raw, 1);
  // Not an SQLite file: say which file, before the journal mode is touched.
  if (const int rc = read_schema(raw); rc != SQLITE_ROW) fail(raw, rc, "read");
  exec("PRAGMA journal_mode=WAL");
  // NORMAL is durable in WAL mode up to the last checkpointed commit after a
  // power loss; a process crash loses no committed transaction.
  exec("PRAGMA synchronous=NORMAL");
  exec("PRAGMA foreign_keys=ON");
}

Database::~Database() = default;

void Database::set_busy_timeout(int busy_timeout_ms) { sqlite3_busy_timeout(db_.get(), busy_timeout_ms); }

void Database::exec(const std::string& sql) {
  char* message = nullptr;
  const int rc = sqlite3_exec(db_.get(), sql.c_str(), nullptr, nullptr, &message);
  if (rc != SQLITE_OK) {
    const std::string text = message != nullptr ? message : sqlite3_errstr(rc);
    sqlite3_free(message);
    throw SqliteError(rc, fmt::format("sqlite: {}: {}", sql.substr(0, 60), text));
  }
}

Statement Database::prepare(std::string_view sql) { return Statement(db_.get(), sql); }

std::int64_t Database::changes() const { return sqlite3_changes64(db_.get()); }

void Statement::Finalizer::operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }

Statement::Statement(sqlite3* db, std::string_view sql) : db_(db) {
  sqlite3_stmt* raw = nullptr;
  const int rc = sqlite3_prepare_v2(db, sql.data(), static_cast<int>(sql.size()), &raw, nullptr);
  stmt_.reset(raw);
  if (rc != SQLITE_OK) fail(db, rc, fmt::format("prepare '{}'", sql.substr(0, 80)));
}

Statement& Statement::bind(int index, std::int64_t value) {
  if (const int rc = sqlite3_bind_int64(stmt_.get(), index, value); rc != SQLITE_OK) fail(db_, rc, "bind");
  return *this;
}

Statement& Statement::bind(int index, double value) {
  if (const int rc = sqlite3_bind_double(stmt_.get(), index, value); rc != SQLITE_OK) fail(db_, rc, "bind");
  return *this;
}

Statement& Statement::bind(int index, std::string_view text) {
  const int rc = sqlite3_bind_text64(stmt_.get(), index, text.data(), text.size(), SQLITE_TRANSIENT, SQLITE_UTF8);
  if (rc != SQLITE_OK) fail(db_, rc, "bind");
  return *this;
}

Statement& Statement::bind_null(int index) {
  if (const int rc = sqlite3_bind_null(stmt_.get(), index); rc != SQLITE_OK) fail(db_, rc, "bind");
  return *this;
}

Statement& Statement::bind(int index, const SqlValue& value) {
  std::visit(
      [&](const auto& v) {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, Null>)
          bind_null(index);
        else
          bind(index, v);
      },
      value);
  return *this;
}

bool Statement::step() {
  const int rc = sqlite3_step(stmt_.get());
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  fail(db_, rc, fmt::format("step '{}'", std::string_view(sqlite3_sql(stmt_.get())).substr(0, 80)));
}

void Statement::run() {
  while (step()) {
  }
  reset();
}

void Statement::reset() {
  sqlite3_reset(stmt_.get());
  sqlite3_clear_bindings(stmt_.get());
}

int Statement::columns() const { return sqlite3_column_count(stmt_.get()); }
bool Statement::is_null(int column) const { return sqlite3_column_type(stmt_.get(), column) == SQLITE_NULL; }
std::int64_t Statement::int64(int column) const { return sqlite3_column_int64(stmt_.get(), column); }
double Statement::real(int column) const { return sqlite3_column_double(stmt_.get(), column); }

std::string Statement::text(int column) const {
  const auto* p = sqlite3_column_text(stmt_.get(), column);
  return p == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(p),
                                                    static_cast<std::size_t>(sqlite3_column_bytes(stmt_.get(), column)));
}

std::optional<double> Statement::optional_real(int column) const {
  return is_null(column) ? std::nullopt : std::optional<double>(real(column));
}

std::string Statement::column_name(int column) const { return sqlite3_column_name(stmt_.get(), column); }

Transaction::Transaction(Database& db) : db_(db) { db_.exec("BEGIN IMMEDIATE"); }

Transaction::~Transaction() {
  if (!done_) {
    try {
      db_.exec("ROLLBACK");
    } catch (...) {  // a destructor must not throw; the connection rolls back on close anyway
    }
  }
}

void Transaction::commit() {
  db_.exec("COMMIT");
  done_ = true;
}

}  // namespace railvsi::scheduler
