#pragma once
// Matrix Market reader for imported structures: "coordinate" format, "real"
// or "integer" entries, "general" or "symmetric" (the lower triangle is
// mirrored), 1-based indices. Errors name the file and the line.
#include <filesystem>
#include <string>

#include "core/types.hpp"

namespace railvsi {

// Throws InputError at `json_path` (the scene key that named the file) with
// "<file>:<line>: <what is wrong>" as the message.
SparseMatrix read_matrix_market(const std::filesystem::path& file, const std::string& json_path);

}  // namespace railvsi
