#pragma once
// Thin RAII wrappers for sqlite3* and sqlite3_stmt*. Values reach SQL only
// through bound parameters: no user text is ever pasted into a statement.
// One Database per thread (SQLite connections are not shared here).
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>

struct sqlite3;
struct sqlite3_stmt;

namespace railvsi::scheduler {

class SqliteError : public std::runtime_error {
 public:
  SqliteError(int code, const std::string& what) : std::runtime_error(what), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};

struct Null {};
using SqlValue = std::variant<Null, std::int64_t, double, std::string>;

class Statement;

// The file is not there (and the mode does not create it), or it is no
// database file at all (a FIFO, a directory, an empty file to open as an
// existing store): bad input, refused before SQLite reads or writes it.
class NoSuchDatabase : public std::runtime_error {
 public:
  explicit NoSuchDatabase(const std::string& file) : std::runtime_error("no such database: " + file) {}
  NoSuchDatabase(const std::string& file, const std::string& why) : std::runtime_error(file + ": " + why) {}
};

enum class OpenMode {
  kCreate,    // read-write, created when missing (submit, run)
  kExisting,  // read-write, NoSuchDatabase when missing (work, cancel, retry)
  kReadOnly,  // SQLITE_OPEN_READONLY, NoSuchDatabase when missing (status, query, check)
};

class Database {
 public:
  // Read-write modes set WAL with a busy timeout, so that several processes
  // and threads can share the file. Read-only never writes: it works on a
  // 0444 file or a read-only mount (see open_read_only in sqlite.cpp).
  explicit Database(const std::string& file, OpenMode mode = OpenMode::kCreate, int busy_timeout_ms = 60000);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Statements without parameters (schema, pragmas, BEGIN/COMMIT).
  void exec(const std::string& sql);
  // How long a statement waits for another connection's lock.
  void set_busy_timeout(int busy_timeout_ms);
  Statement prepare(std::string_view sql);
  std::int64_t changes() const;
  const std::string& file() const { return file_; }
  sqlite3* handle() const { return db_.get(); }
  bool read_only() const { return read_only_; }
  // True when the read-only open fell back to immutable=1 (the -shm could
  // not be created): a write by another process would not be seen.
  bool immutable() const { return immutable_; }

 private:
  struct Closer {
    void operator()(sqlite3* db) const;
  };
  void open(const std::string& name, int flags);
  std::string file_;
  std::unique_ptr<sqlite3, Closer> db_;
  bool read_only_ = false;
  bool immutable_ = false;
};

class Statement {
 public:
  Statement(sqlite3* db, std::string_view sql);
  Statement(Statement&&) noexcept = default;
  Statement& operator=(Statement&&) noexcept = default;

  // Parameters are numbered from 1, as in SQLite.
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, double value);
  Statement& bind(int index, std::string_view text);
  Statement& bind(int index, const char* text) { return bind(index, std::string_view(text)); }
  Statement& bind(int index, const std::string& text) { return bind(index, std::string_view(text)); }
  Statement& bind_null(int index);
  Statement& bind(int index, const SqlValue& value);

  // true while there is a row; throws SqliteError on failure.
  bool step();
  // Runs a statement that returns no rows.
  void run();
  void reset();

  int columns() const;
  bool is_null(int column) const;
  std::int64_t int64(int column) const;
  double real(int column) const;
  std::string text(int column) const;
  std::optional<double> optional_real(int column) const;
  std::string column_name(int column) const;

 private:
  struct Finalizer {
    void operator()(sqlite3_stmt* s) const;
  };
  sqlite3* db_;
  std::unique_ptr<sqlite3_stmt, Finalizer> stmt_;
};

// BEGIN IMMEDIATE on construction (the write lock is taken at once, so two
// workers cannot both read a job as free and then both claim it); ROLLBACK
// unless commit() was called.
class Transaction {
 public:
  explicit Transaction(Database& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Database& db_;
  bool done_ = false;
};

}  // namespace railvsi::scheduler
