#pragma once
// The tables of the study database (one SQLite file: queue and results) and
// their migrations. The version is PRAGMA user_version, and every applied
// migration is also a row of schema_version, for people reading the file.
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

inline constexpr int kStoreSchemaVersion = 16;

// Applies the missing migrations in one BEGIN IMMEDIATE transaction (safe
// when several workers open a new file at once). Throws SqliteError, or
// std::runtime_error for a file written by a newer vsi. up_to_version
// (tests of a migration) stops at an older version.
void migrate(Database& db, int up_to_version = kStoreSchemaVersion);

// Throws std::runtime_error when the file is an SQLite database of another
// program (tables, and no vsi schema version): vsi writes nothing into it.
void require_vsi_or_empty(Database& db);

// For a read-only connection, which cannot migrate: throws
// std::runtime_error unless the file has this vsi's schema version.
void require_current_schema(Database& db);

}  // namespace railvsi::scheduler
