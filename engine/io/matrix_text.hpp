#pragma once
// What the text matrix readers share: numbered lines of the file, entries
// that remember their line, and one assembly that checks them.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "core/types.hpp"

namespace railvsi {

// Lines of a file with their 1-based numbers; errors name the file and a line.
class TextLines {
 public:
  TextLines(const std::filesystem::path& file, std::string json_path);
  bool next(std::string& line);  // false at the end of the file
  long number() const { return number_; }
  const std::string& file() const { return file_; }
  InputError error(const std::string& what) const { return error_at(number_, what); }
  InputError error_at(long line, const std::string& what) const;

 private:
  std::ifstream in_;
  std::string file_, json_path_;
  long number_ = 0;
};

struct MatrixEntry {
  int row = 0, col = 0;  // 0-based
  double value = 0.0;
  long line = 0;  // where the value is written
};

enum class MatrixStorage {
  kLowerTriangle,  // symmetric, the lower triangle stored (Matrix Market symmetric, Harwell-Boeing RSA)
  kFull,           // every entry stored; must be symmetric (Matrix Market general, Harwell-Boeing RUA)
  kEitherTriangle  // lower, upper or both; both must agree (Abaqus matrix input)
};

// The n x n matrix of `entries` (duplicates are summed). Refuses, naming the
// line: a non-finite value, an entry above the diagonal of a lower triangle,
// an entry that differs from its transpose by more than 1e-10 of the largest
// entry (the tolerance of StructureModel).
SparseMatrix assemble_checked(std::vector<MatrixEntry> entries, int n, MatrixStorage storage, const TextLines& lines);

}  // namespace railvsi
