#pragma once
// Abaqus global matrices as written by *MATRIX GENERATE with *MATRIX OUTPUT
// (FORMAT=MATRIX INPUT, the default): one entry per line, "row node, row DOF,
// column node, column DOF, value", the layout of a *MATRIX INPUT data line
// (Abaqus Keywords Reference, *MATRIX INPUT). Lines starting with * (keywords,
// ** comments) are skipped. A symmetric matrix may be given as its lower
// triangle, its upper triangle or both (then both must agree). DOFs are
// Abaqus's 1-6 (U1, U2, U3, UR1, UR2, UR3). The equations are numbered in
// the order of (node, DOF), and the labels are kept.
#include <filesystem>
#include <string>
#include <vector>

#include "io/matrix_reader.hpp"

namespace railvsi {

class AbaqusMatrixReader final : public MatrixReader {
 public:
  std::string_view format() const override { return "Abaqus matrix input"; }
  MatrixFile read(const std::filesystem::path& file, const std::string& json_path) const override;
};

// Writes the lower triangle of A (symmetric) in that layout, equation i as
// labels[i]; labels must be ordered by (node, DOF) so that the reader
// numbers the equations as A does. Throws std::runtime_error when it cannot
// write, std::invalid_argument when labels are not so ordered.
void write_abaqus_matrix(const std::filesystem::path& file, const SparseMatrix& A, const std::vector<DofLabel>& labels);

}  // namespace railvsi
