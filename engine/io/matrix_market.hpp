#pragma once
// Matrix Market reader (and writer) for imported structures: "coordinate" format, "real"
// or "integer" entries, "general" or "symmetric" (the lower triangle is
// mirrored), 1-based indices. Errors name the file and the line.
#include <filesystem>
#include <string>

#include "core/types.hpp"

namespace railvsi {

// Throws InputError at `json_path` (the scene key that named the file) with
// "<file>:<line>: <what is wrong>" as the message.
SparseMatrix read_matrix_market(const std::filesystem::path& file, const std::string& json_path);

// Writes A as "coordinate real": its lower triangle as "symmetric" (A must be
// symmetric: the upper triangle is not looked at), or every stored entry as
// "general". 17 significant digits, so the reader gets the same doubles back.
// Writes `file` directly; see io/file_set_writer.hpp for a set of files that
// appears whole or not at all. Throws std::runtime_error when it cannot write.
void write_matrix_market(const std::filesystem::path& file, const SparseMatrix& A, bool symmetric = true);

}  // namespace railvsi
