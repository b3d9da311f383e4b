#pragma once
// Reading the structure matrices an FE package exports: one MatrixReader per
// file format, chosen by make_matrix_reader from the file's content (and its
// extension when the content says nothing). Every reader checks what the
// format lets it check (sizes, indices, non-finite values, symmetry) and
// throws InputError with "<file>:<line>: <what is wrong>" as the message.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.hpp"

namespace railvsi {

// The package's own name of an equation: node number and DOF component,
// 1-6 = x, y, z translation, rotation about x, y, z (Abaqus DOFs 1-6; ANSYS
// UX, UY, UZ, ROTX, ROTY, ROTZ).
struct DofLabel {
  long node = 0;
  int component = 0;
  bool operator==(const DofLabel&) const = default;
  auto operator<=>(const DofLabel&) const = default;
};

// The DOF component of a name: "UY", "U2", "2" -> 2; "ROTZ", "UR3", "6" -> 6.
// 0 when the name is none of these.
int dof_component(std::string_view name);
// The name printed for a component: Abaqus-style when `abaqus`, else ANSYS-style.
std::string dof_component_name(int component, bool abaqus);

struct MatrixFile {
  SparseMatrix A;  // the whole matrix (a symmetric storage is mirrored)
  // One label per equation when the format carries them (Abaqus), else empty.
  std::vector<DofLabel> labels;
  std::string format;  // for reports: "Matrix Market", "Harwell-Boeing RSA", ...
};

class MatrixReader {
 public:
  virtual ~MatrixReader() = default;
  virtual std::string_view format() const = 0;
  // Errors: InputError at `json_path` (the scene key that named the file).
  virtual MatrixFile read(const std::filesystem::path& file, const std::string& json_path) const = 0;
};

// Matrix Market when the first line is "%%MatrixMarket"; Harwell-Boeing when
// the third line starts with a Harwell-Boeing type (RSA, RUA, RSE, RUE, ...);
// Abaqus when the first data line is "node, dof, node, dof, value". Otherwise
// the extension decides (.mtx, .rsa/.rua/.rse/.rue/.hb/.matrix); else an
// InputError saying which formats are read.
std::unique_ptr<MatrixReader> make_matrix_reader(const std::filesystem::path& file, const std::string& json_path);

// make_matrix_reader(file)->read(file).
MatrixFile read_matrix_file(const std::filesystem::path& file, const std::string& json_path);

}  // namespace railvsi
