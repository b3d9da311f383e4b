#pragma once
// What the service commands share: the database, opened and migrated, and
// study ids given on the command line.
#include <memory>
#include <optional>
#include <string>

#include "store/sqlite.hpp"

namespace railvsi::cli {

std::unique_ptr<scheduler::Database> open_store(const std::string& file);

// The full id of --study (a unique prefix is enough); prints an error and
// returns nullopt when there is no such study.
std::optional<std::string> find_study(scheduler::Database& db, const std::string& id_or_prefix);

}  // namespace railvsi::cli
