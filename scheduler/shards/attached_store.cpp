#include "shards/attached_store.hpp"

#include <fmt/format.h>

namespace railvsi::scheduler {

AttachedStore::AttachedStore(Database& db, const std::filesystem::path& file, std::string alias)
    : db_(db), alias_(std::move(alias)) {
  if (!std::filesystem::is_regular_file(file))
    throw std::runtime_error(fmt::format("{}: no such store file", file.string()));
  // The alias is our own identifier; the file name is a bound parameter.
  db_.prepare(fmt::format("ATTACH DATABASE ? AS {}", alias_)).bind(1, file.string()).run();
}

AttachedStore::~AttachedStore() {
  try {
    db_.exec(fmt::format("DETACH DATABASE {}", alias_));
  } catch (const SqliteError&) {
    // Nothing to do: the connection closes it at the latest.
  }
}

DeferredTransaction::DeferredTransaction(Database& db) : db_(db) { db_.exec("BEGIN"); }

DeferredTransaction::~DeferredTransaction() {
  if (done_) return;
  try {
    db_.exec("ROLLBACK");
  } catch (const SqliteError&) {
  }
}

void DeferredTransaction::commit() {
  db_.exec("COMMIT");
  done_ = true;
}

std::vector<std::string> table_columns(Database& db, const std::string& schema, const std::string& table) {
  Statement s = db.prepare(fmt::format("PRAGMA {}.table_info({})", schema, table));
  std::vector<std::string> names;
  while (s.step()) names.push_back(s.text(1));
  return names;
}

}  // namespace railvsi::scheduler
