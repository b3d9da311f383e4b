#pragma once
// Another store file attached to a connection (ATTACH ... AS alias) for
// the life of the object, and a deferred transaction: unlike BEGIN
// IMMEDIATE it takes a write lock only on the database it writes, so
// copying from an attached store never locks that store for writing.
#include <filesystem>
#include <string>
#include <vector>

#include "store/sqlite.hpp"

namespace railvsi::scheduler {

class AttachedStore {
 public:
  // The file must exist: ATTACH would create a missing one.
  AttachedStore(Database& db, const std::filesystem::path& file, std::string alias);
  ~AttachedStore();
  AttachedStore(const AttachedStore&) = delete;
  AttachedStore& operator=(const AttachedStore&) = delete;

 private:
  Database& db_;
  std::string alias_;
};

class DeferredTransaction {
 public:
  explicit DeferredTransaction(Database& db);
  ~DeferredTransaction();
  DeferredTransaction(const DeferredTransaction&) = delete;
  DeferredTransaction& operator=(const DeferredTransaction&) = delete;
  void commit();

 private:
  Database& db_;
  bool done_ = false;
};

// Column names of a table of a schema ("main" or an alias), in order.
std::vector<std::string> table_columns(Database& db, const std::string& schema, const std::string& table);

}  // namespace railvsi::scheduler
