#pragma once
// Harwell-Boeing files (Duff, Grimes & Lewis, "Users' Guide for the
// Harwell-Boeing Sparse Matrix Collection", 1992): the format of ANSYS
// HBMAT and of SciPy's hb_write. Read: real (or integer) matrices, assembled
// (RSA: lower triangle by columns; RUA: every entry) or elemental (RSE, RUE:
// the element matrices, summed here). Complex, pattern-only, skew and
// rectangular matrices are refused. The fixed-width Fortran fields of the
// header formats are honoured (D exponents included); right-hand sides are
// skipped. Node/DOF labels come from an ANSYS mapping file beside the matrix
// (same name, extension .mapping) when there is one.
#include <filesystem>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "io/matrix_reader.hpp"

namespace railvsi {

class HarwellBoeingReader final : public MatrixReader {
 public:
  std::string_view format() const override { return "Harwell-Boeing"; }
  MatrixFile read(const std::filesystem::path& file, const std::string& json_path) const override;
};

// The ANSYS HBMAT mapping file of `matrix_file` ("<name>.mapping" beside it,
// either case), or an empty path when there is none.
std::filesystem::path mapping_file_of(const std::filesystem::path& matrix_file);

// Reads a mapping file: one line per equation, "equation node DOF-label"
// (e.g. "12  4  UY"); lines whose first field is not a number (the heading)
// are skipped. Every equation 1..n must appear once.
std::vector<DofLabel> read_ansys_mapping(const std::filesystem::path& file, int n, const std::string& json_path);
void write_ansys_mapping(const std::filesystem::path& file, const std::vector<DofLabel>& labels);

// Writes A as RSA (its lower triangle; A must be symmetric) or RUA (every
// stored entry), values as E25.16 (17 significant digits: read back exactly).
// Throws std::runtime_error when it cannot write.
void write_harwell_boeing(const std::filesystem::path& file, const SparseMatrix& A, bool symmetric = true,
                          const std::string& title = "written by railvsi");

}  // namespace railvsi
