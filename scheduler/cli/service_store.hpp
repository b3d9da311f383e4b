#pragma once
// What the service commands share: the database, opened (and migrated when
// writable), and study ids given on the command line.
#include <memory>
#include <optional>
#include <string>

#include "store/sqlite.hpp"

namespace railvsi::cli {

// kCreate and kExisting migrate the file; kReadOnly requires the current
// schema and a sound file (require_sound). A missing file throws scheduler::NoSuchDatabase (exit 2) unless
// the mode creates it.
// The default is for read commands: a command that writes says so.
std::unique_ptr<scheduler::Database> open_store(const std::string& file,
                                                scheduler::OpenMode mode = scheduler::OpenMode::kReadOnly);

// Computes and stores the trains' static envelopes of a line study
// (stored_statics.hpp), or of every line study in the store without an
// id; a failure is logged, not thrown (the readers compute what is missing).
void fill_static_envelopes(scheduler::Database& db, const std::optional<std::string>& study_id);

// The full id of --study (a unique prefix is enough); prints an error and
// returns nullopt when there is no such study.
std::optional<std::string> find_study(scheduler::Database& db, const std::string& id_or_prefix);

// A command's database and study: the file must exist (never created),
// the study be in it. Prints the error and returns nullopt (exit 2)
// otherwise. Read-only unless a writing mode is given (kExisting).
struct OpenedStudy {
  std::unique_ptr<scheduler::Database> db;
  std::string id;
};
std::optional<OpenedStudy> open_study(const std::string& file, const std::string& id_or_prefix,
                                      scheduler::OpenMode mode = scheduler::OpenMode::kReadOnly);

}  // namespace railvsi::cli
