#pragma once
// Matrix Market reader (and writer) for imported structures: "coordinate"
// format, "real" or "integer" entries, "general" or "symmetric" (the lower
// triangle is stored and mirrored), 1-based indices. Errors name the file
// and the line. Matrix Market carries no node or DOF labels.
#include <filesystem>
#include <string>

#include "core/types.hpp"
#include "io/matrix_reader.hpp"

namespace railvsi {

class MatrixMarketReader final : public MatrixReader {
 public:
  std::string_view format() const override { return "Matrix Market"; }
  MatrixFile read(const std::filesystem::path& file, const std::string& json_path) const override;
};

// The matrix alone (MatrixMarketReader().read(...).A).
SparseMatrix read_matrix_market(const std::filesystem::path& file, const std::string& json_path);

// Writes A as "coordinate real": its lower triangle as "symmetric" (A must be
// symmetric: the upper triangle is not looked at), or every stored entry as
// "general". 17 significant digits, so the reader gets the same doubles back.
// Writes `file` directly; see io/file_set_writer.hpp for a set of files that
// appears whole or not at all. Throws std::runtime_error when it cannot write.
void write_matrix_market(const std::filesystem::path& file, const SparseMatrix& A, bool symmetric = true);

}  // namespace railvsi
